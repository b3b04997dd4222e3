// The solve's energy bookkeeping: what each polygon and cluster holds unshot, the exact totals
// that convergence is tested on, and what the ambient term and overshooting estimate from them.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/math.h"
#include "solver/clusters.h"
#include "solver/ranks.h"
#include "solver/solution.h"

namespace rad {

__extension__ typedef __int128 Fixed128;  // GCC's and clang's 128-bit integer

/// A polygon's unshot energy: its unshot radiosity integrated over its leaf elements. `sum` is
/// the mean over the channels (signed: what the ambient term spreads); `magnitude` the mean of
/// each channel's absolute value, what shooter choice and convergence use. They differ only when
/// the channels differ in sign (an edit that changes a colour but not its mean reflectance gives
/// +x in one and -x in another: a sum near 0, yet light to shoot); else magnitude = |sum|.
struct UnshotEnergy {
  double sum = 0.0, magnitude = 0.0;
  DVec3 channels{0.0};  // per channel, signed: what overshooting's ambient is made of
};

/// What a cluster's polygons hold unshot, summed for choosing the shooter (solver.cpp). With
/// overshooting at ambient a (per channel, retention included) polygon p shoots the mean over
/// the channels of |U_pc + rho_c A_p a_c|: U_pc its signed unshot energy in channel c, rho the
/// cluster's reflectance (a cluster lies in one Pure), A_p its area. In a channel where a_c lies
/// beyond every polygon's break -U_pc / (rho_c A_p), the sum over the cluster is linear in a_c.
/// Exact, so a cluster that has just overshot (U_pc = -rho_c A_p a_c) is seen holding nothing.
struct ClusterUnshot {
  double area = 0.0;       // sum of A_p
  DVec3 rho{0.0};          // the reflectance
  DVec3 sum{0.0};          // per channel, sum of U_pc
  DVec3 abs{0.0};          // per channel, sum of |U_pc|: what a channel of rho_c = 0 shoots,
                           // and (their mean) what the cluster shoots without overshooting
  DVec3 lo{0.0}, hi{0.0};  // per channel, least and largest break (lo > hi: no polygon)
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

struct EnergyBalance {
  /// Per polygon: unshot energy, kept current. Negative after an edit lowers an emission or a
  /// reflectance (Chen 1990): shooter choice and convergence use its magnitude.
  std::vector<UnshotEnergy> unshot_energy;
  double emitted_energy = 0.0;  // sum of area x mean-channel emission, and the lights' power
  /// What the unshot fraction and the fixed-point totals are relative to: the emitted energy,
  /// or, after an edit that left next to no emission, the emitted energy before it. Turning
  /// every light off leaves none (or a rounding leftover of either sign), yet their light must
  /// still be shot back out.
  double reference_energy = 0.0;
  double absorbed_energy = 0.0;  // sum over shots of received energy not reflected
  float radiosity_scale = 1.0f;  // emitted power / total area: what relative limits scale by
  double total_area = 0.0;
  /// Sums over the polygons (and the ranks) of the unshot energies' magnitudes and sums, kept by
  /// update_unshot_totals, set_unshot_energies and share_unshot_totals; the same two over this
  /// rank's polygons in fixed point; per cluster, cluster_unshot (0 for other ranks').
  double unshot_abs_total = 0.0, unshot_signed_total = 0.0;
  Fixed128 unshot_abs_fixed = 0, unshot_signed_fixed = 0;
  /// The same per channel, signed.
  DVec3 unshot_channel_total{0.0};
  std::array<Fixed128, 3> unshot_channel_fixed{};
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
  /// Per light of the scene (Hierarchy::lights): what it has still to shoot per channel (its
  /// colour until its shot, then 0), and its power per unit of colour (light_power,
  /// light_source.h). The same on every rank: every rank shoots every light.
  std::vector<Vec3> light_unshot;
  std::vector<double> light_power;

  /// The lights' part of the unshot energy: each light's power times its unshot colour's mean.
  double light_unshot_energy() const {
    double e = 0.0;
    for (size_t i = 0; i < light_unshot.size(); ++i)
      e += light_power[i] * double(mean_component(glm::abs(light_unshot[i])));
    return e;
  }

