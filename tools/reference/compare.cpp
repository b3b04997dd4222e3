#include "reference/compare.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>

#include "core/error.h"

namespace rad {

namespace {

// Barycentric coordinates of p's projection onto the plane of (a, b, c), and p's distance
// from that plane (Ericson, Real-Time Collision Detection, 3.4).
struct Barycentric {
  DVec3 w{0.0};
  double distance = 0.0;
  double inside() const { return std::min({w.x, w.y, w.z}); }
};

Barycentric barycentric(const DVec3& a, const DVec3& b, const DVec3& c, const DVec3& p) {
  const DVec3 v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = glm::dot(v0, v0), d01 = glm::dot(v0, v1), d11 = glm::dot(v1, v1);
  const double d20 = glm::dot(v2, v0), d21 = glm::dot(v2, v1);
  const double denom = d00 * d11 - d01 * d01;
  Barycentric r;
  if (denom <= 0.0) {
    r.w = DVec3(-std::numeric_limits<double>::infinity());
    return r;
  }
  const double v = (d11 * d20 - d01 * d21) / denom, w = (d00 * d21 - d01 * d20) / denom;
  r.w = DVec3(1.0 - v - w, v, w);
  const DVec3 n = glm::cross(v0, v1);
  r.distance = std::abs(glm::dot(v2, n)) / glm::length(n);
  return r;
}

}  // namespace

namespace {

ErrorFigures figures(std::span<const PointComparison> all, const std::vector<uint8_t>& use) {
  ErrorFigures r;
  DVec3 sum_ref(0.0), sum_err(0.0), sum_signed(0.0), sum_stderr(0.0);
  for (size_t i = 0; i < all.size(); ++i) {
    if (!use[i]) continue;
    const PointComparison& c = all[i];
    ++r.points;
    sum_ref += c.reference;
    sum_err += glm::abs(c.rad - c.reference);
    sum_signed += c.rad - c.reference;
    sum_stderr += c.standard_error;
  }
  if (r.points == 0) return r;
  const double n = double(r.points);
  r.mean_reference = sum_ref / n;
  r.mean_abs_error = sum_err / n;
  r.channel_error = r.mean_abs_error / glm::max(r.mean_reference, DVec3(1e-300));
  const double scale =
      std::max((r.mean_reference.x + r.mean_reference.y + r.mean_reference.z) / 3.0, 1e-300);
  auto mean3 = [](const DVec3& v) { return (v.x + v.y + v.z) / 3.0; };
  r.mean_error = mean3(r.mean_abs_error) / scale;
  r.mean_signed_error = mean3(sum_signed) / n / scale;
  r.reference_noise = mean3(sum_stderr) / n / scale;
  for (size_t i = 0; i < all.size(); ++i) {
    if (!use[i]) continue;
    const PointComparison& c = all[i];
    const DVec3 e = glm::abs(c.rad - c.reference);
    r.worst_channel_error =
        glm::max(r.worst_channel_error, e / glm::max(r.mean_reference, DVec3(1e-300)));
    const double err = mean3(e) / scale;
    if (err > r.worst_error) {
      r.worst_error = err;
      r.worst = c;
    }
  }
  return r;
}

std::string format_figures(const ErrorFigures& r) {
  std::string s;
  s += fmt::format(
      "  mean error {:.3f}% of the mean radiosity (bias {:+.3f}%, reference noise "
      "{:.3f}%), {} points\n",
      100.0 * r.mean_error, 100.0 * r.mean_signed_error, 100.0 * r.reference_noise, r.points);
  s += fmt::format("  per channel r g b: mean reference {:.5g} {:.5g} {:.5g}\n", r.mean_reference.x,
                   r.mean_reference.y, r.mean_reference.z);
  s += fmt::format("    mean |error| / mean reference:  {:.3f}% {:.3f}% {:.3f}%\n",
                   100.0 * r.channel_error.x, 100.0 * r.channel_error.y, 100.0 * r.channel_error.z);
  s += fmt::format("    worst |error| / mean reference: {:.2f}% {:.2f}% {:.2f}%\n",
                   100.0 * r.worst_channel_error.x, 100.0 * r.worst_channel_error.y,
                   100.0 * r.worst_channel_error.z);
  const PointComparison& w = r.worst;
  s += fmt::format(
      "  worst point #{} on polygon {} at ({:.4g}, {:.4g}, {:.4g}): rad ({:.4g}, {:.4g}, "
      "{:.4g}) vs reference ({:.4g}, {:.4g}, {:.4g}) +- ({:.2g}, {:.2g}, {:.2g}): {:.2f}% of "
      "the mean radiosity\n",
      w.index, w.triangle, w.position.x, w.position.y, w.position.z, w.rad.x, w.rad.y, w.rad.z,
      w.reference.x, w.reference.y, w.reference.z, w.standard_error.x, w.standard_error.y,
      w.standard_error.z, 100.0 * r.worst_error);
  return s;
}

}  // namespace

ComparisonReport compare_to_reference(const ShadedFacesView& f, const ReferenceSet& ref,
                                      std::span<const uint8_t> emitting,
                                      std::span<const uint8_t> buried,
                                      std::span<const TexelSurface> texels) {
  const size_t face_count = f.indices.size() / 3;
  if (f.position.size() != f.radiosity.size() || f.face_polygon.size() != face_count ||
      ref.values.size() != ref.points.size() ||
      (!f.irradiance.empty() && f.irradiance.size() != f.position.size()) ||
      (!texels.empty() && texels.size() != ref.points.size())) {
    throw Error("compare_to_reference: array sizes disagree");
  }
  int32_t polygons = 0;
  for (int32_t p : f.face_polygon) polygons = std::max(polygons, p + 1);
  std::vector<std::vector<uint32_t>> faces_of(size_t(std::max(polygons, 0)));
  for (size_t i = 0; i < face_count; ++i) {
    if (f.face_polygon[i] >= 0) faces_of[size_t(f.face_polygon[i])].push_back(uint32_t(i));
  }

  ComparisonReport r;
  for (size_t i = 0; i < ref.points.size(); ++i) {
    const ReferencePoint& point = ref.points[i];
    if (point.triangle < 0 || point.triangle >= polygons ||
        faces_of[size_t(point.triangle)].empty()) {
      throw Error(fmt::format("reference point {} lies on polygon {}, which has no output faces", i,
                              point.triangle));
    }
    const DVec3 p(point.position);
    Barycentric best;
    best.w = DVec3(-std::numeric_limits<double>::infinity());
    uint32_t best_face = 0;
    for (uint32_t face : faces_of[size_t(point.triangle)]) {
      const uint32_t* v = &f.indices[3 * size_t(face)];
      const Barycentric b =
          barycentric(DVec3(f.position[v[0]]), DVec3(f.position[v[1]]), DVec3(f.position[v[2]]), p);
      if (b.inside() > best.inside()) {
        best = b;
        best_face = face;
      }
    }
    if (best.inside() < -1e-4) ++r.outside;
    DVec3 w = glm::max(best.w, DVec3(0.0));
    w /= (w.x + w.y + w.z);
    r.largest_plane_distance = std::max(r.largest_plane_distance, best.distance);
    const uint32_t* v = &f.indices[3 * size_t(best_face)];
    PointComparison c;
    c.index = i;
    c.triangle = point.triangle;
    c.position = point.position;
    if (i < texels.size() && texels[i].textured && !f.irradiance.empty()) {
      const DVec3 h = w.x * DVec3(f.irradiance[v[0]]) + w.y * DVec3(f.irradiance[v[1]]) +
                      w.z * DVec3(f.irradiance[v[2]]);
      c.rad = DVec3(texels[i].emission) + DVec3(texels[i].reflectance) * h;
    } else {
      c.rad = w.x * DVec3(f.radiosity[v[0]]) + w.y * DVec3(f.radiosity[v[1]]) +
              w.z * DVec3(f.radiosity[v[2]]);
    }
    c.reference = ref.values[i].radiosity;
    c.standard_error = ref.values[i].standard_error;
    c.buried = i < buried.size() && buried[i] != 0;
    r.per_point.push_back(c);
  }
  std::vector<uint8_t> use(r.per_point.size(), 1);
  r.all = figures(r.per_point, use);
  if (!emitting.empty()) {
    for (size_t i = 0; i < use.size(); ++i) {
      const size_t p = size_t(r.per_point[i].triangle);
      use[i] = p < emitting.size() && emitting[p] ? 0 : 1;
    }
    r.reflecting = figures(r.per_point, use);
  }
  if (!buried.empty()) {
    for (size_t i = 0; i < use.size(); ++i) {
      const size_t p = size_t(r.per_point[i].triangle);
      const bool emits = p < emitting.size() && emitting[p];
      use[i] = !emits && !r.per_point[i].buried ? 1 : 0;
      r.buried += r.per_point[i].buried ? 1 : 0;
    }
    r.visible = figures(r.per_point, use);
  }
  return r;
}

void write_point_comparisons(std::ostream& out, const ComparisonReport& r) {
  out << "index,polygon,x,y,z,rad_r,rad_g,rad_b,ref_r,ref_g,ref_b,stderr_r,stderr_g,stderr_b,"
         "buried\n";
  for (const PointComparison& c : r.per_point) {
    out << fmt::format(
        "{},{},{:.9g},{:.9g},{:.9g},{:.7g},{:.7g},{:.7g},{:.7g},{:.7g},{:.7g},{:.3g},"
        "{:.3g},{:.3g},{}\n",
        c.index, c.triangle, c.position.x, c.position.y, c.position.z, c.rad.x, c.rad.y, c.rad.z,
        c.reference.x, c.reference.y, c.reference.z, c.standard_error.x, c.standard_error.y,
        c.standard_error.z, c.buried ? 1 : 0);
  }
}

std::vector<uint8_t> emitting_polygons(const Hierarchy& h) {
  std::vector<uint8_t> e(h.triangles.size(), 0);
  for (size_t t = 0; t < e.size(); ++t) {
    const Material& m = h.objects[size_t(h.triangles.object[t])].material;
    e[t] = max_component(m.emission) > 0.0f ? 1 : 0;
  }
  return e;
}

std::string format_report(const ComparisonReport& r) {
  std::string s;
  s += fmt::format(
      "{} points ({} outside their faces; largest distance from a face plane "
      "{:.3g})\n",
      r.per_point.size(), r.outside, r.largest_plane_distance);
  s += "all points:\n" + format_figures(r.all);
  if (r.reflecting.points > 0) {
    s += "points on non-emitting polygons:\n" + format_figures(r.reflecting);
  }
  if (r.visible.points > 0) {
    s += fmt::format("visible points (non-emitting, {} buried inside solids left out):\n",
                     r.buried) +
         format_figures(r.visible);
  }
  return s;
}

std::vector<int32_t> assign_face_polygons(const Triangles& t, std::span<const Vec3> position,
                                          std::span<const uint32_t> indices) {
  const size_t face_count = indices.size() / 3;
  std::vector<int32_t> polygon(face_count, -1);
  int32_t hint = 0;  // faces of one polygon come together: try the last match first
  for (size_t face = 0; face < face_count; ++face) {
    const uint32_t* v = &indices[3 * face];
    const DVec3 a(position[v[0]]), b(position[v[1]]), c(position[v[2]]);
    const DVec3 centroid = (a + b + c) / 3.0;
    const DVec3 n = glm::cross(b - a, c - a);
    const double nl = glm::length(n);
    // The mesh's positions are floats: far from the origin their rounding (a few units in the
    // last place of the largest coordinate) tilts a small face's normal and lifts its centroid
    // off the plane by more than a fixed fraction of its size. Both tolerances grow with it.
    const double largest = std::max({glm::length(a), glm::length(b), glm::length(c)});
    const double rounding = 8.0 * double(std::numeric_limits<float>::epsilon()) * largest;
    const double edge = std::sqrt(nl);
    const double min_cosine = edge > 0.0 ? std::min(0.999, 1.0 - 10.0 * rounding / edge) : 0.999;
    // A sliver whose height is within the rounding (a split of a triangle a fraction of a
    // micrometre wide) has a normal of rounding alone, any direction: its plane and place decide.
    const double longest = std::max({glm::length(b - a), glm::length(c - b), glm::length(a - c)});
    const bool sliver = !(nl > 10.0 * rounding * longest);
    auto matches = [&](int32_t tri) {
      const auto& k = t.corners[size_t(tri)];
      const DVec3 tn(t.normal[size_t(tri)]);
      if (!sliver && glm::dot(n / nl, tn) < std::max(min_cosine, 0.0)) return false;
      const Barycentric bc = barycentric(DVec3(k[0]), DVec3(k[1]), DVec3(k[2]), centroid);
      const double size = std::sqrt(double(t.area[size_t(tri)]));
      return bc.inside() > -1e-5 - rounding / std::max(size, 1e-30) &&
             bc.distance <= 1e-4 * size + rounding;
    };
    // Polygons are written in order: search from the last match on, so a face on two
    // overlapping coplanar triangles (furniture boxes that interpenetrate) goes to the one
    // being written.
    for (size_t k = 0; k < t.size(); ++k) {
      const int32_t tri = int32_t((size_t(hint) + k) % t.size());
      if (matches(tri)) {
        polygon[face] = hint = tri;
        break;
      }
    }
    if (polygon[face] < 0) {
      throw Error(
          fmt::format("face {} (centroid {:.6g} {:.6g} {:.6g}) lies on no triangle of the "
                      "scene",
                      face, centroid.x, centroid.y, centroid.z));
    }
  }
  return polygon;
}

}  // namespace rad
