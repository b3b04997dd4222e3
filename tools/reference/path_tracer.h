// An independent estimate of radiosity at points of a scene, by Monte Carlo path tracing: the
// reference rad's solver is measured against (tools/reference, scenes/reference).
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "reference/compare.h"
#include "reference/ray_scene.h"
#include "reference/reference_set.h"
#include "reference/rng.h"

namespace rad {

struct TraceOptions {
  uint64_t seed = 1;
  /// Sample every point until the standard error of each channel is at most this fraction of
  /// that channel's mean radiosity over all points (or max_samples is reached).
  double target_stderr = 0.002;
  uint64_t pilot_samples = 1024;  // per point, before the mean radiosity is known
  uint64_t min_batch = 1024;      // smallest number of samples added at a time
  uint64_t max_samples = uint64_t(1) << 22;
  int roulette_depth = 3;  // bounces before Russian roulette starts
  /// false: no next-event estimation, emission counted only where a path hits an emitter
  /// (much noisier; a check on the MIS weights).
  bool next_event = true;
  /// Bounces after the first surface (0: direct light only); < 0: no limit. For diagnosis.
  int max_bounces = -1;
};

/// Path tracer over a hierarchy's triangles with rad's model: Lambertian, one-sided (only the
/// front face, normal (b - a) x (c - a), emits and reflects; back faces are black), emission
/// E as exitance, radiance of a surface point L = B / pi; textures vary reflectance and
/// emission texel by texel, and rays pass through cut-outs' holes (surface_at, RayScene).
///
/// Method: Kajiya 1986 path tracing ("The Rendering Equation", SIGGRAPH 1986), written for
/// irradiance H(x) = integral of L_in cos(theta) dw over the hemisphere of x:
///   H(x) = integral of (E(y) + rho(y) H(y)) cos / pi dw,   y = the surface point seen along w.
/// Each path vertex samples a direction by the cosine (pdf cos / pi), whose estimator is
/// E(y) + rho(y) H(y), and continues from y with throughput x rho(y). The emission term E(y)
/// is also estimated by next-event estimation: one point on the emitting triangles, chosen by
/// power and uniform in area, with a shadow ray. The two estimates of E are combined by
/// multiple importance sampling with the power heuristic (Veach & Guibas, "Optimally
/// Combining Sampling Techniques for Monte Carlo Rendering", SIGGRAPH 1995), so emission is
/// counted once and the variance stays bounded even where emitters meet other surfaces at an
/// edge (NEE alone has infinite variance there: G ~ 1/r^2). Russian roulette from
/// `roulette_depth` bounces on, with survival = the hit surface's largest reflectance.
class PathTracer {
 public:
  /// Keeps a pointer to `h`, which must outlive the tracer. Throws rad::Error if Embree fails.
  PathTracer(const Hierarchy& h, int roulette_depth = 3, bool next_event = true,
             int max_bounces = -1);

  /// One sample of the irradiance H at point p with front normal n (exitance units: in a
  /// uniform diffuse environment of radiosity B0, H = B0). Thread-safe; the calling thread
  /// must hold a FlushDenormals.
  DVec3 sample_irradiance(const Vec3& p, const Vec3& n, Pcg32& rng) const;

  /// One sample of the radiosity B = E + rho H at a point on triangle `triangle`.
  DVec3 sample_radiosity(const ReferencePoint& point, Pcg32& rng) const;

  /// The nearest surface along from + s w, s in (0, tfar): a front face where one is
  /// coincident with the nearest back face (see sample_irradiance), else whatever is nearest.
  RayHit first_hit(const Vec3& from, const Vec3& w, float tfar) const;

  const Material& material(int32_t triangle) const;

  /// rad::surface_at of the tracer's hierarchy, knowing which triangles are textured.
  TexelSurface surface_at(int32_t triangle, const Vec3& x) const;
  /// Distance by which ray origins leave their surface (a fraction of the scene's diagonal).
  float offset() const { return offset_; }

 private:
  DVec3 direct(const Vec3& p, const Vec3& n, Pcg32& rng) const;
  /// Solid-angle pdf with which direct() picks the point y of emitting triangle `tri`, seen
  /// from a point at distance^2 r2 under cosine cos_y at y.
  double light_pdf(int32_t tri, double r2, double cos_y) const;

  const Hierarchy* h_;
  RayScene scene_;
  std::vector<uint8_t> textured_;  // per triangle: is_textured (solver/texture_factors.h)
  float offset_;
  int roulette_depth_;
  bool next_event_;
  int max_bounces_;
  std::vector<int32_t> emitters_;    // triangles with emission
  std::vector<double> emitter_cdf_;  // by power (area x mean emission), last = 1
  std::vector<double> area_pdf_;     // per triangle: P(chosen) / area; 0 for non-emitters
};

/// What point x of triangle `tri` of `h` reflects and emits: its material's reflectance and
/// emission times its texture factors read at x alone (solver/texture_factors.h with no
/// footprint: the texel there; nothing in a cut-out's hole); `textured` when it has any
/// (is_textured), else the material's.
TexelSurface surface_at(const Hierarchy& h, size_t tri, const Vec3& x);

/// What estimate_radiosity did.
struct TraceStats {
  uint64_t samples = 0;                // paths over all points
  DVec3 mean_radiosity{0.0};           // per channel, over the points
  double worst_relative_stderr = 0.0;  // max over points and channels of stderr / channel mean
  uint64_t points_at_max_samples = 0;
  double seconds = 0.0;
};

/// The radiosity at every point, parallel over points (TBB). Point i draws from its own random
/// stream (seed, i), and how long it is sampled depends only on its own samples and the pilot
/// mean, so results are identical for any thread count. `progress` (optional) is called with
/// the number of points finished, from worker threads, serialised.
std::vector<ReferenceValue> estimate_radiosity(
    const Hierarchy& h, std::span<const ReferencePoint> points, const TraceOptions& options,
    TraceStats* stats = nullptr,
    const std::function<void(size_t done, size_t total)>& progress = {});

}  // namespace rad
