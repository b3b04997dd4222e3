#include "solver/energy_balance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "mesh/subdivide.h"

namespace rad {

PolygonEnergies polygon_energies(const Solution& s, size_t p) {
  const PolygonMesh& m = s.mesh.polygons[p];
  const std::vector<VertexState>& vs = s.vertex_states[p];
  const Vec3 absorptance = Vec3(1.0f) - s.material_of(p).reflectance;
  PolygonEnergies e;
  DVec3 channels(0.0);
  for_each_leaf(m, [&](uint32_t l) {
    const Element& el = m.elements[l];
    const VertexState &v0 = vs[el.v[0]], &v1 = vs[el.v[1]], &v2 = vs[el.v[2]];
    const Vec3 u = v0.unshot + v1.unshot + v2.unshot;
    e.absorbed += double(el.area) *
                  mean_component(absorptance * (v0.last_gain + v1.last_gain + v2.last_gain)) / 3.0;
    e.unshot.sum += double(el.area) * double(mean_component(u)) / 3.0;
    channels += DVec3(u) * (double(el.area) / 3.0);
  });
  const bool one_sign = glm::all(glm::greaterThanEqual(channels, DVec3(0.0))) ||
                        glm::all(glm::lessThanEqual(channels, DVec3(0.0)));
  e.unshot.channels = channels;
  e.unshot.magnitude =
      one_sign ? std::abs(e.unshot.sum)
               : (std::abs(channels.x) + std::abs(channels.y) + std::abs(channels.z)) / 3.0;
  return e;
}

namespace {
// The fixed-point unit: 2^-64 of the reference energy (the emitted energy, see energy_balance.h). A
// polygon's energy is clamped to 2^36 emitted energies (an edit may leave the emission near zero
// and the unshot energy not), so 2^26 polygons of them still sum within 128 bits.
double fixed_scale(const EnergyBalance& e) {
  return std::ldexp(1.0, 64) / (e.reference_energy > 0.0 ? e.reference_energy : 1.0);
}
Fixed128 to_fixed(double e, double scale) {
  const double most = std::ldexp(1.0, 100);
  const double x = e * scale;
  if (!(x == x)) return 0;  // NaN: counted as nothing rather than undefined
  return Fixed128(std::nearbyint(std::clamp(x, -most, most)));
}

// Fixed-point sums of the N values term(i) gives for each i < n. Integer sums are exact, so the
// parallel reduction's order does not matter.
template <size_t N>
using FixedSums = std::array<Fixed128, N>;
template <size_t N, typename Term>
FixedSums<N> sum_fixed(size_t n, const Term& term) {
  auto add = [](FixedSums<N> a, const FixedSums<N>& b) {
    for (size_t k = 0; k < N; ++k) a[k] += b[k];
    return a;
  };
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 1024), FixedSums<N>{},
      [&](const auto& r, FixedSums<N> acc) {
        for (size_t i = r.begin(); i != r.end(); ++i) acc = add(acc, term(i));
        return acc;
      },
      add);
}

// A polygon's unshot energy as the five fixed-point terms of the totals: magnitude, signed sum,
// and the three channels.
FixedSums<5> unshot_terms(const UnshotEnergy& u, double scale) {
  return {to_fixed(u.magnitude, scale), to_fixed(u.sum, scale), to_fixed(u.channels.x, scale),
          to_fixed(u.channels.y, scale), to_fixed(u.channels.z, scale)};
}

// Area-weighted mean reflectance per channel, from the current (possibly edited) materials.
DVec3 mean_reflectance(const Solution& s, double total_area) {
  const Triangles& tris = s.hierarchy->triangles;
  DVec3 rho(0.0);
  for (size_t t = 0; t < tris.size(); ++t)
    rho += DVec3(s.material_of(t).reflectance) * double(tris.area[t]);
  return total_area > 0.0 ? rho / total_area : rho;
}

// Cohen's interreflection factor 1 / (1 - mean reflectance), kept finite.
DVec3 interreflection(const DVec3& mean_rho) {
  return 1.0 / (1.0 - glm::min(mean_rho, DVec3(0.999)));
}

// The mean reflectance less what the clusters' light leaves the scene by (EnergyBalance::
// lost_reflectance): with every retention 1 exactly the mean reflectance.
DVec3 kept_reflectance(const EnergyBalance& e) {
  const DVec3 lost(double(e.lost_reflectance[0]), double(e.lost_reflectance[1]),
                   double(e.lost_reflectance[2]));
  return e.mean_reflectance - lost * std::ldexp(1.0, -64);
}

