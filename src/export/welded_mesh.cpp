#include "export/welded_mesh.h"

#include <bit>
#include <cstring>
#include <unordered_map>

namespace rad {

namespace {

struct BitsHash {
  size_t operator()(const std::array<uint32_t, 3>& k) const {
    uint64_t h = 1469598103934665603ull;  // FNV-1a over the three words
    for (uint32_t w : k) h = (h ^ w) * 1099511628211ull;
    return size_t(h);
  }
};

}  // namespace

WeldedMesh weld_pure(const Hierarchy& h, int32_t object) {
  const SceneObject& o = h.objects[size_t(object)];
  WeldedMesh m;
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, BitsHash> index;
  index.reserve(size_t(o.triangle_count) * 2);
  m.indices.reserve(size_t(o.triangle_count) * 3);
  for (uint32_t t = o.first_triangle; t < o.first_triangle + o.triangle_count; ++t) {
    for (const Vec3& p : h.triangles.corners[t]) {
      // By bit pattern, with -0 as +0 so the two zeros weld.
      const std::array<uint32_t, 3> key = {std::bit_cast<uint32_t>(p.x + 0.0f),
                                           std::bit_cast<uint32_t>(p.y + 0.0f),
                                           std::bit_cast<uint32_t>(p.z + 0.0f)};
      const auto [it, added] = index.try_emplace(key, uint32_t(m.position.size()));
      if (added) m.position.push_back(p);
      m.indices.push_back(it->second);
    }
  }
  return m;
}

}  // namespace rad
