// Triangles and materials read from a model file (Wavefront OBJ, PLY, glTF), before they become a
// scene description (model_scene.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "scene/description.h"
#include "scene/light.h"

namespace rad {

struct ModelMaterial {
  std::string name;
  Vec3 reflectance{0.8f};       // diffuse colour (OBJ Kd), times the texture's mean colour
  Vec3 emission{0.0f};          // OBJ Ke
  TextureMap base_texture;      // OBJ map_Kd, glTF baseColorTexture (empty: none read)
  TextureMap emissive_texture;  // OBJ map_Ke, glTF emissiveTexture (empty: none read)
  SourceLoc loc;                // where it was defined
  bool two_sided = false;       // glTF doubleSided: lit, reflecting and shooting on both sides
  AlphaMask cutout;             // glTF alphaMode MASK or BLEND, OBJ map_d (empty: opaque)
  /// Whether its faces need texture coordinates: it has a texture or a cut-out.
  bool uses_coordinates() const { return base_texture || emissive_texture || cutout; }
};

/// The material of faces that name none: grey 0.8, called `name`, defined at `loc`.
inline ModelMaterial fallback_material(std::string name, SourceLoc loc) {
  ModelMaterial m;
  m.name = std::move(name);
  m.loc = std::move(loc);
  return m;
}

/// A named part of the model (OBJ `o`/`g`): triangles, each with its material.
struct ModelGroup {
  std::string name;
  std::vector<std::array<Vec3, 3>> triangles;  // front by the right-hand rule
  std::vector<uint32_t> material;              // per triangle, into Model::materials
  // The face each triangle came from, or empty when the format gives no more than the file (a
  // located string per triangle would be half of a million-triangle model's import time).
  std::vector<SourceLoc> triangle_locs;
  /// Per triangle, its corners' texture coordinates (v down the image, as glTF), or empty when
  /// no triangle of the group has any.
  std::vector<std::array<Vec2, 3>> triangle_uvs;
};

struct Model {
  std::string path;
  std::vector<ModelMaterial> materials;
  std::vector<ModelGroup> groups;
  /// The lights that are not surfaces (glTF KHR_lights_punctual), placed in the model's space.
  std::vector<Light> lights;
  TextureCounts textures;
  size_t triangle_count() const {
    size_t n = 0;
    for (const ModelGroup& g : groups) n += g.triangles.size();
    return n;
  }
};

/// True when the path's extension names a model format rad reads (.obj, .ply, .gltf, .glb).
bool is_model_file(const std::string& path);

/// Reads a model of any format rad reads, by extension. Errors about opening it are located at
/// `requested_at`, errors in its content at the file. Throws rad::Error.
Model read_model_file(const std::string& path, const SourceLoc& requested_at);

}  // namespace rad
