#include "scene/description.h"

#include <glm/gtc/matrix_transform.hpp>

namespace rad {

const char* to_string(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::Assembly:
      return "Assembly";
    case ObjectKind::Composite:
      return "Composite";
    case ObjectKind::Pure:
      return "Pure";
  }
  return "?";
}

glm::dmat4 transform_matrix(const std::vector<Transform>& transforms) {
  glm::dmat4 m(1.0);
  for (const Transform& t : transforms) {
    switch (t.kind) {
      case Transform::Kind::Translate:
        m = glm::translate(glm::dmat4(1.0), t.v) * m;
        break;
      case Transform::Kind::Rotate:
        m = glm::rotate(glm::dmat4(1.0), glm::radians(t.degrees), glm::normalize(t.v)) * m;
        break;
      case Transform::Kind::Scale:
        m = glm::scale(glm::dmat4(1.0), t.v) * m;
        break;
    }
  }
  return m;
}

}  // namespace rad
