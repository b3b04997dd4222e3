// The path-traced reference seen through a camera's pixels: what rad's pictures (the final
// gather and the Gouraud preview) are measured against.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "export/camera.h"
#include "hierarchy/hierarchy.h"
#include "reference/path_tracer.h"

namespace rad {

struct CameraReferenceOptions {
  Camera camera;
  int width = 200, height = 200;
  /// Paths per pixel along each side of the pixel: k x k, one per stratum of the pixel's area.
  int pixel_samples = 64;
  TraceOptions trace;  // seed, roulette, next event, bounces (the targets are not used)
};

struct CameraReference {
  int width = 0, height = 0;
  /// Per pixel, rows top first (as rad's Image): the mean radiosity B = E + rho H over the
  /// pixel's area at the first surface each ray meets; 0 where a ray meets nothing or a face
  /// from behind (rad's pictures show those black at its default background).
  std::vector<DVec3> radiosity;
  /// Per pixel, 1 where the pixel's centre and the four points half a pixel from it (left,
  /// right, up, down: the middles of its sides) all see the front of one surface: the same
  /// scene object on the same plane (normals within 0.1 degree, the hit points' distances from
  /// the centre's plane within 1e-5 of the scene's diagonal). Coplanar triangles of one object
  /// are one surface, so a polygon's own triangulation leaves pixels interior; a silhouette,
  /// a crease, a contact between objects or a lamp set in a ceiling does not. Such a pixel's
  /// value depends only on the light over one smooth surface, not on how a picture treats
  /// edges.
  std::vector<uint8_t> interior;
  uint64_t paths = 0;
  double seconds = 0.0;
};

/// Renders the reference: pixel (x, y) of a width x height image sees along the camera ray
/// through (x + sx, y + sy) pixels from the top left, as rad's renderers do (camera_frame,
/// export/camera.h), for (sx, sy) over the pixel (a box filter). Each of the k x k paths of a
/// pixel takes its place in the pixel and its first numbers (the light sample and the bounce
/// direction at the first three points of the path) from Owen-scrambled Sobol points, the rest
/// from its own random stream: every path stays uniform, so each pixel is unbiased, and its
/// k x k paths spread over the pixel and the hemisphere far more evenly than random ones.
/// Pixel p draws from hashes and a stream of (seed, p): the same image for any thread count.
/// `progress` (optional) is told rows finished, from worker threads, serialised.
CameraReference render_camera_reference(
    const Hierarchy& h, const CameraReferenceOptions& o,
    const std::function<void(int done, int total)>& progress = {});

}  // namespace rad
