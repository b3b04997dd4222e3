#include "solver/solver_state.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>
#include <tuple>

#include "mesh/sample_points.h"
#include "mesh/subdivide.h"
#include "solver/ranks.h"
#include "visibility/segment.h"

namespace rad {

SolverStats& SolverStats::operator+=(const SolverStats& o) {
  rays += o.rays;
  intensity_cuts += o.intensity_cuts;
  kept_answers += o.kept_answers;
  culled += o.culled;
  roulette += o.roulette;
  hidden += o.hidden;
  vertex_evaluations += o.vertex_evaluations;
  subdivisions += o.subdivisions;
  exact_midpoints += o.exact_midpoints;
  interpolated_midpoints += o.interpolated_midpoints;
  shoot_seconds += o.shoot_seconds;
  refine_seconds += o.refine_seconds;
  return *this;
}

PolygonEnergies polygon_energies(const SolverState& s, size_t p) {
  const PolygonMesh& m = s.mesh.polygons[p];
  const std::vector<VertexState>& vs = s.vertex_states[p];
  const Vec3 absorptance = Vec3(1.0f) - s.material_of(p).reflectance;
  PolygonEnergies e;
  DVec3 channels(0.0);
  for_each_leaf(m, [&](uint32_t l) {
    const Element& el = m.elements[l];
    const VertexState &v0 = vs[el.v[0]], &v1 = vs[el.v[1]], &v2 = vs[el.v[2]];
    const Vec3 u = v0.unshot + v1.unshot + v2.unshot;
    e.absorbed +=
        double(el.area) * mean_component(absorptance * (v0.shot + v1.shot + v2.shot)) / 3.0;
    e.unshot.sum += double(el.area) * double(mean_component(u)) / 3.0;
    channels += DVec3(u) * (double(el.area) / 3.0);
  });
  const bool one_sign = glm::all(glm::greaterThanEqual(channels, DVec3(0.0))) ||
                        glm::all(glm::lessThanEqual(channels, DVec3(0.0)));
  e.unshot.magnitude =
      one_sign ? std::abs(e.unshot.sum)
               : (std::abs(channels.x) + std::abs(channels.y) + std::abs(channels.z)) / 3.0;
  return e;
}

bool SolverState::owns_cluster(size_t c) const {
  return cluster_owner.empty() || cluster_owner[c] == uint32_t(ranks->rank());
}

namespace {
// The fixed-point unit: 2^-64 of the reference energy (the emitted energy, see solver_state.h). A
// polygon's energy is clamped to 2^36 emitted energies (an edit may leave the emission near zero
// and the unshot energy not), so 2^26 polygons of them still sum within 128 bits.
double fixed_scale(const SolverState& s) {
  return std::ldexp(1.0, 64) / (s.reference_energy > 0.0 ? s.reference_energy : 1.0);
}
Fixed128 to_fixed(double e, double scale) {
  const double most = std::ldexp(1.0, 100);
  const double x = e * scale;
  if (!(x == x)) return 0;  // NaN: counted as nothing rather than undefined
  return Fixed128(std::nearbyint(std::clamp(x, -most, most)));
}

// The sums of the absolute and the signed values term(i) gives for i < n. Integer sums are
// exact, so the parallel reduction's order does not matter.
using FixedSums = std::array<Fixed128, 2>;
template <typename Term>
FixedSums sum_fixed(size_t n, const Term& term) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, n, 1024), FixedSums{0, 0},
      [&](const auto& r, FixedSums acc) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
          const FixedSums t = term(i);
          acc[0] += t[0], acc[1] += t[1];
        }
        return acc;
      },
      [](FixedSums a, const FixedSums& b) {
        return FixedSums{a[0] + b[0], a[1] + b[1]};
      });
}

// Area-weighted mean reflectance per channel, from the current (possibly edited) materials.
DVec3 mean_reflectance(const SolverState& s) {
  const Triangles& tris = s.hierarchy->triangles;
  DVec3 rho(0.0);
  for (size_t t = 0; t < tris.size(); ++t)
    rho += DVec3(s.material_of(t).reflectance) * double(tris.area[t]);
  return s.total_area > 0.0 ? rho / s.total_area : rho;
}

