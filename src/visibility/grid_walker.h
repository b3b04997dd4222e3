// The shape of a uniform grid and the one routine that walks a segment through it (3D DDA).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math.h"

namespace rad {

/// A uniform grid's geometry: box [lo, hi] cut into res[0] × res[1] × res[2] equal cells,
/// numbered x fastest: index = (z · res[1] + y) · res[0] + x.
struct GridShape {
  Vec3 lo{0.0f};
  Vec3 hi{0.0f};
  Vec3 cell_size{1.0f};
  Vec3 inv_cell_size{1.0f};
  std::array<int32_t, 3> res{1, 1, 1};

  uint32_t cell_count() const { return uint32_t(res[0]) * uint32_t(res[1]) * uint32_t(res[2]); }
  uint32_t index(int32_t x, int32_t y, int32_t z) const {
    return (uint32_t(z) * uint32_t(res[1]) + uint32_t(y)) * uint32_t(res[0]) + uint32_t(x);
  }
  /// Cell box of (x, y, z).
  Vec3 cell_lo(int32_t x, int32_t y, int32_t z) const {
    return lo + Vec3(float(x), float(y), float(z)) * cell_size;
  }
};

/// Builds the shape of a grid over [lo, hi] with the given resolution (each ≥ 1).
inline GridShape make_grid_shape(const Vec3& lo, const Vec3& hi, std::array<int32_t, 3> res) {
  GridShape g;
  g.lo = lo;
  g.hi = hi;
  g.res = res;
  for (int a = 0; a < 3; ++a) {
    g.cell_size[a] = (hi[a] - lo[a]) / float(res[a]);
    g.inv_cell_size[a] = g.cell_size[a] > 0.0f ? 1.0f / g.cell_size[a] : 0.0f;
  }
  return g;
}

/// A cell reached by the walk: its coordinates and its index in the grid.
struct GridCell {
  int32_t x, y, z;
  uint32_t index;
};

/// Slab test (Kay & Kajiya, "Ray Tracing Complex Scenes", SIGGRAPH 1986) of origin + t·direction
/// against [lo, hi], narrowing [t0, t1] in place; returns false if the interval becomes empty.
/// `inv_direction` = 1 / direction per component (±inf for 0). A NaN from 0·inf (origin on a slab
/// plane of a parallel ray) is ignored, which keeps the test conservative.
inline bool clip_segment_to_box(const Vec3& lo, const Vec3& hi, const Vec3& origin,
                                const Vec3& inv_direction, float& t0, float& t1) {
  for (int a = 0; a < 3; ++a) {
    float ta = (lo[a] - origin[a]) * inv_direction[a];
    float tb = (hi[a] - origin[a]) * inv_direction[a];
    float t_near = ta < tb ? ta : tb;
    float t_far = ta < tb ? tb : ta;
    t0 = t_near > t0 ? t_near : t0;
    t1 = t_far < t1 ? t_far : t1;
  }
  return t0 <= t1;
}

/// Walks the cells that origin + t·direction crosses for t in [t_enter, t_exit] (the part of the
/// segment inside the grid box, e.g. from clip_segment_to_box), in order along the segment,
/// calling visit(const GridCell&) for each; stops early and returns true as soon as visit does.
/// Returns false after the last cell. Amanatides & Woo, "A Fast Voxel Traversal Algorithm for
/// Ray Tracing", Eurographics 1987: per axis, the t of the next cell boundary (t_max) and the t
/// between boundaries (t_delta); step along the axis whose boundary comes first. Templated on the
/// visitor so each cell costs no indirect call. Pure function: thread-safe, no allocation.
template <class Visit>
inline bool walk_grid(const GridShape& g, const Vec3& origin, const Vec3& direction,
                      const Vec3& inv_direction, float t_enter, float t_exit, Visit&& visit) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const Vec3 start = origin + t_enter * direction;
  int32_t cell[3], step[3], stop[3];
  int32_t index_step[3] = {1, g.res[0], g.res[0] * g.res[1]};
  float t_max[3], t_delta[3];
  for (int a = 0; a < 3; ++a) {
    int32_t c = int32_t(std::floor((start[a] - g.lo[a]) * g.inv_cell_size[a]));
    cell[a] = std::clamp(c, 0, g.res[a] - 1);
    if (direction[a] > 0.0f) {
      step[a] = 1;
      stop[a] = g.res[a];
      t_max[a] = (g.lo[a] + float(cell[a] + 1) * g.cell_size[a] - origin[a]) * inv_direction[a];
      t_delta[a] = g.cell_size[a] * inv_direction[a];
    } else if (direction[a] < 0.0f) {
      step[a] = -1;
      stop[a] = -1;
      t_max[a] = (g.lo[a] + float(cell[a]) * g.cell_size[a] - origin[a]) * inv_direction[a];
      t_delta[a] = -g.cell_size[a] * inv_direction[a];
    } else {
      step[a] = 0;
      stop[a] = -1;
      t_max[a] = kInf;
      t_delta[a] = kInf;
    }
    index_step[a] *= step[a];
  }
  GridCell current{cell[0], cell[1], cell[2], g.index(cell[0], cell[1], cell[2])};
  for (;;) {
    if (visit(static_cast<const GridCell&>(current))) return true;
    int axis = t_max[0] < t_max[1] ? (t_max[0] < t_max[2] ? 0 : 2) : (t_max[1] < t_max[2] ? 1 : 2);
    if (t_max[axis] > t_exit) return false;
    int32_t* coord = axis == 0 ? &current.x : axis == 1 ? &current.y : &current.z;
    *coord += step[axis];
    if (*coord == stop[axis]) return false;
    current.index += uint32_t(index_step[axis]);
    t_max[axis] += t_delta[axis];
  }
}

}  // namespace rad
