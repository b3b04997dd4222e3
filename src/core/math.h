// Vector types used across rad (GLM, single precision for geometry).
#pragma once

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

}  // namespace rad
