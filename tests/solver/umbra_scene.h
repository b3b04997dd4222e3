// A small square lamp over a square blocker over a floor, in the void, and the exact direct
// light on the floor: for tests of penumbrae (solver and final render).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene_builder.h"

namespace rad::testing {

inline constexpr float kLampHeight = 2.0f, kLampHalf = 0.15f, kBlockerHeight = 1.0f,
                       kBlockerHalf = 0.5f, kLampEmission = 30.0f;

/// A floor (y = 0, 4 x 4), a black square blocker at height 1 (both faces) and a square lamp at
/// height 2 facing down. Triangles: floor 0-1, blocker 2-5, lamp 6-7.
inline SceneDescription umbra_scene() {
  SceneDescription d;
  const float f = 2.0f, b = kBlockerHalf, l = kLampHalf;
  add_quad(d, "floor", {-f, 0, -f}, {-f, 0, f}, {f, 0, f}, {f, 0, -f}, Vec3(0.5f), Vec3(0.0f));
  add_quad(d, "blocker top", {-b, kBlockerHeight, -b}, {-b, kBlockerHeight, b},
           {b, kBlockerHeight, b}, {b, kBlockerHeight, -b}, Vec3(0.0f), Vec3(0.0f));
  add_quad(d, "blocker bottom", {-b, kBlockerHeight, -b}, {b, kBlockerHeight, -b},
           {b, kBlockerHeight, b}, {-b, kBlockerHeight, b}, Vec3(0.0f), Vec3(0.0f));
  add_quad(d, "lamp", {-l, kLampHeight, -l}, {l, kLampHeight, -l}, {l, kLampHeight, l},
           {-l, kLampHeight, l}, Vec3(0.0f), Vec3(kLampEmission));
  return d;
}

/// The form factor from a point to the rectangle [x0, x1] x [z0, z1] of a parallel plane h
/// above it, facing it (coordinates relative to the point): the corner formula, odd in each
/// side, summed by inclusion and exclusion.
inline double rectangle_factor(double x0, double x1, double z0, double z1, double h) {
  auto corner = [h](double a, double b) {
    const double ah = std::sqrt(a * a + h * h), bh = std::sqrt(b * b + h * h);
    return (a / ah * std::atan(b / ah) + b / bh * std::atan(a / bh)) / (2.0 * std::numbers::pi);
  };
  return corner(x1, z1) - corner(x0, z1) - corner(x1, z0) + corner(x0, z0);
}

/// The exact direct gain H at floor point (x, 0, z): the lamp less the part of it the blocker
/// hides, which seen from the point is the blocker scaled by 2 (the lamp is twice its height).
inline double exact_direct(double x, double z) {
  const double l = kLampHalf, s = kLampHeight / kBlockerHeight;
  const double lamp = rectangle_factor(-l - x, l - x, -l - z, l - z, kLampHeight);
  const double sx0 = std::max(-l, s * -kBlockerHalf - (s - 1.0) * x);
  const double sx1 = std::min(l, s * kBlockerHalf - (s - 1.0) * x);
  const double sz0 = std::max(-l, s * -kBlockerHalf - (s - 1.0) * z);
  const double sz1 = std::min(l, s * kBlockerHalf - (s - 1.0) * z);
  const double hidden = sx0 < sx1 && sz0 < sz1
                            ? rectangle_factor(sx0 - x, sx1 - x, sz0 - z, sz1 - z, kLampHeight)
                            : 0.0;
  return kLampEmission * (lamp - hidden);
}

/// Up close: a lamp kBandLampSize square, kBandLampHeight over a grey floor (reflectance 0.5),
/// its near edge at x = 0, with a black board kBandBoardHeight up over x >= 0 (both faces). From
/// floor point (x < 0, 0, z) the board hides all of the lamp but a band along its near edge, x
/// from 0 to -x (kBandLampHeight / kBandBoardHeight - 1), which weighs far more than its share
/// of the nearest strata's area. Triangles: floor 0-1, board 2-5, lamp 6-7.
inline constexpr float kBandLampHeight = 0.15f, kBandBoardHeight = 0.1f, kBandLampSize = 1.2f;
inline SceneDescription band_scene() {
  SceneDescription d;
  const float l = kBandLampHeight, b = kBandBoardHeight, s = kBandLampSize, h = 0.5f * s;
  add_quad(d, "floor", {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}, Vec3(0.5f), Vec3(0.0f));
  add_quad(d, "board top", {0, b, -2}, {0, b, 2}, {2, b, 2}, {2, b, -2}, Vec3(0.0f), Vec3(0.0f));
  add_quad(d, "board bottom", {0, b, -2}, {2, b, -2}, {2, b, 2}, {0, b, 2}, Vec3(0.0f), Vec3(0.0f));
  add_quad(d, "lamp", {0, l, -h}, {s, l, -h}, {s, l, h}, {0, l, h}, Vec3(0.0f),
           Vec3(kLampEmission));
  return d;
}

/// The exact direct gain H at floor point (x, 0, z), x < 0, of band_scene: the band's.
inline double exact_band_direct(double x, double z) {
  const double a = -x, h = 0.5 * kBandLampSize;
  return kLampEmission * rectangle_factor(a, a * kBandLampHeight / kBandBoardHeight, -h - z, h - z,
                                          kBandLampHeight);
}

}  // namespace rad::testing
