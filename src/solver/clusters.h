// Shooting patches (design §10): groups of a Pure's triangles that shoot as one source, so the
// number of shots follows the surfaces and the lighting, not the tessellation.
#pragma once

#include <cstdint>
#include <vector>

#include "core/aabb.h"
#include "hierarchy/hierarchy.h"

namespace rad {

/// The clusters of a scene as flat arrays; cluster c's polygons are
/// polygons[first[c] .. first[c + 1]) and its outline edges edge_a/b[edge_first[c] ..
/// edge_first[c + 1]).
///
/// A planar cluster holds edge-connected triangles of one Pure within 0.1 degree of one plane; a
/// curved one (a face cluster: Willmott, Heckbert, Garland, EGWR 1999) holds edge-connected
/// triangles whose normals lie within a bounded cone of its axis. Both are split (along their
/// longest axis) until their area is within the bound asked for.
///
/// The outline is the directed boundary of the cluster (edges used by one of its triangles
/// only, in the triangles' order, collinear runs merged): by Stokes' theorem the contour
/// integral of a surface's form factor runs over its boundary only (Baum, Rushmeier, Winget,
/// SIGGRAPH 1989), so an outline costs as much as its corners however finely it is tessellated.
struct Clusters {
  std::vector<uint32_t> first;       // size() + 1 entries
  std::vector<uint32_t> polygons;    // every triangle once, grouped by cluster
  std::vector<uint32_t> cluster_of;  // per triangle
  std::vector<uint32_t> edge_first;  // size() + 1 entries
  std::vector<Vec3> edge_a, edge_b;  // outline edges a -> b
  /// Curved clusters only: the corners on no outline edge (interior[interior_first[c] ..]).
  /// Where a receiver's tangent plane cuts the cluster's box, the outline's clipping is exact
  /// only if none of them lies behind the plane (else the plane may cut a loop that meets no
  /// outline edge, as inside a dome).
  std::vector<uint32_t> interior_first;  // size() + 1 entries
  std::vector<Vec3> interior;
  std::vector<Vec3> centroid;  // area centroid
  std::vector<Vec3> axis;      // unit area-weighted mean normal
  std::vector<float> area;
  std::vector<float> extent;  // box diagonal
  std::vector<Aabb> box;
  /// The normal cone: every triangle normal is within angle acos(cone_cos) of the axis.
  std::vector<float> cone_cos, cone_sin;
  /// Signed distances of the centroid from its triangles' planes, least and greatest (0 for a
  /// planar cluster): with the cone they bound how x sits against every triangle's plane.
  std::vector<float> offset_lo, offset_hi;
  std::vector<uint8_t> planar;

  size_t size() const { return area.size(); }
  uint32_t polygon_count(size_t c) const { return first[c + 1] - first[c]; }
};

/// Clusters of the hierarchy's triangles of at most `max_area`, except single triangles, which
/// stay whole. Deterministic: the same scene gives the same clusters.
Clusters make_clusters(const Hierarchy& h, double max_area);

}  // namespace rad
