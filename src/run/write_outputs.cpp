#include "run/write_outputs.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "core/error.h"
#include "core/progress.h"
#include "export/camera.h"
#include "export/false_colour.h"
#include "export/gathered_image.h"
#include "export/image_file.h"
#include "export/image_render.h"
#include "export/mesh_file.h"

namespace rad {

namespace {

// An image a person would take for a failure: next to no pixel above black once tone mapped.
void warn_if_black(const Image& image, const ToneMap& tone, const std::string& path,
                   const Camera& camera) {
  size_t lit = 0;
  for (const Vec3& p : image.pixels) lit += max_component(tone_map(p, tone)) > 2.0f / 255.0f;
  if (lit * 100 >= image.pixels.size()) return;
  warn(SourceLoc{path, 0, 0},
       fmt::format("the image is almost black ({} of {} pixels lit): the camera ({}) sees no "
                   "lit surface, or only surfaces from behind; give --camera "
                   "EYE_X,EYE_Y,EYE_Z,TARGET_X,TARGET_Y,TARGET_Z[,FOV] to look elsewhere",
                   lit, image.pixels.size(), camera_spec(camera)));
}

// --false-colour lux: the luminance of the light arriving at each vertex, in false colour.
Image false_colour_image(const OutputMesh& mesh, const OutputOptions& o, const Camera& camera,
                         const RenderOptions& ro,
                         const std::function<void(const std::string&)>& say) {
  std::vector<float> lux(mesh.irradiance.size());
  for (size_t v = 0; v < lux.size(); ++v) lux[v] = luminance_of(mesh.irradiance[v]);
  const FalseColourScale scale = make_false_colour_scale(lux, o.false_colour_scale);
  say(fmt::format(
      "False colour: illuminance 0 to {} lx{}{}", format_scale_value(scale.max),
      scale.log_decades ? fmt::format(", logarithmic over {} decades", scale.log_decades) : "",
      o.false_colour_scale.max > 0.0 ? "" : " (set it with --false-colour-max)"));
  return render_false_colour(mesh.position(), lux, mesh.indices(), camera, ro, scale, "lx");
}

}  // namespace

void check_outputs(const OutputOptions& o) {
  if (!o.mesh.empty()) check_writable(o.mesh), check_mesh_extension(o.mesh);
  for (const std::string& image : o.images) check_writable(image), check_image_extension(image);
}

std::optional<Camera> write_outputs(const OutputMesh& mesh, const OutputOptions& o,
                                    const ToneMap& tone,
                                    const std::function<void(const std::string&)>& say,
                                    StagedFiles& files, const SolvedScene* solved) {
  if (!o.mesh.empty()) {
    say(fmt::format("Writing results in file {}", o.mesh));
    MeshFileOptions mo;
    mo.ascii = o.ascii;
    mo.tone = tone;
    // An OBJ names its MTL and images after its final name, and they are staged with it.
    mo.obj_name = o.mesh;
    mo.write_beside = [&](const std::string& path,
                          const std::function<void(const std::string&)>& write) {
      files.write(path, write);
    };
    files.write(o.mesh, [&](const std::string& path) { write_mesh_file(path, mesh, mo); });
  }
  if (o.images.empty()) return std::nullopt;
  const RenderOptions ro{o.image_width, o.image_height};
  const Camera camera = o.camera ? *o.camera
                                 : default_camera(mesh.position(), mesh.indices(),
                                                  float(ro.width) / float(ro.height));
  say(fmt::format("Camera: --camera {}{}", camera_spec(camera), o.camera ? "" : " (the default)"));
  Image image;
  ToneMap shown = tone;
  if (o.false_colour) {
    image = false_colour_image(mesh, o, camera, ro, say);
    shown = ToneMap{.scale = 1.0f, .curve = ToneCurve::Clamp};  // the palette as it is
  } else if (o.render == ImageRender::Final && solved) {
    // Camera rays go through the shadow-ray backend, which holds only what casts shadows.
    for (const SceneObject& obj : solved->state.solution.hierarchy->objects) {
      if (obj.kind == ObjectKind::Pure && obj.triangle_count > 0 && !obj.casts_shadows) {
        warn(obj.loc, fmt::format("'{}' casts no shadows, so the final render does not see it "
                                  "either; --render preview shows it",
                                  obj.name));
        break;
      }
    }
    GatheredImageOptions go;
    go.width = ro.width, go.height = ro.height;
    go.samples = o.pixel_samples;
    go.background = o.background;
    go.transparent = o.transparent;
    if (o.ambient) go.ambient = ambient_radiosity(solved->state.energy, solved->state.solution);
    GatheredImageStats stats;
    Progress progress(solved->quiet ? Progress::Mode::Quiet : Progress::Mode::Auto);
    image = render_gathered_image(solved->state, solved->vis, camera, go, &stats,
                                  [&](double done) { progress.update(done, "final gather"); });
    progress.finish(
        fmt::format("Final gather: {}x{} pixels, {} per pixel, in {:.2f} s ({} camera "
                    "rays, {} shadow rays)",
                    go.width, go.height, go.samples * go.samples, stats.seconds, stats.camera_rays,
                    stats.shadow_rays));
    if (solved->render_seconds) *solved->render_seconds = stats.seconds;
    warn_if_black(image, tone, o.images.front(), camera);
  } else {
    image = render_image(mesh.position(), mesh.display, mesh.indices(), camera, ro);
    warn_if_black(image, tone, o.images.front(), camera);
  }
  for (const std::string& path : o.images) {
    say(fmt::format("Writing image {}", path));
    files.write(path, [&](const std::string& staged) { write_image_file(staged, image, shown); });
  }
  return camera;
}

std::vector<std::string> group_image_paths(const std::string& image,
                                           const std::vector<std::string>& names) {
  const size_t slash = image.find_last_of('/');
  const size_t dot = image.find_last_of('.');
  const bool has_extension =
      dot != std::string::npos && (slash == std::string::npos || dot > slash);
  const std::string stem = has_extension ? image.substr(0, dot) : image;
  const std::string extension = has_extension ? image.substr(dot) : "";
  std::vector<std::string> tags, paths;
  for (size_t g = 0; g < names.size(); ++g) {
    std::string tag = names[g];
    for (char& c : tag) {
      const bool kept = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
      if (!kept) c = '_';
    }
    if (tag.empty() || std::find(tags.begin(), tags.end(), tag) != tags.end())
      tag = fmt::format("group{}", g);
    tags.push_back(tag);
    paths.push_back(stem + "." + tag + extension);
  }
  return paths;
}

}  // namespace rad
