// The options every way of running rad shares: how a scene is read, how it is solved, and what
// is written from the solution. Each mode (app/cli.h) takes the sets it uses and refuses the rest.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "export/camera.h"
#include "export/false_colour.h"
#include "export/tonemap.h"
#include "hierarchy/auto_hierarchy.h"
#include "scene/model_scene.h"
#include "solver/options.h"
#include "visibility/backend.h"

namespace rad {

/// A scene file and how to read it: every mode.
struct SceneInput {
  std::string path;                        // a description (.des) or a model (.obj, .ply, ...)
  ModelOptions model;                      // --emit rules for a model
  std::optional<HierarchyMode> hierarchy;  // --hierarchy; none: default_hierarchy_mode
  std::optional<double> unit;  // --unit: metres per scene unit (none: 1; glTF: metres always)
};

/// How a scene is solved: every mode that solves.
struct RunOptions {
  BackendKind backend = BackendKind::Embree;
  bool packets = true;
  int threads = 0;  // 0: the cores this process may use (see thread_count)
  SolverOptions solver;
  bool quiet = false;
};

enum class ImageRender : uint8_t { Final, Preview };

/// What is written from a solution: the mesh, images, and how their colours are shown.
struct OutputOptions {
  std::string mesh;                 // empty: no mesh file
  std::vector<std::string> images;  // .png, .hdr, .exr or .pfm
  std::optional<Camera> camera;     // none: default_camera frames the scene
  int image_width = 800, image_height = 800;
  // How images are made: a final gather at every pixel (export/gathered_image.h), or the
  // Gouraud raster of the mesh (export/image_render.h), the fast preview.
  ImageRender render = ImageRender::Final;
  int pixel_samples = 3;  // final gather: subsamples per pixel along each axis
  // Final gather: what pixels show where nothing is seen, or transparency (an alpha channel).
  Vec3 background{0.0f};
  bool transparent = false;
  // With two light groups or more: beside each image, one per group of that group's light
  // alone (group_image_paths), through the same camera and exposure.
  bool group_images = false;
  bool ascii = false;   // PLY as text
  bool ambient = true;  // display colours include Cohen's ambient term
  ToneCurve tonemap = ToneCurve::Clamp;
  float exposure = 0.0f;  // stops added to the automatic exposure
  // --false-colour lux: every image shows the illuminance (the luminance of H) in false colour
  // with a legend instead of the tone-mapped radiosity.
  bool false_colour = false;
  FalseColourOptions false_colour_scale;
};

}  // namespace rad
