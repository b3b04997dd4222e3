#include "visibility/uniform_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "visibility/triangle_voxel_overlap.h"

namespace rad {

namespace {

// Cells grow by this fraction of their size when deciding membership: far above float rounding
// of the walker's boundaries (~1e-7 relative), far below a cell.
constexpr double kCellMargin = 1e-4;
constexpr int32_t kMaxAxisCells = 4096;

}  // namespace

// The classic uniform grid sizing (pbrt-v2 accelerators/grid.cpp: ~3·∛N cells along the longest
// axis, i.e. ~27 N cells for a cube) generalised to a chosen total: cubic cells of side s with
// Π ceil(extent / s) ≈ cells_per_triangle · N, flat axes excluded from the volume.
std::array<int32_t, 3> grid_resolution(const Vec3& extent, uint32_t triangle_count,
                                       double cells_per_triangle) {
  double target = std::max(1.0, cells_per_triangle * double(triangle_count));
  bool active[3];
  for (int a = 0; a < 3; ++a) active[a] = extent[a] > 0.0f;
  double s = 0.0;
  for (int iteration = 0; iteration < 3; ++iteration) {
    double volume = 1.0;
    int k = 0;
    for (int a = 0; a < 3; ++a) {
      if (active[a]) {
        volume *= double(extent[a]);
        ++k;
      }
    }
    if (k == 0) break;
    s = std::pow(volume / target, 1.0 / k);
    bool changed = false;
    for (int a = 0; a < 3; ++a) {
      if (active[a] && double(extent[a]) < s) {
        active[a] = false;
        changed = true;
      }
    }
    if (!changed) break;
  }
  std::array<int32_t, 3> res{1, 1, 1};
  for (int a = 0; a < 3; ++a) {
    if (active[a] && s > 0.0) {
      double n = std::round(double(extent[a]) / s);
      res[a] = int32_t(std::clamp(n, 1.0, double(kMaxAxisCells)));
    }
  }
  return res;
}

UniformGrid UniformGrid::build(const Triangles& triangles, std::span<const TriangleRecord> records,
                               uint32_t first, uint32_t count, const Aabb& box,
                               double cells_per_triangle) {
  UniformGrid grid;
  grid.shape_ =
      make_grid_shape(box.lo, box.hi, grid_resolution(box.extent(), count, cells_per_triangle));
  const uint32_t cells = grid.shape_.cell_count();

  // (cell, triangle) pairs, gathered in parallel per block of triangles, then counting-sorted.
  using Pairs = std::vector<std::pair<uint32_t, uint32_t>>;
  tbb::combinable<Pairs> per_thread;
  tbb::parallel_for(tbb::blocked_range<uint32_t>(first, first + count, 1024),
                    [&](const tbb::blocked_range<uint32_t>& r) {
                      Pairs& pairs = per_thread.local();
                      std::vector<uint32_t> hit;
                      for (uint32_t t = r.begin(); t != r.end(); ++t) {
                        hit.clear();
                        overlapped_cells(triangles.corners[t], grid.shape_, kCellMargin, hit);
                        for (uint32_t c : hit) pairs.emplace_back(c, t);
                      }
                    });
  grid.offsets_.assign(size_t(cells) + 1, 0);
  per_thread.combine_each([&](const Pairs& pairs) {
    for (const auto& p : pairs) ++grid.offsets_[p.first + 1];
  });
  for (uint32_t c = 0; c < cells; ++c) grid.offsets_[c + 1] += grid.offsets_[c];
  grid.indices_.resize(grid.offsets_[cells]);
  std::vector<uint32_t> fill(grid.offsets_.begin(), grid.offsets_.end() - 1);
  per_thread.combine_each([&](const Pairs& pairs) {
    for (const auto& p : pairs) grid.indices_[fill[p.first]++] = p.second;
  });
  // Ascending ids per cell: deterministic layout whatever the thread schedule.
  for (uint32_t c = 0; c < cells; ++c) {
    std::sort(grid.indices_.begin() + grid.offsets_[c],
              grid.indices_.begin() + grid.offsets_[c + 1]);
  }
  grid.first_packet_.assign(cells, kNoPackets);
  for (uint32_t c = 0; c < cells; ++c) {
    const std::span<const uint32_t> ids = grid.cell(c);
    if (ids.size() < kPacketMinimum) continue;
    grid.first_packet_[c] = uint32_t(grid.packets_.size());
    for (size_t i = 0; i < ids.size(); ++i) {
      if (i % TrianglePacket::kLanes == 0) grid.packets_.emplace_back();
      grid.packets_.back().set(uint32_t(i % TrianglePacket::kLanes), records[ids[i]]);
    }
  }
  return grid;
}

}  // namespace rad
