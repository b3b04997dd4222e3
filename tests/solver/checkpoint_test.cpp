// Checkpoints: a solve saved and resumed continues exactly as one never stopped, and a file of
// another solve, a damaged one or a truncated one is refused without touching the state.
#include "solver/checkpoint.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "scene_builder.h"
#include "solver/solver.h"

namespace rad {
namespace {

namespace fs = std::filesystem;

Hierarchy lit_box() {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0), Vec3(1, 1, 1), Vec3(0.6f, 0.5f, 0.4f), Vec3(0), 2);
  testing::add_quad(d, "lamp", {0.4f, 0.4f, 0.99f}, {0.4f, 0.6f, 0.99f}, {0.6f, 0.6f, 0.99f},
                    {0.6f, 0.4f, 0.99f}, Vec3(0), Vec3(5));
  testing::add_quad(d, "block", {0.2f, 0.2f, 0.3f}, {0.7f, 0.2f, 0.3f}, {0.7f, 0.7f, 0.3f},
                    {0.2f, 0.7f, 0.3f}, Vec3(0.5f), Vec3(0));
  return build_hierarchy(d);
}

// Every vertex's position and state (and its light groups' states), as bytes.
std::string all_vertices(const SolverState& s) {
  std::string v;
  for (size_t p = 0; p < s.solution.mesh.polygons.size(); ++p) {
    const std::vector<Vec3>& x = s.solution.mesh.polygons[p].positions;
    const std::vector<VertexState>& st = s.solution.vertex_states[p];
    const std::vector<VertexState>& g = s.solution.group_states_of(p);
    v.append(reinterpret_cast<const char*>(x.data()), x.size() * sizeof(Vec3));
    v.append(reinterpret_cast<const char*>(st.data()), st.size() * sizeof(VertexState));
    v.append(reinterpret_cast<const char*>(g.data()), g.size() * sizeof(VertexState));
  }
  return v;
}

