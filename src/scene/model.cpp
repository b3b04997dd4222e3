#include "scene/model.h"

#include <filesystem>

#include "core/file_extension.h"
#include "scene/gltf_reader.h"
#include "scene/obj_reader.h"
#include "scene/ply_reader.h"

namespace rad {

bool is_model_file(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".obj" || e == ".ply" || e == ".gltf" || e == ".glb";
}

Model read_model_file(const std::string& path, const SourceLoc& requested_at) {
  const std::string e = lower_extension(path);
  if (e == ".obj") return read_obj_file(path, requested_at);
  if (e == ".ply") return read_ply_file(path, requested_at);
  if (e == ".gltf" || e == ".glb") return read_gltf_file(path, requested_at);
  throw Error(requested_at, "'" + path + "' is not a model rad reads (.obj, .ply, .gltf, .glb)");
}

}  // namespace rad