  double unshot_fraction() const {
    const double unshot = unshot_abs_total + light_unshot_energy();
    return reference_energy > 0.0 ? unshot / reference_energy : (unshot > 0.0 ? 1.0 : 0.0);
  }
};

/// What polygon p absorbed of the last shot (its vertices' last gain times 1 - rho) and the
/// unshot energy it holds, each integrated over its leaf elements (mean over channels), in one
/// walk.
struct PolygonEnergies {
  double absorbed = 0.0;
  UnshotEnergy unshot;
};
PolygonEnergies polygon_energies(const Solution& solution, size_t p);

/// Unshot energy of polygon p integrated over its leaf elements.
inline UnshotEnergy polygon_unshot_energy(const Solution& solution, size_t p) {
  return polygon_energies(solution, p).unshot;
}

/// Cluster c's unshot energy from its polygons', in order.
ClusterUnshot cluster_unshot(const EnergyBalance& e, const Solution& solution,
                             const Clusters& clusters, size_t c);

/// What cluster c shoots with overshooting at ambient a (per channel: ambient_estimate times
/// its retention), mean over the channels: from e.cluster_unshot in a channel where a lies
/// beyond every break, else polygon by polygon.
double cluster_shooting_energy(const EnergyBalance& e, const Solution& solution,
                               const Clusters& clusters, size_t c, const Vec3& a);

/// Sets the unshot totals, every cluster's energy and the interreflection factor from
/// e.unshot_energy and the materials after they changed. The totals are summed in fixed point
/// (2^-64 of the reference energy), which is exact and so the same in any order and across any
/// split of the polygons between ranks (summed over them too: collective under MPI; `ranks` is
/// null for one process). Floating-point sums would differ in their last bits, and the
/// convergence test with them.
void update_unshot_totals(EnergyBalance& e, const Solution& solution, const Clusters& clusters,
                          Ranks* ranks);

/// Sets the unshot energy of `polygons` to `energies`, keeping this rank's fixed-point sums
/// exact and the energy of their clusters current; then the caller calls share_unshot_totals.
/// Parallel inside; costs what the polygons are, not the scene.
void set_unshot_energies(EnergyBalance& e, const Solution& solution, const Clusters& clusters,
                         std::span<const uint32_t> polygons,
                         std::span<const UnshotEnergy> energies);

/// The totals from this rank's fixed-point sums (summed over the ranks: collective under MPI).
void share_unshot_totals(EnergyBalance& e, Ranks* ranks);

/// The ambient term from the per-polygon unshot energies, per channel (signed), each channel
/// with its own interreflection factor: cheap enough to evaluate every shot. What cluster c
/// overshoots is its reflectance times that times retention(e, c) (a cluster that sees little
/// of the scene receives little of it). A grey estimate (the mean over the channels) would
/// overshoot a scene's weak channel (the Cornell box's blue, a quarter of its red) by the strong
/// ones' share and leave it negative unshot energy, which the display's uniform ambient term
/// then spreads.
Vec3 ambient_estimate(const EnergyBalance& e);

/// Cluster c's retention (EnergyBalance::cluster_retention; 1 until it shoots).
inline double retention(const EnergyBalance& e, size_t c) {
  return c < e.cluster_retention.size() ? e.cluster_retention[c] : 1.0;
}

/// Sets cluster c's retention to r (in [0, 1]) and the interreflection factor with it.
void set_retention(EnergyBalance& e, const Solution& solution, const Clusters& clusters, size_t c,
                   double r);

/// Energies summed exactly: sums[k] is the sum of terms[k] over this rank's terms and then over
/// the ranks (collective under MPI), each term in the fixed point of the unshot totals (2^-64
/// of the reference energy), so the sums have the same bits for any order, any thread count and
/// any split of the terms between the ranks.
void exact_energy_sums(const EnergyBalance& e, Ranks* ranks,
                       std::span<const std::span<const double>> terms, std::span<double> sums);

/// Cohen et al. 1988 ambient term: the unshot energy spread over the scene and reflected
/// 1/(1 - mean reflectance) times. For display only; never added to stored radiosity. With
/// `group` >= 0, the light group's unshot energy alone (the groups' terms add up to the whole's).
Vec3 ambient_radiosity(const EnergyBalance& e, const Solution& solution, int group = -1);

}  // namespace rad
