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

bool may_receive(const SolverState& s, size_t p, const ShotSource& src) {
  if (src.planar && s.clusters.cluster_of[p] == uint32_t(src.cluster)) return false;
  const Triangles& t = s.hierarchy->triangles;
  const auto& c = t.corners[p];
  bool any_in_front = false;
  for (const Vec3& q : c) any_in_front |= receiver_side(src, q) >= 0;
  if (!any_in_front) return false;
  // The source's box against p's plane: its farthest corner in front.
  const Vec3 n = t.normal[p];
  const Vec3 half = src.box.extent() * 0.5f;
  return glm::dot(src.box.center() - c[0], n) + glm::dot(half, glm::abs(n)) > 0.0f;
}

void shoot_to_receivers(SolverState& s, const ShotSource& src, const VisibilityBackend& vis,
                        bool major, std::vector<uint8_t>& received) {
  const Triangles& tris = s.hierarchy->triangles;
  const GatherSettings settings = gather_settings(s);
  received.assign(tris.size(), 0);
  tbb::enumerable_thread_specific<GatherScratch> scratch;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tris.size(), 8), [&](const auto& range) {
    const ScopedFlushDenormals ftz;  // once per range, not per ray batch (see denormals.h)
    for (size_t p = range.begin(); p != range.end(); ++p) {
      if (!may_receive(s, p, src)) continue;
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
