// rad-gen: writes a generated scene (tools/scenegen) as a description file with Data blocks.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "core/error.h"
#include "scene/ies_reader.h"
#include "scenegen/scenegen.h"

int main(int argc, char** argv) {
  CLI::App app{"Writes a generated scene as a rad description file."};
  std::string kind, out_path;
  uint64_t size = 100000, seed = 1;
  app.add_option("KIND", kind, "cornell | soup | nested | stadium | building | room")->required();
  app.add_option("OUT", out_path, "description file to write (.des)")->required();
  app.add_option("--size", size, "approximate number of triangles")->capture_default_str();
  app.add_option("--seed", seed, "random seed")->capture_default_str();
  int lights_reach = -1;
  app.add_option("--lights-reach", lights_reach,
                 "building: each room lights only the rooms within this many rooms (a Lights "
                 "list); -1: every room lights the whole building")
      ->capture_default_str();
  int light_groups = 0;
  app.add_option("--light-groups", light_groups,
                 "building: the rooms dealt round this many light groups, g0, g1, ... (0: none)")
      ->check(CLI::Range(0, 32));
  bool point_lights = false, downlights = false;
  auto* points =
      app.add_flag("--point-lights", point_lights,
                   "building: each room lit by a point light of the ceiling panel's on-axis "
                   "intensity, the same every way, instead of by the panel");
  app.add_flag("--downlights", downlights,
               "building: each room lit by a light whose IES distribution is the ceiling panel's "
               "(written beside OUT as OUT's name with .ies) instead of by the panel")
      ->excludes(points);
  CLI11_PARSE(app, argc, argv);
  try {
    rad::RoomLighting lighting;
    if (point_lights) lighting.kind = rad::RoomLighting::Kind::Point;
    if (downlights) {
      // The file the description names, beside it; parsed back, so the light is what rad reads.
      const std::string ies = std::filesystem::path(out_path).replace_extension(".ies").string();
      const std::string text = rad::downlight_ies();
      std::ofstream file(ies);
      if (!(file << text)) throw rad::Error(fmt::format("cannot write {}", ies));
      lighting.kind = rad::RoomLighting::Kind::Downlight;
      lighting.downlight = std::make_shared<const rad::Photometry>(rad::parse_ies(text, ies));
    }
    rad::SceneDescription scene = rad::generate_scene(rad::parse_scene_kind(kind), size, seed,
                                                      lights_reach, lighting, light_groups);
    std::ofstream out(out_path);
    if (!out) throw rad::Error(fmt::format("cannot write {}", out_path));
    rad::write_description(scene, out);
    size_t triangles = 0;
    for (const auto& o : scene.objects) triangles += o.triangles.size();
    std::fprintf(stderr, "%s: %zu objects, %zu triangles\n", out_path.c_str(), scene.objects.size(),
                 triangles);
    return out.good() ? 0 : 1;
  } catch (const rad::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
