// The radiosity mesh: one vertex table and one element tree per polygon (SPEC §5).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/math.h"
#include "hierarchy/hierarchy.h"

namespace rad {

/// A subdivision element: a triangle of its polygon's vertex table. Element 0 of a polygon is
/// the polygon itself; a split element's four children are stored consecutively from
/// `first_child`: corner a, corner b, corner c, then the middle one.
struct Element {
  uint32_t v[3];
  int32_t first_child = -1;  // -1 for a leaf
  float area = 0.0f;
  bool leaf() const { return first_child < 0; }
};

/// One polygon (an original triangle) and everything its subdivision created. A vertex is
/// stored once however many elements share it, and belongs to this polygon only (the original
/// keeps no connectivity between polygons).
struct PolygonMesh {
  // Per vertex.
  std::vector<Vec3> position;
  std::vector<Vec3> irradiance;  // H: radiosity gathered from all shots so far; B = E + rho * H
  std::vector<Vec3> unshot;      // radiosity received but not yet shot
  std::vector<Vec3> shot;        // H gathered during the current shot only (for subdivision)
  std::vector<Vec3> major;       // part of H gathered from the solver's major shots (see solver)
  // Elements, and the midpoint of every split edge (key: the two end vertices, lower first).
  std::vector<Element> elements;
  std::unordered_map<uint64_t, uint32_t> midpoints;

  size_t vertex_count() const { return position.size(); }
  /// Appends a vertex with zero radiosity; returns its index.
  uint32_t add_vertex(const Vec3& p);
  /// The midpoint vertex of edge (a, b), or -1 if that edge was never split.
  int64_t midpoint(uint32_t a, uint32_t b) const;
};

inline uint64_t edge_key(uint32_t a, uint32_t b) {
  return a < b ? (uint64_t(a) << 32) | b : (uint64_t(b) << 32) | a;
}

struct Mesh {
  std::vector<PolygonMesh> polygons;  // index = triangle id of the hierarchy
};

/// One unsplit polygon per hierarchy triangle, all radiosity zero.
Mesh make_mesh(const Hierarchy& h);

/// Calls f(element_index) for every leaf of polygon `p`, depth-first, children in order.
template <typename F>
void for_each_leaf(const PolygonMesh& p, F&& f) {
  uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    uint32_t e = stack[--top];
    const Element& el = p.elements[e];
    if (el.leaf()) {
      f(e);
    } else {
      for (int c = 3; c >= 0; --c) stack[top++] = uint32_t(el.first_child) + c;
    }
  }
}

size_t count_vertices(const Mesh& m);
size_t count_leaves(const Mesh& m);

}  // namespace rad
