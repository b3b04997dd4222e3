#include "solver/gather.h"

#include <span>

#include "solver/form_factor.h"

namespace rad {

namespace {

// Near field (analytic method): the source's unshot radiosity weighted over the fine samples,
// each taking the visibility of its coarse sample (scratch.coarse_visible). Returns false when
// no fine sample faces the receiver.
bool near_field_mean(const Vec3& x, const Vec3& n, const ShotSource& src, GatherScratch& scratch,
                     Vec3* mean) {
  Vec3 visible(0.0f);
  float weight = 0.0f;
  for (size_t i = 0; i < src.fine_sample.size(); ++i) {
    const float k = sample_kernel(src.fine_sample[i] - x, n, src.normal, src.fine_area_per_sample);
    if (k <= 0.0f) continue;
    weight += k;
    if (scratch.coarse_visible[src.fine_parent[i]]) visible += src.fine_unshot[i] * k;
  }
  if (weight <= 0.0f) return false;
  *mean = visible / weight;
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
  const bool analytic = st.method == FormFactorMethod::Analytic;
  float ff = 0.0f;
  if (analytic) {
    ff = point_to_triangle_form_factor(x, n, src.corner[0], src.corner[1], src.corner[2]);
    if (ff <= 0.0f) {
      ++scratch.stats.culled;
      return Vec3(0.0f);
    }
  }
  ++scratch.stats.vertex_evaluations;

  // EQ 7 weights of the coarse samples; the active ones face the receiver and get a ray.
  const size_t ns = src.sample.size();
  scratch.weight.resize(ns);
  scratch.active.clear();
  float weight_sum = 0.0f;
  Vec3 unoccluded(0.0f);
  for (size_t i = 0; i < ns; ++i) {
    const float k = sample_kernel(src.sample[i] - x, n, src.normal, src.area_per_sample);
    scratch.weight[i] = k;
    if (k > 0.0f) {
      scratch.active.push_back(uint32_t(i));
      weight_sum += k;
      unoccluded += src.unshot[i] * k;
    }
  }
  if (!analytic && scratch.active.empty()) {
    ++scratch.stats.culled;
    return Vec3(0.0f);
  }
  // Gain = scale * sum(k * dB * visibility): the exact form factor over the weights' sum, or
  // EQ 7's A/n.
  const float scale = analytic ? (weight_sum > 0.0f ? ff / weight_sum : 0.0f) : src.area_per_sample;
  const bool near = analytic && !src.fine_sample.empty() && height < src.near_distance;

  // Visibility of the coarse samples: traced, or all visible without shadows or below the cut.
  const size_t na = scratch.active.size();
  scratch.coarse_visible.assign(ns, 1);
  const bool cut = max_component(glm::abs(unoccluded * scale)) < st.cut;  // |.|: negative edits
  if (st.shadows && cut) scratch.stats.intensity_cuts += na;
  if (st.shadows && !cut && na > 0) {
    scratch.segments.resize(na);
    scratch.blocked.resize(na);
    for (size_t j = 0; j < na; ++j) {
      const uint32_t i = scratch.active[j];
      scratch.segments[j] = make_shadow_segment(x, n, src.sample[i], src.normal, st.shadow_offset);
    }
    vis.occluded(std::span<const Segment>(scratch.segments.data(), na),
                 std::span<uint8_t>(scratch.blocked.data(), na), scratch.stats.rays);
    for (size_t j = 0; j < na; ++j) scratch.coarse_visible[scratch.active[j]] = !scratch.blocked[j];
  }

  Vec3 mean;
  if (near && near_field_mean(x, n, src, scratch, &mean)) return mean * ff;
  if (analytic && weight_sum <= 0.0f) {
    // The visible part of the source holds no sample (a sliver above the tangent plane): take it
    // unoccluded with the source's mean unshot radiosity.
    return src.mean_unshot * ff;
  }
  Vec3 visible(0.0f);
  for (const uint32_t i : scratch.active) {
    if (scratch.coarse_visible[i]) visible += src.unshot[i] * scratch.weight[i];
  }
  return visible * scale;
}

}  // namespace rad