// The lit box solved for `shots` shots with the default options (Embree).
SolverState solved(const Hierarchy& h, const VisibilityBackend& vis, int64_t shots) {
  SolverOptions o;
  o.max_shots = shots;
  SolverState s = make_solver_state(h, o);
  solve(s, vis);
  return s;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

fs::path temp_file(const std::string& name) {
  return fs::temp_directory_path() / (name + "-" + std::to_string(getpid()));
}

// `h` solved for `stop` shots, saved to a checkpoint, read back into a fresh state and solved on
// with `o`.
SolverState resumed_after(const Hierarchy& h, const VisibilityBackend& vis, int64_t stop,
                          const SolverOptions& o) {
  const fs::path file = temp_file("rad-ckpt-resumed");
  const SolverState first = solved(h, vis, stop);
  const uint64_t id = solve_fingerprint(h, first.options, BackendKind::Embree);
  write_checkpoint(file, first, id);
  SolverState resumed = make_solver_state(h, o);
  read_checkpoint(file, resumed, id);
  solve(resumed, vis);
  fs::remove(file);
  return resumed;
}

TEST(Checkpoint, ResumedSolveEndsBitIdenticalToAnUninterruptedOne) {
  const Hierarchy h = lit_box();
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState whole = solved(h, *vis, 14);

  const fs::path file = temp_file("rad-ckpt");
  const SolverState first = solved(h, *vis, 6);
  const uint64_t id = solve_fingerprint(h, first.options, BackendKind::Embree);
  write_checkpoint(file, first, id);

  // The stop criteria are not part of the identity: a resumed run may go on.
  const SolverOptions o = whole.options;
  ASSERT_EQ(id, solve_fingerprint(h, o, BackendKind::Embree));
  SolverState resumed = make_solver_state(h, o);
  read_checkpoint(file, resumed, id);
  EXPECT_EQ(resumed.shots.count, 6);
  solve(resumed, *vis);
  fs::remove(file);

  ASSERT_EQ(resumed.shots.count, whole.shots.count);
  EXPECT_EQ(resumed.energy.absorbed_energy, whole.energy.absorbed_energy);
  const auto a = all_vertices(whole), b = all_vertices(resumed);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(a == b);
  ASSERT_EQ(resumed.shots.history.size(), whole.shots.history.size());
  for (size_t i = 0; i < whole.shots.history.size(); ++i) {
    EXPECT_EQ(resumed.shots.history[i].source, whole.shots.history[i].source) << "shot " << i + 1;
  }
}

TEST(Checkpoint, ALitSceneResumedBetweenItsLightsShotsEndsBitIdentical) {
  // Two lights besides the lamp: stopped after the first light's shot, the second is still to
  // shoot; the log holds a light's shot, which new vertices gather again after the resume.
  Hierarchy h = lit_box();
  Light a;
  a.name = "a", a.position = Vec3(0.3f, 0.5f, 0.8f), a.intensity = 2.0f;
  Light b = a;
  b.name = "b", b.kind = LightKind::Spot, b.position = Vec3(0.8f, 0.8f, 0.9f);
  b.direction = glm::normalize(Vec3(-1.0f, -1.0f, -2.0f)), b.colour = Vec3(1.0f, 0.5f, 0.2f);
  h.lights = {a, b};
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState whole = solved(h, *vis, 12);
  EXPECT_EQ(whole.shots.history[0].source, -1);
  EXPECT_EQ(whole.shots.history[1].source, -2);
  for (const int64_t stop : {1, 5}) {
    const SolverState resumed = resumed_after(h, *vis, stop, whole.options);
    ASSERT_EQ(resumed.shots.count, whole.shots.count);
    EXPECT_TRUE(all_vertices(whole) == all_vertices(resumed)) << "stopped after " << stop;
  }
  // Another light is another solve.
  Hierarchy moved = h;
  moved.lights[1].intensity = 3.0f;
  EXPECT_NE(solve_fingerprint(h, whole.options, BackendKind::Embree),
            solve_fingerprint(moved, whole.options, BackendKind::Embree));
}

TEST(Checkpoint, ASolveOfLightGroupsResumedEndsBitIdentical) {
  // The lamp in one group, a light in another, the second light in the default group: every
  // group's vertex states and the shares of the logged shots survive the file.
  Hierarchy h = lit_box();
  for (SceneObject& o : h.objects)
    if (o.name == "lamp") o.group = "lamp";
  Light a;
  a.name = "a", a.position = Vec3(0.3f, 0.5f, 0.8f), a.intensity = 2.0f, a.group = "bulb";
  Light b = a;
  b.name = "b", b.position = Vec3(0.8f, 0.8f, 0.9f), b.group = "";
  h.lights = {a, b};
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState whole = solved(h, *vis, 14);
  ASSERT_EQ(whole.solution.group_count, 3u);
  const SolverState resumed = resumed_after(h, *vis, 6, whole.options);
  ASSERT_EQ(resumed.shots.count, whole.shots.count);
  EXPECT_TRUE(all_vertices(whole) == all_vertices(resumed));
  // Another grouping of the same light is another solve.
  Hierarchy regrouped = h;
  regrouped.lights[1].group = "bulb";
  EXPECT_NE(solve_fingerprint(h, whole.options, BackendKind::Embree),
            solve_fingerprint(regrouped, whole.options, BackendKind::Embree));
}

TEST(Checkpoint, EqualStatesWriteEqualFiles) {
  const Hierarchy h = lit_box();
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const fs::path f1 = temp_file("rad-ckpt-a"), f2 = temp_file("rad-ckpt-b");
  for (const fs::path& f : {f1, f2}) {
    SolverState s = solved(h, *vis, 5);
    s.stats.shoot_seconds = s.stats.refine_seconds = 0;  // the only fields the clock sets
    for (ShotRecord& r : s.shots.history) r.seconds = 0;
    write_checkpoint(f, s, 1);
  }
  const std::string sa = read_bytes(f1), sb = read_bytes(f2);
  EXPECT_GT(sa.size(), 1000u);
  EXPECT_TRUE(sa == sb);
  fs::remove(f1), fs::remove(f2);
}

std::string error_of(const fs::path& file, SolverState& s, uint64_t id) {
  try {
    read_checkpoint(file, s, id);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Checkpoint, RefusesAnotherSolveADamagedFileATruncatedOneAndNoCheckpoint) {
  const Hierarchy h = lit_box();
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  const SolverState s = solved(h, *vis, 4);
  const SolverOptions o = s.options;
  const uint64_t id = solve_fingerprint(h, o, BackendKind::Embree);
  const fs::path file = temp_file("rad-ckpt-bad");
  write_checkpoint(file, s, id);
  const std::string bytes = read_bytes(file);
  auto write = [&](const std::string& b) { std::ofstream(file, std::ios::binary) << b; };

  SolverState fresh = make_solver_state(h, o);
  const auto before = all_vertices(fresh);
  auto untouched = [&] {
    const auto now = all_vertices(fresh);
    return fresh.shots.count == 0 && now == before;
  };

  SolverOptions other = o;
  other.subdivision_threshold *= 2;
  EXPECT_NE(solve_fingerprint(h, other, BackendKind::Embree), id);
  EXPECT_NE(solve_fingerprint(h, o, BackendKind::Grid), id);
  EXPECT_NE(error_of(file, fresh, solve_fingerprint(h, other, BackendKind::Embree))
                .find("checkpoint of another solve"),
            std::string::npos);
  EXPECT_TRUE(untouched());

  for (size_t at : {size_t(40), bytes.size() / 2, bytes.size() - 1}) {
    std::string damaged = bytes;
    damaged[at] = char(damaged[at] ^ 0x10);
    write(damaged);
    EXPECT_NE(error_of(file, fresh, id).find("corrupt checkpoint"), std::string::npos) << at;
    EXPECT_TRUE(untouched());
  }
  write(bytes.substr(0, bytes.size() / 3));
  EXPECT_NE(error_of(file, fresh, id).find("corrupt checkpoint"), std::string::npos);
  write("ply\nformat ascii 1.0\n");
  EXPECT_NE(error_of(file, fresh, id).find("not a rad checkpoint"), std::string::npos);
  fs::remove(file);
  EXPECT_NE(error_of(file, fresh, id).find("cannot read"), std::string::npos);
  EXPECT_TRUE(untouched());

  write(bytes);
  EXPECT_EQ(error_of(file, fresh, id), "");
  EXPECT_EQ(fresh.shots.count, 4);
  fs::remove(file);
}

// A file whose checksum holds but whose copies chain (a copy of a copy): the shot would read a
// gain another thread is writing. Refused as corrupt.
TEST(Checkpoint, RefusesACopyOfACopy) {
  const Hierarchy h = lit_box();
  const auto vis = make_visibility_backend(BackendKind::Embree, h);
  SolverState s = solved(h, *vis, 2);
  const uint64_t id = solve_fingerprint(h, s.options, BackendKind::Embree);
  // Two copies; the second made to copy the first.
  const VertexCopy* first = nullptr;
  VertexCopy* second = nullptr;
  for (auto& cs : s.scene.shared.copies) {
    for (VertexCopy& c : cs) {
      if (!first) {
        first = &c;
      } else if (!second) {
        second = &c;
      }
    }
  }
  ASSERT_TRUE(first && second);
  uint32_t first_polygon = 0;
  for (uint32_t p = 0; p < s.scene.shared.copies.size(); ++p)
    if (!s.scene.shared.copies[p].empty() && &s.scene.shared.copies[p][0] == first)
      first_polygon = p;
  second->from_polygon = first_polygon, second->from_vertex = first->vertex;
  const fs::path file = temp_file("rad-ckpt-chain");
  write_checkpoint(file, s, id);
  SolverState fresh = make_solver_state(h, s.options);
  EXPECT_NE(error_of(file, fresh, id).find("copied from no vertex, or from a copy"),
            std::string::npos);
  EXPECT_EQ(fresh.shots.count, 0);
  fs::remove(file);
}

}  // namespace
}  // namespace rad
