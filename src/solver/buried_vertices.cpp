#include "solver/buried_vertices.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/denormals.h"

namespace rad {

namespace {
Vec3 probe_start(const Triangles& t, size_t p, const Vec3& x) {
  return x + (t.centroid(p) - x) * kGatherInset;
}
}  // namespace

Vec3 find_gather_point(const Triangles& t, size_t p, const Vec3& x, const VisibilityBackend& vis,
                       const BuriedProbe& probe_settings, VisibilityStats& stats) {
  const float offset = probe_settings.offset;
  const Vec3 n = t.normal[p];
  const Vec3 b = off_surface(t.centroid(p), n, offset);
  Vec3 a = off_surface(probe_start(t, p, x), n, offset);
  // Far enough along the normal to leave any solid: the scene's size (a solid's faces lie in
  // its box, and the probe starts within it).
  const float reach = 2e5f * offset;
  bool moved = false;
  for (int k = 0; k < kMaxSolids; ++k) {
    const Segment probe{a, b - a};
    uint8_t blocked = 0;
    vis.occluded(std::span<const Segment>(&probe, 1), std::span<uint8_t>(&blocked, 1), stats);
    if (!blocked) break;
    const SegmentHit hit = vis.first_hit(probe, stats);
    if (!hit.hit) break;  // the two queries disagree only in rounding at t = 0 or 1
    // Met from the front: a wall between the vertex and the centroid, the vertex outside it.
    if (!(glm::dot(hit.normal, probe.direction) > 0.0f)) break;
    // Met from behind, it may still be a face grazed at its edge (the way passes a box's
    // corner): inside, the way straight out along the normal meets a face from behind too, or
    // the way back does. Either may leave the solid where another's face lies coplanar with its
    // own, back to back (a shelf board's end butting against the side panel's face: the board's
    // end and the panel's face are one plane), and the first of two faces at one distance may be
    // the other's, met from the front; the other way then tells.
    const float len = glm::length(probe.direction);
    const Segment up{a, n * reach};
    const SegmentHit above = vis.first_hit(up, stats);
    bool inside = above.hit && glm::dot(above.normal, n) > 0.0f;
    if (!inside) {
      const Segment back{a, probe.direction * (-reach / len)};
      const SegmentHit behind = vis.first_hit(back, stats);
      inside = behind.hit && glm::dot(behind.normal, back.direction) > 0.0f;
    }
    if (!inside) break;
    // From behind: the vertex is inside; it moves just past that face, then looks again.
    const float past = std::min(1.0f, hit.t + 4.0f * offset / len);
    a = a + probe.direction * past;
    moved = true;
    if (past >= 1.0f) break;
  }
  const Vec3 at = a - n * offset;
  return moved && glm::length(at - x) <= probe_settings.depth ? at : x;
}

bool is_covered(const Triangles& t, size_t p, const Vec3& x, const VisibilityBackend& vis,
                const BuriedProbe& probe, VisibilityStats& stats) {
  const Vec3 n = t.normal[p];
  const Segment up{off_surface(probe_start(t, p, x), n, probe.offset), n * probe.depth};
  uint8_t blocked = 0;
  vis.occluded(std::span<const Segment>(&up, 1), std::span<uint8_t>(&blocked, 1), stats);
  return blocked != 0;
}

void find_buried_vertices(const Triangles& t, size_t p, const PolygonMesh& mesh, uint32_t first,
                          const VisibilityBackend& vis, const BuriedProbe& probe,
                          std::vector<MovedVertex>& moved, std::vector<uint32_t>& covered,
                          VisibilityStats& stats) {
  for (uint32_t v = first; v < uint32_t(mesh.vertex_count()); ++v) {
    const Vec3 x = mesh.positions[v];
    const Vec3 at = find_gather_point(t, p, x, vis, probe, stats);
    if (at != x) moved.push_back({v, at});
    if (is_covered(t, p, x, vis, probe, stats)) covered.push_back(v);
  }
}

BuriedVertices find_all_buried_vertices(const Triangles& t, const Mesh& mesh,
                                        const VisibilityBackend& vis, const BuriedProbe& probe,
                                        VisibilityStats& stats) {
  BuriedVertices b;
  b.moved.resize(mesh.polygons.size());
  b.covered.resize(mesh.polygons.size());
  tbb::enumerable_thread_specific<VisibilityStats> local;
  tbb::parallel_for(
      tbb::blocked_range<size_t>(0, mesh.polygons.size(), 64), [&](const auto& range) {
        const ScopedFlushDenormals ftz;
        VisibilityStats& st = local.local();
        for (size_t p = range.begin(); p != range.end(); ++p)
          find_buried_vertices(t, p, mesh.polygons[p], 0, vis, probe, b.moved[p], b.covered[p], st);
      });
  for (const VisibilityStats& st : local) stats += st;
  b.found = true;
  return b;
}

}  // namespace rad
