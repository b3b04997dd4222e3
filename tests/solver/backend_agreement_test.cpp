// Agreement of the outputs (docs/trust.md): every backend gives the same subdivision (the same
// vertices) and the same radiosity within 1e-5 of the largest, on every bundled scene, generated
// scenes and randomised ones (boxes that touch and share faces, triangle soups), where rays
// graze edges and vertices far more often than random rays do.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "scene/parser.h"
#include "scene_builder.h"
#include "scenegen/scenegen.h"
#include "solver/solver.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// A room with a light and n random boxes on a grid of 1/8 steps, so boxes touch, stack and
// share faces exactly.
SceneDescription random_boxes(int n, uint32_t seed) {
  SceneDescription d;
  d.name = "boxes";
  testing::add_closed_box(d, Vec3(0), Vec3(1), Vec3(0.6f), Vec3(0));
  testing::add_quad(d, "light", {0.375f, 0.375f, 0.999f}, {0.375f, 0.625f, 0.999f},
                    {0.625f, 0.625f, 0.999f}, {0.625f, 0.375f, 0.999f}, Vec3(0), Vec3(10));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cell(0, 6), size(1, 3);
  for (int i = 0; i < n; ++i) {
    const Vec3 lo = Vec3(float(cell(rng)), float(cell(rng)), float(cell(rng) / 2)) / 8.0f;
    const Vec3 hi =
        glm::min(lo + Vec3(float(size(rng)), float(size(rng)), float(size(rng))) / 8.0f, Vec3(1));
    // Outward faces: a box seen from outside is the inward box turned inside out.
    SceneDescription b;
    testing::add_closed_box(b, lo, hi, Vec3(0.3f + 0.1f * float(i % 5)), Vec3(0));
    for (ObjectDescription& o : b.objects) {
      for (auto& t : o.triangles) std::swap(t[1], t[2]);
      o.name = "box" + std::to_string(i) + " " + o.name;
      d.roots.push_back(int32_t(d.objects.size()));
      d.objects.push_back(std::move(o));
    }
  }
  return d;
}

// A random triangle soup in the unit cube with a light above it.
SceneDescription lit_soup(uint64_t n, uint64_t seed) {
  SceneDescription d = make_triangle_soup(n, seed);
  testing::add_quad(d, "light", {0.3f, 1.2f, 0.3f}, {0.7f, 1.2f, 0.3f}, {0.7f, 1.2f, 0.7f},
                    {0.3f, 1.2f, 0.7f}, Vec3(0), Vec3(10));
  return d;
}

struct Solved {
  std::vector<size_t> vertices;  // per polygon
  std::vector<Vec3> radiosity;
};

Solved solve_with(const Hierarchy& h, BackendKind kind, int shots, int penumbra_rays) {
  SolverOptions o;
  o.max_shots = shots;
  o.penumbra_rays = penumbra_rays;
  o.max_sample_grid = 4;  // 16 samples a shot: agreement, not accuracy, and brute force is slow
  SolverState s = make_solver_state(h, o);
  solve(s, *make_visibility_backend(kind, h));
  Solved out;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    out.vertices.push_back(s.solution.mesh.polygons[p].vertex_count());
    for (uint32_t v = 0; v < s.solution.mesh.polygons[p].vertex_count(); ++v)
      out.radiosity.push_back(s.solution.radiosity(p, v));
  }
  return out;
}

void expect_agreement(const std::string& name, const Hierarchy& h, int shots, bool with_brute,
                      int penumbra_rays = SolverOptions{}.penumbra_rays) {
  SCOPED_TRACE(name);
  const Solved embree = solve_with(h, BackendKind::Embree, shots, penumbra_rays);
  std::vector<BackendKind> others{BackendKind::Grid};
  if (with_brute) others.push_back(BackendKind::Brute);
  float largest = 0.0f;
  for (const Vec3& b : embree.radiosity) largest = std::max(largest, max_component(b));
  ASSERT_GT(largest, 0.0f);
  for (BackendKind k : others) {
    const Solved other = solve_with(h, k, shots, penumbra_rays);
    size_t differing = 0;
    for (size_t p = 0; p < embree.vertices.size(); ++p)
      differing += embree.vertices[p] != other.vertices[p];
    EXPECT_EQ(differing, 0u) << to_string(k) << ": polygons subdivided differently";
    if (differing) continue;
    float worst = 0.0f;
    for (size_t i = 0; i < embree.radiosity.size(); ++i) {
      worst = std::max(worst, max_component(glm::abs(embree.radiosity[i] - other.radiosity[i])));
    }
    std::printf(
        "[ agree    ] %-28s %6zu triangles, %7zu vertices: embree vs %-5s worst %.3g of the "
        "largest\n",
        name.c_str(), h.triangles.size(), embree.radiosity.size(), to_string(k), worst / largest);
    EXPECT_LE(worst / largest, 1e-5f) << to_string(k);
  }
}

TEST(BackendAgreement, EveryBundledSceneOnEveryBackend) {
  int scenes = 0;
  for (const auto& e : fs::directory_iterator(fs::path(RAD_SOURCE_DIR) / "scenes")) {
    if (e.path().extension() != ".des") continue;
    const Hierarchy h = build_hierarchy(parse_scene_file(e.path().string()));
    expect_agreement(e.path().filename().string(), h, 5, h.triangles.size() <= 300);
    ++scenes;
  }
  EXPECT_GE(scenes, 4);
}

TEST(BackendAgreement, GeneratedScenesAtASmallSize) {
  for (SceneKind kind : {SceneKind::CornellBox, SceneKind::Nested, SceneKind::TeapotInStadium,
                         SceneKind::Building, SceneKind::FurnishedRoom}) {
    const Hierarchy h = build_hierarchy(generate_scene(kind, 1500, 7));
    expect_agreement(std::string("generated ") + to_string(kind), h, 4, false);
  }
}

TEST(BackendAgreement, RandomBoxesThatTouchAndSoupsOnEveryBackend) {
  for (uint32_t seed : {2u, 3u}) {
    expect_agreement("random boxes, seed " + std::to_string(seed),
                     build_hierarchy(random_boxes(6, seed)), 5, true, 0);
  }
  expect_agreement("lit soup", build_hierarchy(lit_soup(150, 5)), 4, true, 0);
}

// Touching boxes put most vertices in a penumbra or a gap, whose rounds the brute-force oracle
// traces 5 times as long as the rest of the solve: one seed with the default penumbra rays (the
// bundled umbra scene's rounds are compared above).
TEST(BackendAgreement, RandomBoxesWithPenumbraRoundsOnEveryBackend) {
  expect_agreement("random boxes, seed 1", build_hierarchy(random_boxes(6, 1)), 5, true,
                   SolverOptions{}.penumbra_rays);
}

}  // namespace
}  // namespace rad
