// Vertices that polygons of one planar cluster share, gathered once and copied to the others.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "core/position_bits.h"
#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"
#include "solver/clusters.h"

namespace rad {

/// A vertex that takes the gain of another at the same position in the same planar cluster
/// (the same point of the same plane and Pure) instead of gathering it again.
struct VertexCopy {
  uint32_t vertex, from_polygon, from_vertex;
};

/// The vertices that polygons of one planar cluster share: a tessellated wall stores each grid
/// point once per triangle around it (six times), and each midpoint of an edge between two of
/// its triangles twice once both split it, but one of them gathers and the others copy its gain
/// after the shot. Found by position: among the initial vertices, the lowest (polygon, vertex)
/// gathers; a midpoint made on a polygon's edge copies the one that gathers there, if that one's
/// polygon received the same shot (else it gathers for itself, from then on, and the lowest
/// (polygon, vertex) of those that gather at a place is the one later midpoints copy). A copy's
/// source is never a copy.
struct SharedVertices {
  struct Place {  // a position in a cluster
    uint32_t cluster;
    PositionBits position;
    bool operator==(const Place&) const = default;
    auto operator<=>(const Place&) const = default;
  };
  struct PlaceHash {
    size_t operator()(const Place& k) const;
  };
  struct Gatherer {
    uint32_t polygon, vertex;
  };
  /// Per polygon: its copies, in vertex order.
  std::vector<std::vector<VertexCopy>> copies;
  /// Whether vertex v of polygon p copies another's gain.
  bool is_copy(uint32_t p, uint32_t v) const;
  /// The midpoint later ones copy at each place on polygon edges where one was made.
  std::unordered_map<Place, Gatherer, PlaceHash> edge_midpoints;
};

/// The initial mesh's vertices shared within planar clusters.
SharedVertices find_shared_vertices(const Mesh& mesh, const Clusters& clusters);

/// Whether polygon p may share vertices: its cluster is planar with other polygons.
bool shares_vertices(const Clusters& clusters, size_t p);

/// Where vertex position `x` of polygon p is shared, if it may be (shares_vertices). (Whether x
/// lies on p's edges is the caller's to say: on_triangle_edge.)
std::optional<SharedVertices::Place> shared_place(const Clusters& clusters, size_t p,
                                                  const Vec3& x);

/// Whether x lies on an edge of the triangle (a midpoint of two points on one edge does, up to
/// rounding; any other point of a subdivision lies a fraction of the smallest element inside).
bool on_triangle_edge(const std::array<Vec3, 3>& c, const Vec3& x);

/// shared.edge_midpoints from the mesh and the copies (after a checkpoint is read): at each
/// place, the lowest (polygon, vertex) that gathers among the midpoints refinement made on
/// polygon edges (vertices from initial_vertices[p] on).
void find_edge_midpoints(SharedVertices& shared, const Mesh& mesh, const Triangles& triangles,
                         const Clusters& clusters, std::span<const uint32_t> initial_vertices);

}  // namespace rad
