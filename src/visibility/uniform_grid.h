// One uniform voxel grid over a range of triangles (design §6): resolution, build, flat cells.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "core/aabb.h"
#include "hierarchy/hierarchy.h"
#include "visibility/grid_walker.h"
#include "visibility/triangle_test.h"

namespace rad {

/// Resolution of a grid over a box of size `extent` holding `triangle_count` triangles, aiming at
/// `cells_per_triangle` cells per triangle in total with near-cubic cells. Axes much thinner than
/// a cell (flat objects) get one cell and the others share the budget. Each axis in [1, 4096].
std::array<int32_t, 3> grid_resolution(const Vec3& extent, uint32_t triangle_count,
                                       double cells_per_triangle);

/// A uniform grid over the triangles [first, first + count) of a triangle table: each cell lists
/// (as global triangle ids, ascending) the triangles that may overlap it. Cells are stored flat:
/// cell i holds indices[offsets[i] .. offsets[i + 1]). A cell of kPacketMinimum triangles or
/// more also has their records in packets of eight, in the same order, tested eight at a time:
/// where a mesh is dense (the rounded edges of a modelled cushion, a plant's leaves) a cell holds
/// dozens of triangles, and rays start right there, on the vertices. Immutable after build;
/// thread-safe reads.
class UniformGrid {
 public:
  UniformGrid() = default;

  static constexpr uint32_t kPacketMinimum = 8;
  static constexpr uint32_t kNoPackets = ~0u;

  /// Builds the grid over `box` (which must contain the triangles; the caller pads it).
  /// Cell membership uses triangle_voxel_overlap with a small margin (see overlapped_cells);
  /// `records` (indexed by triangle id) fill the packets.
  static UniformGrid build(const Triangles& triangles, std::span<const TriangleRecord> records,
                           uint32_t first, uint32_t count, const Aabb& box,
                           double cells_per_triangle);

  const GridShape& shape() const { return shape_; }
  std::span<const uint32_t> cell(uint32_t index) const {
    return {indices_.data() + offsets_[index], indices_.data() + offsets_[index + 1]};
  }
  /// The first of the cell's ceil(size / 8) packets, or kNoPackets for a cell tested one
  /// triangle at a time.
  uint32_t first_packet(uint32_t index) const { return first_packet_[index]; }
  const TrianglePacket& packet(uint32_t p) const { return packets_[p]; }
  /// Total number of (cell, triangle) entries.
  size_t entry_count() const { return indices_.size(); }
  size_t memory_bytes() const {
    return (offsets_.capacity() + indices_.capacity() + first_packet_.capacity()) *
               sizeof(uint32_t) +
           packets_.capacity() * sizeof(TrianglePacket);
  }

 private:
  GridShape shape_;
  std::vector<uint32_t> offsets_;       // cell_count + 1
  std::vector<uint32_t> indices_;       // triangle ids
  std::vector<uint32_t> first_packet_;  // cell_count
  std::vector<TrianglePacket> packets_;
};

}  // namespace rad
