// How a textured surface's reflectance varies: per vertex, its material's base texture filtered
// over the element the vertex stands for, over the texture's mean colour. The material's
// reflectance is its factor times that mean (scene/description.h), so a vertex reflects the
// material's reflectance times its texture factor, and a texture finer than the elements
// averages to the material as a whole.
#pragma once

#include <cstdint>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"

namespace rad {

/// The texture factor at `position` (on triangle p of `t`, which has texture coordinates) of a
/// vertex standing for an element of area `element_area`: the texture averaged over that
/// element's footprint in the image, over the image's mean, per channel (1 where the mean is 0:
/// the channel is 0 throughout).
Vec3 texture_factor(const Triangles& t, size_t p, const TextureMap& texture, const Vec3& position,
                    float element_area);

/// True when polygon p reflects by a texture: its Pure has one and its triangle has texture
/// coordinates.
bool is_textured(const Triangles& t, size_t p, const TextureMap& texture);

/// The factors of every vertex of `mesh` (polygon p), each standing for the smallest leaf
/// element it is a corner of: the initial mesh's.
std::vector<Vec3> initial_texture_factors(const Triangles& t, size_t p, const TextureMap& texture,
                                          const PolygonMesh& mesh);

}  // namespace rad
