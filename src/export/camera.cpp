#include "export/camera.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/aabb.h"
#include "core/error.h"

namespace rad {

namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kMargin = 1.03f;       // the framed face fills 1/1.03 of the view
constexpr float kOpenCoverage = 0.5f;  // a side less covered than this is open
// In a closed room: the eye's height (of the room's), the target's, and how far across the room
// the target lies from the eye's corner; how far off each wall the eye stands beyond the wall's
// reach, and how close to the floor or the ceiling a face is part of it (of the room's extent);
// closer to an eye than kNearEye of the room's diagonal, a triangle counts as that far.
constexpr float kCornerEyeHeight = 0.8f, kCornerTargetHeight = 0.2f, kCornerTargetAcross = 0.75f;
constexpr float kCornerStep = 0.03f, kShellDepth = 0.01f, kNearEye = 0.1f;
constexpr float kMaxRoomFovDeg = 100.0f;  // a tall narrow image
// A wall closes a side when it lies within this fraction of the box's depth across that side
// from the side's face: a room's walls are rarely all exactly on its bounding box (the Cornell
// box's measured red wall leans 3.2 mm in 556; a wall modelled with its thickness has its inner
// face a few centimetres in), while what stands in a room usually stands further in.
constexpr float kWallSlab = 0.08f;
constexpr int kCoverageCells = 64;  // points per side of the grid a side's coverage is read on

float parse_float(std::string_view s, std::string_view spec) {
  const std::string t(s);
  char* end = nullptr;
  const float v = std::strtof(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v)) {
    throw Error("'" + t + "' is not a number in '" + std::string(spec) + "'");
  }
  return v;
}

/// How far the deepest of corners `v` lies inside the face of `box` whose outward normal is
/// `out_sign` along `axis` (0 or less: on it or beyond).
float depth_inside(const Aabb& box, int axis, float out_sign, const std::array<Vec3, 3>& v) {
  const float at = out_sign < 0 ? box.lo[axis] : box.hi[axis];
  float in = 0.0f;
  for (const Vec3& c : v) in = std::max(in, (at - c[axis]) * out_sign);
  return in;
}

/// Whether a triangle with normal n (any length) faces into the box through that face, within
/// 60 degrees.
bool faces_in(const Vec3& n, int axis, float out_sign) {
  return n[axis] * out_sign < -0.5f * glm::length(n);
}

/// How much of the side of `box` whose outward normal is `out_sign` along `axis` is closed: the
/// fraction of a grid of points on its face that triangles cover, seen along the axis, counting
/// the triangles that lie within `slab` of the face and face into the box (within 60 degrees).
/// Only those close it: a closed object's own outer faces lie on its box too, and from outside
/// they are what a viewer should see. The union of the triangles is read, so a wall cut into
/// many pieces, or covered twice, counts once. *reach: how far inside the face the wall comes:
/// the nearest triangles taken first, the depth by which they cover 98% of what all of them
/// cover, so that an eye that far in stands in front of the wall (a leaning one too), and not
/// inside what stands in front of it (which covers nothing the wall has not).
float side_coverage(std::span<const Vec3> p, std::span<const uint32_t> idx, const Aabb& box,
                    int axis, float out_sign, float slab, float* reach) {
  const int u = axis == 2 ? 0 : 2;  // the face's horizontal axis; its vertical one is y
  const float cell_u = (box.hi[u] - box.lo[u]) / kCoverageCells;
  const float cell_y = (box.hi.y - box.lo.y) / kCoverageCells;
  *reach = 0.0f;
  if (!(cell_u > 0.0f && cell_y > 0.0f)) return 0.0f;
  // The triangles that may close the side, nearest the face first: (depth inside it, first index).
  std::vector<std::pair<float, size_t>> near;
  for (size_t f = 0; f + 2 < idx.size(); f += 3) {
    const std::array<Vec3, 3> v{p[idx[f]], p[idx[f + 1]], p[idx[f + 2]]};
    const float in = depth_inside(box, axis, out_sign, v);
    if (in <= slab && faces_in(glm::cross(v[1] - v[0], v[2] - v[0]), axis, out_sign))
      near.emplace_back(in, f);
  }
  std::stable_sort(near.begin(), near.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<uint8_t> covered(size_t(kCoverageCells) * kCoverageCells, 0);
  size_t count = 0;
  std::vector<size_t> counts;  // after each triangle of `near`
  counts.reserve(near.size());
  for (const auto& [in, f] : near) {
    const std::array<Vec3, 3> v{p[idx[f]], p[idx[f + 1]], p[idx[f + 2]]};
    // The triangle seen along the axis, in cells; a cell is covered when its centre is inside.
    std::array<float, 3> cu, cy;
    for (int k = 0; k < 3; ++k) {
      cu[size_t(k)] = (v[size_t(k)][u] - box.lo[u]) / cell_u;
      cy[size_t(k)] = (v[size_t(k)].y - box.lo.y) / cell_y;
    }
    const float twice_area = (cu[1] - cu[0]) * (cy[2] - cy[0]) - (cu[2] - cu[0]) * (cy[1] - cy[0]);
    const auto cell_range = [](const std::array<float, 3>& c) {
      const float lo = std::min({c[0], c[1], c[2]}), hi = std::max({c[0], c[1], c[2]});
      return std::pair{std::clamp(int(std::ceil(lo - 0.5f)), 0, kCoverageCells),
                       std::clamp(int(std::floor(hi - 0.5f)) + 1, 0, kCoverageCells)};
    };
    const auto [i0, i1] = cell_range(cu);
    const auto [j0, j1] = cell_range(cy);
    for (int j = j0; j < j1; ++j) {
      for (int i = i0; i < i1; ++i) {
        const float x = float(i) + 0.5f, y = float(j) + 0.5f;
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k) {
          const size_t a = size_t(k), b = size_t((k + 1) % 3);
          const float edge = (cu[b] - cu[a]) * (y - cy[a]) - (cy[b] - cy[a]) * (x - cu[a]);
          inside = edge * twice_area >= 0.0f;
        }
        uint8_t& cell = covered[size_t(j) * kCoverageCells + size_t(i)];
        if (inside && !cell) cell = 1, ++count;
      }
    }
    counts.push_back(count);
  }
  for (size_t k = 0; k < near.size(); ++k) {
    if (double(counts[k]) >= 0.98 * double(count)) {
      *reach = near[k].first;
      break;
    }
  }
  return float(count) / float(covered.size());
}

}  // namespace

