#include "export/camera.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "core/error.h"
#include "hierarchy/hierarchy.h"
#include "scene/parser.h"

namespace rad {
namespace {

struct Soup {
  std::vector<Vec3> positions;
  std::vector<uint32_t> indices;
  /// Quad a b c d as two triangles, its front by the right-hand rule.
  void quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const uint32_t n = uint32_t(positions.size());
    positions.insert(positions.end(), {a, b, c, d});
    indices.insert(indices.end(), {n, n + 1, n + 2, n, n + 2, n + 3});
  }
  /// The box [0, size] with its six faces facing in: a room.
  void room(Vec3 size) {
    const float w = size.x, h = size.y, d = size.z;
    quad({0, 0, 0}, {0, 0, d}, {w, 0, d}, {w, 0, 0});  // floor
    quad({0, h, 0}, {w, h, 0}, {w, h, d}, {0, h, d});  // ceiling
    quad({0, 0, 0}, {0, h, 0}, {0, h, d}, {0, 0, d});  // x = 0
    quad({w, 0, 0}, {w, 0, d}, {w, h, d}, {w, h, 0});  // x = w
    quad({0, 0, d}, {0, h, d}, {w, h, d}, {w, 0, d});  // z = d
    quad({0, 0, 0}, {w, 0, 0}, {w, h, 0}, {0, h, 0});  // z = 0
  }
  /// The box [lo, hi] with its six faces facing out: a solid.
  void block(Vec3 lo, Vec3 hi) {
    quad({lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z});  // +y
    quad({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});  // -y
    quad({lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z});  // -z
    quad({lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});  // +z
    quad({lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z});  // -x
    quad({hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z});  // +x
  }
};

Soup load_scene(const std::string& name) {
  const Hierarchy h = build_hierarchy(parse_scene_file(std::string(RAD_SOURCE_DIR) + "/" + name));
  Soup s;
  for (const auto& t : h.triangles.corners) {
    for (const Vec3& p : t) {
      s.indices.push_back(uint32_t(s.positions.size()));
      s.positions.push_back(p);
    }
  }
  return s;
}

/// Horizontal image coordinate in [-1, 1] (left to right) of p seen by c.
float screen_x(const Camera& c, Vec3 p) {
  const CameraFrame f = camera_frame(c, 1.0f);
  const Vec3 d = p - c.eye;
  return glm::dot(d, f.right) / (glm::dot(d, f.forward) * f.tan_half_x);
}

TEST(Camera, ParsesEyeTargetAndOptionalFov) {
  const Camera a = parse_camera("278,273,-800,278,273,0");
  EXPECT_EQ(a.eye, Vec3(278, 273, -800));
  EXPECT_EQ(a.target, Vec3(278, 273, 0));
  EXPECT_FLOAT_EQ(a.fov_y_deg, kDefaultFovDeg);
  EXPECT_FLOAT_EQ(parse_camera("0,0,0,0,0,1,60.5").fov_y_deg, 60.5f);
  EXPECT_EQ(parse_camera("-1.5e1,0,0,0,0,1").eye.x, -15.0f);
}

TEST(Camera, RejectsMalformedSpecs) {
  EXPECT_THROW(parse_camera(""), Error);
  EXPECT_THROW(parse_camera("1,2,3,4,5"), Error);
  EXPECT_THROW(parse_camera("1,2,3,4,5,6,7,8"), Error);
  EXPECT_THROW(parse_camera("1,2,x,4,5,6"), Error);
  EXPECT_THROW(parse_camera("1,2,3,,5,6"), Error);
  EXPECT_THROW(parse_camera("1,2,3,1,2,3"), Error);    // eye == target
  EXPECT_THROW(parse_camera("0,0,0,0,0,1,0"), Error);  // fov out of range
  EXPECT_THROW(parse_camera("0,0,0,0,0,1,180"), Error);
}

TEST(Camera, FrameIsOrthonormalWithPositiveXOnTheLeftLookingAlongZ) {
  const Camera c = parse_camera("278,273,-800,278,273,0");
  const CameraFrame f = camera_frame(c, 2.0f);
  EXPECT_NEAR(glm::dot(f.forward, Vec3(0, 0, 1)), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(f.up, Vec3(0, 1, 0)), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(f.right, Vec3(-1, 0, 0)), 1.0f, 1e-6f);
  EXPECT_NEAR(f.tan_half_y, std::tan(39.3 * M_PI / 360.0), 1e-6);
  EXPECT_NEAR(f.tan_half_x, 2.0f * f.tan_half_y, 1e-6f);
  // The Cornell box's red wall (x = 556) is on the left, the green one (x = 0) on the right.
  EXPECT_LT(screen_x(c, Vec3(550, 274, 300)), -0.3f);
  EXPECT_GT(screen_x(c, Vec3(5, 274, 300)), 0.3f);
}

TEST(Camera, LookingStraightDownStillHasAFrame) {
  const CameraFrame f = camera_frame(parse_camera("0,10,0,0,0,0"), 1.0f);
  EXPECT_NEAR(glm::length(f.right), 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(f.right, f.forward), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(f.up, f.forward), 0.0f, 1e-6f);
}

TEST(Camera, DefaultForTheCornellBoxIsThePublishedView) {
  const Soup s = load_scene("scenes/cornell_box.des");
  const Camera c = default_camera(s.positions, s.indices, 1.0f);
  // Published: eye (278, 273, -800), target (278, 273, 0), up +y, fov 39.3.
  EXPECT_NEAR(c.eye.x, 278.0f, 1.0f);
  EXPECT_NEAR(c.eye.y, 273.0f, 2.0f);
  EXPECT_NEAR(c.eye.z, -800.0f, 5.0f);
  EXPECT_NEAR(c.target.x, 278.0f, 1.0f);
  EXPECT_NEAR(c.target.y, 273.0f, 2.0f);
  EXPECT_NEAR(c.target.z, 0.0f, 1.0f);
  EXPECT_EQ(c.up, Vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(c.fov_y_deg, 39.3f);
  EXPECT_LT(screen_x(c, Vec3(550, 274, 300)), 0.0f);  // red wall on the left
}

TEST(Camera, DefaultForAClosedRoomStandsInsideIt) {
  const Soup s = load_scene("scenes/furnace_box.des");
  const Camera c = default_camera(s.positions, s.indices, 1.0f);
  for (int k = 0; k < 3; ++k) {
    EXPECT_GT(c.eye[k], 0.0f);
    EXPECT_LT(c.eye[k], 1.0f);
  }
  // High in a corner, looking down across the room's middle.
  EXPECT_GT(c.eye.y, 0.5f);
  EXPECT_LT(c.target.y, c.eye.y);
  for (const int k : {0, 2})
    EXPECT_GT(std::abs(c.target[k] - c.eye[k]), 0.5f) << "across the room along axis " << k;
  EXPECT_GT(c.fov_y_deg, 50.0f);  // wide enough to show it
}

// A room 5 x 2.7 x 4 m with a solid block in three of its four quarters: the eye stands in the
// empty one, in front of its two walls and above the blocks, and sees each block's top.
TEST(Camera, DefaultForAFurnishedRoomStandsInTheCornerWithTheLeastInTheWay) {
  const float w = 5.0f, h = 2.7f, d = 4.0f;
  for (int empty = 0; empty < 4; ++empty) {
    Soup s;
    s.room({w, h, d});
    const std::array<Vec3, 4> corners{Vec3(0, 0, 0), Vec3(w, 0, 0), Vec3(0, 0, d), Vec3(w, 0, d)};
    std::vector<Vec3> tops;
    for (int k = 0; k < 4; ++k) {
      if (k == empty) continue;
      // A block 1 m wide, 1 m high, 0.5 m from the corner's two walls.
      const Vec3 lo(corners[k].x > 0 ? w - 1.5f : 0.5f, 0.0f, corners[k].z > 0 ? d - 1.5f : 0.5f);
      s.block(lo, lo + Vec3(1.0f));
      tops.push_back(lo + Vec3(0.5f, 1.0f, 0.5f));
    }
    const Camera c = default_camera(s.positions, s.indices, 1.0f);
    const Vec3 corner = corners[size_t(empty)];
    EXPECT_LT(std::abs(c.eye.x - corner.x), 0.5f) << empty;
    EXPECT_LT(std::abs(c.eye.z - corner.z), 0.5f) << empty;
    EXPECT_GT(c.eye.x, 0.0f) << empty;
    EXPECT_LT(c.eye.x, w) << empty;
    EXPECT_GT(c.eye.z, 0.0f) << empty;
    EXPECT_LT(c.eye.z, d) << empty;
    EXPECT_GT(c.eye.y, 1.0f) << empty << ": above the blocks";
    EXPECT_LT(c.eye.y, h) << empty;
    const CameraFrame f = camera_frame(c, 1.0f);
    for (const Vec3& t : tops) {  // every block's top in view
      const Vec3 v = t - c.eye;
      const float ahead = glm::dot(v, f.forward);
      ASSERT_GT(ahead, 0.0f) << empty;
      EXPECT_LT(std::abs(glm::dot(v, f.right)), ahead * f.tan_half_x) << empty;
      EXPECT_LT(std::abs(glm::dot(v, f.up)), ahead * f.tan_half_y) << empty;
    }
  }
}

// A closed object (a cube whose faces point outwards, as a model's do) is seen from outside:
// its own outer faces do not close a side, and from inside the camera would see only their
// backs.
TEST(Camera, DefaultForAClosedObjectStandsOutsideIt) {
  Soup s;
  s.block({0, 0, 0}, {2, 1, 2});
  for (size_t f = 0; f < s.indices.size();
       f += 3) {  // each face's normal points away from (1,.5,1)
    const Vec3 a = s.positions[s.indices[f]], b = s.positions[s.indices[f + 1]],
               c = s.positions[s.indices[f + 2]];
    ASSERT_GT(glm::dot(glm::cross(b - a, c - a), a - Vec3(1, 0.5f, 1)), 0.0f);
  }
  const Camera c = default_camera(s.positions, s.indices, 1.0f);
  EXPECT_LT(c.eye.z, 0.0f);  // outside, before the -z face
  EXPECT_NEAR(c.target.z, 0.0f, 1e-6f);
  EXPECT_EQ(c.fov_y_deg, kDefaultFovDeg);
}

// A closed room whose walls are not all on its bounding box: the Cornell box closed at the front,
// its red wall leaning as measured (x = 552.8 at the floor, 556 at the ceiling), and the same
// room with walls 20 mm thick (their outer faces, facing out, make the box). The camera stands
// inside, in front of every wall, and looks into the room.
TEST(Camera, DefaultForAClosedRoomWithALeaningOrThickWallStandsInsideIt) {
  const float w = 556.0f, h = 548.8f, d = 559.2f;
  const auto red_x = [&](float y) { return 552.8f + (w - 552.8f) * y / h; };
  for (const float thickness : {0.0f, 20.0f}) {
    Soup s;
    // Inside faces, each facing the room's centre.
    s.quad({0, 0, 0}, {0, 0, d}, {red_x(0), 0, d}, {red_x(0), 0, 0});  // floor, +y
    s.quad({0, h, 0}, {w, h, 0}, {w, h, d}, {0, h, d});                // ceiling, -y
    s.quad({0, 0, 0}, {0, h, 0}, {0, h, d}, {0, 0, d});                // green wall, +x
    s.quad({red_x(0), 0, 0}, {red_x(0), 0, d}, {w, h, d}, {w, h, 0});  // red wall, -x
    s.quad({0, 0, d}, {0, h, d}, {w, h, d}, {red_x(0), 0, d});         // back wall, -z
    s.quad({0, 0, 0}, {red_x(0), 0, 0}, {w, h, 0}, {0, h, 0});         // front wall, +z
    const Vec3 centre(w / 2, h / 2, d / 2);
    for (size_t f = 0; f < s.indices.size(); f += 3) {
      const Vec3 a = s.positions[s.indices[f]], b = s.positions[s.indices[f + 1]],
                 c = s.positions[s.indices[f + 2]];
      ASSERT_GT(glm::dot(glm::cross(b - a, c - a), centre - a), 0.0f) << f;
    }
    // The walls' outer faces, facing out.
    if (thickness > 0.0f) s.block(Vec3(-thickness), Vec3(w, h, d) + thickness);
    const Camera c = default_camera(s.positions, s.indices, 1.0f);
    EXPECT_GT(c.eye.x, 0.0f) << thickness;
    EXPECT_LT(c.eye.x, red_x(c.eye.y)) << thickness << ": behind the red wall";
    EXPECT_GT(c.eye.y, 0.0f) << thickness;
    EXPECT_LT(c.eye.y, h) << thickness;
    EXPECT_GT(c.eye.z, 0.0f) << thickness;
    EXPECT_LT(c.eye.z, d) << thickness;
    // It looks across the room, at the wall opposite the one it stands at.
    EXPECT_GT(glm::length(c.target - c.eye), 0.9f * std::min(w, d)) << thickness;
    EXPECT_GT(c.fov_y_deg, kDefaultFovDeg) << thickness;
  }
}

// A cabinet 30 cm deep hung on the wall beside one corner, 1.5 m up, in an otherwise empty
// room: it would stand between that corner's eye and the room, so the eye takes another corner
// (the walls, floor and ceiling themselves weigh nothing: empty, the room gets the first).
TEST(Camera, DefaultForARoomKeepsTheEyeAwayFromAWallCabinet) {
  const float w = 5.0f, h = 2.7f, d = 4.0f;
  Soup s;
  s.room({w, h, d});
  const Camera empty = default_camera(s.positions, s.indices, 1.0f);
  s.block({0.1f, 1.5f, 0.0f}, {1.3f, 2.2f, 0.3f});  // against z = 0, by x = 0
  const Camera c = default_camera(s.positions, s.indices, 1.0f);
  EXPECT_LT(empty.eye.x, 0.5f * w) << "an empty room: the first corner, (-x, -z)";
  EXPECT_LT(empty.eye.z, 0.5f * d);
  EXPECT_FALSE(c.eye.x < 0.5f * w && c.eye.z < 0.5f * d) << "the eye beside the cabinet";
}

TEST(Camera, SpecIsWhatParseCameraReads) {
  const Camera c = parse_camera("1,2,3,4,5.5,-6,45");
  const Camera d = parse_camera(camera_spec(c));
  EXPECT_EQ(d.eye, c.eye);
  EXPECT_EQ(d.target, c.target);
  EXPECT_EQ(d.fov_y_deg, c.fov_y_deg);
  // Values of every digit (a default camera's eye, a field of view from an arctangent) read back
  // to the same floats: the printed camera makes the same image.
  Camera e;
  e.eye = Vec3(2.2857143f, -0.1f / 3.0f, 1e-7f);
  e.target = Vec3(1.0f / 7.0f, 123456.789f, -9.87654321f);
  e.fov_y_deg = std::atan(0.3f) * 114.59156f;
  const Camera f = parse_camera(camera_spec(e));
  EXPECT_EQ(f.eye, e.eye);
  EXPECT_EQ(f.target, e.target);
  EXPECT_EQ(f.fov_y_deg, e.fov_y_deg);
}

TEST(Camera, DefaultPrefersTheOpenSide) {
  // A box open toward +x only: floor, ceiling and the -x, -z, +z walls.
  Soup s;
  s.quad({0, 0, 0}, {0, 0, 2}, {2, 0, 2}, {2, 0, 0});
  s.quad({0, 1, 0}, {2, 1, 0}, {2, 1, 2}, {0, 1, 2});
  s.quad({0, 0, 0}, {0, 1, 0}, {0, 1, 2}, {0, 0, 2});
  s.quad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0});
  s.quad({0, 0, 2}, {0, 1, 2}, {2, 1, 2}, {2, 0, 2});
  const Camera c = default_camera(s.positions, s.indices, 1.0f);
  EXPECT_GT(c.eye.x, 2.0f);
  EXPECT_NEAR(c.eye.z, 1.0f, 1e-5f);
  EXPECT_NEAR(c.target.x, 2.0f, 1e-5f);
}

}  // namespace
}  // namespace rad
