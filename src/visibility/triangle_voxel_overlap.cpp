#include "visibility/triangle_voxel_overlap.h"

#include <algorithm>
#include <cmath>

namespace rad {

namespace {

struct Interval {
  double lo, hi;
};

// Exact range of v·(x − c) for x in the box [lo, hi] (up to rounding of each product).
Interval linear_range(const DVec3& v, const DVec3& c, const DVec3& lo, const DVec3& hi) {
  Interval r{0.0, 0.0};
  for (int a = 0; a < 3; ++a) {
    double p = v[a] * (lo[a] - c[a]);
    double q = v[a] * (hi[a] - c[a]);
    r.lo += std::min(p, q);
    r.hi += std::max(p, q);
  }
  return r;
}

}  // namespace

TriangleFrame make_triangle_frame(const std::array<Vec3, 3>& corners) {
  DVec3 a(corners[0]), b(corners[1]), c(corners[2]);
  DVec3 e_a = a - c, e_b = b - c;
  TriangleFrame t;
  t.c = c;
  t.n = glm::cross(e_a, e_b);
  double n2 = glm::dot(t.n, t.n);
  if (!(n2 > 0.0)) return t;
  t.s_a = glm::cross(e_b, t.n) / n2;
  t.s_b = glm::cross(t.n, e_a) / n2;
  t.degenerate = false;
  return t;
}

// Interval arithmetic (Moore, "Interval Analysis", 1966) applied to the design §6 barycentric
// expressions, as the original program did.
bool triangle_may_overlap_box(const TriangleFrame& t, const DVec3& lo, const DVec3& hi) {
  if (t.degenerate) return false;
  // A relative slack of a few ulps on each range keeps double rounding conservative too.
  constexpr double kSlack = 1e-12;
  Interval d = linear_range(t.n, t.c, lo, hi);
  double sd = kSlack * (std::abs(d.lo) + std::abs(d.hi));
  if (d.lo > sd || d.hi < -sd) return false;
  Interval alpha = linear_range(t.s_a, t.c, lo, hi);
  if (alpha.lo > 1.0 + kSlack || alpha.hi < -kSlack) return false;
  Interval beta = linear_range(t.s_b, t.c, lo, hi);
  if (beta.lo > 1.0 + kSlack || beta.hi < -kSlack) return false;
  Interval sum = linear_range(t.s_a + t.s_b, t.c, lo, hi);
  return !(sum.lo > 1.0 + kSlack || sum.hi < -kSlack);
}

void overlapped_cells(const std::array<Vec3, 3>& corners, const GridShape& grid, double margin,
                      std::vector<uint32_t>& cells) {
  TriangleFrame t = make_triangle_frame(corners);
  if (t.degenerate) return;
  DVec3 glo(grid.lo), size(grid.cell_size);
  int32_t first[3], last[3];
  for (int a = 0; a < 3; ++a) {
    double tlo = std::min({double(corners[0][a]), double(corners[1][a]), double(corners[2][a])});
    double thi = std::max({double(corners[0][a]), double(corners[1][a]), double(corners[2][a])});
    double pad = margin * size[a];
    double inv = size[a] > 0.0 ? 1.0 / size[a] : 0.0;
    first[a] = std::clamp(int32_t(std::floor((tlo - pad - glo[a]) * inv)), 0, grid.res[a] - 1);
    last[a] = std::clamp(int32_t(std::floor((thi + pad - glo[a]) * inv)), 0, grid.res[a] - 1);
  }
  // A triangle inside a single cell needs no test.
  if (first[0] == last[0] && first[1] == last[1] && first[2] == last[2]) {
    cells.push_back(grid.index(first[0], first[1], first[2]));
    return;
  }
  for (int32_t z = first[2]; z <= last[2]; ++z) {
    for (int32_t y = first[1]; y <= last[1]; ++y) {
      for (int32_t x = first[0]; x <= last[0]; ++x) {
        DVec3 lo = glo + DVec3(x, y, z) * size;
        DVec3 hi = lo + size;
        DVec3 pad = margin * size;
        if (triangle_may_overlap_box(t, lo - pad, hi + pad)) cells.push_back(grid.index(x, y, z));
      }
    }
  }
}

}  // namespace rad