// Cohen's interreflection factor 1 / (1 - mean reflectance), kept finite.
DVec3 interreflection(const DVec3& mean_rho) {
  return 1.0 / (1.0 - glm::min(mean_rho, DVec3(0.999)));
}

// The mean reflectance less what the clusters' light leaves the scene by (SolverState::
// lost_reflectance): with every retention 1 exactly the mean reflectance.
DVec3 kept_reflectance(const SolverState& s) {
  const DVec3 lost(double(s.lost_reflectance[0]), double(s.lost_reflectance[1]),
                   double(s.lost_reflectance[2]));
  return s.mean_reflectance - lost * std::ldexp(1.0, -64);
}

// Cluster c's term of SolverState::lost_reflectance at retention r: rho_c area_c (1 - r) in
// 2^-64 of the total area, per channel (a cluster lies in one Pure: one reflectance).
std::array<Fixed128, 3> lost_term(const SolverState& s, size_t c, double r) {
  std::array<Fixed128, 3> t{};
  if (!(s.total_area > 0.0) || r >= 1.0) return t;
  const Vec3 rho = s.material_of(s.clusters.polygons[s.clusters.first[c]]).reflectance;
  const double scale = std::ldexp(1.0, 64) / s.total_area * double(s.clusters.area[c]) * (1.0 - r);
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

// r_p of ClusterUnshot: polygon p's mean reflectance times its area.
double rho_area(const SolverState& s, uint32_t p) {
  return mean_component(s.material_of(p).reflectance) * double(s.hierarchy->triangles.area[p]);
}
}  // namespace

ClusterUnshot cluster_unshot(const SolverState& s, size_t c) {
  ClusterUnshot k;
  k.lo = std::numeric_limits<double>::infinity(), k.hi = -k.lo;
  for (uint32_t j = s.clusters.first[c]; j < s.clusters.first[c + 1]; ++j) {
    const uint32_t p = s.clusters.polygons[j];
    const UnshotEnergy& u = s.unshot_energy[p];
    const double r = rho_area(s, p);
    k.magnitude += u.magnitude;
    k.rest += u.magnitude - std::abs(u.sum);
    if (r > 0.0) {
      k.sum += u.sum, k.rho_area += r;
      k.lo = std::min(k.lo, -u.sum / r), k.hi = std::max(k.hi, -u.sum / r);
    } else {
      k.rest += std::abs(u.sum);
    }
  }
  return k;
}

double cluster_shooting_energy(const SolverState& s, size_t c, double a) {
  const ClusterUnshot& k = s.cluster_unshot[c];
  if (a >= k.hi) return k.rest + (k.sum + k.rho_area * a);
  if (a <= k.lo) return k.rest - (k.sum + k.rho_area * a);
  double e = 0.0;
  for (uint32_t j = s.clusters.first[c]; j < s.clusters.first[c + 1]; ++j) {
    const uint32_t p = s.clusters.polygons[j];
    // The share changes the sum; what cancels between the channels stays to shoot.
    const UnshotEnergy& u = s.unshot_energy[p];
    e += std::abs(u.sum + rho_area(s, p) * a) + u.magnitude - std::abs(u.sum);
  }
  return e;
}

void update_unshot_totals(SolverState& s) {
  const double scale = fixed_scale(s);
  const FixedSums t = sum_fixed(s.unshot_energy.size(), [&](size_t p) {
    const UnshotEnergy& u = s.unshot_energy[p];
    return FixedSums{to_fixed(u.magnitude, scale), to_fixed(u.sum, scale)};
  });
  s.unshot_abs_fixed = t[0], s.unshot_signed_fixed = t[1];
  s.cluster_unshot.resize(s.clusters.size());
  tbb::parallel_for(size_t(0), s.clusters.size(),
                    [&](size_t c) { s.cluster_unshot[c] = cluster_unshot(s, c); });
  s.mean_reflectance = mean_reflectance(s);
  s.lost_reflectance = {};
  for (size_t c = 0; c < s.cluster_retention.size() && c < s.clusters.size(); ++c) {
    const std::array<Fixed128, 3> term = lost_term(s, c, s.cluster_retention[c]);
    for (size_t ch = 0; ch < 3; ++ch) s.lost_reflectance[ch] += term[ch];
  }
  s.interreflection = mean_component(Vec3(interreflection(kept_reflectance(s))));
  share_unshot_totals(s);
}

