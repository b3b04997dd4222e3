// Everything the progressive solver knows between two shots; callers may read it any time
// between steps (the interactive mode edits materials here and continues).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/position_bits.h"
#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"
#include "solver/buried_vertices.h"
#include "solver/clusters.h"
#include "solver/kept_rays.h"
#include "solver/occlusion_culling.h"
#include "solver/options.h"
#include "solver/shot_source.h"
#include "visibility/backend.h"

namespace rad {

/// Counters of a solve, summed over shots (per-thread during a shot, combined after it).
struct SolverStats {
  VisibilityStats rays;
  uint64_t intensity_cuts = 0;  // shadow rays skipped by the intensity cut (all but one)
  uint64_t kept_answers = 0;    // shadow rays not traced again: answer kept (kept_rays.h)
  uint64_t culled = 0;          // vertex evaluations skipped: source behind or facing away
  uint64_t roulette = 0;        // vertex evaluations skipped by the roulette (shot_source.h)
  /// Receiving triangles a shot skipped whole: hidden by an occluder, behind the source, or
  /// beyond the roulette's reach (when culling is on).
  uint64_t hidden = 0;
  uint64_t vertex_evaluations = 0;  // vertex-to-source gathers computed
  uint64_t subdivisions = 0;        // elements split into four
  uint64_t exact_midpoints = 0;     // new vertices whose shot was computed
  uint64_t interpolated_midpoints = 0;
  double shoot_seconds = 0.0, refine_seconds = 0.0;

  SolverStats& operator+=(const SolverStats& o);
};

/// What the solver keeps at a vertex of the radiosity mesh (whose position the mesh keeps, at
/// the same index). One record per vertex, not one array per quantity: a polygon that never
/// splits costs one allocation, not four.
struct VertexState {
  Vec3 irradiance{0.0f};  // H: radiosity gathered from all shots so far; B = E + rho * H
  Vec3 unshot{0.0f};      // radiosity received but not yet shot
  Vec3 shot{0.0f};        // H gathered during the current shot only (for subdivision)
  Vec3 major{0.0f};       // part of H gathered from the solver's major shots (see solver)

