// The radiosity mesh: one vertex table and one element tree per polygon (design §5).
#pragma once

#include <cstdint>
#include <memory>
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

/// The midpoint vertex of every split edge of one polygon (key: edge_key of the two ends).
/// Allocated on the first split: most polygons of a large scene never split, and an empty
/// std::unordered_map alone is 56 bytes.
class MidpointMap {
 public:
  using Map = std::unordered_map<uint64_t, uint32_t>;
  MidpointMap() = default;
  MidpointMap(const MidpointMap& o) : map_(o.map_ ? std::make_unique<Map>(*o.map_) : nullptr) {}
  MidpointMap(MidpointMap&&) noexcept = default;
  MidpointMap& operator=(const MidpointMap& o) { return *this = MidpointMap(o); }
  MidpointMap& operator=(MidpointMap&&) noexcept = default;

  /// The vertex stored for `key`, or -1.
  int64_t find(uint64_t key) const {
    if (!map_) return -1;
    auto it = map_->find(key);
    return it == map_->end() ? -1 : int64_t(it->second);
  }
  /// The entry for `key`, made with value 0 if absent; second: whether it was made.
  std::pair<uint32_t*, bool> try_emplace(uint64_t key) {
    if (!map_) map_ = std::make_unique<Map>();
    auto [it, made] = map_->try_emplace(key, 0u);
    return {&it->second, made};
  }
  size_t size() const { return map_ ? map_->size() : 0; }
  /// The entries, empty before the first split.
  const Map& entries() const {
    static const Map empty;
    return map_ ? *map_ : empty;
  }

 private:
  std::unique_ptr<Map> map_;
};

/// One polygon (an original triangle) and everything its subdivision created. A vertex is
/// stored once however many elements share it, and belongs to this polygon only (the original
/// keeps no connectivity between polygons). What the solver keeps at each vertex is its own,
/// in a table of the same indices (solver/solver_state.h).
struct PolygonMesh {
  std::vector<Vec3> positions;  // the vertex table
  std::vector<Element> elements;
  MidpointMap midpoints;

  size_t vertex_count() const { return positions.size(); }
  /// Appends a vertex; returns its index.
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

/// One unsplit polygon per hierarchy triangle.
Mesh make_mesh(const Hierarchy& h);

/// Calls f(element_index) for every leaf of polygon `p`, depth-first, children in order.
template <typename F>
void for_each_leaf(const PolygonMesh& p, F&& f) {
  if (p.elements.empty()) return;  // another MPI rank's polygon (solver/distribute.h)
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

/// The integral over polygon `p` of a vertex quantity interpolated linearly over each leaf is
/// the sum over leaves of area x (sum of its three vertices' values) / 3. Calls
/// f(area, value(v0) + value(v1) + value(v2)) per leaf (value: of a vertex index), in
/// for_each_leaf's order; `f` does the multiply and accumulates in the precision it needs.
template <typename Value, typename F>
void for_each_leaf_vertex_sum(const PolygonMesh& p, Value&& value, F&& f) {
  for_each_leaf(p, [&](uint32_t e) {
    const Element& el = p.elements[e];
    f(el.area, value(el.v[0]) + value(el.v[1]) + value(el.v[2]));
  });
}

size_t count_vertices(const Mesh& m);
size_t count_leaves(const Mesh& m);

}  // namespace rad