void set_unshot_energies(SolverState& s, std::span<const uint32_t> polygons,
                         std::span<const UnshotEnergy> energies) {
  assert(polygons.size() == energies.size());
  const double scale = fixed_scale(s);
  const FixedSums d = sum_fixed(polygons.size(), [&](size_t i) {
    const UnshotEnergy &before = s.unshot_energy[polygons[i]], &after = energies[i];
    return FixedSums{to_fixed(after.magnitude, scale) - to_fixed(before.magnitude, scale),
                     to_fixed(after.sum, scale) - to_fixed(before.sum, scale)};
  });
  s.unshot_abs_fixed += d[0], s.unshot_signed_fixed += d[1];
  std::vector<uint32_t> clusters;
  for (size_t i = 0; i < polygons.size(); ++i) {
    s.unshot_energy[polygons[i]] = energies[i];
    const uint32_t c = s.clusters.cluster_of[polygons[i]];
    if (clusters.empty() || clusters.back() != c) clusters.push_back(c);  // most runs are long
  }
  std::sort(clusters.begin(), clusters.end());
  clusters.erase(std::unique(clusters.begin(), clusters.end()), clusters.end());
  tbb::parallel_for(size_t(0), clusters.size(), [&](size_t i) {
    s.cluster_unshot[clusters[i]] = cluster_unshot(s, clusters[i]);
  });
}

void share_unshot_totals(SolverState& s) {
  Fixed128 sums[2] = {s.unshot_abs_fixed, s.unshot_signed_fixed};
  sum_over_ranks(s.ranks, sums);
  const double scale = fixed_scale(s);
  s.unshot_abs_total = double(sums[0]) / scale;
  s.unshot_signed_total = double(sums[1]) / scale;
}

size_t SharedVertices::PlaceHash::operator()(const Place& k) const {
  return hash_position_bits(k.position, k.cluster);
}

bool SharedVertices::is_copy(uint32_t p, uint32_t v) const {
  const std::vector<VertexCopy>& cs = copies[p];
  auto it = std::lower_bound(cs.begin(), cs.end(), v,
                             [](const VertexCopy& c, uint32_t x) { return c.vertex < x; });
  return it != cs.end() && it->vertex == v;
}

bool shares_vertices(const Clusters& clusters, size_t p) {
  const uint32_t c = clusters.cluster_of[p];
  return clusters.planar[c] && clusters.polygon_count(c) > 1;
}

std::optional<SharedVertices::Place> shared_place(const Clusters& clusters, size_t p,
                                                  const Vec3& x) {
  if (!shares_vertices(clusters, p)) return std::nullopt;
  return SharedVertices::Place{clusters.cluster_of[p], position_bits(x)};
}

bool on_triangle_edge(const std::array<Vec3, 3>& c, const Vec3& x) {
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = c[size_t(k + 1) % 3] - c[size_t(k)];
    if (glm::length(glm::cross(e, x - c[size_t(k)])) <= 1e-5f * glm::dot(e, e)) return true;
  }
  return false;
}

void find_edge_midpoints(SolverState& s, std::span<const uint32_t> initial_vertices) {
  SharedVertices& sh = s.shared;
  sh.edge_midpoints.clear();
  const Triangles& tris = s.hierarchy->triangles;
  for (uint32_t p = 0; p < s.mesh.polygons.size(); ++p) {
    const PolygonMesh& m = s.mesh.polygons[p];
    for (uint32_t v = initial_vertices[p]; v < m.vertex_count(); ++v) {
      const Vec3& x = m.positions[v];
      const auto place = shared_place(s.clusters, p, x);
      if (!place || !on_triangle_edge(tris.corners[p], x) || sh.is_copy(p, v)) continue;
      sh.edge_midpoints.try_emplace(*place, SharedVertices::Gatherer{p, v});  // lowest first
    }
  }
}

