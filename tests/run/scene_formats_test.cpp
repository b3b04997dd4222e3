// The same scene solves to the same radiosity however it is written: as a description, as an
// OBJ whose every triangle has its own three vertices (the unwelded soup many exporters
// write), and as glTF. Adjacency, clusters and welding must not hang on shared vertex indices.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>

#include "export/scene_export.h"
#include "hierarchy/auto_hierarchy.h"
#include "scene/parser.h"
#include "scenegen/model_pairs.h"
#include "solver/solver.h"
#include "visibility/backend.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

// Radiosity integrated over each triangle of `h` solved as `s`, keyed by the triangle's
// centroid rounded to a micrometre of the scene's millimetres.
std::map<std::array<int64_t, 3>, DVec3> per_triangle(const Hierarchy& h, const SolverState& s) {
  std::map<std::array<int64_t, 3>, DVec3> out;
  for (size_t p = 0; p < h.triangles.size(); ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    DVec3 sum(0.0);
    for_each_leaf(m, [&](uint32_t e) {
      const Element& el = m.elements[e];
      sum += DVec3(s.solution.radiosity(p, el.v[0]) + s.solution.radiosity(p, el.v[1]) +
                   s.solution.radiosity(p, el.v[2])) *
             (double(el.area) / 3.0);
    });
    const Vec3 c = h.triangles.centroid(p);
    out[{std::llround(c.x * 1e3), std::llround(c.y * 1e3), std::llround(c.z * 1e3)}] += sum;
  }
  return out;
}

// 40 shots: most of the light, in a few seconds.
SolverState solve_40_shots(const Hierarchy& h) {
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverOptions o;
  o.max_shots = 40;
  o.converge = 0.0;
  SolverState s = make_solver_state(h, o);
  solve(s, *vis);
  return s;
}

TEST(SceneFormats, TheCornellBoxSolvesAlikeAsADescriptionAnObjSoupAndGltf) {
  const fs::path dir = fs::temp_directory_path() / ("rad_formats_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string des = std::string(RAD_SOURCE_DIR) + "/scenes/cornell_box.des";
  const Hierarchy h = load_hierarchy(des, {}, std::nullopt);
  write_obj_soup(h, (dir / "box.obj").string());
  const SceneDescription d = parse_scene_file(des);
  write_scene_file((dir / "box.gltf").string(), d, h);

  const auto reference = per_triangle(h, solve_40_shots(h));
  double total = 0.0;
  for (const auto& [key, b] : reference) total += b.x + b.y + b.z;
  for (const char* name : {"box.obj", "box.gltf"}) {
    const Hierarchy other = load_hierarchy((dir / name).string(), {}, std::nullopt);
    ASSERT_EQ(other.triangles.size(), h.triangles.size()) << name;
    const auto solved = per_triangle(other, solve_40_shots(other));
    ASSERT_EQ(solved.size(), reference.size()) << name << ": the same triangles, by centroid";
    double diff = 0.0;
    for (const auto& [key, b] : reference) {
      const auto it = solved.find(key);
      ASSERT_NE(it, solved.end()) << name;
      const DVec3 d3 = glm::abs(it->second - b);
      diff += d3.x + d3.y + d3.z;
    }
    EXPECT_LT(diff / total, 0.005) << name << ": the mean difference over the triangles";
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace rad
