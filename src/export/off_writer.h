// Geomview COFF output: the original's viewer family.
#pragma once

#include <ostream>

#include "export/output_mesh.h"
#include "export/tonemap.h"

namespace rad {

/// Writes "COFF", the counts "V F 0", one line "x y z r g b a" per vertex (the display colour,
/// tone-mapped and sRGB-encoded as in PLY, as 0-1 floats: the PLY byte / 255; a = 1), and one
/// line "3 i j k" per face.
void write_off(std::ostream& out, const OutputMesh& mesh, const ToneMap& tm);

}  // namespace rad
