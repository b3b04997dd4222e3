// What shadow rays are traced against: the hierarchy's triangles, with every flat region that
// a tessellation cut into many triangles put back together from its outline.
#pragma once

#include <optional>

#include "hierarchy/hierarchy.h"

namespace rad {

/// The hierarchy with each flat region of a Pure (edge-connected triangles within 0.1 degree
/// whose corners all lie in one plane, to the scenes' ambiguity distance) bounded by one simple
/// loop re-triangulated from that loop by ear clipping, when that takes fewer triangles and
/// covers the same area; other triangles are kept as they are. The same surfaces, so the same
/// answer to every segment (up to the rounding along the seams it removes), in a structure that
/// does not grow with the tessellation. Nullopt when no region gets fewer triangles.
std::optional<Hierarchy> merge_flat_regions(const Hierarchy& h);

}  // namespace rad
