// --stage solved: a model with no light of its own, set on the stage, converges on its own; the
// floor and the model's top receive light; the same model scaled by 0.01 or 100 and moved is
// lit the same and framed the same, up to that scale.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "run/object_illuminance.h"
#include "run/scene_unit.h"
#include "run/stage_camera.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// A unit cube on y = 0, scaled and moved, as an OBJ file with no emitting material.
fs::path write_cube(float scale, Vec3 at, const std::string& tag) {
  const fs::path p =
      fs::temp_directory_path() / ("rad_staged_" + std::to_string(getpid()) + "_" + tag + ".obj");
  std::ofstream f(p);
  f << "o cube\n";
  for (int k = 0; k < 8; ++k) {
    const Vec3 v =
        at + scale * Vec3(k & 1 ? 0.5f : -0.5f, k & 2 ? 1.0f : 0.0f, k & 4 ? 0.5f : -0.5f);
    f << "v " << v.x << " " << v.y << " " << v.z << "\n";
  }
  // Each face counterclockwise seen from outside.
  f << "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";
  return p;
}

struct Lit {
  StopReason stop = StopReason::MaxShots;
  int64_t shots = 0;
  double floor = 0.0, top = 0.0, side = 0.0;  // mean irradiance (lux) over their vertices
  Camera camera;
};

Lit solve_staged(float scale, Vec3 at, const std::string& tag) {
  const fs::path obj = write_cube(scale, at, tag);
  SceneInput in;
  in.path = obj.string();
  in.model.stage = StageOptions{};
  const Hierarchy h = load_scene(in);
  fs::remove(obj);
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  Lit lit;
  lit.stop = solve(s, *vis);  // no limit: it must end on its own
  lit.shots = s.shots.count;
  double sum[3] = {0, 0, 0};
  size_t count[3] = {0, 0, 0};
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const std::string& name = h.objects[size_t(h.triangles.object[p])].name;
    const Vec3 n = h.triangles.normal[p];
    const int which = name == "stage floor" ? 0 : name == "stage light" ? -1 : n.y > 0.9f ? 1 : 2;
    if (which < 0 || (which == 2 && std::abs(n.y) > 0.1f)) continue;  // the light; the bottom
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    for (uint32_t v = 0; v < m.vertex_count(); ++v) {
      sum[which] += s.solution.vertex_states[p][v].irradiance.y;
      ++count[which];
    }
  }
  lit.floor = sum[0] / double(std::max<size_t>(count[0], 1));
  lit.top = sum[1] / double(std::max<size_t>(count[1], 1));
  lit.side = sum[2] / double(std::max<size_t>(count[2], 1));
  lit.camera = stage_camera(*h.model->stage, 1.0f);
  return lit;
}

TEST(StagedModel, ALightlessModelOnTheStageConvergesWithItsFloorAndTopLit) {
  const Lit one = solve_staged(1.0f, Vec3(0.0f), "one");
  EXPECT_EQ(one.stop, StopReason::Converged);
  EXPECT_LT(one.shots, 2000);
  // The light is made to give the floor below it kStageIlluminance; the cube's top is nearer.
  EXPECT_GT(one.top, kStageIlluminance);
  EXPECT_LT(one.top, 3.0 * kStageIlluminance);
  EXPECT_GT(one.floor, 0.2 * kStageIlluminance);
  EXPECT_LT(one.floor, one.top);
  EXPECT_GT(one.side, 0.05 * kStageIlluminance);  // lit too, from the floor and the light's edge
  EXPECT_LT(one.side, one.top);

  for (const float scale : {0.01f, 100.0f}) {
    const Vec3 at = scale * Vec3(5.0f, -2.0f, -3.0f);
    const Lit s = solve_staged(scale, at, std::to_string(int(scale * 100)));
    EXPECT_EQ(s.stop, StopReason::Converged) << scale;
    // The same picture: the same light on every part, the camera where it was, scaled.
    EXPECT_NEAR(s.top, one.top, 0.02 * one.top) << scale;
    EXPECT_NEAR(s.floor, one.floor, 0.02 * one.floor) << scale;
    EXPECT_NEAR(s.side, one.side, 0.02 * one.side) << scale;
    const Vec3 offset = (s.camera.eye - s.camera.target) / scale;
    const Vec3 one_offset = one.camera.eye - one.camera.target;
    EXPECT_NEAR(glm::length(offset - one_offset), 0.0f, 1e-4f * glm::length(one_offset));
    EXPECT_NEAR(glm::length((s.camera.target - at) / scale - one.camera.target), 0.0f, 1e-4f);
    EXPECT_EQ(s.camera.fov_y_deg, one.camera.fov_y_deg);
  }
}

// The stage camera frames the model: every corner of its box in view, the box filling most of
// the image, from in front, the right and above; the light above the model is out of view.
TEST(StagedModel, TheStageCameraFramesTheModelAndNotTheLight) {
  Aabb b;
  b.extend(Vec3(-1.0f, 0.0f, -0.5f));
  b.extend(Vec3(1.0f, 1.0f, 0.5f));
  const Stage stage = plan_stage(b, {});
  for (const float aspect : {1.0f, 2.0f, 0.5f}) {
    const Camera c = stage_camera(stage, aspect);
    const CameraFrame f = camera_frame(c, aspect);
    EXPECT_GT(c.eye.z, b.hi.z);
    EXPECT_GT(c.eye.x, 0.0f);
    EXPECT_GT(c.eye.y, b.hi.y);
    float widest = 0.0f;
    for (int k = 0; k < 8; ++k) {
      const Vec3 p(k & 1 ? b.hi.x : b.lo.x, k & 2 ? b.hi.y : b.lo.y, k & 4 ? b.hi.z : b.lo.z);
      const Vec3 d = p - c.eye;
      const float depth = glm::dot(d, f.forward);
      ASSERT_GT(depth, 0.0f);
      const float x = glm::dot(d, f.right) / (depth * f.tan_half_x);
      const float y = glm::dot(d, f.up) / (depth * f.tan_half_y);
      EXPECT_LE(std::abs(x), 0.86f) << aspect;
      EXPECT_LE(std::abs(y), 0.86f) << aspect;
      widest = std::max({widest, std::abs(x), std::abs(y)});
    }
    EXPECT_GT(widest, 0.84f) << aspect;  // as near as the margin allows
    // The light's corners lie above the top of the view.
    for (int k = 0; k < 4; ++k) {
      const Vec3 p(k & 1 ? stage.light_hi.x : stage.light_lo.x, stage.light_y,
                   k & 2 ? stage.light_hi.y : stage.light_lo.y);
      const Vec3 d = p - c.eye;
      const float depth = glm::dot(d, f.forward);
      if (depth <= 0.0f) continue;  // behind the camera
      EXPECT_GT(glm::dot(d, f.up) / (depth * f.tan_half_y), 1.0f) << aspect << " corner " << k;
    }
  }
}

}  // namespace
}  // namespace rad
