// How a textured or cut-out surface's reflectance varies: per vertex, its material's base
// texture filtered over the element the vertex stands for, over the texture's mean colour, times
// the opaque fraction of that element when the surface is cut out. The material's reflectance
// is its factor times that mean (scene/description.h), so a vertex reflects the material's
// reflectance times its texture factor, and a texture finer than the elements averages to the
// material as a whole; a hole reflects, and so shoots, nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"

namespace rad {

/// The texture factor at `position` (on triangle p of `t`, whose Pure is `o`, is_textured) of a
/// vertex standing for an element of area `element_area`: the base texture averaged over that
/// element's footprint in the image, over the image's mean, per channel (1 where the mean is 0:
/// the channel is 0 throughout; 1 without a base texture), times the footprint's opaque
/// fraction when `o` is cut out.
Vec3 texture_factor(const Triangles& t, size_t p, const SceneObject& o, const Vec3& position,
                    float element_area);

/// True when polygon p reflects by a texture or a cut-out: its Pure `o` has one and its triangle
/// has texture coordinates.
bool is_textured(const Triangles& t, size_t p, const SceneObject& o);

/// The factors of every vertex of `mesh` (polygon p, of Pure `o`), each standing for the
/// smallest leaf element it is a corner of: the initial mesh's.
std::vector<Vec3> initial_texture_factors(const Triangles& t, size_t p, const SceneObject& o,
                                          const PolygonMesh& mesh);

}  // namespace rad
