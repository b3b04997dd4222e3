// The files written from one solved view, the same for every mode.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "export/camera.h"
#include "export/output_mesh.h"
#include "export/tonemap.h"
#include "run/output_files.h"
#include "run/run_options.h"
#include "visibility/backend.h"

namespace rad {

/// What a final gather renders from: the solved state and the visibility it was solved with;
/// `quiet`: no progress bar.
struct SolvedScene {
  const SolverState& state;
  const VisibilityBackend& vis;
  bool quiet = false;
  double* render_seconds = nullptr;  // when given, set to the final gather's time
};

/// Refuses, before any work is done, a mesh or image name whose extension no writer takes, or
/// one that cannot be written (check_writable). Throws rad::Error.
void check_outputs(const OutputOptions& o);

/// Writes o.mesh and every o.images from `mesh`, shown with `tone`, into `files` (which the
/// caller commits, with any other output of the run); images through o.camera (or
/// default_camera) at o.image_width x o.image_height, or with o.false_colour the luminance of
/// the light arriving in false colour with a legend at their left (render_false_colour). `say`
/// is told each file's name first. With o.render Final and `solved` given, images are rendered
/// by final gather (render_gathered_image); else (or in false colour) by the raster of `mesh`.
/// Returns the camera the images were rendered through (none without images).
std::optional<Camera> write_outputs(const OutputMesh& mesh, const OutputOptions& o,
                                    const ToneMap& tone,
                                    const std::function<void(const std::string&)>& say,
                                    StagedFiles& files, const SolvedScene* solved = nullptr);

/// The images of light groups `names` beside `image`, one per group: its stem, a dot, the
/// group's name with every character but letters, digits, '-' and '_' made '_', and its
/// extension (box.png, "Desk lamp": box.Desk_lamp.png); "group" and the group's index where
/// that leaves no name or the name of a group before it ("": box.group0.png).
std::vector<std::string> group_image_paths(const std::string& image,
                                           const std::vector<std::string>& names);

}  // namespace rad
