#include "mesh/sample_points.h"

namespace rad {

std::vector<Vec3> regular_sample_barycentrics(int m) {
  std::vector<Vec3> out;
  out.reserve(size_t(m) * m);
  const float inv = 1.0f / float(m);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; i + j < m; ++j) {
      // Upward sub-triangle (i, j), (i+1, j), (i, j+1) in grid steps along b and c.
      float b = (float(i) + 1.0f / 3.0f) * inv, c = (float(j) + 1.0f / 3.0f) * inv;
      out.emplace_back(1.0f - b - c, b, c);
      if (i + j + 1 < m) {  // downward neighbour (i+1, j), (i, j+1), (i+1, j+1)
        b = (float(i) + 2.0f / 3.0f) * inv;
        c = (float(j) + 2.0f / 3.0f) * inv;
        out.emplace_back(1.0f - b - c, b, c);
      }
    }
  }
  return out;
}

uint32_t locate_leaf(const PolygonMesh& p, Vec3 w, Vec3* leaf_bary) {
  uint32_t e = 0;
  while (!p.elements[e].leaf()) {
    // Children of split_element: corner a (w.x > 1/2), corner b, corner c, else the middle one
    // whose corners are the midpoints (bc, ca, ab).
    const uint32_t first = uint32_t(p.elements[e].first_child);
    if (w.x >= 0.5f) {
      e = first;
      w = Vec3(2.0f * w.x - 1.0f, 2.0f * w.y, 2.0f * w.z);
    } else if (w.y >= 0.5f) {
      e = first + 1;
      w = Vec3(2.0f * w.x, 2.0f * w.y - 1.0f, 2.0f * w.z);
    } else if (w.z >= 0.5f) {
      e = first + 2;
      w = Vec3(2.0f * w.x, 2.0f * w.y, 2.0f * w.z - 1.0f);
    } else {
      e = first + 3;
      w = Vec3(1.0f - 2.0f * w.x, 1.0f - 2.0f * w.y, 1.0f - 2.0f * w.z);
    }
  }
  if (leaf_bary) *leaf_bary = w;
  return e;
}

}  // namespace rad
