// Vector types used across rad (GLM, single precision for geometry).
#pragma once

#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace rad {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using DVec3 = glm::dvec3;

/// Largest of the three components.
inline float max_component(const Vec3& v) { return glm::max(v.x, glm::max(v.y, v.z)); }

/// Mean of the three components (a colour's grey level).
inline float mean_component(const Vec3& v) { return (v.x + v.y + v.z) * (1.0f / 3.0f); }
/// The same in double: a double vector would otherwise convert to float and round by 6e-8.
inline double mean_component(const DVec3& v) { return (v.x + v.y + v.z) / 3.0; }

/// splitmix64's finaliser (Steele, Lea and Flood 2014): the 64 bits of z, well mixed.
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// splitmix64: 64 well-mixed bits of a key, the same on every run, thread and rank; what every
/// deterministic draw of the project is made from.
inline uint64_t splitmix64(uint64_t z) { return mix64(z + 0x9e3779b97f4a7c15ull); }

}  // namespace rad
