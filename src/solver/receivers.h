// The polygons a shot reached, as the shot hands them to refinement and the bookkeeping.
#pragma once

#include <cstdint>
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
  /// Per polygon (sized with `marked`), after a major shot: its leaves whose middle gained from
  /// the shot more than the subdivision limit beyond their corners' mean (shoot.cpp), sorted;
  /// empty for the polygons not in `polygons`.
  std::vector<std::vector<uint32_t>> bright_middles;
  std::vector<LeafRef> middle_work;    // the leaves looked at (shoot.cpp)
  std::vector<uint8_t> middle_bright;  // per leaf looked at: whether its middle is bright
};

}  // namespace rad
