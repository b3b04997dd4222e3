#include "solver/refine.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include "mesh/subdivide.h"
#include "solver/shoot.h"
#include "solver/texture_factors.h"

namespace rad {

namespace {

// Unshot radiosity interpolated to a midpoint of a textured polygon: the ends' mean `unshot`
// was reflected by the ends' mean texture factor `ends`; the midpoint reflects by its own.
Vec3 to_reflectance(const Vec3& unshot, const Vec3& ends, const Vec3& own) {
  Vec3 u = unshot;
  for (int k = 0; k < 3; ++k) u[k] = ends[k] > 0.0f ? unshot[k] * own[k] / ends[k] : 0.0f;
  return u;
}

// update(a, b, mid, g) on the states of vertices a, b and mid of polygon p: the whole's (g = -1),
// then each light group's (g = 0, 1, ...), which new vertices get by the same rules.
template <typename Update>
void whole_and_groups(Solution& sol, uint32_t p, uint32_t a, uint32_t b, uint32_t mid,
                      Update&& update) {
  std::vector<VertexState>& vs = sol.vertex_states[p];
  update(vs[a], vs[b], vs[mid], -1);
  const size_t n = sol.group_count;
  for (size_t g = 0; g < n; ++g) {
    std::vector<VertexState>& gs = sol.group_states[p];
    update(gs[a * n + g], gs[b * n + g], gs[mid * n + g], int(g));
  }
}

struct ExactVertex {
  uint32_t polygon, vertex, a, b;
  // A vertex shared with another polygon's (solver_state.h) copies it instead of gathering.
  int64_t from_polygon = -1;
  uint32_t from_vertex = 0;
};

// A new midpoint on polygon p's own edges, where the neighbour across may make the same one;
// `exact`: its index in the pass's exact list, or -1.
struct EdgeMidpoint {
  uint32_t vertex;
  int64_t exact;
};

// A new midpoint (computed or copied) whose shot gain the straight line between its edge's ends
// misses by more than this share of the subdivision limit is *bent*: the elements it is a
// corner of split again though their vertices differ less (and their new midpoints are looked
// at alike, down to the minimum size), for the shot's light bends there (a penumbra's edge) and
// a linear element would smear the bend across its width. (A lamp's fall-off over a bare floor
// bends too little to split anything more: the limit has split it already.)
constexpr float kBendShare = 0.25f;

// Whether midpoint `mid` of edge (a, b) of polygon p is bent by the shot just gathered (its
// last_gain against its ends'). Gains are weighed by the material's reflectance, not the
// texel's: a texture's own pattern is no bend of the light. A vertex inside a solid gathers
// elsewhere (buried_vertices.h) and takes no part.
bool is_bent(const Solution& s, const BuriedVertices& buried, uint32_t p, uint32_t mid, uint32_t a,
             uint32_t b, float limit) {
  if (buried.is_moved(p, mid) || buried.is_moved(p, a) || buried.is_moved(p, b)) return false;
  const std::vector<VertexState>& vs = s.vertex_states[p];
  const Vec3 rho = s.material_of(p).reflectance;
  return differs(rho * vs[mid].last_gain, rho * (vs[a].last_gain + vs[b].last_gain) * 0.5f,
                 limit * kBendShare);
}

// Whether element e of polygon p holds the edge of a major shot's shadow: one of its vertices
// got nothing from the shot (all its rays blocked, or the source behind its plane or outside
// a spot's cone: each a line where the light starts with a kink) and another more than the
// bend's share of the limit. The light rises from nothing with a kink at an umbra's edge, which a
// straight line across the element carries into the umbra; and where the light grows in small steps
// (a source whose samples cross the occluder's edge one by one) no two vertices differ by the
// limit.
bool holds_shadow_edge(const Solution& s, const BuriedVertices& buried, uint32_t p, uint32_t e,
                       float limit) {
  const PolygonMesh& m = s.mesh.polygons[p];
  const std::vector<VertexState>& vs = s.vertex_states[p];
  const Vec3 rho = s.material_of(p).reflectance;
  bool dark = false, lit = false;
  for (uint32_t v : m.elements[e].v) {
    if (buried.is_moved(p, v)) return false;
    const Vec3 g = vs[v].last_gain;
    dark = dark || g == Vec3(0.0f);
    lit = lit || max_component(glm::abs(rho * g)) > limit * kBendShare;
  }
  return dark && lit;
}

// Whether element e of polygon p (mesh m, vertex states vs) is to be split: its vertices'
// radiosities differ by more than `limit`, or it crosses into a solid (some of its vertices
// buried, some not: its light to shoot falls to nothing across it, buried_vertices.h), or,
// with `shadow_edges` (after a major shot, exact midpoints), it holds the shot's shadow edge,
// and it is still at least `min_split`; or, down to kCoverSplits levels below that, across
// the edge of a cover (some of its vertices covered, some not: the light falls within a few gap
// widths). Which of its edges to split: in *d (01, 12, 20).
constexpr float kCoverSplits = 3.0f;
bool needs_split(const Solution& s, const BuriedVertices& buried, uint32_t p, uint32_t e,
                 float limit, float min_split, bool shadow_edges,
                 std::span<const LeafRef> bright_middles, std::array<bool, 3>* d) {
  const PolygonMesh& m = s.mesh.polygons[p];
  auto B = [&](uint32_t v) { return s.radiosity(p, v); };
  const Element& el = m.elements[e];
  // Its middle lit more than its corners say (no smaller than min_split: shoot.cpp).
  if (std::binary_search(bright_middles.begin(), bright_middles.end(), LeafRef{p, e})) {
    *d = {true, true, true};
    return true;
  }
  const Vec3 b0 = B(el.v[0]), b1 = B(el.v[1]), b2 = B(el.v[2]);
  const bool in0 = buried.is_moved(p, el.v[0]), in1 = buried.is_moved(p, el.v[1]),
             in2 = buried.is_moved(p, el.v[2]);
  *d = {in0 != in1 || differs(b0, b1, limit), in1 != in2 || differs(b1, b2, limit),
        in2 != in0 || differs(b2, b0, limit)};
  if (!((*d)[0] || (*d)[1] || (*d)[2])) {
    if (!shadow_edges || !holds_shadow_edge(s, buried, p, e, limit) || split_size(m, e) < min_split)
      return false;
    *d = {true, true, true};
    return true;
  }
  const float size = split_size(m, e, *d);
  if (size >= min_split) return true;
  // A contact stays at the smallest size: below it, vertices land on the contact lines, where
  // the buried probes' first hits differ between the backends (they then split differently).
  if (in0 != in1 || in1 != in2) return false;
  const bool c0 = buried.is_covered(p, el.v[0]), c1 = buried.is_covered(p, el.v[1]),
             c2 = buried.is_covered(p, el.v[2]);
  if (c0 == c1 && c1 == c2) return false;
  // Down to the same floor whatever the gap: stopping at the gap's width (a lamp 1 cm below a
  // ceiling, elements of 2.7 cm) left the living room of tools/real_rooms at 2.89% against
  // 2.64%, for 6% fewer vertices.
  return size >= min_split * std::exp2(-kCoverSplits);
}

}  // namespace

bool needs_refinement(const SolverOptions& options, const EnergyBalance& energy,
                      const SceneCaches& scene, const Solution& sol, uint32_t p, bool major_shot,
                      std::span<const LeafRef> bright_middles) {
  const PolygonMesh& m = sol.mesh.polygons[p];
  const float limit = subdivision_limit(options, energy);
  const bool edges = major_shot && options.midpoints == MidpointRule::Exact;
  bool any = false;
  std::array<bool, 3> d;
  for_each_leaf(m, [&](uint32_t e) {
    any = any || needs_split(sol, scene.buried, p, e, limit, min_split_size(scene), edges,
                             bright_middles, &d);
  });
  return any;
}

std::vector<uint32_t> needing_refinement(const SolverOptions& options, const EnergyBalance& energy,
                                         const SceneCaches& scene, const Solution& sol,
                                         std::span<const uint32_t> polygons) {
  std::vector<uint8_t> needs(polygons.size());
  tbb::parallel_for(size_t(0), polygons.size(), [&](size_t i) {
    needs[i] = needs_refinement(options, energy, scene, sol, polygons[i]);
  });
  std::vector<uint32_t> out;
  for (size_t i = 0; i < polygons.size(); ++i)
    if (needs[i]) out.push_back(polygons[i]);
  return out;
}

Vec3 regather_shots(const Hierarchy& h, const Clusters& clusters, const ShotLog& shots,
                    const Vec3& x, uint32_t polygon, bool major_only, const VisibilityBackend& vis,
                    const GatherSettings& settings, GatherScratch& scratch, Vec3* major_part,
                    std::span<Vec3> group_all, std::span<Vec3> group_major) {
  const Triangles& tris = h.triangles;
  const Vec3 n = tris.normal[polygon], centroid = tris.centroid(polygon);
  const GatherSettings own = receiver_settings(settings, h, polygon);
  const size_t groups = std::max(group_all.size(), group_major.size());
  const std::span<Vec3> gain = group_gains(scratch, groups);
  std::fill(group_all.begin(), group_all.end(), Vec3(0.0f));
  std::fill(group_major.begin(), group_major.end(), Vec3(0.0f));
  Vec3 all(0.0f), major(0.0f);
  for (const ShotSource& k : shots.sources) {
    if ((major_only && !k.major) || !may_receive(h, clusters, polygon, k)) continue;
    const Vec3 g = gather_from_source(x, n, centroid, k, vis, own, scratch, nullptr, gain);
    all += g;
    if (k.major) major += g;
    for (size_t i = 0; i < group_all.size(); ++i) group_all[i] += gain[i];
    if (k.major)
      for (size_t i = 0; i < group_major.size(); ++i) group_major[i] += gain[i];
  }
  if (major_part) *major_part = major;
  return all;
}

namespace {

// The splitting both refinements share. `reached`: after a shot, the polygons it reached (they
// may copy each other's new midpoints, and the options' midpoint rule applies; after a major
// shot with exact midpoints, a bent one splits its elements again, is_bent, and so does an
// element across the shot's shadow edge, holds_shadow_edge); null after an edit, where every
// new midpoint is computed. compute(x, scratch) sets a computed new midpoint's state.
template <typename Compute>
void refine(RefineContext ctx, std::span<const uint32_t> polygons, const Receivers* reached,
            bool major, const VisibilityBackend& vis, const Compute& compute) {
  const bool after_shot = reached != nullptr;
  const Triangles& tris = ctx.solution.hierarchy->triangles;
  const float limit = subdivision_limit(ctx.options, ctx.energy);
  const float min_split = min_split_size(ctx.scene);
  // Only the given polygons are looked at: a shot of a Lights list reaches a few rooms of a
  // building, and per-polygon work over the whole scene would cost more than the shot.
  const size_t np = polygons.size();
  if (np == 0) return;
  const bool all_exact = ctx.options.midpoints == MidpointRule::Exact || !after_shot;
  const size_t groups = ctx.solution.group_count;

  std::vector<std::vector<uint32_t>> check(np), next(np);
  std::vector<std::vector<ExactVertex>> exact(np);
  std::vector<std::vector<EdgeMidpoint>> on_edges(np);
  SharedVertices& shared = ctx.scene.shared;
  // Copies take the current shot's state from a vertex that has it: only after a shot.
  const bool may_copy = after_shot && all_exact;
  std::vector<uint64_t> splits(np, 0), interpolated(np, 0);
  std::vector<VisibilityStats> probes(np);

  // Per polygon, the exact midpoints of the last pass that are bent (sorted). Only after a
  // major shot, whose sharp shadows the interpolation of later vertices keeps (the umbra scene's
  // minor shots bend nowhere; a building's many need not pay for looking).
  const bool bends = after_shot && all_exact && major;
  std::vector<std::vector<uint32_t>> bent(np);
  std::vector<ExactVertex> flat;
  // The first pass looks at every leaf of the polygons as it walks them (a list per polygon
  // would cost a million allocations a shot in a large scene, most polygons never splitting);
  // later passes at the children made by the one before.
  bool first_pass = true;
  for (bool any = true; any; first_pass = false) {
    // 1. Split what needs it; interpolated midpoints get their values now (their ends are
    //    final: only vertices of elements checked in this pass are ends).
    tbb::parallel_for(tbb::blocked_range<size_t>(0, np, 16), [&](const auto& range) {
      for (size_t i = range.begin(); i != range.end(); ++i) {
        next[i].clear();
        exact[i].clear();
        on_edges[i].clear();
        if (!first_pass && check[i].empty()) continue;
        const uint32_t p = polygons[i];
        const bool sharing = shares_vertices(ctx.scene.clusters, p);
        // The shot's bright middles name leaves of the first pass only (their children are
        // new): later passes look at the children's corners.
        const std::span<const LeafRef> middles =
            after_shot && first_pass ? reached->bright_middles_of(p) : std::span<const LeafRef>();
        PolygonMesh& m = ctx.solution.mesh.polygons[p];
        std::vector<VertexState>& vs = ctx.solution.vertex_states[p];
        std::vector<TextureFactors>& factors = ctx.solution.texture_factors[p];
        auto consider = [&](uint32_t e) {
          const uint32_t v[3] = {m.elements[e].v[0], m.elements[e].v[1], m.elements[e].v[2]};
          std::array<bool, 3> d;
          if (!needs_split(ctx.solution, ctx.scene.buried, p, e, limit, min_split, bends, middles,
                           &d)) {
            // A corner bent in the last pass splits it too.
            const std::vector<uint32_t>& b = bent[i];
            auto is_in = [&](uint32_t x) { return std::binary_search(b.begin(), b.end(), x); };
            if (b.empty() || !(is_in(v[0]) || is_in(v[1]) || is_in(v[2])) ||
                split_size(m, e) < min_split)
              return;
            d = {true, true, true};
          }
          const bool d01 = d[0], d12 = d[1], d20 = d[2];
          const bool exact_edge[3][3] = {{false, d01, d20}, {d01, false, d12}, {d20, d12, false}};
          auto index_of = [&](uint32_t x) { return x == v[0] ? 0 : x == v[1] ? 1 : 2; };
          NewMidpoint created[3];
          const int n = split_element(m, e, created);
          vs.resize(m.vertex_count());
          if (groups > 0) ctx.solution.group_states[p].resize(m.vertex_count() * groups);
          if (!factors.empty()) {
            factors.resize(m.vertex_count());
            for (int k = 0; k < n; ++k) {
              factors[created[k].vertex] =
                  texture_factor(tris, p, ctx.solution.object_of(p), m.positions[created[k].vertex],
                                 m.elements[size_t(m.elements[e].first_child)].area);
            }
          }
          ++splits[i];
          for (int k = 0; k < n; ++k) {
            const NewMidpoint& c = created[k];
            const bool computed = all_exact || exact_edge[index_of(c.a)][index_of(c.b)];
            if (sharing && on_triangle_edge(tris.corners[p], m.positions[c.vertex])) {
              on_edges[i].push_back({c.vertex, computed ? int64_t(exact[i].size()) : -1});
            }
            if (computed) {
              exact[i].push_back({p, c.vertex, c.a, c.b});
            } else {
              auto interpolate = [&](const VertexState& a, const VertexState& b, VertexState& mid,
                                     int) {
                mid.irradiance = (a.irradiance + b.irradiance) * 0.5f;
                mid.unshot = (a.unshot + b.unshot) * 0.5f;
                if (!factors.empty()) {
                  mid.unshot = to_reflectance(
                      mid.unshot, (factors[c.a].reflectance + factors[c.b].reflectance) * 0.5f,
                      factors[c.vertex].reflectance);
                }
                mid.last_gain = (a.last_gain + b.last_gain) * 0.5f;
                mid.major = (a.major + b.major) * 0.5f;
              };
              whole_and_groups(ctx.solution, p, c.a, c.b, c.vertex, interpolate);
              ++interpolated[i];
            }
          }
          const uint32_t first = uint32_t(m.elements[e].first_child);
          for (uint32_t c = 0; c < 4; ++c) next[i].push_back(first + c);
        };
        // Splitting a leaf appends elements, but the walk keeps indices only and does not
        // visit the new children.
        const uint32_t made_before = uint32_t(m.vertex_count());
        if (first_pass) {
          for_each_leaf(m, consider);
        } else {
          for (uint32_t e : check[i]) consider(e);
        }
        // The new vertices inside solids, before any of them gathers (step 3).
        if (ctx.scene.buried.found && ctx.options.shadows) {
          find_buried_vertices(tris, p, m, made_before, vis, buried_probe(ctx.scene),
                               ctx.scene.buried.moved[p], ctx.scene.buried.covered[p], probes[i]);
        }
      }
    });
    // 2. Midpoints on polygon edges: one at a place where another gathers copies it, if that
    //    one's polygon received this shot; else it gathers too, and the lowest (polygon, vertex)
    //    of those that gather is the one later midpoints there copy (find_edge_midpoints rebuilds
    //    the same from the mesh). In polygon order, so whatever the thread count.
    for (size_t i = 0; i < np; ++i) {
      const uint32_t p = polygons[i];
      for (const EdgeMidpoint& e : on_edges[i]) {
        const PolygonMesh& m = ctx.solution.mesh.polygons[p];
        const auto place = shared_place(ctx.scene.clusters, p, m.positions[e.vertex]);
        const SharedVertices::Gatherer self{p, e.vertex};
        const auto [it, made] = shared.edge_midpoints.try_emplace(*place, self);
        if (made) continue;
        SharedVertices::Gatherer& g = it->second;
        if (may_copy && e.exact >= 0 && reached->marked[g.polygon]) {
          ExactVertex& x = exact[i][size_t(e.exact)];
          x.from_polygon = g.polygon, x.from_vertex = g.vertex;
          shared.copies[p].push_back({e.vertex, g.polygon, g.vertex});
        } else if (std::tie(p, e.vertex) < std::tie(g.polygon, g.vertex)) {
          g = self;
        }
      }
    }
    // 3. Compute the current shot exactly at the midpoints of edges beyond the limit.
    flat.clear();
    for (size_t i = 0; i < np; ++i) flat.insert(flat.end(), exact[i].begin(), exact[i].end());
    parallel_gather(flat.size(), 16, ctx.stats, [&](size_t begin, size_t end, GatherScratch& sc) {
      for (size_t i = begin; i != end; ++i) {
        const ExactVertex& x = flat[i];
        if (x.from_polygon < 0) compute(x, sc);
      }
    });
    // 4. The copies take the state of the vertex they share (made in step 3, or earlier and
    //    gathered in the shot): the same point of the same plane and Pure.
    tbb::parallel_for(size_t(0), flat.size(), [&](size_t i) {
      const ExactVertex& x = flat[i];
      if (x.from_polygon < 0) return;
      const VertexState& from = ctx.solution.vertex_states[size_t(x.from_polygon)][x.from_vertex];
      VertexState& to = ctx.solution.vertex_states[x.polygon][x.vertex];
      to.irradiance = from.irradiance, to.unshot = from.unshot;
      to.last_gain = from.last_gain, to.major = from.major;
      for (size_t g = 0; g < groups; ++g) {
        ctx.solution.group_states[x.polygon][x.vertex * groups + g] =
            ctx.solution.group_states[size_t(x.from_polygon)][x.from_vertex * groups + g];
      }
    });
    // 5. Which of them are bent, computed or copied alike (a copy's state is the shot's at the
    //    same point), for the next pass.
    if (bends) {
      tbb::parallel_for(size_t(0), np, [&](size_t i) {
        bent[i].clear();
        for (const ExactVertex& x : exact[i])
          if (is_bent(ctx.solution, ctx.scene.buried, x.polygon, x.vertex, x.a, x.b, limit))
            bent[i].push_back(x.vertex);
        std::sort(bent[i].begin(), bent[i].end());
      });
    }
    ctx.stats.exact_midpoints += flat.size();
    any = false;
    for (size_t i = 0; i < np; ++i) {
      std::swap(check[i], next[i]);
      any |= !check[i].empty();
    }
  }
  for (size_t i = 0; i < np; ++i) {
    ctx.stats.subdivisions += splits[i];
    ctx.stats.interpolated_midpoints += interpolated[i];
    ctx.stats.rays += probes[i];
  }
}

}  // namespace

void refine_after_shot(RefineContext ctx, const Receivers& reached, const ShotSource& src,
                       const VisibilityBackend& vis, bool major,
                       std::span<const uint32_t> polygons) {
  const Hierarchy& h = *ctx.solution.hierarchy;
  const Triangles& tris = h.triangles;
  const GatherSettings settings = gather_settings(ctx.options, ctx.scene, ctx.energy);
  const size_t groups = ctx.solution.group_count;
  refine(ctx, polygons, &reached, major, vis, [&](const ExactVertex& x, GatherScratch& sc) {
    const Vec3 at = ctx.scene.buried.gather_point(
        x.polygon, x.vertex, ctx.solution.mesh.polygons[x.polygon].positions[x.vertex]);
    const Vec3 rho = ctx.solution.reflectance(x.polygon, x.vertex);
    const Vec3 rho_a = ctx.solution.reflectance(x.polygon, x.a);
    const Vec3 rho_b = ctx.solution.reflectance(x.polygon, x.b);
    // The major shots first: regather_shots uses the scratch's group_gain for each.
    sc.group_major.resize(groups);
    Vec3 whole_major_h(0.0f);
    regather_shots(h, ctx.scene.clusters, ctx.shots, at, x.polygon, true, vis, settings, sc,
                   &whole_major_h, {}, sc.group_major);
    const Vec3 whole_dh = gather_from_source(at, tris.normal[x.polygon], tris.centroid(x.polygon),
                                             src, vis, receiver_settings(settings, h, x.polygon),
                                             sc, nullptr, group_gains(sc, groups));
    const std::vector<TextureFactors>& factors = ctx.solution.texture_factors[x.polygon];
    // Whether the edge's ends and the midpoint shoot what they gather (buried_vertices.h).
    const std::vector<Vec3>& positions = ctx.solution.mesh.polygons[x.polygon].positions;
    const bool a_shoots = vertex_shoots(ctx.scene, x.polygon, x.a, positions[x.a]);
    const bool b_shoots = vertex_shoots(ctx.scene, x.polygon, x.b, positions[x.b]);
    const bool mid_shoots = vertex_shoots(ctx.scene, x.polygon, x.vertex, positions[x.vertex]);
    // The midpoint's state from its edge's ends, the shot's gain dh there and the major shots'
    // gains major_h there: the whole's, and each light group's alike.
    auto update = [&](const VertexState& a, const VertexState& b, VertexState& mid, int g) {
      const Vec3 dh = g < 0 ? whole_dh : sc.group_gain[size_t(g)];
      const Vec3 major_h = g < 0 ? whole_major_h : sc.group_major[size_t(g)];
      // Earlier minor shots: interpolated from the edge's ends (design §5).
      Vec3 minor_a = a.irradiance - a.last_gain - a.major;
      Vec3 minor_b = b.irradiance - b.last_gain - b.major;
      if (major) {  // the ends' major part includes this shot's
        minor_a += a.last_gain;
        minor_b += b.last_gain;
      }
      const Vec3 earlier_h = (minor_a + minor_b) * 0.5f + major_h;
      // The unshot radiosity of a vertex that does not shoot holds none of its gains.
      const Vec3 a_u = a_shoots ? a.unshot - rho_a * a.last_gain : a.unshot;
      const Vec3 b_u = b_shoots ? b.unshot - rho_b * b.last_gain : b.unshot;
      const Vec3 earlier_u =
          factors.empty()
              ? (a_u + b_u) * 0.5f
              : to_reflectance((a_u + b_u) * 0.5f,
                               (factors[x.a].reflectance + factors[x.b].reflectance) * 0.5f,
                               factors[x.vertex].reflectance);
      mid.irradiance = earlier_h + dh;
      mid.unshot = mid_shoots ? earlier_u + rho * dh : earlier_u;
      mid.last_gain = dh;
      mid.major = major ? major_h + dh : major_h;
    };
    whole_and_groups(ctx.solution, x.polygon, x.a, x.b, x.vertex, update);
  });
}

void refine_after_edit(RefineContext ctx, const Vec3& d_rho, const VisibilityBackend& vis,
                       std::span<const uint32_t> polygons) {
  const Hierarchy& h = *ctx.solution.hierarchy;
  const size_t groups = ctx.solution.group_count;
  const GatherSettings settings = gather_settings(ctx.options, ctx.scene, ctx.energy);
  refine(ctx, needing_refinement(ctx.options, ctx.energy, ctx.scene, ctx.solution, polygons),
         nullptr, false, vis, [&](const ExactVertex& x, GatherScratch& sc) {
           // Every earlier shot gathered again: H exact.
           const Vec3 at = ctx.scene.buried.gather_point(
               x.polygon, x.vertex, ctx.solution.mesh.polygons[x.polygon].positions[x.vertex]);
           Vec3 major_h(0.0f);
           sc.group_all.resize(groups), sc.group_major.resize(groups);
           const Vec3 all_h =
               regather_shots(h, ctx.scene.clusters, ctx.shots, at, x.polygon, false, vis, settings,
                              sc, &major_h, sc.group_all, sc.group_major);
           // Unshot: the edit's part d_rho * H exact, the rest interpolated (transient).
           const std::vector<TextureFactors>& f = ctx.solution.texture_factors[x.polygon];
           auto d_rho_at = [&](uint32_t v) { return f.empty() ? d_rho : d_rho * f[v].reflectance; };
           const bool shoots =
               vertex_shoots(ctx.scene, x.polygon, x.vertex,
                             ctx.solution.mesh.polygons[x.polygon].positions[x.vertex]);
           // The whole's state and each light group's alike.
           auto update = [&](const VertexState& a, const VertexState& b, VertexState& mid, int g) {
             mid.irradiance = g < 0 ? all_h : sc.group_all[size_t(g)];
             mid.major = g < 0 ? major_h : sc.group_major[size_t(g)];
             mid.unshot = (a.unshot - d_rho_at(x.a) * a.irradiance + b.unshot -
                           d_rho_at(x.b) * b.irradiance) *
                          0.5f;
             if (shoots) mid.unshot += d_rho_at(x.vertex) * mid.irradiance;
             mid.last_gain = Vec3(0.0f);
           };
           whole_and_groups(ctx.solution, x.polygon, x.a, x.b, x.vertex, update);
         });
}

}  // namespace rad
