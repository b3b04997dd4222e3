// `rad serve` from start to stop: parse, build, solve in the background while serving the page,
// and on Ctrl-C or SIGTERM write the requested files from where the solve got to.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "export/camera.h"
#include "hierarchy/auto_hierarchy.h"
#include "scene/model_scene.h"
#include "serve/server.h"
#include "serve/session.h"
#include "visibility/backend.h"

namespace rad {

struct ServeConfig {
  std::string scene;
  ModelOptions model;                      // for a model file as the scene
  std::optional<HierarchyMode> hierarchy;  // none: default_hierarchy_mode
  ServerOptions server;
  SessionOptions session;
  BackendKind backend = BackendKind::Embree;
  bool packets = true;
  int threads = 0;                  // 0: all cores
  std::string output;               // mesh written on exit; empty: none
  std::vector<std::string> images;  // images written on exit
  std::optional<Camera> camera;     // for the images; none: default_camera
  int image_width = 800, image_height = 800;
  bool ascii = false;  // PLY as text
  bool quiet = false;
  std::string web_modules;  // node_modules with three and lil-gui; empty: default
};

/// Runs the server until SIGINT or SIGTERM, prints its address first. Output names are checked
/// and the page's modules located before anything is solved. Returns the exit status; throws
/// rad::Error on bad input (scene, output names, missing modules, an address it cannot bind).
int run_serve(const ServeConfig& c);

}  // namespace rad
