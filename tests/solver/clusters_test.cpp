// Shooting clusters: how they are formed, their outline form factor, and energy balance per shot.
#include "solver/clusters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "scene_builder.h"
#include "solver/form_factor.h"
#include "solver/shoot.h"
#include "solver/solver.h"

namespace rad {
namespace {

SceneDescription quad_scene(int k) {
  SceneDescription d;
  testing::add_quad(d, "quad", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, Vec3(0.5f), Vec3(1), k);
  return d;
}

TEST(Clusters, ATessellatedQuadIsOneClusterWithAFourEdgeOutline) {
  for (int k : {1, 3, 8, 24}) {
    const Hierarchy h = build_hierarchy(quad_scene(k));
    const Clusters c = make_clusters(h, 100.0);
    ASSERT_EQ(c.size(), 1u) << k;
    EXPECT_EQ(c.polygon_count(0), h.triangles.size());
    EXPECT_EQ(c.edge_a.size(), 4u) << "collinear boundary runs merged, k = " << k;
    EXPECT_TRUE(c.planar[0]);
    EXPECT_NEAR(c.area[0], 1.0f, 1e-5f);
  }
}

TEST(Clusters, AreSplitToTheAreaAskedForWhateverTheTessellation) {
  for (int k : {1, 4, 16}) {
    const Hierarchy h = build_hierarchy(quad_scene(k));
    const Clusters c = make_clusters(h, 0.3);
    for (size_t i = 0; i < c.size(); ++i) {
      if (c.polygon_count(i) > 1) {
        EXPECT_LE(c.area[i], 0.3f + 1e-5f) << k;
      }
    }
    // k = 1: the two triangles (each larger than 0.3) stand alone; finer: four quarters.
    EXPECT_EQ(c.size(), k == 1 ? 2u : 4u) << k;
    for (size_t t = 0; t < h.triangles.size(); ++t) {
      const uint32_t ci = c.cluster_of[t];
      bool found = false;
      for (uint32_t j = c.first[ci]; j < c.first[ci + 1]; ++j) found |= c.polygons[j] == t;
      EXPECT_TRUE(found);
    }
  }
}

// The outline's contour (with its tangent-plane closing terms) against the sum of the exact
// clipped triangle form factors, for receivers all around, many of whose tangent planes cut the
// quad.
TEST(Clusters, OutlineFormFactorEqualsTheSumOverItsTriangles) {
  const Hierarchy h = build_hierarchy(quad_scene(6));
  const Clusters c = make_clusters(h, 100.0);
  ASSERT_EQ(c.size(), 1u);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.5f, 2.5f);
  std::normal_distribution<float> gauss;
  int cut = 0, compared = 0;
  for (int t = 0; t < 4000; ++t) {
    const Vec3 x(u(rng), u(rng), std::abs(u(rng)) * 0.5f + 0.01f);
    const Vec3 n = glm::normalize(Vec3(gauss(rng), gauss(rng), gauss(rng)));
    double want = 0.0;
    bool crosses = false;
    for (size_t i = 0; i < h.triangles.size(); ++i) {
      const auto& k = h.triangles.corners[i];
      want += point_to_triangle_form_factor(x, n, k[0], k[1], k[2], Arithmetic::Double);
      for (const Vec3& p : k) crosses |= glm::dot(p - x, n) < 0.0f;
    }
    const double got = point_to_outline_form_factor(x, n, c.edge_a.data(), c.edge_b.data(),
                                                    c.edge_a.size(), c.axis[0]);
    ASSERT_NEAR(got, want, 2e-6) << "x " << x.x << ' ' << x.y << ' ' << x.z;
    cut += crosses && want > 0.0;
    ++compared;
  }
  EXPECT_GT(cut, 1000) << "the clipped case is exercised";
}

Hierarchy sphere(int stacks) {
  SceneDescription d;
  ObjectDescription o;
  o.name = "sphere";
  o.material = {Vec3(0.5f), Vec3(0.0f)};
  const int slices = 2 * stacks;
  auto at = [&](int i, int j) {
    const float th = 3.14159265f * float(i) / float(stacks);
    const float ph = 2 * 3.14159265f * float(j) / float(slices);
    return Vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
  };
  for (int i = 0; i < stacks; ++i) {
    for (int j = 0; j < slices; ++j) {
      const Vec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), e = at(i, j + 1);
      if (i > 0) o.triangles.push_back({a, e, c});
      if (i + 1 < stacks) o.triangles.push_back({a, c, b});
    }
  }
  o.triangle_locs.resize(o.triangles.size());
  d.roots.push_back(0);
  d.objects.push_back(o);
  return build_hierarchy(d);
}