SharedVertices find_shared_vertices(const Mesh& mesh, const Clusters& clusters) {
  SharedVertices sh;
  const size_t np = mesh.polygons.size();
  sh.copies.resize(np);
  struct Key {
    SharedVertices::Place place;
    uint32_t polygon, vertex;
  };
  std::vector<Key> keys;
  for (size_t p = 0; p < np; ++p) {
    for (uint32_t v = 0; v < mesh.polygons[p].vertex_count(); ++v) {
      if (const auto k = shared_place(clusters, p, mesh.polygons[p].positions[v]))
        keys.push_back({*k, uint32_t(p), v});
    }
  }
  auto tie = [](const Key& k) { return std::tie(k.place, k.polygon, k.vertex); };
  std::sort(keys.begin(), keys.end(), [&](const Key& a, const Key& b) { return tie(a) < tie(b); });
  for (size_t i = 1, first = 0; i < keys.size(); ++i) {
    if (!(keys[i].place == keys[first].place)) {
      first = i;
      continue;
    }
    sh.copies[keys[i].polygon].push_back({keys[i].vertex, keys[first].polygon, keys[first].vertex});
  }
  for (std::vector<VertexCopy>& c : sh.copies)
    std::sort(c.begin(), c.end(),
              [](const VertexCopy& a, const VertexCopy& b) { return a.vertex < b.vertex; });
  return sh;
}

float scene_size(const Hierarchy& h) {
  // Ritter's bounding sphere (Graphics Gems, 1990): distances only, so the same however the
  // scene is turned, and within a few percent of the smallest sphere (a box's diagonal exactly).
  const auto& corners = h.triangles.corners;
  if (corners.empty()) return 0.0f;
  auto farthest = [&](const DVec3& from) {
    DVec3 best = from;
    double d2 = -1.0;
    for (const auto& c : corners) {
      for (const Vec3& p : c) {
        const DVec3 q(p);
        if (glm::dot(q - from, q - from) > d2) d2 = glm::dot(q - from, q - from), best = q;
      }
    }
    return best;
  };
  const DVec3 y = farthest(DVec3(corners[0][0])), z = farthest(y);
  DVec3 centre = (y + z) * 0.5;
  double r = glm::length(z - y) * 0.5;
  for (const auto& c : corners) {
    for (const Vec3& p : c) {
      const double d = glm::length(DVec3(p) - centre);
      if (d > r) {  // grow the sphere just enough to take p
        const double grown = (r + d) * 0.5;
        centre += (DVec3(p) - centre) * ((grown - r) / d);
        r = grown;
      }
    }
  }
  return float(2.0 * r);
}

