// The files written from one solved view, the same for every mode.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "export/camera.h"
#include "export/output_mesh.h"
#include "export/tonemap.h"
#include "run/output_files.h"
#include "run/run_options.h"

namespace rad {

/// Refuses, before any work is done, a mesh or image name whose extension no writer takes, or
/// one that cannot be written (check_writable). Throws rad::Error.
void check_outputs(const OutputOptions& o);

/// Writes o.mesh and every o.images from `mesh`, shown with `tone`, into `files` (which the
/// caller commits, with any other output of the run); images through o.camera (or
/// default_camera) at o.image_width x o.image_height, or with o.false_colour the luminance of
/// the light arriving in false colour with a legend at their left (render_false_colour). `say`
/// is told each file's name first.
/// Returns the camera the images were rendered through (none without images).
std::optional<Camera> write_outputs(const OutputMesh& mesh, const OutputOptions& o,
                                    const ToneMap& tone,
                                    const std::function<void(const std::string&)>& say,
                                    StagedFiles& files);

}  // namespace rad