// A tessellated sphere makes face clusters, each within the cone, and about as many at any
// tessellation: not one cluster (one shot) per triangle.
TEST(Clusters, ACurvedMeshMakesFaceClustersWithABoundedNormalCone) {
  size_t counts[2];
  int i = 0;
  for (int stacks : {40, 160}) {
    const Hierarchy h = sphere(stacks);
    const Clusters c = make_clusters(h, 100.0);
    std::printf("sphere: %zu triangles, %zu clusters\n", h.triangles.size(), c.size());
    EXPECT_LT(c.size() * 10, h.triangles.size());
    for (size_t k = 0; k < c.size(); ++k) {
      EXPECT_GE(c.cone_cos[k], std::cos(2 * 25.0f * 3.14159265f / 180.0f) - 1e-4f);
    }
    counts[i++] = c.size();
  }
  EXPECT_LT(counts[1], 2 * counts[0]) << "16x the triangles, not many more clusters";
}

// In a closed scene every shot's power lands on the receivers: the power they gain (their `shot`
// values integrated over their leaf elements after refinement) equals the power shot (the
// samples' area times unshot radiosity), for every shot, however finely the walls are cut.
void expect_energy_balance(int k, int shots) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(1.0f), Vec3(0.5f), Vec3(1.0f), k);
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  // Without overshooting: an overshot source holds unshot radiosity of both signs, whose power
  // shot can be near 0 while its parts are not, and the error relative to it means nothing.
  // Without the roulette: it gives the receivers the power shot on average over its draws, not
  // at each shot (roulette_test.cpp checks the average).
  SolverOptions o;
  o.overshoot = false;
  o.roulette = 0.0f;
  SolverState s = make_solver_state(h, o);
  double worst = 0.0;
  for (int i = 0; i < shots; ++i) {
    for (std::vector<VertexState>& vs : s.solution.vertex_states)
      for (VertexState& v : vs) v.last_gain = Vec3(0.0f);
    if (!step(s, *vis)) break;
    const ShotSource& src = s.shots.sources.back();
    double shot_power = 0.0;
    for (size_t j = 0; j < src.sample_count; ++j) {
      shot_power += double(src.sample.area[j]) * double(mean_component(src.sample.value(j)));
    }
    double gained = 0.0;
    for (size_t q = 0; q < s.solution.mesh.polygons.size(); ++q) {
      const std::vector<VertexState>& vs = s.solution.vertex_states[q];
      for_each_leaf_vertex_sum(
          s.solution.mesh.polygons[q], [&](uint32_t v) { return vs[v].last_gain; },
          [&](float area, Vec3 sum) {
            gained += double(area) * double(mean_component(sum)) / 3.0;
          });
    }
    const double err = std::abs(gained / shot_power - 1.0);
    worst = std::max(worst, err);
    EXPECT_LE(err, 5e-3) << "k = " << k << ", shot " << i + 1 << ": gained " << gained << " of "
                         << shot_power;
  }
  std::printf("furnace k = %d: worst energy imbalance of a shot %.3f%% over %d shots\n", k,
              100.0 * worst, shots);
}

