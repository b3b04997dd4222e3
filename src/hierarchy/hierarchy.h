// The object hierarchy of design §3 (Assembly / Composite / Pure) over a flat table of
// world-space triangles, laid out depth-first so every object's triangles are contiguous.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/aabb.h"
#include "core/error.h"
#include "scene/description.h"
#include "scene/light.h"

namespace rad {

/// Flat world-space triangles (structure of arrays). Index = triangle id = polygon id.
struct Triangles {
  std::vector<std::array<Vec3, 3>> corners;  // a, b, c
  std::vector<Vec3> normal;                  // unit, (b-a)x(c-a) normalised
  std::vector<float> area;
  std::vector<int32_t> object;  // the Pure that owns the triangle
  /// Texture coordinates of a, b and c (scene/description.h's convention), or empty when no
  /// triangle of the scene has any.
  std::vector<std::array<Vec2, 3>> uv;
  size_t size() const { return corners.size(); }
  Vec3 centroid(size_t i) const {
    return (corners[i][0] + corners[i][1] + corners[i][2]) * (1.0f / 3.0f);
  }
};

/// Triangles [first, first + count) of the depth-first table: one object and all below it.
struct TriangleRange {
  uint32_t first = 0, count = 0;
};

struct SceneObject {
  std::string name;
  ObjectKind kind = ObjectKind::Pure;
  SourceLoc loc;
  int32_t parent = -1;
  std::vector<int32_t> children;
  Aabb box;                     // of all triangles below
  uint32_t first_triangle = 0;  // triangles below this object: [first, first + count)
  uint32_t triangle_count = 0;
  Material material;            // Pure only
  TextureMap base_texture;      // Pure only: see ObjectDescription::base_texture
  TextureMap emissive_texture;  // Pure only: see ObjectDescription::emissive_texture
  AlphaMask cutout;             // Pure only: see ObjectDescription::cutout
  // The per-object flags of design §8, resolved: the object's own setting, else its nearest
  // ancestor's, else the default.
  bool casts_shadows = true;     // false: shadow rays pass through its triangles
  bool receives_shadows = true;  // false: its vertices take every visibility term as 1
  // A Pure's second face of each triangle (ObjectFlags::two_sided): its triangles' second half
  // are the first half's, turned over.
  bool two_sided = false;
  std::string group;  // light group of its emission (ObjectFlags::group); "": the default group
  int32_t influence = -1;          // the object whose Lights list applies here; -1: lights all
  std::vector<TriangleRange> lit;  // with a Lights list: what it lights, sorted and merged
};

struct Hierarchy {
  std::string scene_name;
  std::string source_path;
  std::vector<SceneObject> objects;
  std::vector<int32_t> roots;
  Triangles triangles;
  Aabb bounds;
  /// The lights that are not surfaces (scene/light.h), in world space.
  std::vector<Light> lights;
  uint32_t dropped_degenerate = 0;    // zero-area triangles removed while building
  std::optional<ModelSummary> model;  // the model file's materials and textures, if a model
};

/// Largest coordinate magnitude a scene may use: the form factor kernels take distances to the
/// fourth power in single precision (A cos cos / r^2 (pi r^2 + A) grows as L^4 in the scene's
/// size L), which must stay below 3.4e38.
inline constexpr float kMaxCoordinate = 1e8f;

/// What copies of copies may make before the build refuses (each copy doubling an object would
/// otherwise grow exponentially with the file).
struct BuildLimits {
  size_t max_triangles = 50'000'000;
  size_t max_objects = 10'000'000;
  int max_depth = 256;
};

/// Builds the hierarchy: computes normals, areas and boxes, drops zero-area triangles (one
/// warning counting them), orders triangles depth-first, and resolves the per-object flags and
/// the names in Lights lists (every object of a listed name). Throws rad::Error if an object
/// ends up empty or a list names no object. Copies (ObjectDescription::copy_of) are flattened,
/// transforms applied (a mirroring one keeps each triangle's front); beyond `limits` it throws.
/// With !warn it says nothing (a regrouped scene built again: the first build warned).
Hierarchy build_hierarchy(const SceneDescription& scene, const BuildLimits& limits = {},
                          bool warn = true);

/// Whether a shooter whose Pure has SceneObject::influence `influence` lights triangle t.
bool influence_reaches(const Hierarchy& h, int32_t influence, uint32_t t);

/// True when `object` is the index of a Pure: the objects that hold a material.
bool is_pure(const Hierarchy& h, int64_t object);

/// Counts per kind, triangles, emitters, materials (and a model's textures), bounds: the
/// summary printed by `rad --check`.
std::string summarize(const Hierarchy& h);

}  // namespace rad
