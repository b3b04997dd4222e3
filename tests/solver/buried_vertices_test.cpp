// Vertices inside solids gather just outside them; vertices beyond a wall stay where they are.
#include "solver/buried_vertices.h"

#include <gtest/gtest.h>

#include <cmath>

#include "mesh/subdivide.h"
#include "scene_builder.h"
#include "solver/edits.h"
#include "solver/solver.h"

namespace rad {
namespace {

// A closed box [lo, hi] with its faces towards the outside: a solid.
void add_solid_box(SceneDescription& d, const std::string& name, Vec3 lo, Vec3 hi) {
  const Vec3 p[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z},
                     {lo.x, hi.y, lo.z}, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z},
                     {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  const Vec3 rho(0.5f), e(0.0f);
  testing::add_quad(d, name + " bottom", p[0], p[3], p[2], p[1], rho, e);  // normal -z
  testing::add_quad(d, name + " top", p[4], p[5], p[6], p[7], rho, e);     // +z
  testing::add_quad(d, name + " front", p[0], p[1], p[5], p[4], rho, e);   // -y
  testing::add_quad(d, name + " back", p[3], p[7], p[6], p[2], rho, e);    // +y
  testing::add_quad(d, name + " left", p[0], p[4], p[7], p[3], rho, e);    // -x
  testing::add_quad(d, name + " right", p[1], p[2], p[6], p[5], rho, e);   // +x
}

// A board [0, 1] x [0, 1] at z = 0 facing up (triangles 0 and 1), then whatever `more` adds.
template <typename More>
Hierarchy board_and(More more) {
  SceneDescription d;
  testing::add_quad(d, "board", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Vec3(0.5f), Vec3(0));
  more(d);
  return build_hierarchy(d);
}

class BuriedVertexTest : public ::testing::TestWithParam<BackendKind> {};

// The board's end x > 0.98 is sunk into a panel 4 cm thick (x from 0.98 to 1.02): its corners
// there lie inside the panel and move just past the panel's face at x = 0.98, along the way to
// their triangle's centroid; the corners at x = 0 stay.
TEST_P(BuriedVertexTest, AVertexInsideASolidGathersJustOutsideIt) {
  const Hierarchy h = board_and([](SceneDescription& d) {
    add_solid_box(d, "panel", {0.98f, -0.5f, -0.5f}, {1.02f, 1.5f, 0.5f});
  });
  const auto vis = make_visibility_backend(GetParam(), h);
  const float offset = shadow_offset(h.bounds);
  VisibilityStats stats;
  for (size_t p = 0; p < 2; ++p) {
    for (const Vec3& x : h.triangles.corners[p]) {
      const Vec3 at = find_gather_point(h.triangles, p, x, *vis, {offset, 1.0f}, stats);
      if (x.x < 0.5f) {
        EXPECT_EQ(at, x);
        continue;
      }
      EXPECT_LT(at.x, 0.98f) << "corner (" << x.x << ", " << x.y << ") of triangle " << p;
      EXPECT_GT(at.x, 0.98f - 20.0f * offset);
      EXPECT_NEAR(at.z, 0.0f, 1e-6f);  // on the board's plane
      // Along the way to the centroid.
      const Vec3 to_c = glm::normalize(h.triangles.centroid(p) - x);
      EXPECT_GT(glm::dot(glm::normalize(at - x), to_c), 0.9999f);
      // Deeper inside than the probe's depth (2 cm in, 1 cm allowed): it stays, dark.
      EXPECT_EQ(find_gather_point(h.triangles, p, x, *vis, {offset, 0.01f}, stats), x);
    }
  }
}

// A box stands on the board, another on the box: the upper box's bottom and the lower box's top
// are one plane, back to back, and the upper one's triangles come first, so the way straight up
// from inside the lower box meets the upper box's bottom first, from the front. A vertex of the
// board under the lower box is inside it all the same (the way back from its probe leaves the
// box through a face met from behind) and gathers just past the box's side.
TEST_P(BuriedVertexTest, AVertexUnderABoxWithAnotherOnTopGathersBesideIt) {
  const Hierarchy h = board_and([](SceneDescription& d) {
    add_solid_box(d, "upper", {0.3f, 0.35f, 0.2f}, {0.55f, 0.7f, 0.4f});
    add_solid_box(d, "lower", {0.3f, 0.35f, 0.0f}, {0.55f, 0.7f, 0.2f});
  });
  const auto vis = make_visibility_backend(GetParam(), h);
  const float offset = shadow_offset(h.bounds);
  VisibilityStats stats;
  // On triangle 0, whose centroid (2/3, 1/3) lies beside the box; the way back from it leaves
  // the box through the middle of its face x = 0.3.
  const Vec3 x(0.4f, 0.55f, 0.0f);
  const Vec3 at = find_gather_point(h.triangles, 0, x, *vis, {offset, 1.0f}, stats);
  EXPECT_GT(at.x, 0.55f);
  EXPECT_LT(at.x, 0.55f + 20.0f * offset);
  EXPECT_NEAR(at.z, 0.0f, 1e-6f);
}

// The board runs under a wall 2 cm thick at x = 0.5 into the next room: its corners beyond the
// wall are outside every solid (the probe meets the wall's front) and stay where they are.
TEST_P(BuriedVertexTest, AVertexBeyondAWallStaysWhereItIs) {
  const Hierarchy h = board_and([](SceneDescription& d) {
    add_solid_box(d, "wall", {0.49f, -0.5f, -0.5f}, {0.51f, 1.5f, 1.0f});
  });
  const auto vis = make_visibility_backend(GetParam(), h);
  VisibilityStats stats;
  for (size_t p = 0; p < 2; ++p) {
    for (const Vec3& x : h.triangles.corners[p]) {
      EXPECT_EQ(find_gather_point(h.triangles, p, x, *vis, {shadow_offset(h.bounds), 1.0f}, stats),
                x);
    }
  }
}

// Every backend moves every vertex to the same point.
TEST(BuriedVerticesAgreement, EveryBackendMovesTheVerticesAlike) {
  const Hierarchy h = board_and([](SceneDescription& d) {
    add_solid_box(d, "panel", {0.98f, -0.5f, -0.5f}, {1.02f, 1.5f, 0.5f});
    add_solid_box(d, "leg", {-0.01f, -0.01f, -0.5f}, {0.03f, 0.03f, 0.02f});
  });
  const Mesh mesh = make_solver_state(h, {}).solution.mesh;
  std::vector<BuriedVertices> found;
  for (BackendKind k : {BackendKind::Embree, BackendKind::Grid, BackendKind::Brute}) {
    const auto vis = make_visibility_backend(k, h);
    VisibilityStats stats;
    found.push_back(
        find_all_buried_vertices(h.triangles, mesh, *vis, {shadow_offset(h.bounds), 1.0f}, stats));
  }
  size_t moved = 0;
  for (size_t p = 0; p < mesh.polygons.size(); ++p) {
    moved += found[0].moved[p].size();
    for (size_t b = 1; b < found.size(); ++b) {
      ASSERT_EQ(found[b].moved[p].size(), found[0].moved[p].size());
      for (size_t i = 0; i < found[0].moved[p].size(); ++i) {
        EXPECT_EQ(found[b].moved[p][i].vertex, found[0].moved[p][i].vertex);
        EXPECT_EQ(found[b].moved[p][i].at, found[0].moved[p][i].at);
      }
    }
  }
  EXPECT_GT(moved, 2u);
}

// Lit from above, the board's corners sunk 5 mm into the panel gather about what the board gets
// just beside the panel, not the nothing a point inside it sees.
TEST_P(BuriedVertexTest, ASunkCornerGathersWhatTheBoardGetsBesideTheSolid) {
  const Hierarchy h = board_and([](SceneDescription& d) {
    add_solid_box(d, "panel", {0.995f, -0.5f, -0.5f}, {1.035f, 1.5f, 0.5f});
    testing::add_quad(d, "lamp", {0.2f, 0.2f, 1}, {0.2f, 0.8f, 1}, {0.8f, 0.8f, 1}, {0.8f, 0.2f, 1},
                      Vec3(0), Vec3(1));
  });
  const auto vis = make_visibility_backend(GetParam(), h);
  SolverOptions o;
  o.max_shots = 1;
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  const PolygonMesh& m = s.solution.mesh.polygons[0];
  // Triangle 0 is (0,0) (1,0) (1,1): vertices 1 and 2 lie in the panel.
  const float sunk = s.solution.vertex_states[0][1].irradiance.x;
  const float open = s.solution.vertex_states[0][0].irradiance.x;
  EXPECT_GT(m.positions[1].x, 0.995f);
  EXPECT_GT(open, 0.05f);
  EXPECT_GT(sunk, 0.5f * open) << "a corner inside the panel gathers as if outside it";
}

// After the lamp's shot, a board's corner sunk into a panel holds, to shoot, what it gathers times
// the board's reflectance when it lies just under the panel's face (1 mm, within kShootingDepth of
// the smallest size: the visible part of its elements reflects that light), and nothing when
// deeper (5 mm: its polygon might cross a panel thinner than its elements, whose other side it
// would light).
TEST_P(BuriedVertexTest, ACornerJustUnderAFaceShootsWhatItGathersADeeperOneNothing) {
  for (const float sunk : {0.001f, 0.005f}) {
    const Hierarchy h = board_and([&](SceneDescription& d) {
      add_solid_box(d, "panel", {1.0f - sunk, -0.5f, -0.5f}, {1.04f - sunk, 1.5f, 0.5f});
      testing::add_quad(d, "lamp", {0.2f, 0.2f, 1}, {0.2f, 0.8f, 1}, {0.8f, 0.8f, 1},
                        {0.8f, 0.2f, 1}, Vec3(0), Vec3(1));
    });
    const auto vis = make_visibility_backend(GetParam(), h);
    SolverOptions o;
    o.max_shots = 1;
    SolverState s = make_solver_state(h, o);
    solve(s, *vis);
    // Triangle 0 is (0,0) (1,0) (1,1): its vertex 1 lies in the panel, moved 1.4 sunk along the
    // way to the centroid.
    ASSERT_TRUE(s.scene.buried.is_moved(0, 1)) << "sunk " << sunk;
    const float reach = kShootingDepth * s.scene.min_size;
    ASSERT_EQ(1.5f * sunk < reach, sunk == 0.001f) << "the smallest size is " << s.scene.min_size;
    const VertexState& corner = s.solution.vertex_states[0][1];
    EXPECT_GT(corner.irradiance.x, 0.05f);
    if (sunk == 0.001f) {
      EXPECT_FLOAT_EQ(corner.unshot.x, 0.5f * corner.irradiance.x);
    } else {
      EXPECT_EQ(corner.unshot.x, 0.0f);
    }
  }
}

// Without shadows nothing blocks a buried vertex's view: no vertex moves, those made by
// refinement or by an edit included, and a restored checkpoint has none to forget.
TEST(BuriedVertices, WithoutShadowsNoVertexMovesNotEvenOneMadeLater) {
  const Hierarchy h = board_and([](SceneDescription& d) {
    add_solid_box(d, "panel", {0.995f, -0.5f, -0.5f}, {1.035f, 1.5f, 0.5f});
    testing::add_quad(d, "lamp", {0.2f, 0.2f, 1}, {0.2f, 0.8f, 1}, {0.8f, 0.8f, 1}, {0.8f, 0.2f, 1},
                      Vec3(0), Vec3(1));
  });
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  o.shadows = false;
  o.max_shots = 6;
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  force_subdivide(edit_context(s), 0, *vis);
  ASSERT_TRUE(s.scene.buried.found);
  for (size_t p = 0; p < s.scene.buried.moved.size(); ++p)
    EXPECT_TRUE(s.scene.buried.moved[p].empty()) << "polygon " << p;
}

// A box standing 1 mm above the board, under a lamp: the board's vertices under the box are
// covered, the others not, and refinement splits the elements across the footprint's edge below
// the smallest size (the light falls from the open board's to nothing within millimetres of it)
// and no others.
TEST(BuriedVertices, ElementsAcrossTheEdgeOfACoverSplitBelowTheSmallestSize) {
  const Hierarchy h = board_and([](SceneDescription& d) {
    add_solid_box(d, "box", {0.3f, 0.3f, 0.001f}, {0.7f, 0.7f, 0.2f});
    testing::add_quad(d, "lamp", {0.2f, 0.2f, 1}, {0.2f, 0.8f, 1}, {0.8f, 0.8f, 1}, {0.8f, 0.2f, 1},
                      Vec3(0), Vec3(1));
  });
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  o.max_shots = 6;
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  const float min_size = s.scene.min_size;
  auto under_box = [](const Vec3& x) {
    return x.x > 0.3f && x.x < 0.7f && x.y > 0.3f && x.y < 0.7f;
  };
  // Distance from the footprint's outline.
  auto from_edge = [](const Vec3& x) {
    const float dx = std::max(0.3f - x.x, x.x - 0.7f), dy = std::max(0.3f - x.y, x.y - 0.7f);
    if (dx <= 0.0f && dy <= 0.0f) return -std::max(dx, dy);  // inside: to the nearest side
    return std::hypot(std::max(dx, 0.0f), std::max(dy, 0.0f));
  };
  size_t covered = 0, small = 0;
  for (size_t p = 0; p < 2; ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      if (!s.scene.buried.is_covered(p, v)) continue;
      ++covered;
      EXPECT_TRUE(under_box(m.positions[v])) << "a covered vertex outside the footprint";
    }
    for_each_leaf(m, [&](uint32_t e) {
      if (element_size(m, e) >= min_size) return;
      ++small;
      Vec3 c(0.0f);
      for (uint32_t v : m.elements[e].v) c += m.positions[v] / 3.0f;
      EXPECT_LT(from_edge(c), 2.0f * min_size) << "a small element away from the edge";
    });
  }
  EXPECT_GT(covered, 0u);
  EXPECT_GT(small, 0u) << "elements across the footprint's edge split below the smallest size";
}

INSTANTIATE_TEST_SUITE_P(AllBackends, BuriedVertexTest,
                         ::testing::Values(BackendKind::Embree, BackendKind::Grid,
                                           BackendKind::Brute),
                         [](const auto& test) { return std::string(to_string(test.param)); });

}  // namespace
}  // namespace rad
