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
constexpr float kMaxInsideFovDeg = 100.0f;

float parse_float(std::string_view s, std::string_view spec) {
  const std::string t(s);
  char* end = nullptr;
  const float v = std::strtof(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v)) {
    throw Error("'" + t + "' is not a number in '" + std::string(spec) + "'");
  }
  return v;
}

/// Area of the triangles lying on the plane axis = `at` (within eps), projected onto it.
float area_on_plane(std::span<const Vec3> p, std::span<const uint32_t> idx, int axis, float at,
                    float eps, float out_sign) {
  float area = 0.0f;
  for (size_t f = 0; f + 2 < idx.size(); f += 3) {
    const Vec3 &a = p[idx[f]], &b = p[idx[f + 1]], &c = p[idx[f + 2]];
    if (std::abs(a[axis] - at) > eps || std::abs(b[axis] - at) > eps ||
        std::abs(c[axis] - at) > eps) {
      continue;
    }
    // Only faces towards the inside close the side: a closed object's own outer faces lie on
    // its box too, and from outside they are what a viewer should see.
    const float normal = glm::cross(b - a, c - a)[axis];
    if (normal * out_sign < 0.0f) area += 0.5f * std::abs(normal);
  }
  return area;
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
  const float eps = 1e-3f * std::max(box.diagonal(), 1e-30f);

  // The sides facing -z, +z, -x, +x: axis, direction of the outward normal.
  struct Side {
    int axis;
    float sign;
  };
  constexpr std::array<Side, 4> kSides{{{2, -1.0f}, {2, 1.0f}, {0, -1.0f}, {0, 1.0f}}};
  Side best = kSides[0];
  float best_coverage = 2.0f;
  for (const Side& s : kSides) {
    const int u = s.axis == 2 ? 0 : 2;  // the face's horizontal axis; its vertical one is y
    const float face = ext[u] * ext.y;
    const float at = s.sign < 0 ? box.lo[s.axis] : box.hi[s.axis];
    const float cover =
        face > 0.0f ? area_on_plane(positions, indices, s.axis, at, eps, s.sign) / face : 0.0f;
    if (cover < best_coverage - 1e-3f) best = s, best_coverage = cover;
  }

  const int u = best.axis == 2 ? 0 : 2;
  const float half_w = 0.5f * ext[u], half_h = 0.5f * ext.y, depth = ext[best.axis];
  const float fit = std::max(half_h, half_w / std::max(aspect, 1e-6f));  // half-height to show
  Vec3 out(0.0f);
  out[best.axis] = best.sign;  // outward normal of the chosen face
  Vec3 face_centre = mid;
  face_centre[best.axis] = best.sign < 0 ? box.lo[best.axis] : box.hi[best.axis];
  if (best_coverage < kOpenCoverage) {
    const float tan_half = std::tan(kDefaultFovDeg * kPi / 360.0f);
    const float dist = std::max(fit * kMargin / tan_half, 1e-3f * box.diagonal());
    cam.eye = face_centre + out * dist;
    cam.target = face_centre;
  } else {
    cam.eye = face_centre - out * (1e-3f * std::max(depth, 1e-30f));
    cam.target = face_centre - out * depth;
    const float fov = 360.0f / kPi * std::atan(fit / std::max(depth, 1e-30f));
    cam.fov_y_deg = std::clamp(fov, kDefaultFovDeg, kMaxInsideFovDeg);
  }
  return cam;
}

}  // namespace rad
