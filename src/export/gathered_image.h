// Pictures by final gather (Reichert 1992; Chen et al. 1991): a camera ray per subsample,
// through the visibility backends; at the point it sees, the direct light of every emitter and
// light recomputed there with shadow rays, and the light that came by bounces interpolated
// from the solution's vertices. Sharper than the mesh: shadow edges, contact shadows and
// textures show at the pixel, not at the element.
#pragma once

#include <functional>

#include "export/camera.h"
#include "export/image.h"
#include "solver/gather.h"
#include "solver/solver_state.h"
#include "visibility/backend.h"

namespace rad {

struct GatheredImageOptions {
  int width = 800, height = 800;  // pixels
  int samples = 3;                // subsamples per pixel along each axis (3: 9 per pixel)
  /// Added to the bounced light everywhere: Cohen's ambient term where a solve stopped short
  /// (ambient_radiosity), or 0.
  Vec3 ambient{0.0f};
  Vec3 background{0.0f};  // where a ray meets nothing
  /// Instead of the background, an alpha per pixel: the part of its samples that meet a
  /// surface (Image::alpha; the colour premultiplied by it).
  bool transparent = false;
};

/// What a final gather measured.
struct GatheredImageStats {
  uint64_t camera_rays = 0;
  uint64_t shadow_rays = 0;
  size_t polygons_seen = 0;  // polygons whose vertices' bounced light was separated
  double seconds = 0.0;
};

/// How a subsample gathers its direct light: as a vertex does (gather_settings), with 8 penumbra
/// rounds whatever the solver's and for every emitter (GatherSettings::penumbra_every_source):
/// in a penumbra each stratum's rays end at points drawn by what they give that point, so a
/// face close to a big source behind an occluder reads the light of the band it sees, not the
/// band's share of the area, and a small lamp's penumbra shows as a window's does.
GatherSettings pixel_gather_settings(const SolverState& s);

/// Renders the solved state `s` seen from `camera`: each pixel the mean over `samples`^2
/// jittered subsamples of the radiosity B = E + rho (H_direct + H_bounced) at the surface a
/// camera ray meets (the background where none; black on a face seen from behind, as
/// render_image draws it). E and rho are read at the point (textures at the pixel's
/// footprint); H_direct is gathered there from every emitter and light as a shot would
/// (direct_light.h), its first shadow rays ending at one of several sets of points per source,
/// drawn per subsample, and in a penumbra the solver's penumbra rounds for every emitter
/// (GatherSettings::penumbra_every_source), so a penumbra is smooth; H_bounced is the solution's H
/// less its direct part at each vertex (gathered again there with the shots' own ends, never below
/// 0), interpolated over the leaf element that holds the point. Deterministic: the same bytes for
/// any thread count. `progress`, when given, is told the fraction done from this thread.
Image render_gathered_image(const SolverState& s, const VisibilityBackend& vis,
                            const Camera& camera, const GatheredImageOptions& o,
                            GatheredImageStats* stats = nullptr,
                            const std::function<void(double)>& progress = {});

}  // namespace rad
