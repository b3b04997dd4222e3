#include "mesh/subdivide.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace rad {

int split_element(PolygonMesh& p, uint32_t e, NewMidpoint created[3]) {
  assert(p.elements[e].leaf());
  const uint32_t v0 = p.elements[e].v[0], v1 = p.elements[e].v[1], v2 = p.elements[e].v[2];
  int n = 0;
  auto mid = [&](uint32_t a, uint32_t b) {
    auto [slot, inserted] = p.midpoints.try_emplace(edge_key(a, b));
    if (inserted) {
      *slot = p.add_vertex((p.positions[a] + p.positions[b]) * 0.5f);
      created[n++] = {*slot, a, b};
    }
    return *slot;
  };
  const uint32_t m01 = mid(v0, v1), m12 = mid(v1, v2), m20 = mid(v2, v0);
  const float child_area = p.elements[e].area * 0.25f;
  const int32_t first = int32_t(p.elements.size());
  p.elements.push_back({{v0, m01, m20}, -1, child_area});
  p.elements.push_back({{m01, v1, m12}, -1, child_area});
  p.elements.push_back({{m20, m12, v2}, -1, child_area});
  p.elements.push_back({{m12, m20, m01}, -1, child_area});
  p.elements[e].first_child = first;
  return n;
}

float longest_edge(const PolygonMesh& p, uint32_t e) {
  const Element& el = p.elements[e];
  const Vec3 &a = p.positions[el.v[0]], &b = p.positions[el.v[1]], &c = p.positions[el.v[2]];
  return glm::sqrt(
      glm::max(glm::dot(b - a, b - a), glm::max(glm::dot(c - b, c - b), glm::dot(a - c, a - c))));
}

float element_size(const PolygonMesh& p, uint32_t e) {
  return std::sqrt(2.0f * p.elements[e].area);
}

float split_size(const PolygonMesh& p, uint32_t e, const std::array<bool, 3>& along) {
  const Element& el = p.elements[e];
  float longest = 0.0f;
  for (size_t k = 0; k < 3; ++k) {
    if (along[k])
      longest =
          std::max(longest, glm::length(p.positions[el.v[(k + 1) % 3]] - p.positions[el.v[k]]));
  }
  return std::max(element_size(p, e), longest * (std::numbers::sqrt2_v<float> * 0.5f));
}

}  // namespace rad