  /// Takes a shot's gain dh (H before the reflectance rho): into H, the current shot and, for a
  /// major shot, the major part; into the light to shoot only when the vertex `shoots` (not one
  /// inside a solid, buried_vertices.h).
  void receive(const Vec3& dh, const Vec3& rho, bool major_shot, bool shoots) {
    irradiance += dh;
    if (shoots) unshot += rho * dh;
    shot = dh;
    if (major_shot) major += dh;
  }
};

/// A polygon's unshot energy: its unshot radiosity integrated over its leaf elements. `sum` is
/// the mean over the channels (signed: what the ambient term spreads); `magnitude` the mean of
/// each channel's absolute value, what shooter choice and convergence use. They differ only when
/// the channels differ in sign (an edit that changes a colour but not its mean reflectance gives
/// +x in one and -x in another: a sum near 0, yet light to shoot); else magnitude = |sum|.
struct UnshotEnergy {
  double sum = 0.0, magnitude = 0.0;
};

/// What a cluster's polygons hold unshot, summed for choosing the shooter (solver.cpp). With
/// overshooting polygon p shoots |u_p + r_p a| + m_p - |u_p|: u_p its signed unshot energy, m_p
/// its magnitude, r_p its mean reflectance times its area, a the ambient estimate. Where a lies
/// beyond every polygon's break -u_p / r_p, the sum over the cluster is linear in a.
struct ClusterUnshot {
  double magnitude = 0.0;            // sum of m_p: what it shoots without overshooting
  double sum = 0.0, rho_area = 0.0;  // sums of u_p and r_p over the polygons with r_p > 0
  double rest = 0.0;                 // sum of the terms that do not depend on a
  double lo = 0.0, hi = 0.0;         // least and largest break (lo > hi: no polygon has one)
};

/// A cluster's shots summed: the energy they carried (each shot's magnitude) and the part of it
/// the scene received (sign for sign). One shot under the roulette lands an unbiased but noisy
/// part (a small one may land nothing, or a far receiver's gain divided by its chance); the sum
/// is weighted by the shots' energies, so the first (major, without the roulette) weighs most.
struct ShotBalance {
  double shot = 0.0, landed = 0.0;
  /// landed / shot within [0, 1]; 1 before any shot.
  double retention() const;
};

/// One line of the convergence history.
struct ShotRecord {
  int64_t shot;            // 1-based
  int32_t source;          // cluster that shot
  double seconds;          // since the solve began
  double unshot_fraction;  // unshot / emitted energy after the shot
};

/// A vertex that takes the gain of another at the same position in the same planar cluster
/// (the same point of the same plane and Pure) instead of gathering it again.
struct VertexCopy {
  uint32_t vertex, from_polygon, from_vertex;
};

/// The vertices that polygons of one planar cluster share: a tessellated wall stores each grid
/// point once per triangle around it (six times), and each midpoint of an edge between two of
/// its triangles twice once both split it, but one of them gathers and the others copy its gain
/// after the shot. Found by position: among the initial vertices, the lowest (polygon, vertex)
/// gathers; a midpoint made on a polygon's edge copies the one that gathers there, if that one's
/// polygon received the same shot (else it gathers for itself, from then on, and the lowest
/// (polygon, vertex) of those that gather at a place is the one later midpoints copy). A copy's
/// source is never a copy.
struct SharedVertices {
  struct Place {  // a position in a cluster
    uint32_t cluster;
    PositionBits position;
    bool operator==(const Place&) const = default;
    auto operator<=>(const Place&) const = default;
  };
  struct PlaceHash {
    size_t operator()(const Place& k) const;
  };
  struct Gatherer {
    uint32_t polygon, vertex;
  };
  /// Per polygon: its copies, in vertex order.
  std::vector<std::vector<VertexCopy>> copies;
  /// Whether vertex v of polygon p copies another's gain.
  bool is_copy(uint32_t p, uint32_t v) const;
  /// The midpoint later ones copy at each place on polygon edges where one was made.
  std::unordered_map<Place, Gatherer, PlaceHash> edge_midpoints;
};

class Ranks;

/// Vertices [begin, end) of one polygon: a work item of a shot's gathering loop.
struct VertexRange {
  uint32_t polygon = 0, begin = 0, end = 0;
  uint32_t receiver = 0;  // the polygon's index in SolverState::receivers
};

__extension__ typedef __int128 Fixed128;  // GCC's and clang's 128-bit integer

struct SolverState {
  const Hierarchy* hierarchy = nullptr;
  SolverOptions options;
  Mesh mesh;
  /// Per polygon, per vertex of its mesh (same indices; as long as its vertex table).
  std::vector<std::vector<VertexState>> vertex_states;
  /// Materials per hierarchy object (copied so they can be edited between shots).
  std::vector<Material> materials;
  /// The shooting patches (design §10), of at most (max_sample_grid x max_size)^2 each.
  Clusters clusters;
  SharedVertices shared;
  /// The vertices inside solids and where they gather instead (buried_vertices.h): found at
  /// the first step, when a visibility backend is at hand, and for new vertices as they are made.
  BuriedVertices buried;
  /// The flat occluders and the tree over the triangles that cull receivers hidden from a source
  /// (empty without shadows).
  OcclusionCulling culling;
  /// Per polygon: unshot energy, kept current. Negative after an edit lowers an emission or a
  /// reflectance (Chen 1990): shooter choice and convergence use its magnitude.
  std::vector<UnshotEnergy> unshot_energy;
  double emitted_energy = 0.0;  // sum of area x mean-channel emission
  /// What the unshot fraction and the fixed-point totals are relative to: the emitted energy,
  /// or, after an edit that left next to no emission, the emitted energy before it. Turning
  /// every light off leaves none (or a rounding leftover of either sign), yet their light must
  /// still be shot back out.
  double reference_energy = 0.0;
  double absorbed_energy = 0.0;  // sum over shots of received energy not reflected
  float radiosity_scale = 1.0f;  // emitted power / total area: what relative limits scale by
  double total_area = 0.0;
  float min_size = 0.0f;  // smallest element edge
  float max_size = 0.0f;  // largest element edge of the initial mesh
  float shadow_offset = 0.0f;
  /// regular_sample_barycentrics(q) for q = 1 .. 4 x max_sample_grid (index q; 0 is empty):
  /// where a source's triangles are cut into fine points.
  std::vector<std::vector<Vec3>> barycentric_grids;
  /// Every shot so far, in order. New vertices made by refinement gather the major ones again;
  /// vertices made by a forced subdivision gather them all, so their radiosity is exact.
  std::vector<ShotSource> shot_log;
  int64_t shots = 0;
  SolverStats stats;
  std::vector<ShotRecord> history;
  /// Sums over the polygons (and the ranks) of the unshot energies' magnitudes and sums, kept by
  /// update_unshot_totals, set_unshot_energies and share_unshot_totals; the same two over this
  /// rank's polygons in fixed point; per cluster, cluster_unshot (0 for other ranks').
  double unshot_abs_total = 0.0, unshot_signed_total = 0.0;
  Fixed128 unshot_abs_fixed = 0, unshot_signed_fixed = 0;
  std::vector<ClusterUnshot> cluster_unshot;
  /// Cohen's interreflection factor 1 / (1 - kept reflectance), mean over the channels, where
  /// the kept reflectance is the mean reflectance over the area less what the clusters' light
  /// leaves the scene by (cluster_retention): in a closed scene each bounce lands all it
  /// reflects, in an open one only what the surfaces' shots land. Kept current by
  /// update_unshot_totals (materials edited) and set_retention (a shot measured).
  double interreflection = 1.0;
  /// Per cluster: what its shots carried and what of it the scene received (ShotBalance), and
  /// the fraction that gives (1 until the cluster shoots; empty or short: 1), the rest having
  /// left the scene. By reciprocity also the fraction of a uniform ambient radiosity the cluster
  /// receives: what overshooting may expect back.
  std::vector<ShotBalance> cluster_balance;
  std::vector<double> cluster_retention;
  /// The area-weighted mean reflectance per channel (materials as edited) and the part of it
  /// that retention loses, sum over clusters of rho_c area_c (1 - retention_c) in fixed point
  /// (2^-64 of the total area): exact, so the same for any order of the shots that set it.
  DVec3 mean_reflectance{0.0};
  std::array<Fixed128, 3> lost_reflectance{};
  /// The polygons that may have gained from the last shot: a mask per polygon and their list
  /// in index order (shoot_to_receivers; kept between shots so a small shot costs little).
  std::vector<uint8_t> received;
  std::vector<uint32_t> receivers;
  std::vector<VertexRange> gather_work;  // the receivers' vertices in work items (shoot.cpp)
  std::vector<uint32_t> unhidden;        // the triangles culling left to a shot (shoot.cpp)
  /// Per cluster shot often enough: its shadow-ray answers kept for its next shot
  /// (kept_rays.h), and the bytes they hold in all.
  std::unordered_map<int32_t, KeptRays> kept_rays;
  size_t kept_rays_bytes = 0;
  std::vector<uint64_t> cluster_last_shot;  // per cluster: the number of its last shot, 0: none
  /// What a shot of each cluster costs, in vertices gathered (those of its last shot's
  /// receivers; 0: not shot yet), for choosing the shooter (solver.cpp).
  std::vector<double> cluster_cost;
  /// Under MPI (solver/distribute.h): the ranks solving together, the owner of each cluster and
  /// which polygons are this rank's. One process: null and empty, every polygon its own.
  Ranks* ranks = nullptr;
  std::vector<uint32_t> cluster_owner;
  std::vector<uint8_t> owned;

