// --unit: a scene in centimetres is lit as in metres. A point light of I cd 200 units = 2 m
// above a floor gives I / 4 lx at its foot and I h / r^3 (in metres) elsewhere; areas and a
// light's power are reported in square metres and lumens; glTF stays in metres.
#include "run/scene_unit.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "run/object_illuminance.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// A black floor 4 m across, 400 cd straight above its centre at 2 m: lengths written in `per_m`
// units to the metre.
fs::path write_lamp_scene(double per_m) {
  const fs::path p = fs::temp_directory_path() / ("rad_unit_" + std::to_string(getpid()) + "_" +
                                                  std::to_string(int(per_m)) + ".des");
  const double a = 2.0 * per_m, h = 2.0 * per_m;
  std::ofstream(p) << "\"lamp over a floor\"\n"
                   << "Object \"floor\" Pure { Reflectivity 0 Color <1 1 1> Emission 0\n"
                   << "  Data { <" << -a << " 0 " << -a << "> <" << -a << " 0 " << a << "> <" << a
                   << " 0 " << a << ">  <" << -a << " 0 " << -a << "> <" << a << " 0 " << a << "> <"
                   << a << " 0 " << -a << "> } }\n"
                   << "Object \"lamp\" Light { Type Point Position <0 " << h
                   << " 0> Intensity 400 }\n";
  return p;
}

struct Solved {
  Hierarchy h;
  SolverState s;
};

std::unique_ptr<Solved> solve_scene(const SceneInput& in) {
  auto out = std::make_unique<Solved>(Solved{load_scene(in), {}});
  const auto vis = make_visibility_backend(BackendKind::Embree, out->h);
  out->s = make_solver_state(out->h, SolverOptions{});
  solve(out->s, *vis);
  return out;
}

TEST(SceneUnit, APointLightTwoMetresUpInCentimetresGivesAQuarterOfItsCandelaAtItsFoot) {
  const fs::path cm = write_lamp_scene(100.0);
  SceneInput in;
  in.path = cm.string();
  in.unit = 0.01;
  const auto lit = solve_scene(in);
  double foot = 0.0;
  for (size_t p = 0; p < lit->s.solution.mesh.polygons.size(); ++p) {
    const PolygonMesh& m = lit->s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      const Vec3 x = m.positions[v] / 100.0f;  // metres
      const double r2 = double(glm::dot(x, x)) + 4.0;
      const double exact = 400.0 * 2.0 / (r2 * std::sqrt(r2));  // I h / r^3
      const double got = lit->s.solution.vertex_states[p][v].irradiance.y;
      EXPECT_NEAR(got, exact, 1e-3 * exact) << x.x << ", " << x.z;
      if (glm::dot(x, x) < 1e-12f) foot = got;
    }
  }
  EXPECT_NEAR(foot, 100.0, 0.1);  // I / 4
  const std::vector<ObjectIlluminance> o = object_illuminance(lit->s, metres_per_unit(in));
  ASSERT_EQ(o.size(), 1u);
  EXPECT_NEAR(o[0].area, 16.0, 1e-4);  // m^2
  EXPECT_NEAR(o[0].max, 100.0, 0.1);
  // The light's power as the solve counts it, back in square metres: 4 pi I lumens.
  EXPECT_NEAR(lit->s.energy.light_power[0] * 0.01 * 0.01, 4.0 * std::numbers::pi * 400.0, 1.0);

  // The same file read as metres: the lamp is 200 m up.
  in.unit.reset();
  const auto far = solve_scene(in);
  EXPECT_NEAR(object_illuminance(far->s)[0].max, 400.0 / (200.0 * 200.0), 1e-5);
  // And the scene written in metres is lit as the one in centimetres.
  const fs::path m = write_lamp_scene(1.0);
  const auto metres = solve_scene(SceneInput{m.string(), {}, {}, {}});
  EXPECT_NEAR(object_illuminance(metres->s)[0].mean, o[0].mean, 1e-4 * o[0].mean);
  fs::remove(cm), fs::remove(m);
}

TEST(SceneUnit, OnlyPointAndSpotLightsDependOnTheUnit) {
  Hierarchy h;
  for (LightKind k : {LightKind::Point, LightKind::Spot, LightKind::Directional}) {
    Light l;
    l.kind = k, l.intensity = 10.0f;
    h.lights.push_back(l);
  }
  apply_scene_unit(h, 0.001);  // millimetres
  EXPECT_FLOAT_EQ(h.lights[0].intensity, 1e7f);
  EXPECT_FLOAT_EQ(h.lights[1].intensity, 1e7f);
  EXPECT_FLOAT_EQ(h.lights[2].intensity, 10.0f);  // lux: no length in it
  apply_scene_unit(h, 1.0);
  EXPECT_FLOAT_EQ(h.lights[0].intensity, 1e7f);
}

TEST(SceneUnit, GltfIsInMetresWhateverUnitSays) {
  SceneInput in;
  in.path = "room.des";
  EXPECT_EQ(metres_per_unit(in), 1.0);
  in.unit = 0.0254;
  EXPECT_EQ(metres_per_unit(in), 0.0254);
  in.path = "room.OBJ";
  EXPECT_EQ(metres_per_unit(in), 0.0254);
  in.path = "room.gltf";
  EXPECT_EQ(metres_per_unit(in), 1.0);
  in.path = "room.GLB";
  EXPECT_EQ(metres_per_unit(in), 1.0);
}

}  // namespace
}  // namespace rad
