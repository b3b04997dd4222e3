#include "app/batch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "app/batch_summary.h"
#include "core/error.h"
#include "core/interrupt.h"
#include "export/image_file.h"
#include "export/mesh_file.h"
#include "run/scene_job.h"
#include "scene/model.h"

namespace rad {

namespace {

namespace fs = std::filesystem;

// Scene paths: .txt arguments are lists (one path per line, '#' comments, relative to the list).
std::vector<std::string> expand_scene_list(const std::vector<std::string>& args) {
  std::vector<std::string> scenes;
  for (const std::string& a : args) {
    if (fs::path(a).extension() != ".txt") {
      scenes.push_back(a);
      continue;
    }
    std::ifstream in(a);
    if (!in) throw Error(SourceLoc{a}, "cannot read the scene list");
    std::string line;
    while (std::getline(in, line)) {
      line = line.substr(0, line.find('#'));
      while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back())))
        line.pop_back();
      while (!line.empty() && std::isspace(static_cast<unsigned char>(line.front())))
        line.erase(0, 1);
      if (line.empty()) continue;
      const fs::path p(line);
      scenes.push_back(p.is_absolute() ? line : (fs::path(a).parent_path() / p).string());
    }
  }
  return scenes;
}

struct Row {
  std::string scene, status, detail;
  SceneJobResult result;
};

}  // namespace

int run_batch(const CommandLine& cmd) {
  // Check every format before any work, so a typo fails at once.
  std::vector<std::string> mesh_exts, image_exts;
  for (const std::string& f : cmd.batch.formats) {
    const std::string name = "x." + f;
    try {
      check_mesh_extension(name);
      mesh_exts.push_back(f);
    } catch (const Error&) {
      try {
        check_image_extension(name);
      } catch (const Error&) {
        throw Error("unknown batch format '" + f +
                    "' (mesh: ply off obj gltf glb; image: png "
                    "hdr exr pfm)");
      }
      image_exts.push_back(f);
    }
  }
  if (mesh_exts.size() > 1) throw Error("batch writes one mesh format per scene");
  const std::vector<std::string> scenes = expand_scene_list(cmd.batch.scenes);
  // --emit is for the models of the list; a list of descriptions alone has no use for it.
  const bool any_model = std::any_of(scenes.begin(), scenes.end(),
                                     [](const std::string& s) { return is_model_file(s); });
  if (!cmd.job.input.model.emit.empty() && !any_model) {
    throw Error(
        "--emit names the materials of a model (.obj, .ply, .gltf, .glb), and every scene of "
        "this batch is a description: give the lamps' objects an Emission line instead");
  }
  if (cmd.job.input.model.stage && !any_model) {
    throw Error(
        "--stage sets a model (.obj, .ply, .gltf, .glb) on a floor under a light, and every "
        "scene of this batch is a description, which places its own: leave --stage out");
  }
  fs::create_directories(cmd.batch.dir);

  // Names over the whole list, so every shard gives a scene the same one.
  std::vector<std::string> names;
  std::set<std::string> used;
  for (const std::string& scene : scenes) {
    std::string name = fs::path(scene).stem().string();
    for (int k = 2; !used.insert(name).second; ++k)
      name = fs::path(scene).stem().string() + "-" + std::to_string(k);
    names.push_back(name);
  }

  std::vector<Row> rows;
  for (size_t i = size_t(cmd.batch.shard_index); i < scenes.size();
       i += size_t(cmd.batch.shard_count)) {
    const std::string& scene = scenes[i];
    const std::string& name = names[i];
    const fs::path base = fs::path(cmd.batch.dir) / name;
    SceneJob job = cmd.job;
    job.input.path = scene;
    if (!is_model_file(scene)) job.input.model.emit.clear(), job.input.model.stage.reset();
    job.stats_json = base.string() + ".json";
    job.skip_if_done = true;
    if (!mesh_exts.empty()) job.outputs.mesh = base.string() + "." + mesh_exts[0];
    for (const std::string& e : image_exts) job.outputs.images.push_back(base.string() + "." + e);
    if (!cmd.run.quiet) std::printf("== %s\n", scene.c_str());
    Row row{scene, "ok", "", {}};
    try {
      row.result = run_scene_job(cmd.run, job);
      row.detail = to_string(row.result.stop);
      if (row.result.stop == StopReason::Interrupted) row.status = "partial";
      if (row.result.skipped) row.status = "done", row.detail = "outputs complete: skipped";
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      row.status = "FAILED";
      row.detail = e.what();
    }
    rows.push_back(row);
    if (!row.result.skipped) {  // a skipped scene keeps the row of the run that solved it
      const SceneJobResult& x = row.result;
      merge_batch_record(
          cmd.batch.dir,
          {name, scene, row.status == "FAILED" ? "failed" : row.status, row.detail, x.seconds,
           x.shots, uint64_t(x.vertices), cmd.batch.shard_index, cmd.batch.shard_count});
    }
    if (interrupt_signal()) break;  // Ctrl-C: the scene in progress was written; no more
  }

  int failed = 0;
  std::printf("\n%-40s %-7s %7s %9s %9s  %s\n", "scene", "status", "shots", "vertices", "seconds",
              "result");
  for (const Row& r : rows) {
    failed += r.status == "FAILED";
    if (r.status != "FAILED" && !r.result.skipped) {
      std::printf("%-40s %-7s %7lld %9zu %9.2f  %s\n", r.scene.c_str(), r.status.c_str(),
                  static_cast<long long>(r.result.shots), r.result.vertices, r.result.seconds,
                  r.detail.c_str());
    } else {
      std::printf("%-40s %-7s %7s %9s %9s  %s\n", r.scene.c_str(), r.status.c_str(), "-", "-", "-",
                  r.detail.c_str());
    }
  }
  std::printf("%zu scene%s, %d failed\n", rows.size(), rows.size() == 1 ? "" : "s", failed);
  if (interrupt_signal()) return interrupted_exit_status(interrupt_signal());
  return failed ? 1 : 0;
}

}  // namespace rad
