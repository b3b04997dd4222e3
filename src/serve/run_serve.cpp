#include "serve/run_serve.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <csignal>
#include <cstdio>
#include <memory>

#include "core/error.h"
#include "export/image_file.h"
#include "export/image_render.h"
#include "export/mesh_file.h"
#include "hierarchy/auto_hierarchy.h"
#include "hierarchy/hierarchy.h"
#include "scene/scene_file.h"
#include "serve/shutdown.h"
#include "serve/web_assets.h"

namespace rad {

int run_serve(const ServeConfig& c) {
  auto say = [&](const std::string& s) {
    if (c.quiet) return;
    std::fputs((s + "\n").c_str(), stdout);
    std::fflush(stdout);
  };
  if (!c.output.empty()) check_mesh_extension(c.output);
  for (const std::string& image : c.images) check_image_extension(image);
  WebAssets assets =
      load_web_assets(c.web_modules.empty() ? default_web_modules_dir() : c.web_modules);

  const Hierarchy hierarchy = load_hierarchy(c.scene, c.model, c.hierarchy);
  const int threads = c.threads > 0 ? c.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  const std::unique_ptr<VisibilityBackend> visibility =
      make_visibility_backend(c.backend, hierarchy, VisibilityOptions{c.packets});
  Session session(hierarchy, *visibility, c.session);
  Server server(session, std::move(assets), c.server);
  server.bind();
  if (!is_loopback_host(c.server.host)) {
    std::fprintf(stderr,
                 "warning: serving on %s: anyone who can reach this address can see and edit "
                 "the scene\n",
                 c.server.host.c_str());
  }
  session.start();
  server.start();
  // The address goes out even with --quiet: it is what the user (or a test) needs.
  std::printf("rad serve: %s (%zu triangles, %s backend); Ctrl-C stops%s\n", server.url().c_str(),
              hierarchy.triangles.size(), to_string(c.backend),
              c.output.empty() ? "" : fmt::format(" and writes {}", c.output).c_str());
  std::fflush(stdout);

  const int sig = wait_for_shutdown();
  say(fmt::format("\nStopping ({})", sig == SIGTERM ? "SIGTERM" : "Ctrl-C"));
  server.stop();
  session.stop();

  const auto snap = session.snapshot();
  say(fmt::format("{} shots, unshot fraction {:.3e}, {} elements", snap->shots,
                  snap->unshot_fraction, snap->elements));
  if (c.output.empty() && c.images.empty()) return 0;
  const OutputMesh& mesh = snap->mesh;
  if (!c.output.empty()) {
    say(fmt::format("Writing results in file {}", c.output));
    MeshFileOptions mo;
    mo.ascii = c.ascii;
    mo.tone = snap->tone;  // the exposure the page showed
    write_mesh_file(c.output, mesh, mo);
  }
  if (!c.images.empty()) {
    const RenderOptions ro{c.image_width, c.image_height};
    const Camera camera = c.camera ? *c.camera
                                   : default_camera(mesh.position(), mesh.indices(),
                                                    float(ro.width) / float(ro.height));
    const Image image = render_image(mesh.position(), mesh.display, mesh.indices(), camera, ro);
    for (const std::string& path : c.images) {
      say(fmt::format("Writing image {}", path));
      write_image_file(path, image, snap->tone);
    }
  }
  return 0;
}

}  // namespace rad
