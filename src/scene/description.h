// The scene as written in a description file (design §2): a tree of objects, as parsed.
#pragma once

#include <array>
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "scene/light.h"
#include "scene/stage.h"
#include "scene/texture.h"

namespace rad {

enum class ObjectKind : uint8_t { Assembly, Composite, Pure };

const char* to_string(ObjectKind kind);

/// A Pure's surface: reflectance = Reflectivity x Color, emission = Emission x Color, per
/// channel (design §2). Emission is radiant exitance, in the same units as radiosity.
/// A Pure with a base-colour texture (ObjectDescription::base_texture) reflects `reflectance`
/// on average: its factor times the texture's mean colour.
struct Material {
  Vec3 reflectance{0.0f};
  Vec3 emission{0.0f};
};

/// An object named in a `Lights` list, where it was written.
struct NamedObject {
  std::string name;
  SourceLoc loc;
};

/// The texture coordinates of a triangle that has none among triangles that have some (a
/// textured face without them): its vertices reflect their texture's mean.
inline const std::array<Vec2, 3> kNoTextureCoordinates = {
    Vec2(std::numeric_limits<float>::quiet_NaN()), Vec2(std::numeric_limits<float>::quiet_NaN()),
    Vec2(std::numeric_limits<float>::quiet_NaN())};

/// The original's proposed per-object flags (design §8), as written; unset means "as the parent".
/// They apply to the object and everything below it, the nearest setting winning.
struct ObjectFlags {
  std::optional<bool> casts_shadows;     // false: invisible to shadow rays
  std::optional<bool> receives_shadows;  // false: every visibility term of its vertices is 1
  std::optional<bool> two_sided;         // true: each triangle also faces the other way
  bool has_lights = false;               // an influence list was given: it lights only
  std::vector<NamedObject> lights;       // itself and these objects (with all below them)
  // The light group of what emits in and below the object (its Pures' emission and its
  // Lights without a Group of their own): one solution per group (solver/light_groups.h).
  std::optional<std::string> group;
};

/// One placement step as written: Translate <v>, Rotate <axis> degrees, or Scale <v> (a
/// uniform Scale s is <s s s>).
struct Transform {
  enum class Kind : uint8_t { Translate, Rotate, Scale };
  Kind kind = Kind::Translate;
  DVec3 v{0.0};          // the translation, the rotation's axis, or the scale factors
  double degrees = 0.0;  // Rotate only
};

/// The matrix of transforms applied in the order written (the first is applied first).
glm::dmat4 transform_matrix(const std::vector<Transform>& transforms);

/// One object of the description. Children index SceneDescription::objects.
struct ObjectDescription {
  std::string name;
  ObjectKind kind = ObjectKind::Pure;
  SourceLoc loc;  // where "Object" was written
  ObjectFlags flags;
  // Placement (design §8), as written: applied to everything below, after the transforms of the
  // objects inside and before those of the objects around it.
  std::vector<Transform> transforms;
  // A copy of an earlier object (`Copy "name"`): its kind, contents and flags, placed by this
  // object's transform on top of the original's. Holds no children or triangles itself.
  int32_t copy_of = -1;
  std::vector<int32_t> children;  // Assembly and Composite only
  Material material;              // Pure only
  /// Pure only: a model material's base-colour texture, or none. Each vertex then reflects the
  /// material's reflectance scaled by the texture filtered over its element, over the
  /// texture's mean (solver/texture_factors.h).
  TextureMap base_texture;
  /// Pure only: a model material's emissive texture, or none: the emission is then its factor
  /// times the texture's mean, and each vertex scales it likewise.
  TextureMap emissive_texture;
  /// Pure only: where a model's material is cut out (texture alpha below a cutoff), or none.
  /// Shadow rays pass through the holes in every backend, and each vertex receives, reflects
  /// and shoots only for the opaque part of its element.
  AlphaMask cutout;
  std::vector<std::array<Vec3, 3>> triangles;  // Pure only: corners a, b, c (front: (b-a)x(c-a))
  std::vector<SourceLoc> triangle_locs;        // Pure only: where each was written (or empty)
  /// Pure only: texture coordinates of each triangle's corners (glTF convention: v down the
  /// image), or empty when it has none.
  std::vector<std::array<Vec2, 3>> triangle_uvs;
  /// Set for a Light object alone (`Object "lamp" Light { ... }`, or a model's light): the light
  /// in the object's own coordinates, placed by the transforms around it as a Pure's triangles
  /// are. Such an object has no children, triangles or material (its `kind` is Pure, unused);
  /// build_hierarchy makes it a Hierarchy::lights entry, not a SceneObject.
  std::optional<Light> light;
};

/// Base-colour textures of a model's materials: those read (the material reflects their mean
/// colour) and those named but not found or not decodable (the material keeps its colour alone).
struct TextureCounts {
  size_t read = 0;
  size_t unread = 0;
};

/// What a model file held besides its triangles, for the summary of `rad --check`, and the
/// stage it was set on (--stage), which the run layer prints and frames.
struct ModelSummary {
  std::vector<std::string> materials;  // names, in the file's order
  TextureCounts textures;
  std::optional<Stage> stage;
};

struct SceneDescription {
  std::string name;                   // the scene's name (first string of the file)
  std::string path;                   // the description file
  std::optional<ModelSummary> model;  // set when the scene is a model file
  std::vector<ObjectDescription> objects;
  std::vector<int32_t> roots;  // top-level objects, in file order
};

}  // namespace rad
