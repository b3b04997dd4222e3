// What shadow rays are traced against: the hierarchy's triangles, with every flat region that
// a tessellation cut into many triangles put back together from its outline.
#pragma once

#include <array>
#include <optional>
#include <vector>

#include "hierarchy/hierarchy.h"

namespace rad {

/// The hierarchy with each flat region of a Pure (edge-connected triangles within 0.1 degree
/// whose corners all lie in one plane, to the scenes' ambiguity distance) bounded by one simple
/// loop re-triangulated from that loop by ear clipping, when that takes fewer triangles and
/// covers the same area; other triangles are kept as they are. The same surfaces, so the same
/// answer to every segment (up to the rounding along the seams it removes), in a structure that
/// does not grow with the tessellation. Nullopt when no region gets fewer triangles.
std::optional<Hierarchy> merge_flat_regions(const Hierarchy& h);

/// A flat region of a Pure as triangles that cover exactly its surface and do not overlap (its
/// loop's ear clipping, or its own one or two triangles).
struct FlatRegion {
  std::vector<std::array<Vec3, 3>> triangles;
  Vec3 normal{0.0f};  // unit, the area-weighted mean of its triangles'
  Vec3 point{0.0f};   // a corner: the plane is dot(normal, x - point) = 0
  float area = 0.0f;
  int32_t object = -1;  // its Pure
};

/// Every flat region of the hierarchy whose corners lie in one plane (to the scenes' ambiguity
/// distance) and which is one or two triangles or bounded by one simple loop; the others
/// (regions with holes, bent ones) are left out.
std::vector<FlatRegion> flat_regions(const Hierarchy& h);

}  // namespace rad
