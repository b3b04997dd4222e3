// Receivers hidden from a shot's source behind a flat occluder, found before any shadow ray: a
// light in one room of a building then costs that room and what its doors show, not every
// vertex in front of it (whose rays the walls would all block).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/aabb.h"
#include "hierarchy/hierarchy.h"
#include "visibility/occluders.h"

namespace rad {

struct ShotSource;

/// A bounding-volume tree over the triangles (median splits of their centroids along the
/// longest axis). Node i's triangles are order[first[i] .. first[i] + count[i]); an inner node's
/// children are i + 1 and right[i].
struct ReceiverTree {
  std::vector<Aabb> box;
  std::vector<uint32_t> first, count, right;
  /// 0 where a triangle of the node takes every visibility term as 1 (it receives no shadows):
  /// hiding it would change its gain.
  std::vector<uint8_t> cullable;
  std::vector<uint32_t> order;
  bool leaf(size_t i) const { return right[i] == 0; }
};

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

/// What culling needs of a scene, made once: its shadow-casting flat occluders and the tree over
/// its triangles.
struct OcclusionCulling {
  std::vector<Occluder> occluders;
  /// occluders[k].box, side by side: every shot looks at them all (the roulette's reach).
  std::vector<Aabb> occluder_boxes;
  ReceiverTree tree;
  /// How far every point a shadow ray may start or end lies from its polygon (the shadow offset
  /// and the inset, with room for rounding): boxes grow by it and crossings keep clear of edges.
  double margin = 0.0;
  bool empty() const { return occluders.empty(); }
};

/// The culling data of `h`: its flat regions (visibility/occluders.h) whose Pure casts shadows,
/// fused where coplanar and touching.
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
