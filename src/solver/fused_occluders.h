// The flat occluders of occlusion culling: a scene's shadow-casting flat regions, fused where
// coplanar and touching, each with what it covers of its plane on a grid of cells.
#pragma once

#include <cstdint>
#include <vector>

#include "core/aabb.h"
#include "hierarchy/hierarchy.h"

namespace rad {

/// Flat regions in one plane that touch and do not overlap, fused into one occluder (a wall's
/// pieces around a door, with the lintel), with what it covers of its plane on a grid of cells.
struct Occluder {
  DVec3 normal{0.0}, origin{0.0}, u{0.0}, w{0.0};  // the plane and its 2D frame
  glm::dvec2 lo{0.0}, hi{0.0};                     // its triangles' 2D box, cut into the cells
  uint32_t columns = 0, rows = 0;                  // at most 64 columns: a row is a word
  /// Per row, one bit per column: the cell lies wholly inside its triangles (full), or meets
  /// them (partly).
  std::vector<uint64_t> full, partly;
  Aabb box;
  /// 1: some of the scene lies behind it seen from the side its normal points to; 2: from the
  /// other side. A floor or an outer wall hides nothing from inside.
  uint8_t hides_behind = 0;
  /// Its regions' centres and areas: a source scores it by the solid angle they fill.
  std::vector<Vec3> part_centre;
  std::vector<float> part_area;
};

/// The occluders of `h`: its flat regions (visibility/occluders.h) whose Pure casts shadows,
/// fused (union-find, at most a few tens of triangles each) where they lie in one plane within
/// `margin` and the backends' ambiguity distance, touch within `margin`, and do not overlap.
std::vector<Occluder> fuse_occluders(const Hierarchy& h, double margin);

}  // namespace rad
