#include "run/write_outputs.h"

#include <fmt/format.h>

#include "export/image_file.h"
#include "export/image_render.h"
#include "export/mesh_file.h"

namespace rad {

void check_outputs(const OutputOptions& o) {
  if (!o.mesh.empty()) check_writable(o.mesh), check_mesh_extension(o.mesh);
  for (const std::string& image : o.images) check_writable(image), check_image_extension(image);
}

void write_outputs(const OutputMesh& mesh, const OutputOptions& o, const ToneMap& tone,
                   const std::function<void(const std::string&)>& say, StagedFiles& files) {
  if (!o.mesh.empty()) {
    say(fmt::format("Writing results in file {}", o.mesh));
    MeshFileOptions mo;
    mo.ascii = o.ascii;
    mo.tone = tone;
    files.write(o.mesh, [&](const std::string& path) { write_mesh_file(path, mesh, mo); });
  }
  if (o.images.empty()) return;
  const RenderOptions ro{o.image_width, o.image_height};
  const Camera camera = o.camera ? *o.camera
                                 : default_camera(mesh.position(), mesh.indices(),
                                                  float(ro.width) / float(ro.height));
  const Image image = render_image(mesh.position(), mesh.display, mesh.indices(), camera, ro);
  for (const std::string& path : o.images) {
    say(fmt::format("Writing image {}", path));
    files.write(path, [&](const std::string& staged) { write_image_file(staged, image, tone); });
  }
}

}  // namespace rad
