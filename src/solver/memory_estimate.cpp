#include "solver/memory_estimate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>

#include "mesh/subdivide.h"

namespace rad {

namespace {
// Per item, with std::vector's doubling slack (half a capacity on average) and the node of an
// unordered_map entry (key, value, next pointer, allocator header, bucket).
constexpr double kSlack = 1.5;
constexpr double kVertexBytes = (sizeof(Vec3) + sizeof(VertexState)) * kSlack;
constexpr double kElementBytes = sizeof(Element) * kSlack;
constexpr double kMidpointBytes = 48.0;
}  // namespace

double worst_case_growth_bytes(const SolverState& s) {
  const float min_split = min_split_size(s.scene);
  // With light groups a vertex has a state per group too.
  const double group_bytes = double(s.solution.group_count) * sizeof(VertexState) * kSlack;
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, s.solution.mesh.polygons.size()), 0.0,
      [&](const tbb::blocked_range<size_t>& r, double bytes) {
        for (size_t p = r.begin(); p < r.end(); ++p) {
          const PolygonMesh& m = s.solution.mesh.polygons[p];
          for_each_leaf(m, [&](uint32_t e) {
            const float size = split_size(m, e);
            if (!(size >= min_split)) return;
            const double d = std::floor(std::log2(double(size) / double(min_split))) + 1.0;
            const double side = std::exp2(d);                         // edge segments per side
            const double vertices = (side + 1) * (side + 2) / 2 - 3;  // all new
            const double elements = (std::exp2(2 * d + 2) - 1) / 3 - 1;
            bytes +=
                vertices * (kVertexBytes + kMidpointBytes + group_bytes) + elements * kElementBytes;
          });
        }
        return bytes;
      },
      [](double a, double b) { return a + b; });
}

double shot_log_bytes(const SolverState& s, size_t c) {
  // n samples padded to lanes (10 floats each, 3 more for the ray ends), about 16 n fine
  // samples (10 floats each and 6 for their cells, a group index per lane group), the outline.
  const int m = sample_grid_for(s, s.scene.clusters.extent[c]);
  const double n = double(m) * m, fine = 16.0 * n;
  const double outline =
      double(s.scene.clusters.edge_first[c + 1] - s.scene.clusters.edge_first[c]);
  // Each light group's share: 3 floats per lane of each.
  const double shares = double(s.solution.group_count) * 4.0 * 3.0 * ((n + 8) + (fine + 8 * n));
  return sizeof(ShotSource) + 4.0 * (13.0 * (n + 8) + 16.0 * (fine + 8 * n) + fine / 8) +
         24.0 * outline + shares;
}

}  // namespace rad
