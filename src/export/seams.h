// How far the radiosity jumps across edges shared by neighbouring polygons (the original keeps
// no connectivity between polygons, so a subdivided polygon can show a seam against its
// unsplit neighbour).
#pragma once

#include <string>

#include "export/output_mesh.h"
#include "hierarchy/hierarchy.h"

namespace rad {

struct SeamReport {
  size_t shared_edges = 0;      // pairs of coplanar polygons sharing an edge
  size_t vertices_checked = 0;  // output vertices on those edges
  double largest_jump = 0.0;    // max over them of the largest channel |B_this - B_other|
  double mean_jump = 0.0;
  double mean_radiosity = 0.0;  // of the output vertices (mean over channels): the scale
  Vec3 where{0.0f};             // position of the largest jump
};

/// For every edge shared by two coplanar polygons, compares each output vertex lying on it
/// with the other polygon's radiosity interpolated along the same edge.
SeamReport measure_seams(const OutputMesh& mesh, const Triangles& triangles);

}  // namespace rad
