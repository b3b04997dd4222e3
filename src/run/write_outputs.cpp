#include "run/write_outputs.h"

#include <fmt/format.h>

#include "core/error.h"
#include "export/camera.h"
#include "export/image_file.h"
#include "export/image_render.h"
#include "export/mesh_file.h"

namespace rad {

void check_outputs(const OutputOptions& o) {
  if (!o.mesh.empty()) check_writable(o.mesh), check_mesh_extension(o.mesh);
  for (const std::string& image : o.images) check_writable(image), check_image_extension(image);
}

std::optional<Camera> write_outputs(const OutputMesh& mesh, const OutputOptions& o,
                                    const ToneMap& tone,
                                    const std::function<void(const std::string&)>& say,
                                    StagedFiles& files) {
  if (!o.mesh.empty()) {
    say(fmt::format("Writing results in file {}", o.mesh));
    MeshFileOptions mo;
    mo.ascii = o.ascii;
    mo.tone = tone;
    files.write(o.mesh, [&](const std::string& path) { write_mesh_file(path, mesh, mo); });
  }
  if (o.images.empty()) return std::nullopt;
  const RenderOptions ro{o.image_width, o.image_height};
  const Camera camera = o.camera ? *o.camera
                                 : default_camera(mesh.position(), mesh.indices(),
                                                  float(ro.width) / float(ro.height));
  say(fmt::format("Camera: --camera {}{}", camera_spec(camera), o.camera ? "" : " (the default)"));
  const Image image = render_image(mesh.position(), mesh.display, mesh.indices(), camera, ro);
  // An image a person would take for a failure: next to no pixel above black once tone mapped.
  size_t lit = 0;
  for (const Vec3& p : image.pixels) lit += max_component(tone_map(p, tone)) > 2.0f / 255.0f;
  if (lit * 100 < image.pixels.size()) {
    warn(SourceLoc{o.images.front(), 0, 0},
         fmt::format("the image is almost black ({} of {} pixels lit): the camera ({}) sees no "
                     "lit surface, or only surfaces from behind; give --camera "
                     "EYE_X,EYE_Y,EYE_Z,TARGET_X,TARGET_Y,TARGET_Z[,FOV] to look elsewhere",
                     lit, image.pixels.size(), camera_spec(camera)));
  }
  for (const std::string& path : o.images) {
    say(fmt::format("Writing image {}", path));
    files.write(path, [&](const std::string& staged) { write_image_file(staged, image, tone); });
  }
  return camera;
}

}  // namespace rad
