#include "export/welded_mesh.h"

#include <unordered_map>

#include "core/position_bits.h"

namespace rad {

WeldedMesh weld_pure(const Hierarchy& h, int32_t object) {
  const SceneObject& o = h.objects[size_t(object)];
  WeldedMesh m;
  std::unordered_map<PositionBits, uint32_t, PositionBitsHash> index;
  index.reserve(size_t(o.triangle_count) * 2);
  m.indices.reserve(size_t(o.triangle_count) * 3);
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
    for (const Vec3& p : h.triangles.corners[t]) {
      const auto [it, added] = index.try_emplace(position_bits(p), uint32_t(m.position.size()));
      if (added) m.position.push_back(p);
      m.indices.push_back(it->second);
    }
  }
  return m;
}

}  // namespace rad
