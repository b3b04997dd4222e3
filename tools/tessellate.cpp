// rad-tessellate: cuts every triangle of a scene into k x k congruent triangles (a barycentric
// grid), so the surfaces stay exactly the same and the same path-traced reference applies.
// Used to check that the answer and the time do not depend on the tessellation.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>
#include <string>

#include "core/error.h"
#include "scene/parser.h"
#include "scenegen/scenegen.h"

int main(int argc, char** argv) {
  CLI::App app{"Cuts every triangle of a description into k x k congruent triangles."};
  std::string in_path, out_path;
  int k = 2;
  app.add_option("IN", in_path, "description file to read (.des)")->required();
  app.add_option("OUT", out_path, "description file to write (.des)")->required();
  app.add_option("--k", k, "cuts per edge")->check(CLI::Range(1, 1024))->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    rad::SceneDescription scene = rad::parse_scene_file(in_path);
    size_t triangles = 0;
    for (rad::ObjectDescription& o : scene.objects) {
      o.triangles = rad::tessellate_triangles(o.triangles, k);
      o.triangle_locs.clear();
      triangles += o.triangles.size();
    }
    std::ofstream out(out_path);
    if (!out) throw rad::Error(fmt::format("cannot write {}", out_path));
    rad::write_description(scene, out);
    std::fprintf(stderr, "%s: %zu triangles\n", out_path.c_str(), triangles);
    return out.good() ? 0 : 1;
  } catch (const rad::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
