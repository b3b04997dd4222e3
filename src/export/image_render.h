// Pictures of the solved mesh: z-buffered, antialiased rasterization of its Gouraud-shaded faces.
#pragma once

#include <span>

#include "export/camera.h"
#include "export/image.h"

namespace rad {

/// The largest image side, in pixels (the command line refuses more).
constexpr int kMaxImageSize = 16384;

struct RenderOptions {
  int width = 800, height = 800;  // pixels
  int samples = 4;                // subsamples per pixel along each axis (4: 16 per pixel)
};

/// Renders triangles (3 indices per face into `positions`/`colours`) seen from `camera`:
/// per-vertex linear colours interpolated perspective-correctly (Gouraud), nearest face wins,
/// `samples`² regularly placed subsamples per pixel averaged with a box filter. Faces are
/// one-sided: a face seen from behind (its front is (b-a)x(c-a)) is drawn black but still hides
/// what lies behind it. Background is black. Shared edges are watertight: vertices snap to a
/// fixed-point grid and every subsample on an edge belongs to exactly one face. Deterministic;
/// runs in parallel over bands of rows. Throws rad::Error for a size or sample count out of range.
Image render_image(std::span<const Vec3> positions, std::span<const Vec3> colours,
                   std::span<const uint32_t> indices, const Camera& camera,
                   const RenderOptions& options);

}  // namespace rad
