#include "solver/direct_light.h"

#include <cassert>
#include <cmath>

#include "solver/light_source.h"
#include "solver/occlusion_culling.h"
#include "solver/shoot.h"
#include "visibility/segment.h"

namespace rad {

DirectLight make_direct_light(const SolverState& s, uint32_t variants) {
  assert(variants >= 1);
  DirectLight d;
  d.variants = variants;
  const Clusters& clusters = s.scene.clusters;
  for (size_t c = 0; c < clusters.size(); ++c) {
    bool emits = false;
    for (uint32_t j = clusters.first[c]; j < clusters.first[c + 1] && !emits; ++j) {
      emits = s.solution.material_of(clusters.polygons[j]).emission != Vec3(0.0f);
    }
    if (emits) d.sources.push_back(make_emission_source(s, int32_t(c)));
  }
  const Hierarchy& h = *s.solution.hierarchy;
  for (size_t i = 0; i < h.lights.size(); ++i) {
    // As edited (set_light): what it shoots is in units of its shots' intensity (light_unit).
    const LightSetting edited = i < s.solution.lights.size()
                                    ? s.solution.lights[i]
                                    : LightSetting{h.lights[i].colour, h.lights[i].intensity};
    const Vec3 colour = edited.colour * (edited.intensity / light_unit(h.lights[i]));
    d.sources.push_back(make_light_source(s.scene.shooting_lights, int32_t(i), colour, h.bounds));
  }
  if (!s.scene.culling.empty()) {
    // Each source's unhidden triangles once, kept as runs of consecutive indices (a room's
    // triangles are consecutive in the depth-first order), then counted and placed.
    const size_t n = h.triangles.size();
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> runs(d.sources.size());
    std::vector<uint32_t> seen;
    for (size_t i = 0; i < d.sources.size(); ++i) {
      const ShotSource& src = d.sources[i];
      // The sun lies beyond the planes of all occluders, in no box: it is not culled.
      if (src.light >= 0 && src.emitter->kind == LightKind::Directional) {
        runs[i].push_back({0, uint32_t(n)});
        continue;
      }
      unhidden_triangles(s.scene.culling, src, seen);
      for (size_t j = 0; j < seen.size();) {
        size_t k = j + 1;
        while (k < seen.size() && seen[k] == seen[k - 1] + 1) ++k;
        runs[i].push_back({seen[j], seen[k - 1] + 1});
        j = k;
      }
    }
    d.lit_first.assign(n + 1, 0);
    for (const auto& r : runs) {
      for (const auto& [first, last] : r) {
        for (uint32_t p = first; p < last; ++p) ++d.lit_first[p + 1];
      }
    }
    for (size_t p = 0; p < n; ++p) d.lit_first[p + 1] += d.lit_first[p];
    d.lit_by.resize(d.lit_first[n]);
    std::vector<uint32_t> next(d.lit_first.begin(), d.lit_first.end() - 1);
    for (size_t i = 0; i < runs.size(); ++i) {
      for (const auto& [first, last] : runs[i]) {
        for (uint32_t p = first; p < last; ++p) d.lit_by[next[p]++] = uint32_t(i);
      }
    }
  }
  d.ends.resize(d.sources.size() * variants);
  for (size_t i = 0; i < d.sources.size(); ++i) {
    for (uint32_t k = 0; k < variants; ++k) {
      std::vector<float>& e = d.ends[i * variants + k];
      if (d.sources[i].light >= 0) continue;  // a light's rays end at the light
      if (k == 0) {
        const ShotSource& src = d.sources[i];
        e = src.end_x;
        e.insert(e.end(), src.end_y.begin(), src.end_y.end());
        e.insert(e.end(), src.end_z.begin(), src.end_z.end());
      } else {
        draw_ray_ends(d.sources[i], k, s.scene.shadow_offset, nullptr, e);
      }
    }
  }
  return d;
}

Vec3 direct_gain(const SolverState& s, const DirectLight& d, size_t p, const Vec3& x, const Vec3& n,
                 uint32_t set, const VisibilityBackend& vis, const GatherSettings& settings,
                 DirectLightScratch& scratch) {
  if (scratch.sources.size() != d.sources.size()) {
    scratch.sources = d.sources;
    scratch.set.assign(d.sources.size(), 0);
  }
  const uint32_t k = set % d.variants;
  const Vec3 centroid = s.solution.hierarchy->triangles.centroid(p);
  Vec3 sum(0.0f);
  const bool listed = !d.lit_first.empty();
  const size_t first = listed ? d.lit_first[p] : 0;
  const size_t last = listed ? d.lit_first[p + 1] : d.sources.size();
  for (size_t j = first; j < last; ++j) {
    const size_t i = listed ? d.lit_by[j] : j;
    ShotSource& src = scratch.sources[i];
    if (!may_receive(*s.solution.hierarchy, s.scene.clusters, p, src)) continue;
    if (src.light < 0 && scratch.set[i] != k) {
      const std::vector<float>& e = d.ends[i * d.variants + k];
      const size_t m = src.end_x.size();
      std::copy(e.begin(), e.begin() + long(m), src.end_x.begin());
      std::copy(e.begin() + long(m), e.begin() + long(2 * m), src.end_y.begin());
      std::copy(e.begin() + long(2 * m), e.end(), src.end_z.begin());
      scratch.set[i] = k;
    }
    sum += gather_from_source(x, n, centroid, src, vis, settings, scratch.gather);
  }
  return sum;
}

}  // namespace rad