// Cluster c's term of EnergyBalance::lost_reflectance at retention r: rho_c area_c (1 - r) in
// 2^-64 of the total area, per channel (a cluster lies in one Pure: one reflectance).
std::array<Fixed128, 3> lost_term(const Solution& s, const Clusters& clusters, double total_area,
                                  size_t c, double r) {
  std::array<Fixed128, 3> t{};
  if (!(total_area > 0.0) || r >= 1.0) return t;
  const Vec3 rho = s.material_of(clusters.polygons[clusters.first[c]]).reflectance;
  const double scale = std::ldexp(1.0, 64) / total_area * double(clusters.area[c]) * (1.0 - r);
  for (int ch = 0; ch < 3; ++ch) t[size_t(ch)] = to_fixed(double(rho[ch]), scale);
  return t;
}

// 128-bit sums over the ranks, in place (collective under MPI): each as three limbs (the top one
// signed, two of 32 bits below), which any number of ranks add up in 64 bits without carries.
void sum_over_ranks(Ranks* ranks, std::span<Fixed128> sums) {
  if (!ranks) return;
  std::vector<int64_t> limbs(3 * sums.size());
  for (size_t i = 0; i < sums.size(); ++i) {
    limbs[3 * i] = int64_t(sums[i] >> 64);
    limbs[3 * i + 1] = int64_t((sums[i] >> 32) & 0xffffffff);
    limbs[3 * i + 2] = int64_t(sums[i] & 0xffffffff);
  }
  ranks->sum(limbs);
  for (size_t i = 0; i < sums.size(); ++i) {
    sums[i] = (Fixed128(limbs[3 * i]) << 64) + (Fixed128(limbs[3 * i + 1]) << 32) +
              Fixed128(limbs[3 * i + 2]);
  }
}

}  // namespace

ClusterUnshot cluster_unshot(const EnergyBalance& e, const Solution& s, const Clusters& clusters,
                             size_t c) {
  ClusterUnshot k;
  k.lo = DVec3(std::numeric_limits<double>::infinity()), k.hi = -k.lo;
  k.rho = DVec3(s.material_of(clusters.polygons[clusters.first[c]]).reflectance);
  for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j) {
    const uint32_t p = clusters.polygons[j];
    const UnshotEnergy& u = e.unshot_energy[p];
    const double area = double(s.hierarchy->triangles.area[p]);
    k.area += area;
    k.sum += u.channels;
    k.abs += glm::abs(u.channels);
    for (int ch = 0; ch < 3; ++ch) {
      if (!(k.rho[ch] > 0.0) || !(area > 0.0)) continue;
      const double at = -u.channels[ch] / (k.rho[ch] * area);
      k.lo[ch] = std::min(k.lo[ch], at), k.hi[ch] = std::max(k.hi[ch], at);
    }
  }
  return k;
}

double cluster_shooting_energy(const EnergyBalance& e, const Solution& s, const Clusters& clusters,
                               size_t c, const Vec3& a) {
  const ClusterUnshot& k = e.cluster_unshot[c];
  double shoots = 0.0;
  for (int ch = 0; ch < 3; ++ch) {
    const double x = double(a[ch]), rho = k.rho[ch];
    if (!(rho > 0.0)) {
      shoots += k.abs[ch];
    } else if (x >= k.hi[ch]) {
      shoots += k.sum[ch] + rho * k.area * x;
    } else if (x <= k.lo[ch]) {
      shoots -= k.sum[ch] + rho * k.area * x;
    } else {
      for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1]; ++j) {
        const uint32_t p = clusters.polygons[j];
        shoots += std::abs(e.unshot_energy[p].channels[ch] +
                           rho * double(s.hierarchy->triangles.area[p]) * x);
      }
    }
  }
  return shoots / 3.0;
}

void update_unshot_totals(EnergyBalance& e, const Solution& s, const Clusters& clusters,
                          Ranks* ranks) {
  const double scale = fixed_scale(e);
  const FixedSums<5> t = sum_fixed<5>(
      e.unshot_energy.size(), [&](size_t p) { return unshot_terms(e.unshot_energy[p], scale); });
  e.unshot_abs_fixed = t[0], e.unshot_signed_fixed = t[1];
  e.unshot_channel_fixed = {t[2], t[3], t[4]};
  e.cluster_unshot.resize(clusters.size());
  tbb::parallel_for(size_t(0), clusters.size(),
                    [&](size_t c) { e.cluster_unshot[c] = cluster_unshot(e, s, clusters, c); });
  e.mean_reflectance = mean_reflectance(s, e.total_area);
  e.lost_reflectance = {};
  for (size_t c = 0; c < e.cluster_retention.size() && c < clusters.size(); ++c) {
    const std::array<Fixed128, 3> term =
        lost_term(s, clusters, e.total_area, c, e.cluster_retention[c]);
    for (size_t ch = 0; ch < 3; ++ch) e.lost_reflectance[ch] += term[ch];
  }
  e.interreflection = mean_component(Vec3(interreflection(kept_reflectance(e))));
  share_unshot_totals(e, ranks);
}

