// The in-house voxel-grid visibility backend of design §6: per-object grids and the object walk.
#pragma once

#include <memory>

#include "visibility/backend.h"

namespace rad {

/// Default grid density (cells per triangle, in total per grid). Ray speed is flat between 1 and
/// 4 cells per triangle on every generated scene (RAD_BENCH_GRID_SWEEP=1 visibility_bench prints
/// the sweep), so 2; pbrt-v2's ~3·∛N cells per axis (~27 per triangle in a cube) is far past
/// the optimum for shadow rays this short.
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