  bool owns(size_t polygon) const { return owned.empty() || owned[polygon]; }
  bool owns_cluster(size_t c) const;

  const Material& material_of(size_t polygon) const {
    return materials[size_t(hierarchy->triangles.object[polygon])];
  }
  /// Radiosity B = E + rho * H of vertex v of polygon p.
  Vec3 radiosity(size_t p, uint32_t v) const {
    const Material& m = material_of(p);
    return m.emission + m.reflectance * vertex_states[p][v].irradiance;
  }
  double unshot_fraction() const {
    return reference_energy > 0.0 ? unshot_abs_total / reference_energy : 0.0;
  }
};

/// How vertices inside solids are probed (buried_vertices.h): a vertex moves at most the smallest
/// elements' size, as far as the last elements that reach out of a solid extend.
inline BuriedProbe buried_probe(const SolverState& s) { return {s.shadow_offset, s.min_size}; }

/// The diameter of a sphere that holds every corner, about the smallest: what the default
/// element sizes scale with. Unlike the bounding box's diagonal it does not change when the
/// scene is turned (the Cornell box turned 30 and 20 degrees has a box diagonal 1.47 times its
/// own, and refined one level less); for an axis-aligned box the two are equal.
float scene_size(const Hierarchy& h);

/// The state before the first shot: the unsplit mesh, emitters' unshot radiosity = emission.
/// Keeps a pointer to `h`, which must outlive the state.
SolverState make_solver_state(const Hierarchy& h, const SolverOptions& options);

/// The initial mesh's vertices shared within planar clusters.
SharedVertices find_shared_vertices(const Mesh& mesh, const Clusters& clusters);

/// Whether polygon p may share vertices: its cluster is planar with other polygons.
bool shares_vertices(const Clusters& clusters, size_t p);

/// Where vertex position `x` of polygon p is shared, if it may be (shares_vertices). (Whether x
/// lies on p's edges is the caller's to say: on_triangle_edge.)
std::optional<SharedVertices::Place> shared_place(const Clusters& clusters, size_t p,
                                                  const Vec3& x);

/// Whether x lies on an edge of the triangle (a midpoint of two points on one edge does, up to
/// rounding; any other point of a subdivision lies a fraction of the smallest element inside).
bool on_triangle_edge(const std::array<Vec3, 3>& c, const Vec3& x);

/// s.shared.edge_midpoints from the mesh and the copies (after a checkpoint is read): at each
/// place, the lowest (polygon, vertex) that gathers among the midpoints refinement made on
/// polygon edges (vertices from initial_vertices[p] on).
void find_edge_midpoints(SolverState& s, std::span<const uint32_t> initial_vertices);

/// Cluster c's unshot energy from its polygons', in order.
ClusterUnshot cluster_unshot(const SolverState& s, size_t c);

/// What cluster c shoots with overshooting at ambient a (ClusterUnshot's sum): from
/// s.cluster_unshot where a lies beyond every break, else polygon by polygon.
double cluster_shooting_energy(const SolverState& s, size_t c, double a);

/// Sets the unshot totals, every cluster's energy and the interreflection factor from
/// unshot_energy and the materials after they changed. The
/// totals are summed in fixed point (2^-64 of the emitted energy), which is exact and so the
/// same in any order and across any split of the polygons between ranks (summed over them too:
/// collective under MPI). Floating-point sums would differ in their last bits, and the
/// convergence test with them.
void update_unshot_totals(SolverState& s);

/// Sets the unshot energy of `polygons` to `energies`, keeping this rank's fixed-point sums
/// exact and the energy of their clusters current; then the caller calls share_unshot_totals.
/// Parallel inside; costs what the polygons are, not the scene.
void set_unshot_energies(SolverState& s, std::span<const uint32_t> polygons,
                         std::span<const UnshotEnergy> energies);

/// The totals from this rank's fixed-point sums (summed over the ranks: collective under MPI).
void share_unshot_totals(SolverState& s);

/// What polygon p absorbed of the last shot (its vertices' `shot` times 1 - rho) and the unshot
/// energy it holds, each integrated over its leaf elements (mean over channels), in one walk.
struct PolygonEnergies {
  double absorbed = 0.0;
  UnshotEnergy unshot;
};
PolygonEnergies polygon_energies(const SolverState& s, size_t p);

/// Unshot energy of polygon p integrated over its leaf elements.
inline UnshotEnergy polygon_unshot_energy(const SolverState& s, size_t p) {
  return polygon_energies(s, p).unshot;
}

/// The ambient term from the per-polygon unshot energies (mean over channels, signed): cheap
/// enough to evaluate every shot. What cluster c expects back of it is that times
/// retention(s, c): a cluster that sees little of the scene receives little of it.
float ambient_estimate(const SolverState& s);

/// Cluster c's retention (SolverState::cluster_retention; 1 until it shoots).
inline double retention(const SolverState& s, size_t c) {
  return c < s.cluster_retention.size() ? s.cluster_retention[c] : 1.0;
}

/// Sets cluster c's retention to r (in [0, 1]) and the interreflection factor with it.
void set_retention(SolverState& s, size_t c, double r);

/// Energies summed exactly: sums[k] is the sum of terms[k] over this rank's terms and then over
/// the ranks (collective under MPI), each term in the fixed point of the unshot totals (2^-64
/// of the reference energy), so the sums have the same bits for any order, any thread count and
/// any split of the terms between the ranks.
void exact_energy_sums(const SolverState& s, std::span<const std::span<const double>> terms,
                       std::span<double> sums);

/// Cohen et al. 1988 ambient term: the unshot energy spread over the scene and reflected
/// 1/(1 - mean reflectance) times. For display only; never added to stored radiosity.
Vec3 ambient_radiosity(const SolverState& s);

}  // namespace rad
