#include "export/mesh_file.h"

#include <algorithm>
#include <filesystem>

#include "core/error.h"
#include "export/atomic_file.h"
#include "export/ply_writer.h"

namespace rad {

namespace {
std::string extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}
}  // namespace

void check_mesh_extension(const std::string& path) {
  const std::string e = extension(path);
  if (e != ".ply") {
    throw Error(SourceLoc{path}, "unknown output format '" + e + "' (expected .ply)");
  }
}

void write_mesh_file(const std::string& path, const OutputMesh& mesh, const MeshFileOptions& o) {
  check_mesh_extension(path);
  AtomicFile f(path);
  write_ply(f.stream(), mesh, o.tone, o.ascii);
  f.commit();
}

}  // namespace rad
