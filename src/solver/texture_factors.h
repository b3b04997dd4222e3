// How a textured or cut-out surface's reflectance and emission vary: per vertex, its material's
// base (emissive) texture filtered over the element the vertex stands for, over the texture's
// mean colour, times the opaque fraction of that element when the surface is cut out. The
// material's reflectance (emission) is its factor times that mean (scene/description.h), so a
// vertex reflects (emits) the material's times its texture factor, and a texture finer than the
// elements averages to the material as a whole; a hole reflects, emits and shoots nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "mesh/patch_mesh.h"

namespace rad {

/// What a vertex's reflectance and emission are over its material's.
struct TextureFactors {
  Vec3 reflectance{1.0f};
  Vec3 emission{1.0f};
};

/// The texture factors at `position` (on triangle p of `t`, whose Pure is `o`, is_textured) of a
/// vertex standing for an element of area `element_area`: the base (emissive) texture averaged
/// over that element's footprint in the image, over the image's mean, per channel (1 where the
/// mean is 0: the channel is 0 throughout; 1 without that texture), times the footprint's
/// opaque fraction when `o` is cut out.
TextureFactors texture_factor(const Triangles& t, size_t p, const SceneObject& o,
                              const Vec3& position, float element_area);

/// True when polygon p reflects or emits by a texture or a cut-out: its Pure `o` has one and its
/// triangle has texture coordinates.
bool is_textured(const Triangles& t, size_t p, const SceneObject& o);

/// The factors of every vertex of `mesh` (polygon p, of Pure `o`), each standing for the
/// smallest leaf element it is a corner of: the initial mesh's.
std::vector<TextureFactors> initial_texture_factors(const Triangles& t, size_t p,
                                                    const SceneObject& o, const PolygonMesh& mesh);

}  // namespace rad
