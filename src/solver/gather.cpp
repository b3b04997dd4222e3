#include "solver/gather.h"

#include <algorithm>
#include <numbers>
#include <span>

#include "solver/form_factor.h"

namespace rad {

namespace {

constexpr size_t W = SampleLanes::kLanes;

// Per-lane partial sums of the kernel weights k, of k times the visible unshot radiosity, and
// (coarse samples) of the plain integrand cos cos / (pi r^2) without EQ 7's A/n. Kept per lane
// across calls and added up once, in a fixed order (deterministic).
struct KernelSums {
  float w[W] = {}, r[W] = {}, g[W] = {}, b[W] = {}, p[W] = {};
  float weight() const {
    float t = 0.0f;
    for (size_t j = 0; j < W; ++j) t += w[j];
    return t;
  }
  Vec3 weighted() const {
    Vec3 t(0.0f);
    for (size_t j = 0; j < W; ++j) t += Vec3(r[j], g[j], b[j]);
    return t;
  }
  float plain() const {
    float t = 0.0f;
    for (size_t j = 0; j < W; ++j) t += p[j];
    return t;
  }
};

// sample_kernel over lanes [begin, end) of `s` (whole groups of W) added to `sums`, the
// unshot radiosity counted with factor `visible` (1 or 0). Coarse samples also write each
// weight to k[i] and sum the plain integrand. Branch-free with a fixed inner width: each group
// of W lanes is a few vector instructions.
template <bool Coarse>
void add_kernels(const SampleLanes& s, size_t begin, size_t end, const Vec3& x, const Vec3& n,
                 const Vec3& n_s, float area_per_sample, float visible, float* k,
                 KernelSums& sums) {
  constexpr float pi = std::numbers::pi_v<float>;
  // Raw pointers: a store through k could otherwise alias the vectors' own storage.
  const float* __restrict sx = s.x.data(), * __restrict sy = s.y.data(), * __restrict sz = s.z.data();
  const float* __restrict sr = s.r.data(), * __restrict sg = s.g.data(), * __restrict sb = s.b.data();
  const float* __restrict live = s.live.data();
  float* __restrict kout = k;
  const float xx = x.x, xy = x.y, xz = x.z, nx = n.x, ny = n.y, nz = n.z;
  const float mx = -n_s.x, my = -n_s.y, mz = -n_s.z;
  float* __restrict w = sums.w, * __restrict r = sums.r, * __restrict g = sums.g, * __restrict b = sums.b, * __restrict p = sums.p;
  for (size_t c = begin; c < end; c += W) {
#pragma omp simd
    for (size_t j = 0; j < W; ++j) {
      const size_t i = c + j;
      const float dx = sx[i] - xx, dy = sy[i] - xy, dz = sz[i] - xz;
      const float r2 = dx * dx + dy * dy + dz * dz;
      const float cr = nx * dx + ny * dy + nz * dz;
      const float cs = mx * dx + my * dy + mz * dz;
      // Selects, not branches: lanes that do not face get weight 0 and a harmless divisor (the
      // compiler will not if-convert a division that might trap).
      const bool faces = (cr > 0.0f) & (cs > 0.0f) & (r2 > 0.0f);
      const float mask = faces ? live[i] : 0.0f, d2 = faces ? r2 : 1.0f;
      const float kv = cr * cs / (d2 * (pi * d2 + area_per_sample)) * mask;
      if constexpr (Coarse) {
        p[j] += cr * cs / (pi * d2 * d2) * mask;
        kout[i] = kv;
      }
      const float kvis = kv * visible;
      w[j] += kv;
      r[j] += kvis * sr[i];
      g[j] += kvis * sg[i];
      b[j] += kvis * sb[i];
    }
  }
}

// Near field (analytic method): the source's unshot radiosity weighted over the fine samples,
// each taking the visibility of its coarse sample (scratch.coarse_visible). Returns false when
// no fine sample faces the receiver.
bool near_field_mean(const Vec3& x, const Vec3& n, const ShotSource& src, GatherScratch& scratch,
                     Vec3* mean) {
  KernelSums sums;
  for (size_t c = 0; c + 1 < src.fine_begin.size(); ++c) {
    add_kernels<false>(src.fine_sample, src.fine_begin[c], src.fine_begin[c + 1], x, n, src.normal,
                       src.fine_area_per_sample, scratch.coarse_visible[c] ? 1.0f : 0.0f, nullptr,
                       sums);
  }
  const float weight = sums.weight();
  if (weight <= 0.0f) return false;
  *mean = sums.weighted() / weight;
  return true;
}

}  // namespace

Vec3 gather_from_source(const Vec3& x_vertex, const Vec3& n, const Vec3& centroid,
                        const ShotSource& src, const VisibilityBackend& vis,
                        const GatherSettings& st, GatherScratch& scratch) {
  const Vec3 x = x_vertex + (centroid - x_vertex) * st.inset;
  // One-sided source: a receiver behind its plane gets nothing.
  const float height = glm::dot(x - src.corner[0], src.normal);
  if (height <= 0.0f) {
    ++scratch.stats.culled;
    return Vec3(0.0f);
  }
  // EQ 7 weights of the coarse samples; the active ones face the receiver and get a ray. The
  // active list is built without branches: which samples face the receiver changes from vertex
  // to vertex.
  const SampleLanes& sm = src.sample;
  const size_t ns = sm.size();
  scratch.weight.resize(ns);
  scratch.active.resize(ns);
  float* k = scratch.weight.data();
  KernelSums sums;
  add_kernels<true>(sm, 0, ns, x, n, src.normal, src.area_per_sample, 1.0f, k, sums);
  const float weight_sum = sums.weight();
  const Vec3 unoccluded = sums.weighted();
  size_t na = 0;
  for (size_t i = 0; i < ns; ++i) {
    scratch.active[na] = uint32_t(i);
    na += k[i] > 0.0f ? 1 : 0;
  }

  const bool analytic = st.method == FormFactorMethod::Analytic;
  float ff = 0.0f;
  if (analytic) {
    const Vec3 to_source = src.centroid - x;
    const float d2 = glm::dot(to_source, to_source);
    // Far, and the source wholly and clearly in front of the tangent plane (every point of it
    // lies within one longest edge of its centroid): no grazing integrand for the rule to miss.
    const bool far =
        d2 > src.far_distance * src.far_distance && glm::dot(n, to_source) > src.longest_edge;
    if (far) {
      KernelSums coarse;
      scratch.far_weight.resize(src.coarse_sample.size());
      add_kernels<true>(src.coarse_sample, 0, src.coarse_sample.size(), x, n, src.normal, 0.0f,
                        0.0f, scratch.far_weight.data(), coarse);
      ff = std::clamp(src.richardson_fine * sums.plain() - src.richardson_coarse * coarse.plain(),
                      0.0f, 1.0f);
    } else {
      const bool close = d2 < src.single_distance * src.single_distance;
      ff = point_to_triangle_form_factor(x, n, src.corner[0], src.corner[1], src.corner[2],
                                         close ? Arithmetic::Single : Arithmetic::Double);
    }
  }
  if (analytic ? ff <= 0.0f : na == 0) {
    ++scratch.stats.culled;
    return Vec3(0.0f);
  }
  ++scratch.stats.vertex_evaluations;

  // Gain = scale * sum(k * dB * visibility): the exact form factor over the weights' sum, or
  // EQ 7's A/n.
  const float scale = analytic ? (weight_sum > 0.0f ? ff / weight_sum : 0.0f) : src.area_per_sample;
  const bool near = analytic && !src.fine_sample.empty() && height < src.near_distance;

  // Visibility of the coarse samples: traced, or all visible without shadows or below the cut.
  const bool cut = max_component(glm::abs(unoccluded * scale)) < st.cut;  // |.|: negative edits
  if (st.shadows && cut) scratch.stats.intensity_cuts += na;
  const bool traced = st.shadows && !cut && na > 0;
  if (traced) {
    scratch.segments.resize(na);
    scratch.blocked.resize(na);
    for (size_t j = 0; j < na; ++j) {
      scratch.segments[j] =
          make_shadow_segment(x, n, sm.point(scratch.active[j]), src.normal, st.shadow_offset);
    }
    vis.occluded(std::span<const Segment>(scratch.segments.data(), na),
                 std::span<uint8_t>(scratch.blocked.data(), na), scratch.stats.rays);
  }

  Vec3 mean;
  if (near) {
    scratch.coarse_visible.assign(ns, 1);
    if (traced) {
      for (size_t j = 0; j < na; ++j)
        scratch.coarse_visible[scratch.active[j]] = !scratch.blocked[j];
    }
    if (near_field_mean(x, n, src, scratch, &mean)) return mean * ff;
  }
  if (analytic && weight_sum <= 0.0f) {
    // The visible part of the source holds no sample (a sliver above the tangent plane): take it
    // unoccluded with the source's mean unshot radiosity.
    return src.mean_unshot * ff;
  }
  if (!traced) return unoccluded * scale;
  // The visible samples summed afresh (not the blocked ones subtracted): a vertex in full
  // umbra gets exactly zero.
  Vec3 visible(0.0f);
  for (size_t j = 0; j < na; ++j) {
    if (!scratch.blocked[j]) visible += sm.value(scratch.active[j]) * k[scratch.active[j]];
  }
  return visible * scale;
}

}  // namespace rad
