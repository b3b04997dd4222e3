// The same scene written two ways (tools/scenegen/model_pairs.h), each side solved with the
// defaults to convergence: the time of each side and how far apart their light is. tools/bench
// prints the table (docs/models.md quotes it).
//
// The difference is the mean over surface bins of |a - b| over the mean of b (channels summed):
// a bin is the part of the surface facing one way (its normal rounded) in one cell of a 4 x 4 x 4
// grid over the scene's box, so the two layouts' polygons meet in the same bins whatever their
// names, numbering or vertex sharing. What a bin holds is the light a viewer shows integrated
// over it, as a viewer of the solved mesh shows it (shown(), below), sampled 16 times a leaf
// element. The time is the solve's alone, on all cores.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "core/error.h"
#include "export/scene_export.h"
#include "hierarchy/auto_hierarchy.h"
#include "scene/parser.h"
#include "scenegen/model_pairs.h"
#include "solver/solver.h"
#include "solver/texture_factors.h"
#include "visibility/backend.h"

namespace rad {
namespace {

using Key = std::tuple<int, int, int, int, int, int>;  // cell x y z, normal x y z rounded

struct Side {
  double seconds = 0.0;
  size_t shots = 0, vertices = 0;
  std::map<Key, DVec3> bins;
};

// The light a viewer of the solved mesh shows at the point of leaf element `el` of polygon p with
// barycentric weights w: the radiosity linear over the element, or on a textured or cut-out
// surface the texel's emission (what the final render shows; the glTF output carries emission
// per vertex) and its reflectance times H linear over the element (the glTF output's texture
// times COLOR_0).
DVec3 shown(const Hierarchy& h, const Solution& s, size_t p, const Element& el, const Vec3& x,
            const Vec3& w, bool textured) {
  Vec3 sum(0.0f);
  if (!textured) {
    for (int k = 0; k < 3; ++k) sum += s.radiosity(p, el.v[k]) * w[k];
    return DVec3(sum);
  }
  const SceneObject& o = h.objects[size_t(h.triangles.object[p])];
  const TextureFactors f = texture_factor(h.triangles, p, o, x, 1e-12f);
  for (int k = 0; k < 3; ++k) sum += s.vertex_states[p][el.v[k]].irradiance * w[k];
  return DVec3(o.material.emission * f.emission + o.material.reflectance * f.reflectance * sum);
}

Side solve_side(const Hierarchy& h) {
  Side side;
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = make_solver_state(h, SolverOptions{});
  const auto start = std::chrono::steady_clock::now();
  solve(s, *vis);
  side.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  side.shots = s.shots.count;
  const Aabb box = h.bounds;
  const Vec3 size = glm::max(box.hi - box.lo, Vec3(1e-30f));
  for (size_t p = 0; p < h.triangles.size(); ++p) {
    const PolygonMesh& m = s.solution.mesh.polygons[p];
    side.vertices += m.positions.size();
    const bool textured = is_textured(h.triangles, p, h.objects[size_t(h.triangles.object[p])]);
    const Vec3 n = h.triangles.normal[p];
    for_each_leaf(m, [&](uint32_t e) {
      const Element& el = m.elements[e];
      const Vec3 a = m.positions[el.v[0]], b = m.positions[el.v[1]], c = m.positions[el.v[2]];
      // 16 points, one in each of the 16 congruent triangles of the element's 4 x 4 split (their
      // centroids), each into the bin it lies in: an element across a cell's side is shared.
      constexpr int kSplit = 4;
      const double weight = double(el.area) / (kSplit * kSplit);
      for (int i = 0; i < kSplit; ++i) {
        for (int j = 0; i + j < kSplit; ++j) {
          for (int up = 0; up < 2 && i + j + up < kSplit; ++up) {
            const float u = (float(i) + (up ? 2.0f : 1.0f) / 3.0f) / kSplit;
            const float v = (float(j) + (up ? 2.0f : 1.0f) / 3.0f) / kSplit;
            const Vec3 w(1.0f - u - v, u, v);
            const Vec3 x = a * w.x + b * w.y + c * w.z;
            const Vec3 cell = glm::clamp(x - box.lo, Vec3(0.0f), size) / size * 3.999f;
            const Key key{int(cell.x),
                          int(cell.y),
                          int(cell.z),
                          int(std::lround(n.x * 10)),
                          int(std::lround(n.y * 10)),
                          int(std::lround(n.z * 10))};
            side.bins[key] += shown(h, s.solution, p, el, x, w, textured) * weight;
          }
        }
      }
    });
  }
  return side;
}

// Sum over bins of |a - b| over the sum of b, channels summed.
double difference(const Side& a, const Side& b) {
  double diff = 0.0, total = 0.0;
  auto add = [&](const DVec3& x, const DVec3& y) {
    const DVec3 d = glm::abs(x - y);
    diff += d.x + d.y + d.z;
    total += y.x + y.y + y.z;
  };
  for (const auto& [key, y] : b.bins) {
    const auto it = a.bins.find(key);
    add(it == a.bins.end() ? DVec3(0.0) : it->second, y);
  }
  for (const auto& [key, x] : a.bins) {
    if (!b.bins.contains(key)) add(x, DVec3(0.0));
  }
  return total > 0.0 ? diff / total : 0.0;
}

void bm_pair(benchmark::State& st, const std::function<Hierarchy()>& make_a,
             const std::function<Hierarchy()>& make_b) {
  Side a, b;
  for (auto _ : st) {
    a = solve_side(make_a());
    b = solve_side(make_b());
  }
  st.counters["seconds_a"] = a.seconds;
  st.counters["seconds_b"] = b.seconds;
  st.counters["shots_a"] = double(a.shots);
  st.counters["shots_b"] = double(b.shots);
  st.counters["vertices_a"] = double(a.vertices);
  st.counters["vertices_b"] = double(b.vertices);
  st.counters["difference_pct"] = 100.0 * difference(a, b);
}

// Where the Cornell box is written as an OBJ soup and as glTF.
std::string pairs_folder() {
  return (std::filesystem::temp_directory_path() / ("rad_pairs_" + std::to_string(getpid())))
      .string();
}

void register_all() {
  const std::string cornell = RAD_SOURCE_DIR "/scenes/cornell_box.des";
  const std::string dir = pairs_folder();
  std::filesystem::create_directories(dir);
  auto description = [=] { return load_hierarchy(cornell, {}, std::nullopt); };
  auto soup = [=] {
    write_obj_soup(description(), dir + "/box.obj");
    return load_hierarchy(dir + "/box.obj", {}, std::nullopt);
  };
  auto gltf = [=] {
    write_scene_file(dir + "/box.gltf", parse_scene_file(cornell), description());
    return load_hierarchy(dir + "/box.gltf", {}, std::nullopt);
  };
  const auto checker = checker_texture();
  const std::vector<std::tuple<std::string, std::function<Hierarchy()>, std::function<Hierarchy()>>>
      pairs = {
          {"obj_soup/description", soup, description},
          {"gltf/description", gltf, description},
          {"checker_texture/squares", [=] { return build_hierarchy(checker_room(checker, true)); },
           [=] { return build_hierarchy(checker_room(checker, false)); }},
          {"checker_emitter/squares",
           [=] { return build_hierarchy(checker_lit_room(checker, true)); },
           [=] { return build_hierarchy(checker_lit_room(checker, false)); }},
          {"cutout_leaf/polygons", [] { return build_hierarchy(cutout_room(true)); },
           [] { return build_hierarchy(cutout_room(false)); }},
          {"two_sided/back_to_back",
           [] {
             return build_hierarchy(parse_scene_text(
                 screen_room(screen_object("screen", "TwoSided Yes", false)), "two_sided.des"));
           },
           [] {
             return build_hierarchy(parse_scene_text(
                 screen_room(screen_object("near", "", false) + screen_object("far", "", true)),
                 "back_to_back.des"));
           }},
      };
  for (const auto& [name, a, b] : pairs) {
    benchmark::RegisterBenchmark(("pair/" + name).c_str(),
                                 [a, b](benchmark::State& st) { bm_pair(st, a, b); })
        ->Iterations(1)
        ->UseRealTime()
        ->Unit(benchmark::kSecond);
  }
}

}  // namespace

void remove_pairs_folder() { std::filesystem::remove_all(pairs_folder()); }

}  // namespace rad

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  rad::register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  rad::remove_pairs_folder();
  return 0;
}
