#include "solver/gather.h"

#include <span>

#include "solver/form_factor.h"

namespace rad {

Vec3 gather_from_source(const Vec3& x_vertex, const Vec3& n, const Vec3& centroid,
                        const ShotSource& src, const VisibilityBackend& vis,
                        const GatherSettings& st, GatherScratch& scratch) {
  const Vec3 x = x_vertex + (centroid - x_vertex) * st.inset;
  // One-sided source: a receiver behind its plane gets nothing.
  if (glm::dot(x - src.corner[0], src.normal) <= 0.0f) {
    ++scratch.stats.culled;
    return Vec3(0.0f);
  }
  float ff = 0.0f;
  if (st.method == FormFactorMethod::Analytic) {
    ff = point_to_triangle_form_factor(x, n, src.corner[0], src.corner[1], src.corner[2]);
    if (ff <= 0.0f) {
      ++scratch.stats.culled;
      return Vec3(0.0f);
    }
  }
  ++scratch.stats.vertex_evaluations;

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
  // Scale turning sum(k * dB * vis) into the gain.
  float scale;
  if (st.method == FormFactorMethod::Analytic) {
    if (weight_sum <= 0.0f) {
      // The visible part of the source holds no sample (e.g. a sliver above the tangent
      // plane): take it unoccluded with the source's mean unshot radiosity.
      return src.mean_unshot * ff;
    }
    scale = ff / weight_sum;
  } else {
    if (scratch.active.empty()) {
      ++scratch.stats.culled;
      return Vec3(0.0f);
    }
    scale = src.area_per_sample;
  }
  unoccluded *= scale;
  if (!st.shadows) return unoccluded;
  if (max_component(glm::abs(unoccluded)) < st.cut) {  // |.|: edits shoot negative energy
    scratch.stats.intensity_cuts += scratch.active.size();
    return unoccluded;
  }

  const size_t na = scratch.active.size();
  scratch.segments.resize(na);
  scratch.blocked.resize(na);
  for (size_t j = 0; j < na; ++j) {
    const uint32_t i = scratch.active[j];
    scratch.segments[j] =
        make_shadow_segment(x, n, src.sample[i], src.normal, st.shadow_offset);
  }
  vis.occluded(std::span<const Segment>(scratch.segments.data(), na),
               std::span<uint8_t>(scratch.blocked.data(), na), scratch.stats.rays);
  Vec3 visible(0.0f);
  for (size_t j = 0; j < na; ++j) {
    if (!scratch.blocked[j]) {
      const uint32_t i = scratch.active[j];
      visible += src.unshot[i] * scratch.weight[i];
    }
  }
  return visible * scale;
}

}  // namespace rad
