// Receivers hidden from a shot's source behind a flat occluder, found before any shadow ray: a
// light in one room of a building then costs that room and what its doors show, not every
// vertex in front of it (whose rays the walls would all block).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/aabb.h"
#include "core/box_tree.h"
#include "hierarchy/hierarchy.h"
#include "solver/fused_occluders.h"

namespace rad {

struct ShotSource;

/// What culling needs of a scene, made once: its shadow-casting flat occluders and the tree over
/// its triangles.
struct OcclusionCulling {
  std::vector<Occluder> occluders;
  /// occluders[k].box, side by side: every shot looks at them all (the roulette's reach).
  std::vector<Aabb> occluder_boxes;
  /// The tree over the triangles (receivers), and per node 0 where one of its triangles takes
  /// every visibility term as 1 (it receives no shadows): hiding it would change its gain.
  BoxTree tree;
  std::vector<uint8_t> cullable;
  /// How far every point a shadow ray may start or end lies from its polygon (the shadow offset
  /// and the inset, with room for rounding): boxes grow by it and crossings keep clear of edges.
  double margin = 0.0;
  /// What rounding may move a point by anywhere in the scene (part of the margin).
  double rounding = 0.0;
  bool empty() const { return occluders.empty(); }
};

/// The culling data of `h`: its fused occluders (fused_occluders.h) and the tree over its
/// triangles.
OcclusionCulling make_occlusion_culling(const Hierarchy& h, float shadow_offset);

/// The triangles some of whose segments to `src` may be unblocked, in index order, into `out`:
/// every triangle but those in a subtree of c.tree whose box is hidden. A box is hidden when
/// every segment from the box of the source's ray ends to it crosses one occluder (Teller and
/// Hanrahan, "Global visibility algorithms for illumination computations", SIGGRAPH 1993, find
/// what a source sees through the cells and portals of a building; this is the cheaper
/// conservative half: the crossings of the segments between the two boxes' corners bound the
/// crossings of all segments between them, so one coverage test decides). The occluders are
/// the 32 nearest the source by solid angle that no other one already hides. Culling removes gains
/// that shadow rays to every sample would have made zero (a gain taken with fewer rays, under the
/// intensity cut or from a sliver of the source no sample lies on, may have come through).
void unhidden_triangles(const OcclusionCulling& c, const ShotSource& src,
                        std::vector<uint32_t>& out);

}  // namespace rad
