// Measuring rad's displayed radiosity against a reference: Gouraud interpolation over rad's
// output faces at each reference point, and the error figures (library rad_reference_compare).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "hierarchy/hierarchy.h"
#include "reference/reference_set.h"

namespace rad {

/// rad's output faces, as OutputMesh holds them (or as read back from a PLY file): per-vertex
/// positions and linear radiosity, three indices per face, and the polygon each face belongs to.
struct ShadedFacesView {
  std::span<const Vec3> position;
  std::span<const Vec3> radiosity;
  std::span<const uint32_t> indices;
  std::span<const int32_t> face_polygon;
  /// Per-vertex irradiance H (may be empty): what a textured point's radiosity is made from.
  std::span<const Vec3> irradiance = {};
};

/// What a reference point of a textured polygon reflects and emits, read from its texture at
/// the point: the comparison takes E + rho H there, H interpolated from the face's vertices, as
/// rad's pictures read a texture at the point rather than filtered over an element (a vertex's
/// radiosity holds its texture filtered over its element).
struct TexelSurface {
  bool textured = false;
  Vec3 reflectance{0.0f}, emission{0.0f};
};

/// One reference point as rad shows it.
struct PointComparison {
  size_t index = 0;  // into the reference set
  int32_t triangle = 0;
  Vec3 position{0.0f};
  DVec3 rad{0.0};             // Gouraud-interpolated from rad's face
  DVec3 reference{0.0};       // the reference value
  DVec3 standard_error{0.0};  // the reference's standard error
  bool buried = false;        // inside a solid (buried_points.h)
};

/// Error figures over a set of points.
struct ErrorFigures {
  size_t points = 0;
  DVec3 mean_reference{0.0};  // per channel, over points
  DVec3 mean_abs_error{0.0};  // per channel, mean over points of |B_rad - B_ref|
  DVec3 channel_error{0.0};   // mean_abs_error / mean_reference, per channel
  /// The headline figure: mean over points and channels of |B_rad - B_ref| divided by the mean
  /// over points and channels of B_ref.
  double mean_error = 0.0;
  /// Mean over points and channels of B_rad - B_ref, over the mean radiosity: a bias.
  double mean_signed_error = 0.0;
  /// Max over points of |B_rad - B_ref| / mean_reference, per channel.
  DVec3 worst_channel_error{0.0};
  /// The point whose channel-mean |B_rad - B_ref| is largest, and that error over the mean
  /// radiosity (all channels).
  PointComparison worst;
  double worst_error = 0.0;
  /// The reference's own noise: mean over points and channels of its standard error, over the
  /// mean radiosity. A perfect solver would still show a mean error of about 0.8 times this.
  double reference_noise = 0.0;
};

struct ComparisonReport {
  /// Points not inside any face of their polygon (by more than 1e-4 in barycentrics); the
  /// nearest face's interpolation, clamped to it, is used for them.
  size_t outside = 0;
  double largest_plane_distance = 0.0;  // of a point from the face used, scene units

  ErrorFigures all;  // every point
  /// Only points on polygons that do not emit (when emitters were named; else points = 0).
  /// Emitters' radiosity is mostly their emission, exact in any solver, yet it dominates the
  /// mean radiosity of a scene lit by a small bright source such as the Cornell box.
  ErrorFigures reflecting;
  /// Only points on polygons that do not emit and that are not buried inside a solid (when
  /// buried points were given; else points = 0): what a viewer can see.
  ErrorFigures visible;
  size_t buried = 0;  // points left out of `visible` as buried

  std::vector<PointComparison> per_point;
};

/// For each reference point, finds the face of the same polygon (triangle index = polygon id)
/// that contains it, interpolates the three vertex radiosities with the point's barycentric
/// coordinates in that face, and gathers the error figures. `emitting[p]` != 0 marks polygon p
/// as an emitter (for ComparisonReport::reflecting; may be empty); `buried[i]` != 0 marks
/// reference point i as inside a solid (for ComparisonReport::visible; may be empty);
/// `texels[i]`, when textured and the faces carry irradiance, makes point i's value
/// E + rho H (may be empty). Throws rad::Error if a point's polygon has no faces or the view's
/// arrays disagree in size.
ComparisonReport compare_to_reference(const ShadedFacesView& faces, const ReferenceSet& reference,
                                      std::span<const uint8_t> emitting = {},
                                      std::span<const uint8_t> buried = {},
                                      std::span<const TexelSurface> texels = {});

/// Every point as CSV: index, polygon, x, y, z, rad_r, rad_g, rad_b, ref_r, ref_g, ref_b,
/// stderr_r, stderr_g, stderr_b, buried (0 or 1).
void write_point_comparisons(std::ostream& out, const ComparisonReport& report);

/// 1 for every triangle (= polygon) of h whose material emits, else 0.
std::vector<uint8_t> emitting_polygons(const Hierarchy& h);

/// A few lines for people: the headline, per-channel figures, the worst point, the noise.
std::string format_report(const ComparisonReport& report);

/// For faces read back from a file (which drops polygon ids): the polygon of each face, found
/// as the triangle of `triangles` whose plane holds the face (same facing) and which contains
/// its centroid. Throws rad::Error naming a face that matches no triangle.
std::vector<int32_t> assign_face_polygons(const Triangles& triangles,
                                          std::span<const Vec3> position,
                                          std::span<const uint32_t> indices);

}  // namespace rad
