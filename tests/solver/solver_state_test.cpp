// The solver state's own helpers: the scene's size the default limits scale with.
#include "solver/solver_state.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene_builder.h"

namespace rad {
namespace {

Hierarchy box(float turn_y, float turn_x) {
  SceneDescription d;
  testing::add_closed_box(d, Vec3(0.0f), Vec3(2.0f, 1.0f, 3.0f), Vec3(0.5f), Vec3(1.0f));
  const float cy = std::cos(turn_y), sy = std::sin(turn_y), cx = std::cos(turn_x),
              sx = std::sin(turn_x);
  for (ObjectDescription& o : d.objects) {
    for (auto& t : o.triangles) {
      for (Vec3& p : t) {
        p = Vec3(cy * p.x + sy * p.z, p.y, -sy * p.x + cy * p.z);
        p = Vec3(p.x, cx * p.y - sx * p.z, sx * p.y + cx * p.z) + Vec3(7.0f, -3.0f, 2.0f);
      }
    }
  }
  return build_hierarchy(d);
}

TEST(SceneSize, IsABoxsDiagonalHoweverTheBoxIsTurned) {
  const float diagonal = std::sqrt(4.0f + 1.0f + 9.0f);
  const Hierarchy straight = box(0.0f, 0.0f), turned = box(0.5236f, 0.3491f);
  EXPECT_NEAR(scene_size(straight), diagonal, 1e-5f * diagonal);
  EXPECT_NEAR(straight.bounds.diagonal(), diagonal, 1e-5f * diagonal);
  // For a box Ritter's first two passes find two opposite corners, whose sphere holds the rest:
  // the diagonal, to the rounding of the turn. The turned box's bounding box is far off.
  EXPECT_NEAR(scene_size(turned), diagonal, 1e-5f * diagonal);
  EXPECT_GT(turned.bounds.diagonal(), 1.2f * diagonal);
}

}  // namespace
}  // namespace rad
