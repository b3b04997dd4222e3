// Solver against analytic answers, run over every visibility backend.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_builder.h"
#include "solver/form_factor.h"
#include "solver/solver.h"

namespace rad {
namespace {

using testing::Solved;

std::unique_ptr<Solved> solve_scene(const SceneDescription& d, BackendKind kind,
                                    SolverOptions o = {}) {
  auto r = std::make_unique<Solved>();
  r->h = build_hierarchy(d);
  r->vis = make_visibility_backend(kind, r->h);
  r->s = make_solver_state(r->h, o);
  solve(r->s, *r->vis);
  return r;
}

// Calls f(position, radiosity, inside) for every vertex of every polygon of the named object.
// `inside` is where a vertex's radiosity is defined: the limit from inside its own polygon,
// approached towards the polygon's centroid (at a corner touching another surface the limit
// depends on the direction; elsewhere it is the value at the vertex).
template <typename F>
void for_each_vertex_of(const Solved& r, const std::string& name, F&& f) {
  for (size_t p = 0; p < r.h.triangles.size(); ++p) {
    if (r.h.objects[size_t(r.h.triangles.object[p])].name != name) continue;
    const PolygonMesh& m = r.s.solution.mesh.polygons[p];
    const Vec3 centroid = (m.positions[0] + m.positions[1] + m.positions[2]) / 3.0f;
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      f(m.positions[v], r.s.solution.radiosity(p, v),
        m.positions[v] + (centroid - m.positions[v]) * 1e-4f);
    }
  }
}

// Lambert's point-to-polygon form factor of a quad (two triangles), the reference.
double quad_form_factor(Vec3 x, Vec3 n, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  return double(point_to_triangle_form_factor(x, n, a, b, c)) +
         point_to_triangle_form_factor(x, n, a, c, d);
}

// Errors as the project states them: |B - B_ref| over the mean reference radiosity of the
// receiving surface (the normalisation of the Cornell box target).
struct ErrorSummary {
  std::vector<std::pair<double, double>> values;  // (B, B_ref)
  double mean = 0, worst = 0;
  void add(double b, double ref) { values.push_back({b, ref}); }
  void finish() {
    double ref_mean = 0;
    for (auto [b, r] : values) ref_mean += r;
    ref_mean /= double(values.size());
    for (auto [b, r] : values) {
      const double e = std::abs(b - r) / ref_mean;
      mean += e, worst = std::max(worst, e);
      if (e > 0.02) std::printf("  B %.5g, reference %.5g\n", b, r);
    }
    mean /= double(values.size());
  }
  int count() const { return int(values.size()); }
};

class AnalyticScenes : public ::testing::TestWithParam<BackendKind> {};

// A lamp that absorbs everything over a flat floor: one bounce, B = rho E F at every vertex.
TEST_P(AnalyticScenes, LampOverFloorMatchesLambertAtEveryVertex) {
  SceneDescription d;
  const float rho = 0.5f, e = 10.0f;
  // Pre-tessellated: vertex-based subdivision cannot see a peak that no vertex sees.
  testing::add_quad(d, "floor", {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, Vec3(rho), Vec3(0),
                    8);
  const Vec3 la(0.05f, -0.45f, 1), lb(0.05f, 0.05f, 1), lc(0.55f, 0.05f, 1), ld(0.55f, -0.45f, 1);
  testing::add_quad(d, "lamp", la, lb, lc, ld, Vec3(0), Vec3(e));
  const auto r = solve_scene(d, GetParam());
  ErrorSummary err;
  for_each_vertex_of(*r, "floor", [&](Vec3, Vec3 b, Vec3 q) {
    err.add(b.x, rho * e * quad_form_factor(q, {0, 0, 1}, la, lb, lc, ld));
  });
  err.finish();
  std::printf("lamp over floor: %d vertices, mean error %.4f%%, worst %.4f%%\n", err.count(),
              100 * err.mean, 100 * err.worst);
  EXPECT_GT(err.count(), 200) << "the floor should have been subdivided under the lamp";
  EXPECT_LE(err.mean, 0.005);
  EXPECT_LE(err.worst, 0.02);
}

// An emitting wall standing on a floor, sharing its edge: the vertices on the shared edge get
// the limit from inside the floor, not the 0 that a point exactly on the line would get.
TEST_P(AnalyticScenes, PerpendicularSquaresSharingAnEdgeMatchLambertAtEveryVertex) {
  SceneDescription d;
  const float rho = 0.5f, e = 10.0f;
  testing::add_quad(d, "floor", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Vec3(rho), Vec3(0));
  const Vec3 wa(0, 0, 0), wb(0, 1, 0), wc(0, 1, 1), wd(0, 0, 1);  // x = 0, facing +x
  testing::add_quad(d, "wall", wa, wb, wc, wd, Vec3(0), Vec3(e));
  const auto r = solve_scene(d, GetParam());
  ErrorSummary err;
  int on_edge = 0;
  for_each_vertex_of(*r, "floor", [&](Vec3 p, Vec3 b, Vec3 q) {
    on_edge += p.x == 0.0f;
    err.add(b.x, rho * e * quad_form_factor(q, {0, 0, 1}, wa, wb, wc, wd));
  });
  err.finish();
  std::printf(
      "perpendicular squares: %d vertices (%d on the shared edge), mean error %.4f%%, "
      "worst %.4f%%\n",
      err.count(), on_edge, 100 * err.mean, 100 * err.worst);
  EXPECT_GE(on_edge, 2);
  EXPECT_LE(err.mean, 0.005);
  EXPECT_LE(err.worst, 0.02);
}

// Lamp (half-width 0.2, height 2) above a blocker (half-width 0.5, height 1): floor points with
// |x|, |y| <= 0.8 see none of the lamp.
TEST_P(AnalyticScenes, VertexInFullUmbraGetsZero) {
  SceneDescription d;
  testing::add_quad(d, "floor", {-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}, Vec3(0.5f), Vec3(0),
                    8);
  testing::add_quad(d, "blocker", {-0.5f, -0.5f, 1}, {-0.5f, 0.5f, 1}, {0.5f, 0.5f, 1},
                    {0.5f, -0.5f, 1}, Vec3(0), Vec3(0));
  testing::add_quad(d, "lamp", {-0.2f, -0.2f, 2}, {-0.2f, 0.2f, 2}, {0.2f, 0.2f, 2},
                    {0.2f, -0.2f, 2}, Vec3(0), Vec3(10));
  const auto r = solve_scene(d, GetParam());
  // Polygon corners are computed exactly: 0. Midpoints added by subdivision on edges within the
  // limit are interpolated from their ends (design §5), so they may hold up to half the limit.
  const float limit = r->s.options.subdivision_threshold * r->s.energy.radiosity_scale;
  int umbra_corners = 0, lit = 0;
  for (size_t p = 0; p < r->h.triangles.size(); ++p) {
    if (r->h.objects[size_t(r->h.triangles.object[p])].name != "floor") continue;
    const PolygonMesh& m = r->s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      const Vec3 q = m.positions[v];
      const float b = r->s.solution.radiosity(p, v).x;
      if (std::max(std::abs(q.x), std::abs(q.y)) < 0.75f) {
        if (v < 3) {
          ++umbra_corners;
          EXPECT_EQ(b, 0.0f) << "at " << q.x << ", " << q.y;
        } else {
          EXPECT_LE(b, 0.5f * limit) << "at " << q.x << ", " << q.y;
        }
      } else if (std::max(std::abs(q.x), std::abs(q.y)) > 1.5f) {
        lit += b > 0.0f;
      }
    }
  }
  EXPECT_GE(umbra_corners, 9);
  EXPECT_GT(lit, 0);
}

// Closed box, uniform E and rho: B = E / (1 - rho) everywhere, and energy is conserved.
TEST_P(AnalyticScenes, FurnaceBoxConvergesToEOverOneMinusRho) {
  SceneDescription d;
  const float rho = 0.5f, e = 1.0f;
  testing::add_closed_box(d, Vec3(0), Vec3(1), Vec3(rho), Vec3(e), 2);
  SolverOptions o;
  o.max_size = 0.25f;  // a coarser initial mesh than the default diagonal / 16: three backends
  const auto r = solve_scene(d, GetParam(), o);
  const double expected = e / (1 - rho);
  double worst = 0;
  for (const char* face : {"bottom", "top", "front", "back", "left", "right"}) {
    for_each_vertex_of(*r, face, [&](Vec3, Vec3 b, Vec3) {
      worst = std::max(worst, std::abs(b.y - expected) / expected);
    });
  }
  const double balance =
      (r->s.energy.absorbed_energy + r->s.energy.unshot_abs_total) / r->s.energy.emitted_energy;
  std::printf("furnace: worst vertex error %.4f%%, (absorbed + unshot) / emitted = %.5f\n",
              100 * worst, balance);
  EXPECT_LE(worst, 0.005);
  EXPECT_NEAR(balance, 1.0, 0.01);
}

// A closed furnace with a block standing on its floor: every visible point still sees only
// surfaces of radiosity E/(1 - rho), so any systematic shortfall is visibility lost by the
// sampling of the sources (16 regular samples on each big face alias against the block:
// measured mean -0.33%, worst vertex 3.5% dark, which fails the worst-vertex bound; see
// SolverOptions::max_sample_grid).
TEST(FurnaceWithABlock, KeepsEOverOneMinusRhoEverywhereVisible) {
  SceneDescription d;
  const float rho = 0.5f, e = 1.0f;
  testing::add_closed_box(d, Vec3(0), Vec3(1), Vec3(rho), Vec3(e));
  const Vec3 lo(0.3f, 0.3f, 0.0f), hi(0.6f, 0.6f, 0.4f);  // on the bottom face (z = 0)
  const Vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                     {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                     {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  // Outward faces (no bottom: it would lie on the box's floor).
  testing::add_quad(d, "block", p[4], p[5], p[6], p[7], Vec3(rho), Vec3(e));  // top, +z
  testing::add_quad(d, "block", p[0], p[1], p[5], p[4], Vec3(rho), Vec3(e));  // y = lo, -y
  testing::add_quad(d, "block", p[3], p[7], p[6], p[2], Vec3(rho), Vec3(e));  // y = hi, +y
  testing::add_quad(d, "block", p[0], p[4], p[7], p[3], Vec3(rho), Vec3(e));  // x = lo, -x
  testing::add_quad(d, "block", p[1], p[2], p[6], p[5], Vec3(rho), Vec3(e));  // x = hi, +x
  const auto r = solve_scene(d, BackendKind::Embree);
  const double expected = e / (1 - rho);
  double sum = 0, worst = 0;
  size_t n = 0;
  for (const std::string face : {"bottom", "top", "front", "back", "left", "right", "block"}) {
    for_each_vertex_of(*r, face, [&](Vec3 x, Vec3 b, Vec3) {
      const bool under_block = face == "bottom" && x.x >= lo.x - 1e-5f && x.x <= hi.x + 1e-5f &&
                               x.y >= lo.y - 1e-5f && x.y <= hi.y + 1e-5f;
      if (under_block) return;  // hidden: sees nothing
      const double err = (b.y - expected) / expected;
      sum += err, worst = std::max(worst, std::abs(err)), ++n;
    });
  }
  std::printf("furnace with a block: %zu vertices, mean error %+.3f%%, worst %.3f%%\n", n,
              100 * sum / double(n), 100 * worst);
  // The bounds every analytic scene here is held to (mean 0.5%, worst 2%); the furnace
  // without a block meets the tighter 0.5% everywhere, but the block's base edges are contact
  // lines where a vertex's limit depends on the side it is approached from.
  EXPECT_LE(std::abs(sum / double(n)), 0.005);
  EXPECT_LE(worst, 0.02);
}

INSTANTIATE_TEST_SUITE_P(AllBackends, AnalyticScenes,
                         ::testing::Values(BackendKind::Embree, BackendKind::Grid,
                                           BackendKind::Brute),
                         [](const auto& param) { return std::string(to_string(param.param)); });

}  // namespace
}  // namespace rad
