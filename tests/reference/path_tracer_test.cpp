// The reference path tracer against scenes with closed-form radiosity, and its determinism.
#include "reference/path_tracer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "reference/reference_points.h"
#include "scene/parser.h"

namespace rad {
namespace {

Hierarchy load(const char* name) {
  return build_hierarchy(parse_scene_file(std::string(RAD_SOURCE_DIR) + "/scenes/" + name));
}

// Form factor from a differential area at height d above the corner of an A x B rectangle in
// a parallel plane (d = 1 units; A, B signed so rectangles can be subtracted).
double corner_rectangle(double a, double b) {
  const double sa = std::sqrt(1.0 + a * a), sb = std::sqrt(1.0 + b * b);
  return (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb)) / (2.0 * std::numbers::pi);
}

// From a differential area at (x, y), facing the square [0, 1]^2 one unit away, to that square:
// the sum over the four rectangles with a corner below the point.
double point_to_unit_square(double x, double y) {
  double f = 0.0;
  for (double a : {1.0 - x, x}) {
    for (double b : {1.0 - y, y}) f += corner_rectangle(a, b);
  }
  return f;
}

TEST(ParallelSquares, DifferentialFormFactorMatchesPublishedValues) {
  // At the centre: 4 x the corner form factor of a 0.5 x 0.5 rectangle.
  EXPECT_NEAR(point_to_unit_square(0.5, 0.5), 0.2394565, 1e-7);
  // Averaged over the receiver it is the square-to-square form factor 0.19982.
  double mean = 0.0;
  const int n = 200;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) mean += point_to_unit_square((i + 0.5) / n, (j + 0.5) / n);
  }
  EXPECT_NEAR(mean / (n * n), 0.19982, 2e-5);
}

TEST(PathTracer, FurnaceBoxIsTwoEverywhere) {
  const Hierarchy h = load("furnace_box.des");
  PointOptions po;
  po.total = 96;
  po.min_per_triangle = 8;
  const std::vector<ReferencePoint> points = make_reference_points(h.triangles, po);
  TraceOptions to;
  to.pilot_samples = 512;
  to.target_stderr = 0.001;
  TraceStats stats;
  const std::vector<ReferenceValue> values = estimate_radiosity(h, points, to, &stats);
  ASSERT_EQ(values.size(), points.size());
  DVec3 mean(0.0);
  double worst = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double b = values[i].radiosity[c], se = values[i].standard_error[c];
      EXPECT_LE(se, 0.001 * 2.0 * 1.05) << "point " << i;
      EXPECT_NEAR(b, 2.0, 5.0 * se + 1e-9) << "point " << i << " channel " << c;
      worst = std::max(worst, std::abs(b - 2.0) / 2.0);
    }
    mean += values[i].radiosity;
  }
  mean /= double(values.size());
  std::printf(
      "furnace box: %zu points, %llu paths, %.2f s; mean B %.5f %.5f %.5f (exact 2), worst "
      "point %.3f%%\n",
      points.size(), (unsigned long long)stats.samples, stats.seconds, mean.x, mean.y, mean.z,
      100.0 * worst);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], 2.0, 2.0 * 0.0005);
}