TEST(Clusters, EveryShotConservesEnergyInAClosedScene) {
  expect_energy_balance(1, 40);
  expect_energy_balance(16, 40);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

// The furnace box cut 8 x 8: every point at E / (1 - rho) = 2 whatever the tessellation (the
// area-weighted mean within 0.5%).
TEST(Clusters, TessellatedFurnaceKeepsEOverOneMinusRho) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(1.0f), Vec3(0.5f), Vec3(1.0f), 8);
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, {});
  solve(s, *vis);
  double area = 0.0, sum = 0.0, worst = 0.0;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for_each_leaf(m, [&](uint32_t e) {
      const Element& el = m.elements[e];
      const double b = double(mean_component(s.solution.radiosity(p, el.v[0]) +
                                             s.solution.radiosity(p, el.v[1]) +
                                             s.solution.radiosity(p, el.v[2]))) /
                       3.0;
      area += el.area;
      sum += double(el.area) * b;
      worst = std::max(worst, std::abs(b / 2.0 - 1.0));
    });
  }
  const double mean = sum / area;
  std::printf("furnace cut 8 x 8: %lld shots, mean %.5f (%+.3f%%), worst element %.2f%%\n",
              (long long)s.shots.count, mean, 100.0 * (mean / 2.0 - 1.0), 100.0 * worst);
  EXPECT_NEAR(mean, 2.0, 0.01);
  EXPECT_LE(worst, 0.02) << "the analytic scenes' worst-vertex bound";
}

}  // namespace
}  // namespace rad
namespace rad {
namespace {

// Inside a shallow dome (the inner face of a spherical cap: one curved cluster), a receiver
// below the rim facing up: its tangent plane cuts the dome along a loop that meets no outline
// edge, so the outline's clipping would count the part below the plane negatively. The gather
// must agree with the exact sum of the clipped triangle form factors.
TEST(Clusters, InsideADomeTheTangentPlaneLoopIsNotMissed) {
  SceneDescription d;
  ObjectDescription o;
  o.name = "dome";
  o.material = {Vec3(0.5f), Vec3(1.0f)};
  const int rings = 12, slices = 48;
  const float cap = 20.0f * 3.14159265f / 180.0f;
  auto at = [&](int i, int j) {  // the unit sphere around the origin, the cap around -y
    const float th = cap * float(i) / float(rings), ph = 2 * 3.14159265f * float(j) / slices;
    return Vec3(std::sin(th) * std::cos(ph), -std::cos(th), std::sin(th) * std::sin(ph));
  };
  auto add = [&](Vec3 a, Vec3 b, Vec3 c) {  // facing the sphere's centre
    if (glm::dot(glm::cross(b - a, c - a), -(a + b + c)) < 0.0f) std::swap(b, c);
    o.triangles.push_back({a, b, c});
  };
  for (int i = 0; i < rings; ++i) {
    for (int j = 0; j < slices; ++j) {
      if (i > 0) add(at(i, j), at(i, j + 1), at(i + 1, j + 1));
      add(at(i, j), at(i + 1, j + 1), at(i + 1, j));
    }
  }
  o.triangle_locs.resize(o.triangles.size());
  d.roots.push_back(0);
  d.objects.push_back(o);
  const Hierarchy h = build_hierarchy(d);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions opt;
  opt.max_size = 1.0f;  // one cluster
  const SolverState s = make_solver_state(h, opt);
  ASSERT_EQ(s.scene.clusters.size(), 1u);
  ASSERT_FALSE(s.scene.clusters.planar[0]);
  const ShotSource src = make_shot_source(s, 0);
  const Vec3 x(0.05f, -0.97f, 0.0f), n(0.0f, 1.0f, 0.0f);
  double exact = 0.0;
  for (size_t t = 0; t < h.triangles.size(); ++t) {
    const auto& k = h.triangles.corners[t];
    exact += point_to_triangle_form_factor(x, n, k[0], k[1], k[2], Arithmetic::Double);
  }
  GatherSettings g = gather_settings(s);
  g.shadows = false;
  g.inset = 0.0f;
  GatherScratch sc;
  const double got = gather_from_source(x, n, x, src, *vis, g, sc).x;  // unit emission
  const double outline = point_to_outline_form_factor(
      x, n, src.edge_a.data(), src.edge_b.data(), src.edge_a.size(), src.axis, Arithmetic::Double);
  std::printf("dome: exact %.4f, gathered %.4f, outline alone %.4f\n", exact, got, outline);
  EXPECT_NEAR(got, exact, 0.05 * exact);
}

}  // namespace
}  // namespace rad