void set_unshot_energies(EnergyBalance& e, const Solution& s, const Clusters& clusters,
                         std::span<const uint32_t> polygons,
                         std::span<const UnshotEnergy> energies) {
  assert(polygons.size() == energies.size());
  const double scale = fixed_scale(e);
  const FixedSums<5> d = sum_fixed<5>(polygons.size(), [&](size_t i) {
    FixedSums<5> after = unshot_terms(energies[i], scale);
    const FixedSums<5> before = unshot_terms(e.unshot_energy[polygons[i]], scale);
    for (size_t k = 0; k < 5; ++k) after[k] -= before[k];
    return after;
  });
  e.unshot_abs_fixed += d[0], e.unshot_signed_fixed += d[1];
  for (size_t ch = 0; ch < 3; ++ch) e.unshot_channel_fixed[ch] += d[2 + ch];
  std::vector<uint32_t> changed;
  for (size_t i = 0; i < polygons.size(); ++i) {
    e.unshot_energy[polygons[i]] = energies[i];
    const uint32_t c = clusters.cluster_of[polygons[i]];
    if (changed.empty() || changed.back() != c) changed.push_back(c);  // most runs are long
  }
  std::sort(changed.begin(), changed.end());
  changed.erase(std::unique(changed.begin(), changed.end()), changed.end());
  tbb::parallel_for(size_t(0), changed.size(), [&](size_t i) {
    e.cluster_unshot[changed[i]] = cluster_unshot(e, s, clusters, changed[i]);
  });
}

void share_unshot_totals(EnergyBalance& e, Ranks* ranks) {
  Fixed128 sums[5] = {e.unshot_abs_fixed, e.unshot_signed_fixed, e.unshot_channel_fixed[0],
                      e.unshot_channel_fixed[1], e.unshot_channel_fixed[2]};
  sum_over_ranks(ranks, sums);
  const double scale = fixed_scale(e);
  e.unshot_abs_total = double(sums[0]) / scale;
  e.unshot_signed_total = double(sums[1]) / scale;
  e.unshot_channel_total = DVec3(double(sums[2]), double(sums[3]), double(sums[4])) / scale;
}

double ShotBalance::retention() const {
  if (!(shot > 0.0)) return 1.0;
  const double r = landed / shot;
  return std::isfinite(r) ? std::clamp(r, 0.0, 1.0) : 1.0;
}

void set_retention(EnergyBalance& e, const Solution& s, const Clusters& clusters, size_t c,
                   double r) {
  assert(r >= 0.0 && r <= 1.0);
  if (e.cluster_retention.size() < clusters.size())
    e.cluster_retention.resize(clusters.size(), 1.0);
  const std::array<Fixed128, 3> was =
                                    lost_term(s, clusters, e.total_area, c, e.cluster_retention[c]),
                                now = lost_term(s, clusters, e.total_area, c, r);
  for (size_t ch = 0; ch < 3; ++ch) e.lost_reflectance[ch] += now[ch] - was[ch];
  e.cluster_retention[c] = r;
  e.interreflection = mean_component(Vec3(interreflection(kept_reflectance(e))));
}

void exact_energy_sums(const EnergyBalance& e, Ranks* ranks,
                       std::span<const std::span<const double>> terms, std::span<double> sums) {
  assert(terms.size() == sums.size());
  const double scale = fixed_scale(e);
  std::vector<Fixed128> fixed(terms.size(), 0);
  for (size_t k = 0; k < terms.size(); ++k) {
    const std::span<const double> t = terms[k];
    fixed[k] =
        sum_fixed<1>(t.size(), [&](size_t i) { return FixedSums<1>{to_fixed(t[i], scale)}; })[0];
  }
  sum_over_ranks(ranks, fixed);
  for (size_t k = 0; k < terms.size(); ++k) sums[k] = double(fixed[k]) / scale;
}

Vec3 ambient_estimate(const EnergyBalance& e) {
  if (e.total_area <= 0.0) return Vec3(0.0f);
  return Vec3(e.unshot_channel_total / e.total_area * interreflection(kept_reflectance(e)));
}

Vec3 ambient_radiosity(const EnergyBalance& e, const Solution& s, int group) {
  const Hierarchy& h = *s.hierarchy;
  if (e.total_area <= 0.0) return Vec3(0.0f);
  const size_t n = s.group_count;
  assert(group < int(n));
  DVec3 unshot(0.0);
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    const std::vector<VertexState>& vs = s.vertex_states[t];
    DVec3 u(0.0);
    for_each_leaf_vertex_sum(
        s.mesh.polygons[t],
        [&](uint32_t v) {
          return group < 0 ? vs[v].unshot : s.group_states[t][v * n + size_t(group)].unshot;
        },
        [&](float area, Vec3 sum) { u += DVec3(sum) * (double(area) / 3.0); });
    unshot += u;
  }
  return Vec3(unshot / e.total_area * interreflection(kept_reflectance(e)));
}

}  // namespace rad
