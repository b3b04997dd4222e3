// Crack-free triangles over the leaf elements of a polygon (T-vertices included, its own and
// those a neighbour in the same plane made on the edge they share).
#pragma once

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/position_bits.h"
#include "mesh/patch_mesh.h"

namespace rad {

/// Vertex `vertex` of polygon `polygon`.
struct VertexRef {
  uint32_t polygon, vertex;
};

/// The vertices on the edges of a group of polygons that lie in one plane and one Pure, by
/// exact position: where one of them split an edge they share and its neighbour did not, the
/// neighbour's faces take the midpoint as a T-vertex, with its value, instead of interpolating
/// across it (which leaves a seam, and misses a shadow's edge or a light's peak there).
class SeamVertices {
 public:
  /// Adds a vertex at x; the first one added at a position is the one found.
  void add(const Vec3& x, VertexRef v);
  /// The vertex at exactly x, or null.
  const VertexRef* find(const Vec3& x) const;
  bool empty() const { return at_.empty(); }

 private:
  std::unordered_map<PositionBits, VertexRef, PositionBitsHash> at_;
};

/// The faces to write for one polygon. Indices below the polygon's vertex count name its
/// vertices; index vertex_count + k names centroids[k], an extra vertex at the mean of three
/// polygon vertices (its value is their mean too, which is what Gouraud shading shows there);
/// index vertex_count + centroids.size() + k names seam[k], another polygon's vertex.
struct PolygonFaces {
  std::vector<uint32_t> triangles;  // 3 indices per face, same orientation as the polygon
  std::vector<std::array<uint32_t, 3>> centroids;
  std::vector<VertexRef> seam;
};

/// Triangulates every leaf of `p` (polygon `self`). A leaf with a midpoint on its edge (a
/// T-vertex: its own polygon's, or from `seams` another polygon's at the position where p would
/// put it) is split through that vertex so the written faces have no cracks: fanned from the
/// opposite corner when only one edge carries such vertices, from an added centroid otherwise.
PolygonFaces triangulate_leaves(const PolygonMesh& p, uint32_t self = 0,
                                const SeamVertices* seams = nullptr);

}  // namespace rad
