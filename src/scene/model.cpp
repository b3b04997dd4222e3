#include "scene/model.h"

#include <filesystem>

#include "scene/gltf_reader.h"
#include "scene/obj_reader.h"
#include "scene/ply_reader.h"

namespace rad {

namespace {
std::string extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}
}  // namespace

bool is_model_file(const std::string& path) {
  const std::string e = extension(path);
  return e == ".obj" || e == ".ply" || e == ".gltf" || e == ".glb";
}

Model read_model_file(const std::string& path, const SourceLoc& requested_at) {
  const std::string e = extension(path);
  if (e == ".obj") return read_obj_file(path, requested_at);
  if (e == ".ply") return read_ply_file(path, requested_at);
  if (e == ".gltf" || e == ".glb") return read_gltf_file(path, requested_at);
  throw Error(requested_at, "'" + path + "' is not a model rad reads (.obj, .ply, .gltf, .glb)");
}

}  // namespace rad
