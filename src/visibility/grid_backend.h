// The in-house voxel-grid visibility backend of SPEC §6: per-object grids and the object walk.
#pragma once

#include <memory>

#include "visibility/backend.h"

namespace rad {

/// Default grid density (cells per triangle, in total per grid). Measured with
/// RAD_BENCH_GRID_SWEEP=1 visibility_bench (100k triangles, vertex → 16 samples, one core,
/// Mrays/s at 0.5 / 1 / 2 / 4 / 8): cornell 3.2 / 3.5 / 3.4 / 3.2 / 2.6, soup 1.8 / 1.8 / 2.6 /
/// 2.9 / 2.8, nested 1.8 / 1.8 / 1.6 / 1.6 / 1.6, stadium 0.7 / 0.8 / 1.2 / 1.1 / 1.2, building
/// 2.1 / 2.4 / 2.4 / 2.1 / 2.4 — flat between 1 and 4, so 2 (the pbrt-v2 ~3·∛N per axis means ~27
/// cells per triangle in a cube, which is far past the optimum here).
inline constexpr double kDefaultCellsPerTriangle = 2.0;

/// Builds a uniform grid over each Pure and each Composite (one grid over all of a Composite's
/// triangles; its Pures get none) and keeps only bounding boxes for Assemblies. A segment walks
/// the root object list: each object's (slightly padded) box is tested; an Assembly recurses into
/// its children, a Composite or Pure walks its grid with the 3D DDA; the first triangle hit ends
/// the segment. Immutable after construction; thread-safe; no allocation, lock or virtual call
/// per ray. Grids are built in parallel with TBB.
std::unique_ptr<VisibilityBackend> make_grid_backend(
    const Hierarchy& h, const VisibilityOptions& options,
    double cells_per_triangle = kDefaultCellsPerTriangle);

}  // namespace rad
