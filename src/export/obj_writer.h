// Wavefront OBJ output with per-vertex colours ("v x y z r g b").
#pragma once

#include <ostream>

#include "export/output_mesh.h"
#include "export/tonemap.h"

namespace rad {

/// Writes one "v x y z r g b" line per vertex (the display colour, tone-mapped and sRGB-encoded
/// as in PLY, as 0-1 floats: the PLY byte / 255) and one "f i j k" line per face (1-based).
void write_obj(std::ostream& out, const OutputMesh& mesh, const ToneMap& tm);

}  // namespace rad
