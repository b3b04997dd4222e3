// Where a vertex gathers when it lies inside a solid of the scene.
//
// Real models interpenetrate: a shelf board's end is sunk a few tenths of a millimetre into the
// side panel, a table top into its legs, a foot of a sofa into the floor. A vertex of the board
// at that end lies inside the panel, every shadow ray from it leaves through the panel's face
// from behind, and it gathers nothing; interpolated over its elements, its zero darkens the
// visible board next to it. So such a vertex gathers instead at the nearest point of its own
// polygon outside the solid, towards the polygon's centroid: the radiosity there is what the
// visible part of its elements continues to at the contact line (as the discontinuity meshing
// of Baum et al., "Making radiosity usable", SIGGRAPH 1991, splits surfaces where they
// intersect, without the splitting). A vertex is inside a solid when the first surface met on
// the way from it towards its polygon's centroid, just off the polygon, is met from behind (and
// so is the first met straight out along its normal or back the other way): a
// vertex beyond a wall (a floor running under it into the next room) meets the wall's front and
// stays where it is.
//
// What a moved vertex gathers is its radiosity (what is shown and what refinement compares).
// It is light to shoot too when the vertex lies just under the solid's face, less than
// kShootingDepth of the smallest element size (a board's end sunk a fraction of a millimetre
// into a panel, a foot into the floor): the elements around it, split to the smallest size
// across the contact, lie inside the solid or outside on that face's side, and their visible
// part reflects what the vertex gathers. Held back, that light is lost to the scene: the
// furnished rooms' books close short of the emitted energy and their shells are too dark. A
// vertex deeper inside shoots nothing: its polygon may cross a solid thinner than its
// elements (a shelf board through a panel), and its light would reach, by interpolation, the
// elements on the solid's other side, a closed compartment where no light is. Its unshot
// radiosity stays what the buried point receives, nothing, so the part of a polygon hidden
// inside a solid (the floor under a box standing on it) adds no light to the scene.
//
// The same probes find the *covered* vertices: those with a surface within the smallest element
// size straight above them, where a surface runs under another a gap's width away (the floor
// under a model standing 1 mm up, the wall behind a shelf, a drawer's side in its compartment).
// Under a cover the light falls from the open side's to nothing within a few gap widths, far
// less than the smallest element, and an element across the cover's edge would carry the open
// side's light under it by interpolation: refinement splits such elements below the smallest
// size (refine.cpp).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"
#include "visibility/backend.h"

namespace rad {

/// How far toward its polygon's centroid a point gathers, and the probes below start, as a
/// fraction of the way (GatherSettings::inset): off the edges, where a wall meeting the polygon
/// would leave a ray running along the wall's plane to rounding, and the backends could answer
/// differently.
constexpr float kGatherInset = 1e-4f;

/// How deep under a solid's face a moved vertex may lie and still shoot what it gathers, as a
/// fraction of the smallest element size (see above).
constexpr float kShootingDepth = 0.25f;

/// Whether a vertex at `x` that gathers at `at` reflects what it gathers into the light it
/// shoots: it was not moved, or moved less than `reach` (kShootingDepth times the smallest
/// element size).
inline bool shoots_from(const Vec3& x, const Vec3& at, float reach) {
  return at == x || glm::length(at - x) < reach;
}

/// A vertex that gathers elsewhere than at its position.
struct MovedVertex {
  uint32_t vertex;
  Vec3 at;  // on its polygon's plane
};

/// Per polygon, its vertices that lie inside a solid and where each gathers, by vertex index;
/// empty for most. Derived from the geometry alone, so not saved: a state restored from a
/// checkpoint finds them again.
struct BuriedVertices {
  std::vector<std::vector<MovedVertex>> moved;  // per polygon, sorted by vertex
  std::vector<std::vector<uint32_t>> covered;   // per polygon, the covered vertices, sorted
  bool found = false;                           // every vertex made so far was looked at

  /// Where vertex v of polygon p gathers: its own position `x`, or where it was moved.
  Vec3 gather_point(size_t p, uint32_t v, const Vec3& x) const {
    if (p >= moved.size() || moved[p].empty()) return x;
    const auto it = std::lower_bound(moved[p].begin(), moved[p].end(), v,
                                     [](const MovedVertex& m, uint32_t u) { return m.vertex < u; });
    return it != moved[p].end() && it->vertex == v ? it->at : x;
  }
  /// Whether a surface lies within the smallest element size straight above vertex v of p.
  bool is_covered(size_t p, uint32_t v) const {
    return p < covered.size() && std::binary_search(covered[p].begin(), covered[p].end(), v);
  }
  /// shoots_from for vertex v of polygon p, at `x`.
  bool shoots(size_t p, uint32_t v, const Vec3& x, float reach) const {
    return shoots_from(x, gather_point(p, v, x), reach);
  }
  /// Whether vertex v of polygon p was moved (it lies inside a solid).
  bool is_moved(size_t p, uint32_t v) const {
    if (p >= moved.size() || moved[p].empty()) return false;
    const auto it = std::lower_bound(moved[p].begin(), moved[p].end(), v,
                                     [](const MovedVertex& m, uint32_t u) { return m.vertex < u; });
    return it != moved[p].end() && it->vertex == v;
  }
};

/// How vertices are probed. A vertex deeper inside than `depth` stays where it is, dark: only
/// the vertices of elements that reach out of the solid shape what is seen (refinement splits
/// elements that cross into a solid down to the smallest size), and the inside of a footprint
/// (the floor under a box standing on it) is dark, as no light reaches it.
struct BuriedProbe {
  float offset = 0.0f;  // the shadow offset: how far off the surface the probe runs and how
                        // far past a solid's face a moved vertex stops
  float depth = 0.0f;   // how far a vertex may move
};

/// Where the vertex at `x` of polygon `p` (triangles t) gathers: x, or the point of p just
/// outside the solids it lies in (at most `kMaxSolids` nested or in a row), if that is within
/// probe.depth of x. One occlusion query for a vertex that lies outside every solid (nearly all
/// of them).
Vec3 find_gather_point(const Triangles& t, size_t p, const Vec3& x, const VisibilityBackend& vis,
                       const BuriedProbe& probe, VisibilityStats& stats);
inline constexpr int kMaxSolids = 4;

/// Whether a surface lies within probe.depth straight above the vertex at `x` of polygon p: an
/// occlusion query, whose answer every backend gives alike (a first hit's may differ where the
/// probe meets an edge).
bool is_covered(const Triangles& t, size_t p, const Vec3& x, const VisibilityBackend& vis,
                const BuriedProbe& probe, VisibilityStats& stats);

/// Looks at every vertex from index `first` on of polygon p's mesh and records those that move
/// and those covered (appended: indices grow). Thread-safe for distinct polygons.
void find_buried_vertices(const Triangles& t, size_t p, const PolygonMesh& mesh, uint32_t first,
                          const VisibilityBackend& vis, const BuriedProbe& probe,
                          std::vector<MovedVertex>& moved, std::vector<uint32_t>& covered,
                          VisibilityStats& stats);

/// Every vertex of every polygon of `mesh` (in parallel; deterministic).
BuriedVertices find_all_buried_vertices(const Triangles& t, const Mesh& mesh,
                                        const VisibilityBackend& vis, const BuriedProbe& probe,
                                        VisibilityStats& stats);

}  // namespace rad
