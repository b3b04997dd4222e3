// PLY output: the contract other tools read (per-vertex linear radiosity and tone-mapped
// display colour; the README's "Output" section documents the properties).
#pragma once

#include <ostream>

#include "export/output_mesh.h"
#include "export/tonemap.h"

namespace rad {

/// Writes one vertex element (float x y z; uchar red green blue = display colour, tone-mapped
/// and sRGB-encoded; float radiosity_r/g/b = linear radiosity; float irradiance_r/g/b = H; with
/// texture coordinates, float s t, t up the image as in OBJ) and one face element
/// (list uchar uint vertex_indices). Binary little-endian unless `ascii`.
void write_ply(std::ostream& out, const OutputMesh& mesh, const ToneMap& tm, bool ascii);

}  // namespace rad