Camera parse_camera(std::string_view spec) {
  std::vector<float> v;
  size_t start = 0;
  while (true) {
    const size_t comma = spec.find(',', start);
    v.push_back(parse_float(spec.substr(start, comma - start), spec));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (v.size() != 6 && v.size() != 7) {
    throw Error("expected ex,ey,ez,tx,ty,tz[,fov_deg], got '" + std::string(spec) + "'");
  }
  Camera c;
  c.eye = Vec3(v[0], v[1], v[2]);
  c.target = Vec3(v[3], v[4], v[5]);
  if (v.size() == 7) c.fov_y_deg = v[6];
  if (c.eye == c.target) throw Error("the eye and the target are the same point");
  if (!(c.fov_y_deg > 0.0f && c.fov_y_deg < 180.0f)) {
    throw Error("the field of view must be in (0, 180) degrees");
  }
  return c;
}

CameraFrame camera_frame(const Camera& c, float aspect) {
  CameraFrame f;
  f.forward = glm::normalize(c.target - c.eye);
  Vec3 up = c.up;
  if (glm::length(glm::cross(f.forward, up)) < 1e-6f * glm::length(up)) up = Vec3(0, 0, 1);
  f.right = glm::normalize(glm::cross(f.forward, up));
  f.up = glm::cross(f.right, f.forward);
  f.tan_half_y = std::tan(c.fov_y_deg * kPi / 360.0f);
  f.tan_half_x = f.tan_half_y * aspect;
  return f;
}

std::string camera_spec(const Camera& c) {
  // The shortest text that reads back to the same floats: the printed camera gives the image.
  return fmt::format("{},{},{},{},{},{},{}", c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y,
                     c.target.z, c.fov_y_deg);
}

Camera default_camera(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                      float aspect) {
  Aabb box;
  for (const Vec3& p : positions) box.extend(p);
  Camera cam;
  if (box.empty()) return cam;
  const Vec3 ext = box.extent(), mid = box.center();

  // The sides facing -z, +z, -x, +x: axis, direction of the outward normal.
  struct Side {
    int axis;
    float sign;
  };
  constexpr std::array<Side, 4> kSides{{{2, -1.0f}, {2, 1.0f}, {0, -1.0f}, {0, 1.0f}}};
  Side best = kSides[0];
  float best_coverage = 2.0f;
  std::array<float, 4> reach{};
  for (size_t k = 0; k < kSides.size(); ++k) {
    const Side& s = kSides[k];
    const float cover =
        side_coverage(positions, indices, box, s.axis, s.sign, kWallSlab * ext[s.axis], &reach[k]);
    if (cover < best_coverage - 1e-3f) best = s, best_coverage = cover;
  }

  if (best_coverage < kOpenCoverage) {
    const int u = best.axis == 2 ? 0 : 2;
    const float half_w = 0.5f * ext[u], half_h = 0.5f * ext.y;
    const float fit = std::max(half_h, half_w / std::max(aspect, 1e-6f));  // half-height to show
    Vec3 out(0.0f), face_centre = mid;
    out[best.axis] = best.sign;  // outward normal of the chosen face
    face_centre[best.axis] = best.sign < 0 ? box.lo[best.axis] : box.hi[best.axis];
    const float tan_half = std::tan(kDefaultFovDeg * kPi / 360.0f);
    const float dist = std::max(fit * kMargin / tan_half, 1e-3f * box.diagonal());
    cam.eye = face_centre + out * dist;
    cam.target = face_centre;
    return cam;
  }
  // Every side closed: a room. The eye stands high in a corner, in front of both walls, and
  // looks down across the room, where the furniture along the far walls faces it and the backs
  // of what stands against the walls beside it are out of view. Of the four corners, the one
  // with the least in the way: what stands in the room weighed by area over squared distance
  // from the eye, the view it would take up, so that a cabinet hung beside one corner's eye
  // counts more than a sofa across the room. The room's shell is left out: a triangle within
  // kShellDepth of one side's face, or facing into the room within its wall's reach
  // (side_coverage) and kShellDepth more, or lying flat within kWallSlab of the floor or the
  // ceiling (a rug too).
  // The corners (-x, -z), (+x, -z), (-x, +z), (+x, +z): their sides along x and z (-1 or +1),
  // and where the eye would stand in each, off both walls by their reach and kCornerStep more.
  constexpr std::array<std::array<float, 2>, 4> kCorners{{{-1, -1}, {1, -1}, {-1, 1}, {1, 1}}};
  const auto reach_of = [&](int axis, float sign) {  // kSides' order: -z, +z, -x, +x
    return reach[size_t((axis == 0 ? 2 : 0) + (sign > 0 ? 1 : 0))];
  };
  std::array<Vec3, 4> eyes;
  for (size_t k = 0; k < kCorners.size(); ++k) {
    const auto [sx, sz] = kCorners[k];
    const float in_x = reach_of(0, sx) + kCornerStep * ext.x;
    const float in_z = reach_of(2, sz) + kCornerStep * ext.z;
    eyes[k] = Vec3(sx < 0 ? box.lo.x + in_x : box.hi.x - in_x, box.lo.y + kCornerEyeHeight * ext.y,
                   sz < 0 ? box.lo.z + in_z : box.hi.z - in_z);
  }
  const auto part_of_the_shell = [&](const std::array<Vec3, 3>& v, const Vec3& n) {
    for (size_t k = 0; k < kSides.size(); ++k) {
      const Side& s = kSides[k];
      const float depth = depth_inside(box, s.axis, s.sign, v);
      const float skin = kShellDepth * ext[s.axis];  // a wall, its outer faces too
      if (depth <= skin || (faces_in(n, s.axis, s.sign) && depth <= reach[k] + skin)) return true;
    }
    const float low = std::max({v[0].y, v[1].y, v[2].y}) - box.lo.y,
                high = box.hi.y - std::min({v[0].y, v[1].y, v[2].y});
    return std::abs(n.y) > 0.9f * glm::length(n) && std::min(low, high) <= kWallSlab * ext.y;
  };
  const float near2 = kNearEye * kNearEye * glm::dot(ext, ext);
  std::array<double, 4> in_the_way{};
  for (size_t f = 0; f + 2 < indices.size(); f += 3) {
    const std::array<Vec3, 3> v{positions[indices[f]], positions[indices[f + 1]],
                                positions[indices[f + 2]]};
    const Vec3 n = glm::cross(v[1] - v[0], v[2] - v[0]);
    if (part_of_the_shell(v, n)) continue;
    const Vec3 centroid = (v[0] + v[1] + v[2]) * (1.0f / 3.0f);
    const double area = 0.5 * double(glm::length(n));
    for (size_t k = 0; k < eyes.size(); ++k) {
      const Vec3 d = centroid - eyes[k];
      in_the_way[k] += area / double(std::max(glm::dot(d, d), near2));
    }
  }
  // Ties (within rounding: a symmetric room) go to the first corner in kCorners' order.
  size_t pick = 0;
  for (size_t k = 1; k < in_the_way.size(); ++k)
    if (in_the_way[k] < in_the_way[pick] * (1.0 - 1e-4)) pick = k;
  cam.eye = eyes[pick];
  // The target: low, kCornerTargetAcross of the way from the corner to the opposite one.
  const auto [sx, sz] = kCorners[pick];
  const Vec3 at(sx < 0 ? box.lo.x : box.hi.x, box.lo.y, sz < 0 ? box.lo.z : box.hi.z);
  cam.target = Vec3(at.x + (mid.x - at.x) * 2.0f * kCornerTargetAcross,
                    box.lo.y + kCornerTargetHeight * ext.y,
                    at.z + (mid.z - at.z) * 2.0f * kCornerTargetAcross);
  const float half_width = std::tan(kRoomHalfWidthDeg * kPi / 180.0f);
  cam.fov_y_deg = std::clamp(360.0f / kPi * std::atan(half_width / std::max(aspect, 1e-6f)),
                             kDefaultFovDeg, kMaxRoomFovDeg);
  return cam;
}

}  // namespace rad
