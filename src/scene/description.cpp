#include "scene/description.h"

namespace rad {

const char* to_string(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::Assembly: return "Assembly";
    case ObjectKind::Composite: return "Composite";
    case ObjectKind::Pure: return "Pure";
  }
  return "?";
}

}  // namespace rad