SolverState make_solver_state(const Hierarchy& h, const SolverOptions& options) {
  SolverState s;
  s.hierarchy = &h;
  s.options = options;
  s.mesh = make_mesh(h);
  // Default sizes: 1/256 and 1/16 of the scene's size (about 3.8 mm and 60 mm in the 0.55 m
  // Cornell box).
  const float size = scene_size(h);
  s.min_size = options.min_size > 0.0f ? options.min_size : size / 256.0f;
  s.max_size = options.max_size > 0.0f ? options.max_size : size / 16.0f;
  s.max_size = std::max(s.max_size, 2.0f * s.min_size);
  // The initial mesh: uniform splits down to max_size (vertices have no radiosity yet).
  tbb::parallel_for(size_t(0), s.mesh.polygons.size(), [&](size_t p) {
    PolygonMesh& m = s.mesh.polygons[p];
    std::vector<uint32_t> big;
    for (bool any = true; any;) {
      big.clear();
      for_each_leaf(m, [&](uint32_t e) {
        if (longest_edge(m, e) > s.max_size) big.push_back(e);
      });
      NewMidpoint created[3];
      for (uint32_t e : big) split_element(m, e, created);
      any = !big.empty();
    }
  });
  s.materials.reserve(h.objects.size());
  for (const SceneObject& o : h.objects) s.materials.push_back(o.material);
  s.unshot_energy.assign(h.triangles.size(), UnshotEnergy{});
  double total_area = 0.0;
  s.vertex_states.resize(h.triangles.size());
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    const Vec3 e = s.material_of(t).emission;
    s.vertex_states[t].assign(s.mesh.polygons[t].vertex_count(), VertexState{.unshot = e});
    s.unshot_energy[t] = polygon_unshot_energy(s, t);
    s.emitted_energy += s.unshot_energy[t].sum;
    total_area += h.triangles.area[t];
  }
  s.reference_energy = s.emitted_energy;
  s.total_area = total_area;
  s.radiosity_scale = total_area > 0.0 ? float(s.emitted_energy / total_area) : 1.0f;
  if (!(s.radiosity_scale > 0.0f)) s.radiosity_scale = 1.0f;
  s.shadow_offset = shadow_offset(h.bounds);
  assert(options.sample_grid >= 1 && options.max_sample_grid <= 64);
  const int max_m = std::max(options.sample_grid, options.max_sample_grid);
  // A cluster's n <= max_m^2 strata each stand for at most one initial element's square: its
  // area, not its width, bounds it, so a tessellated wall splits as its two triangles would
  // (a diagonal bound split the Cornell walls into quarters once tessellated: 31 clusters and
  // 50% more shots than the 21 of the untessellated box).
  const double side = double(max_m) * double(s.max_size);
  s.clusters = make_clusters(h, side * side);
  s.shared = find_shared_vertices(s.mesh, s.clusters);
  if (options.shadows && options.occlusion_culling)
    s.culling = make_occlusion_culling(h, s.shadow_offset);
  update_unshot_totals(s);
  s.barycentric_grids.resize(size_t(4 * max_m) + 1);
  for (int q = 1; q <= 4 * max_m; ++q)
    s.barycentric_grids[size_t(q)] = regular_sample_barycentrics(q);
  return s;
}

double ShotBalance::retention() const {
  if (!(shot > 0.0)) return 1.0;
  const double r = landed / shot;
  return std::isfinite(r) ? std::clamp(r, 0.0, 1.0) : 1.0;
}

void set_retention(SolverState& s, size_t c, double r) {
  assert(r >= 0.0 && r <= 1.0);
  if (s.cluster_retention.size() < s.clusters.size())
    s.cluster_retention.resize(s.clusters.size(), 1.0);
  const std::array<Fixed128, 3> was = lost_term(s, c, s.cluster_retention[c]),
                                now = lost_term(s, c, r);
  for (size_t ch = 0; ch < 3; ++ch) s.lost_reflectance[ch] += now[ch] - was[ch];
  s.cluster_retention[c] = r;
  s.interreflection = mean_component(Vec3(interreflection(kept_reflectance(s))));
}

void exact_energy_sums(const SolverState& s, std::span<const std::span<const double>> terms,
                       std::span<double> sums) {
  assert(terms.size() == sums.size());
  const double scale = fixed_scale(s);
  std::vector<Fixed128> fixed(terms.size(), 0);
  for (size_t k = 0; k < terms.size(); ++k) {
    const std::span<const double> t = terms[k];
    fixed[k] = sum_fixed(t.size(), [&](size_t i) {
      const Fixed128 x = to_fixed(t[i], scale);
      return FixedSums{x, x};
    })[0];
  }
  sum_over_ranks(s.ranks, fixed);
  for (size_t k = 0; k < terms.size(); ++k) sums[k] = double(fixed[k]) / scale;
}

float ambient_estimate(const SolverState& s) {
  if (s.total_area <= 0.0) return 0.0f;
  return float(s.unshot_signed_total / s.total_area * s.interreflection);
}

Vec3 ambient_radiosity(const SolverState& s) {
  const Hierarchy& h = *s.hierarchy;
  if (s.total_area <= 0.0) return Vec3(0.0f);
  DVec3 unshot(0.0);
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    const std::vector<VertexState>& vs = s.vertex_states[t];
    DVec3 u(0.0);
    for_each_leaf_vertex_sum(
        s.mesh.polygons[t], [&](uint32_t v) { return vs[v].unshot; },
        [&](float area, Vec3 sum) { u += DVec3(sum) * (double(area) / 3.0); });
    unshot += u;
  }
  return Vec3(unshot / s.total_area * interreflection(kept_reflectance(s)));
}

}  // namespace rad
