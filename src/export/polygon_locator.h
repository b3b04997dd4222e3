// Which polygon of the scene a point seen by a camera ray lies on: the visibility backends
// trace merged surfaces and name no triangle, so the point found is placed back on the scene's
// own triangles.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "core/box_tree.h"
#include "hierarchy/hierarchy.h"

namespace rad {

/// A box tree over the hierarchy's triangles (which must outlive it), each box grown by the
/// tolerance of a hit point's position.
class PolygonLocator {
 public:
  explicit PolygonLocator(const Triangles& t, const Aabb& bounds);
  /// The triangle holding x whose front faces along `front` (a surface's front normal, any
  /// length): of those whose plane passes within the tolerance of x and that face the same
  /// way (within about 8 degrees), the one x lies nearest to (inside, or least outside; the lowest
  /// index among equals), or -1 when none is within the tolerance. `stack` is the caller's, reused.
  int32_t locate(const Vec3& x, const Vec3& front,
                 std::vector<std::pair<uint32_t, int>>& stack) const;

 private:
  const Triangles* triangles_;
  float tolerance_;
  BoxTree tree_;
};

}  // namespace rad
