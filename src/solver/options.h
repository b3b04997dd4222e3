// Settings of the progressive radiosity solver.
#pragma once

#include <cstddef>
#include <cstdint>

namespace rad {

/// How a receiving vertex turns the source's samples into a contribution.
enum class FormFactorMethod : uint8_t {
  /// EQ 7 as the original computes it: sum over samples of
  /// dB(s) vis cos cos (A/n) / (pi r^2 + A/n).
  Samples,
  /// The exact unoccluded point-to-polygon form factor (Baum et al. 1989) times the
  /// kernel-weighted mean over the samples of dB(s) * vis. Exact when nothing blocks and the
  /// source is uniform; the default (see the README for the measured errors).
  Analytic,
};

/// Which new midpoints get the current shot computed rather than interpolated.
enum class MidpointRule : uint8_t {
  /// The original's rule (design §5): only midpoints of edges whose ends differ by more than the
  /// limit; the others get the mean of their ends, which keeps an unsplit neighbour's edge
  /// free of discontinuity when T-vertices are drawn without being split.
  Interpolate,
  /// Every new midpoint. rad splits faces through T-vertices when it writes them, so computed
  /// values there show no discontinuity either, and a peak between two equal ends is not missed
  /// (interpolation misses a shadow or highlight that falls between two vertices).
  Exact,
};

/// "analytic" | "samples": the names --form-factor takes.
inline const char* to_string(FormFactorMethod m) {
  return m == FormFactorMethod::Samples ? "samples" : "analytic";
}

struct SolverOptions {
  bool shadows = true;  // false: every visibility term is 1 (-noshadows)
  /// A source polygon gets n = m^2 samples, m from sample_grid up to max_sample_grid: the
  /// least m that puts its samples no farther apart than the initial mesh's element size, or
  /// max_sample_grid when none in range does. Regular samples alias against occluders on a big
  /// source: a big wall with the fewest samples leaves the surfaces it lights too dark.
  int sample_grid = 4;
  int max_sample_grid = 8;
  FormFactorMethod method = FormFactorMethod::Analytic;
  /// Subdivision limit: split an element when two of its vertices differ by more than
  /// this fraction of the radiosity scale (in any channel).
  float subdivision_threshold = 0.05f;
  MidpointRule midpoints = MidpointRule::Exact;
  /// Smallest edge length an element may reach; <= 0 derives it from the scene: its size
  /// (scene_size, solver_state.h) over kMinSizeDivisor.
  float min_size = 0.0f;
  static constexpr float kMinSizeDivisor = 256.0f;
  /// Largest edge length an element starts with: polygons are split uniformly to this size
  /// before the first shot (<= 0 derives it from the scene). Subdivision only looks at
  /// vertices, so a light's peak in the middle of a big floor whose corners are all dim would
  /// otherwise never be seen (the Cornell floor lit by its light alone comes out far too dark
  /// with the bare 2-triangle floor). Derived: the scene's size over kMaxSizeDivisor, at least
  /// twice min_size.
  float max_size = 0.0f;
  static constexpr float kMaxSizeDivisor = 16.0f;
  /// Intensity cut: one shadow ray instead of one per sample for a vertex whose unoccluded gain
  /// from the shot is below this fraction of the radiosity scale (to the sample that weighs
  /// most: the gain is the unoccluded one if it is clear, else 0).
  float intensity_cut = 1e-4f;
  /// Russian roulette over far receivers (shot_source.h): a point whose gain from a shot is
  /// bounded below this fraction of the radiosity scale gathers only with a probability
  /// bound / level, its gain divided by it; the answer is the same on average and a shot costs
  /// the receivers near it. 0: every receiver gathers every shot.
  float roulette = 1e-2f;
  /// Penumbra rays: where a vertex's shadow rays to a shot's samples disagree (some blocked,
  /// some not: it sees part of the source), or its rays to the source's corners disagree with
  /// them, this many more rays per sample, each to a point of the sample's stratum drawn by a
  /// hash of the vertex with the odds of the light that point gives it, and the sample's
  /// visibility is the mean of these rays' answers. Every vertex sees
  /// the same points of a source through its first rays, so a penumbra would come in steps of
  /// one sample; the vertices that see all of a source or none of it pay nothing more but the
  /// corners' rays. Only for the shots of kPenumbraSampleShare. 0: off (a penumbra in steps).
  /// The final render's vertices gather their direct light again with the same rounds
  /// (solver/direct_light.h), so their bounced light stays exact (docs/solver.md).
  // 8: with refinement's bend and shadow-edge rules (refine.cpp) scenes/umbra.des comes within
  // 0.37% to 0.43% of its reference as built, scaled, cut finer, moved and turned, against
  // 0.52% to 0.93% with 0 (tools/bench_umbra, docs/solver.md). The 1M building
  // (tools/bench_lights, panels) casts no more rays: none of its shots is major.
  int penumbra_rays = 8;
  /// Penumbra rays go to the shots whose mean sample carries at least this fraction of the
  /// emitted energy: a lamp's first shot (its 16 samples step by a sixteenth of its light), not
  /// the walls' many shots over up to 64 samples, whose steps are small.
  static constexpr double kPenumbraSampleShare = 0.005;
  /// Stop when unshot energy <= converge x emitted energy.
  double converge = 1e-3;
  /// Shots carrying at least this fraction of the emitted energy are "major": a vertex created
  /// later by subdivision gathers them again exactly instead of interpolating their part from
  /// the edge's ends (0 keeps the original's pure interpolation). The first shots of the
  /// lights hold most of the energy and all the sharp shadows, so this is where interpolation
  /// errors came from.
  double major_shot_fraction = 0.02;
  /// Overshooting (Feda, Purgathofer 1992): each shooter also shoots its share of the ambient
  /// term and keeps it as negative unshot radiosity; the next shooter is the cluster with the
  /// most to shoot, share included (solver.cpp).
  bool overshoot = true;
  /// Occlusion culling (occlusion_culling.h): receivers that a flat occluder hides from a source
  /// get no shadow rays and no gain. The same result but for the gains taken with fewer rays
  /// than samples: under the intensity cut (one ray) and where no sample faces the receiver
  /// (none: the visible sliver of a source).
  bool occlusion_culling = true;
  /// Keep every shot in the shot log (an edit's new vertices gather them all again); false
  /// keeps the major ones only, all that a solve without edits gathers again: a batch solve of
  /// a large scene makes a hundred thousand shots of about 17 KiB each.
  bool log_minor_shots = true;
  /// Memory for shadow-ray answers kept between shots of the same cluster (kept_rays.h); 0: none.
  size_t kept_rays_bytes = size_t(128) << 20;
  int64_t max_shots = -1;   // < 0: no limit
  double time_limit = 0.0;  // seconds; <= 0: no limit
};

}  // namespace rad
