// One Pure's triangles as an indexed mesh: what the scene writers of rad convert store.
#pragma once

#include <cstdint>
#include <vector>

#include "hierarchy/hierarchy.h"

namespace rad {

struct WeldedMesh {
  std::vector<Vec3> position;     // each distinct corner once, in first-use order
  std::vector<uint32_t> indices;  // 3 per triangle, in the hierarchy's order and winding
};

/// The triangles of Pure `object` of `h` with corners that are equal to the last bit merged:
/// a tessellated surface stores each point once instead of once per triangle around it.
WeldedMesh weld_pure(const Hierarchy& h, int32_t object);

}  // namespace rad
