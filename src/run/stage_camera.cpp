#include "run/stage_camera.h"

#include <algorithm>

namespace rad {

namespace {
constexpr float kFill = 0.85f;  // of the image's half-width and half-height the box may fill
}  // namespace

Camera stage_camera(const Stage& stage, float aspect) {
  Camera c;
  c.target = stage.model.center();
  c.eye = c.target + stage.view_direction;
  const CameraFrame f = camera_frame(c, std::max(aspect, 1e-6f));
  // With the eye at distance d behind the target along -forward, a corner p (relative to the
  // target) lies at depth d + p.forward; it is in view when |p.right| <= depth tan_half_x and
  // |p.up| <= depth tan_half_y. The nearest d that holds for every corner:
  float d = 0.0f;
  const Vec3 lo = stage.model.lo, hi = stage.model.hi;
  for (int k = 0; k < 8; ++k) {
    const Vec3 p = Vec3(k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z) - c.target;
    const float depth = glm::dot(p, f.forward);
    d = std::max(d, std::abs(glm::dot(p, f.right)) / (kFill * f.tan_half_x) - depth);
    d = std::max(d, std::abs(glm::dot(p, f.up)) / (kFill * f.tan_half_y) - depth);
  }
  // A box with no extent along the view (never from a planned stage) still gets a distance.
  d = std::max(d, 1e-3f * std::max(stage.model.diagonal(), 1e-30f));
  c.eye = c.target + stage.view_direction * d;
  return c;
}

}  // namespace rad
