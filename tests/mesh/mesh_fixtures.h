// Small polygon meshes for mesh tests.
#pragma once

#include <random>

#include "mesh/patch_mesh.h"
#include "mesh/subdivide.h"

namespace rad::testing {

/// One unsplit polygon with corners a, b, c.
inline PolygonMesh one_polygon(Vec3 a = {0, 0, 0}, Vec3 b = {1, 0, 0}, Vec3 c = {0, 1, 0}) {
  PolygonMesh p;
  p.add_vertex(a);
  p.add_vertex(b);
  p.add_vertex(c);
  p.elements.push_back({{0, 1, 2}, -1, 0.5f * glm::length(glm::cross(b - a, c - a))});
  return p;
}

/// Splits random leaves `splits` times (deterministic for a seed).
inline void split_randomly(PolygonMesh& p, int splits, unsigned seed) {
  std::mt19937 rng(seed);
  for (int i = 0; i < splits; ++i) {
    std::vector<uint32_t> leaves;
    for_each_leaf(p, [&](uint32_t e) { leaves.push_back(e); });
    NewMidpoint created[3];
    split_element(p, leaves[rng() % leaves.size()], created);
  }
}

}  // namespace rad::testing
