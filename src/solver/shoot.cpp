#include "solver/shoot.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/denormals.h"

namespace rad {

GatherSettings gather_settings(const SolverState& s) {
  GatherSettings g;
  g.method = s.options.method;
  g.shadows = s.options.shadows;
  g.cut = s.options.intensity_cut * s.radiosity_scale;
  g.shadow_offset = s.shadow_offset;
  return g;
}

Vec3 polygon_centroid(const Triangles& t, size_t p) {
  const auto& c = t.corners[p];
  return (c[0] + c[1] + c[2]) * (1.0f / 3.0f);
}

namespace {

// True when no point of polygon p can see the front of the source, or the source lies
// entirely behind p's plane.
bool cannot_receive(const Triangles& t, size_t p, const ShotSource& src) {
  const auto& c = t.corners[p];
  bool any_in_front = false;
  for (const Vec3& q : c) any_in_front |= glm::dot(q - src.corner[0], src.normal) > 0.0f;
  if (!any_in_front) return true;
  const Vec3 n = t.normal[p];
  bool source_in_front = false;
  for (const Vec3& q : src.corner) source_in_front |= glm::dot(q - c[0], n) > 0.0f;
  return !source_in_front;
}

}  // namespace

void shoot_to_receivers(SolverState& s, const ShotSource& src, const VisibilityBackend& vis,
                        bool major, std::vector<uint8_t>& received) {
  const Triangles& tris = s.hierarchy->triangles;
  const GatherSettings settings = gather_settings(s);
  received.assign(tris.size(), 0);
  tbb::enumerable_thread_specific<GatherScratch> scratch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tris.size(), 8), [&](const auto& range) {
    const ScopedFlushDenormals ftz;  // once per range, not per ray batch (see denormals.h)
    for (size_t p = range.begin(); p != range.end(); ++p) {
      if (int32_t(p) == src.polygon || cannot_receive(tris, p, src)) continue;
      received[p] = 1;
      PolygonMesh& mesh = s.mesh.polygons[p];
      const Vec3 n = tris.normal[p], centroid = polygon_centroid(tris, p);
      const Vec3 rho = s.material_of(p).reflectance;
      auto body = [&](size_t v0, size_t v1) {
        GatherScratch& sc = scratch.local();
        for (size_t v = v0; v < v1; ++v) {
          MeshVertex& x = mesh.vertices[v];
          const Vec3 dh = gather_from_source(x.position, n, centroid, src, vis, settings, sc);
          x.irradiance += dh;
          x.unshot += rho * dh;
          x.shot = dh;
          if (major) x.major += dh;
        }
      };
      const size_t nv = mesh.vertex_count();
      if (nv < 256) {
        body(0, nv);
      } else {  // a finely subdivided polygon: split its vertices across threads too
        tbb::parallel_for(tbb::blocked_range<size_t>(0, nv, 64), [&](const auto& r) {
          const ScopedFlushDenormals inner;  // another thread may run this range
          body(r.begin(), r.end());
        });
      }
    }
  });
  for (const GatherScratch& sc : scratch) s.stats += sc.stats;
}

}  // namespace rad