TEST(PathTracer, ParallelSquaresReceiverMatchesPointFormFactor) {
  const Hierarchy h = load("parallel_squares.des");
  PointOptions po;
  po.total = 200;
  // Only the receiver (the target stderr is relative to the mean over the points given).
  std::vector<ReferencePoint> points;
  for (const ReferencePoint& p : make_reference_points(h.triangles, po)) {
    if (h.objects[size_t(h.triangles.object[size_t(p.triangle)])].material.emission.x == 0.0f) {
      points.push_back(p);
    }
  }
  TraceOptions to;
  to.pilot_samples = 512;
  to.target_stderr = 0.001;
  TraceStats stats;
  const std::vector<ReferenceValue> values = estimate_radiosity(h, points, to, &stats);
  double sum_signed = 0.0, sum_error = 0.0, sum_exact = 0.0, worst = 0.0, worst_sigmas = 0.0;
  size_t receivers = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const ReferencePoint& p = points[i];
    const Material& m = h.objects[size_t(h.triangles.object[size_t(p.triangle)])].material;
    ASSERT_EQ(m.emission, Vec3(0.0f));
    ++receivers;
    ASSERT_NEAR(p.position.z, 1.0f, 1e-6f);
    const double exact = 0.5 * 1.0 * point_to_unit_square(p.position.x, p.position.y);
    for (int c = 0; c < 3; ++c) {
      const double b = values[i].radiosity[c], se = values[i].standard_error[c];
      EXPECT_NEAR(b, exact, 5.0 * se)
          << "point " << i << " at " << p.position.x << ", " << p.position.y;
      sum_signed += b - exact;
      sum_error += std::abs(b - exact);
      sum_exact += exact;
      worst = std::max(worst, std::abs(b - exact) / exact);
      worst_sigmas = std::max(worst_sigmas, std::abs(b - exact) / se);
    }
  }
  EXPECT_GT(receivers, 50u);
  std::printf(
      "parallel squares: %zu receiver points, %llu paths, %.2f s; mean |error| %.3f%% of "
      "the mean, bias %+.3f%%, worst point %.3f%% (%.1f standard errors)\n",
      receivers, (unsigned long long)stats.samples, stats.seconds, 100.0 * sum_error / sum_exact,
      100.0 * sum_signed / sum_exact, 100.0 * worst, worst_sigmas);
  EXPECT_LT(sum_error / sum_exact, 0.0015);
  EXPECT_LT(std::abs(sum_signed) / sum_exact, 0.0005);
}

TEST(PathTracer, NextEventEstimationAgreesWithHemisphereSamplingOnCornellBox) {
  // The same points estimated with NEE + MIS and with emission counted only on hits: two
  // estimators sharing no emission code must agree within their errors (catches double
  // counting or a wrong MIS weight, which the analytic scenes might not).
  const Hierarchy h = load("cornell_box.des");
  PointOptions po;
  po.total = 0;
  po.min_per_triangle = 1;
  const std::vector<ReferencePoint> points = make_reference_points(h.triangles, po);
  TraceOptions to;
  to.target_stderr = 1.0;  // the pilot only: a fixed number of samples per point
  to.pilot_samples = 10000;
  const std::vector<ReferenceValue> nee = estimate_radiosity(h, points, to);
  to.next_event = false;
  to.pilot_samples = 100000;
  const std::vector<ReferenceValue> hits = estimate_radiosity(h, points, to);
  double sum_diff = 0.0, sum_var = 0.0, sum_b = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const double d = hits[i].radiosity[c] - nee[i].radiosity[c];
      const double var =
          std::pow(hits[i].standard_error[c], 2) + std::pow(nee[i].standard_error[c], 2);
      EXPECT_LE(std::abs(d), 5.0 * std::sqrt(var) + 1e-12) << "point " << i << " channel " << c;
      if (h.objects[size_t(h.triangles.object[size_t(points[i].triangle)])].material.emission.x >
          0) {
        continue;  // emitters: the emission, identical in both, would hide the comparison
      }
      sum_diff += d;
      sum_var += var;
      sum_b += nee[i].radiosity[c];
    }
  }
  std::printf(
      "Cornell box, %zu points: hits-only minus NEE = %+.3f%% of the reflected radiosity "
      "(+- %.3f%%)\n",
      points.size(), 100.0 * sum_diff / sum_b, 100.0 * std::sqrt(sum_var) / sum_b);
  EXPECT_LE(std::abs(sum_diff), 4.0 * std::sqrt(sum_var));
}

