// Pinhole cameras: the look-at camera a user gives, and the default that frames a scene.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "core/math.h"

namespace rad {

/// Vertical field of view of the published Cornell box camera, degrees.
inline constexpr float kDefaultFovDeg = 39.3f;
/// Inside a closed room the default camera sees this far either side of its view, degrees: from
/// a corner, the walls meeting there lie about 45 degrees either side of it.
inline constexpr float kRoomHalfWidthDeg = 40.0f;

/// A right-handed look-at pinhole camera. With eye (278, 273, -800), target (278, 273, 0) and up
/// +y, +x is on the image's left (the Cornell box's red wall).
struct Camera {
  Vec3 eye{0.0f, 0.0f, -1.0f};
  Vec3 target{0.0f};
  Vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = kDefaultFovDeg;  // vertical field of view, degrees, in (0, 180)
};

/// Orthonormal camera basis and the half-extents of the view at unit depth.
struct CameraFrame {
  Vec3 right, up, forward;  // forward points from the eye toward the target
  float tan_half_x = 1.0f, tan_half_y = 1.0f;
};

/// Parses "ex,ey,ez,tx,ty,tz[,fov_deg]"; throws rad::Error when the text is malformed, the eye
/// equals the target or the field of view is outside (0, 180).
Camera parse_camera(std::string_view spec);

/// The basis of `c` for an image of aspect `width / height`. When the view direction is parallel
/// to `up`, +z is used as the up hint instead.
CameraFrame camera_frame(const Camera& c, float aspect);

/// Frames the bounding box of `positions` (faces: 3 indices each) from its most open side: of the
/// four sides facing ±x and ±z, the one whose face is least covered by triangles that face into
/// the box and lie on it or near it (within 8% of the box's depth across that side: a leaning or
/// thick wall closes its side too); a closed object's outer faces leave its sides open: it is
/// seen from outside; ties prefer -z, then +z, -x, +x. When that side is open the eye is outside
/// the box looking at its centre, far enough for the side's face to fill the view (the Cornell
/// box gives its published view). When even that side is closed (a room), the eye stands high in
/// a corner, in front of both walls, and looks down across the room, seeing kRoomHalfWidthDeg
/// either side (the vertical field of view from `aspect`, kept within 39.3 to 100 degrees): of
/// the four corners, the one with the least in the way (what stands in the room, its walls,
/// floor and ceiling left out, weighed by area over squared distance from the eye); ties go to
/// (-x, -z), then (+x, -z), (-x, +z), (+x, +z). Up is +y.
Camera default_camera(std::span<const Vec3> positions, std::span<const uint32_t> indices,
                      float aspect);

/// The camera in the syntax --camera takes: "ex,ey,ez,tx,ty,tz,fov".
std::string camera_spec(const Camera& c);

}  // namespace rad
