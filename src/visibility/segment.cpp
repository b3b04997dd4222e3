#include "visibility/segment.h"

namespace rad {

// 1e-5 of the diagonal: ~100x the float spacing of coordinates in a scene centred near its
// box, and well below the smallest features of the bundled scenes (Cornell box: 9.5 µm on 1 m).
float shadow_offset(const Aabb& scene_bounds) {
  float d = scene_bounds.diagonal();
  return d > 0.0f ? 1e-5f * d : 1e-6f;
}

}  // namespace rad