TEST(PathTracer, ResultsDoNotDependOnThreadCount) {
  const Hierarchy h = load("cornell_box.des");
  PointOptions po;
  po.total = 40;
  po.min_per_triangle = 1;
  const std::vector<ReferencePoint> points = make_reference_points(h.triangles, po);
  TraceOptions to;
  to.pilot_samples = 64;
  to.min_batch = 64;
  to.max_samples = 256;
  std::vector<ReferenceValue> one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = estimate_radiosity(h, points, to);
  }
  many = estimate_radiosity(h, points, to);
  ASSERT_EQ(one.size(), many.size());
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].radiosity, many[i].radiosity) << "point " << i;
    EXPECT_EQ(one[i].standard_error, many[i].standard_error) << "point " << i;
    EXPECT_EQ(one[i].samples, many[i].samples) << "point " << i;
  }
}

TEST(PathTracer, BackFacesAreBlack) {
  // The parallel squares seen from behind the receiver: a point on the emitter's back side
  // gets nothing, so a receiver turned away from the emitter stays black.
  SceneDescription s;
  s.name = "back";
  ObjectDescription emitter;
  emitter.name = "emitter";
  emitter.material = {Vec3(0.0f), Vec3(1.0f)};
  emitter.triangles = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)}};
  ObjectDescription receiver;
  receiver.name = "receiver";
  receiver.material = {Vec3(0.5f), Vec3(0.0f)};
  receiver.triangles = {{Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1)}};  // faces +z: away
  s.objects = {emitter, receiver};
  s.roots = {0, 1};
  const Hierarchy h = build_hierarchy(s);
  const PathTracer tracer(h);
  Pcg32 rng(1, 0);
  FlushDenormals denormals;
  const ReferencePoint p = point_on_triangle(h.triangles, 1, 0.3f, 0.3f);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(tracer.sample_radiosity(p, rng), DVec3(0.0));
}

TEST(PathTracer, AFrontFaceWinsOverACoincidentBackFace) {
  // Two rooms' walls back to back: the unit emitter square at z = 0 facing +z, and a black wall
  // on the same square facing -z. A receiver at z = 1 sees the emitter, whichever of the two
  // coplanar triangles Embree reports first (hemisphere sampling alone: every path's hit counts).
  SceneDescription s;
  s.name = "back to back";
  ObjectDescription emitter, wall, receiver;
  emitter.name = "emitter";
  emitter.material = {Vec3(0.0f), Vec3(1.0f)};
  emitter.triangles = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)},
                       {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}};
  wall.name = "wall";
  wall.material = {Vec3(0.0f), Vec3(0.0f)};
  wall.triangles = {{Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, 0, 0)},
                    {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)}};
  receiver.name = "receiver";
  receiver.material = {Vec3(0.5f), Vec3(0.0f)};
  receiver.triangles = {{Vec3(0, 0, 1), Vec3(1, 1, 1), Vec3(1, 0, 1)}};  // faces -z
  for (const ObjectDescription& o : {wall, emitter, receiver}) {
    s.roots.push_back(int32_t(s.objects.size()));
    s.objects.push_back(o);
  }
  const Hierarchy h = build_hierarchy(s);
  const PathTracer tracer(h, 3, /*next_event=*/false);
  Pcg32 rng(7, 0);
  FlushDenormals denormals;
  const ReferencePoint p = point_on_triangle(h.triangles, 4, 0.5f, 0.25f);
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += tracer.sample_radiosity(p, rng).x;
  const double exact = 0.5 * point_to_unit_square(p.position.x, p.position.y);
  // Each path gives 0.5 (it meets the emitter, p ~ 0.2) or 0: standard error ~0.45% of the
  // mean, so 2% is 4.4 of them; taking the back face loses about half the hits (-50%).
  EXPECT_NEAR(sum / n, exact, 0.02 * exact);
}

TEST(PathTracer, EmitterThatReflectsNothingShowsItsEmission) {
  const Hierarchy h = load("parallel_squares.des");
  const PathTracer tracer(h);
  Pcg32 rng(1, 0);
  FlushDenormals denormals;
  for (int32_t t = 0; t < int32_t(h.triangles.size()); ++t) {
    if (tracer.material(t).emission.x == 0.0f) continue;
    const ReferencePoint p = point_on_triangle(h.triangles, t, 0.2f, 0.3f);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(tracer.sample_radiosity(p, rng), DVec3(1.0));
  }
}

}  // namespace
}  // namespace rad
