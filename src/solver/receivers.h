// The polygons a shot reached, as the shot hands them to refinement and the bookkeeping.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace rad {

/// Vertices [begin, end) of one polygon: a work item of a shot's gathering loop.
struct VertexRange {
  uint32_t polygon = 0, begin = 0, end = 0;
  uint32_t receiver = 0;  // the polygon's index in Receivers::polygons
};

/// Leaf `element` of `polygon`: a work item of the look at leaves' middles after a major shot.
struct LeafRef {
  uint32_t polygon = 0, element = 0;
  auto operator<=>(const LeafRef&) const = default;  // by polygon, then element
};

/// The polygons that may have gained from the last shot (shoot_to_receivers, shoot.h): a mask
/// per polygon and their list in index order. The others' VertexState::last_gain is stale. Kept
/// from shot to shot with the loop's work lists, so a small shot costs what it reaches, not
/// the scene.
struct Receivers {
  std::vector<uint8_t> marked;           // per polygon: 1 when listed in `polygons`
  std::vector<uint32_t> polygons;        // in index order
  std::vector<VertexRange> gather_work;  // their vertices in work items (shoot.cpp)
  std::vector<uint32_t> unhidden;        // the triangles culling left to the shot (shoot.cpp)
  /// After a major shot: the leaves of `polygons` whose middle gained from the shot more than
  /// the subdivision limit beyond their corners' mean (shoot.cpp), by polygon, then element.
  std::vector<LeafRef> bright_middles;
  std::vector<LeafRef> middle_work;    // the leaves looked at (shoot.cpp)
  std::vector<uint8_t> middle_bright;  // per leaf looked at: whether its middle is bright

  /// The bright middles of polygon p (sorted by element).
  std::span<const LeafRef> bright_middles_of(uint32_t p) const {
    const auto [first, last] =
        std::equal_range(bright_middles.begin(), bright_middles.end(), LeafRef{p, 0},
                         [](const LeafRef& a, const LeafRef& b) { return a.polygon < b.polygon; });
    return {first, last};
  }
};

}  // namespace rad
