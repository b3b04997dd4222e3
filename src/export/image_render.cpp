#include "export/image_render.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "core/error.h"

namespace rad {

namespace {

constexpr int kMaxSamples = 16;                  // subsamples per pixel along either axis
constexpr int64_t kMaxCoord = int64_t(1) << 29;  // fixed-point coordinates stay below this
constexpr float kGuard = 2.0f;  // faces are clipped to twice the view's half-extent
constexpr int kBandRows = 8;    // pixel rows per band (the unit of parallel work)

/// A vertex in camera space (x right, y up, z = depth along the view) with its colour. Double
/// precision, so vertices on a common line (T-junctions between polygons) stay on it to far below
/// the fixed-point grid.
struct ClipVertex {
  DVec3 q;
  Vec3 colour;
};

/// A projected, snapped, positively oriented triangle.
struct ScreenTri {
  std::array<int64_t, 3> x, y;  // fixed point: 2 * half_step units per subsample
  std::array<float, 3> inv_z;
  std::array<Vec3, 3> colour;
  int64_t area2;  // twice the area, > 0
  int64_t x_lo, x_hi, y_lo, y_hi;
};

bool lex_less(const DVec3& a, const DVec3& b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

class Clipper {
 public:
  Clipper(double near, double tan_x, double tan_y)
      : near_(near), gx_(kGuard * tan_x), gy_(kGuard * tan_y) {}

  /// Signed distance of q to clip plane k (>= 0: kept).
  double distance(int k, const DVec3& q) const {
    switch (k) {
      case 0:
        return q.z - near_;
      case 1:
        return gx_ * q.z - q.x;
      case 2:
        return gx_ * q.z + q.x;
      case 3:
        return gy_ * q.z - q.y;
      default:
        return gy_ * q.z + q.y;
    }
  }

  /// Sutherland–Hodgman against the five planes. Edge intersections are computed from the
  /// lexicographically smaller endpoint, so two faces sharing an edge cut it at the same point.
  int clip(std::array<ClipVertex, 9>& poly, int n) const {
    std::array<ClipVertex, 9> out;
    for (int k = 0; k < 5 && n > 0; ++k) {
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const ClipVertex& a = poly[size_t(i)];
        const ClipVertex& b = poly[size_t((i + 1) % n)];
        const double da = distance(k, a.q), db = distance(k, b.q);
        if (da >= 0.0) out[size_t(m++)] = a;
        if ((da >= 0.0) != (db >= 0.0)) {
          const bool swap = lex_less(b.q, a.q);
          const ClipVertex& s = swap ? b : a;
          const ClipVertex& e = swap ? a : b;
          const double ds = swap ? db : da, de = swap ? da : db;
          const double t = ds / (ds - de);
          out[size_t(m++)] = {s.q + t * (e.q - s.q), s.colour + float(t) * (e.colour - s.colour)};
        }
      }
      n = m;
      std::copy(out.begin(), out.begin() + n, poly.begin());
    }
    return n;
  }

 private:
  double near_, gx_, gy_;
};

int64_t floor_div(int64_t a, int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/// Index range [lo, hi] of the subsamples whose centres (2 i + 1) * h lie in [a, b].
void sample_range(int64_t a, int64_t b, int64_t h, int64_t count, int64_t* lo, int64_t* hi) {
  *lo = std::max<int64_t>(0, floor_div(a + h - 1, 2 * h));
  *hi = std::min<int64_t>(count - 1, floor_div(b - h, 2 * h));
}

/// True when samples exactly on edge a -> b belong to this face (a consistent tie rule: the
/// sample is nudged by (-1, -delta), so every sample lies in exactly one of two faces that share
/// the edge).
bool owns_edge(int64_t dx, int64_t dy) { return dy > 0 || (dy == 0 && dx < 0); }

class Rasterizer {
 public:
  // Guard-band clipping keeps pixel coordinates within [-W/2, 3W/2] (and likewise for H), so
  // with |coordinate| < 2^29 every edge function (a difference of two products of differences)
  // stays below 2^62: exact in int64.
  explicit Rasterizer(const RenderOptions& o)
      : o_(o),
        sw_(int64_t(o.width) * o.samples),
        sh_(int64_t(o.height) * o.samples),
        half_step_(std::max<int64_t>(
            1, kMaxCoord / (2 * int64_t(std::max(o.width, o.height)) * 2 * o.samples))) {}

  /// Projects a clipped polygon and adds its fan triangles.
  void add_polygon(const std::array<ClipVertex, 9>& poly, int n, const CameraFrame& f) {
    std::array<int64_t, 9> x, y;
    std::array<float, 9> iz;
    const double unit = 2.0 * double(half_step_) * o_.samples;  // fixed-point units per pixel
    for (int i = 0; i < n; ++i) {
      const DVec3& q = poly[size_t(i)].q;
      iz[size_t(i)] = float(1.0 / q.z);
      const double px = (0.5 + 0.5 * q.x / (q.z * f.tan_half_x)) * o_.width;
      const double py = (0.5 - 0.5 * q.y / (q.z * f.tan_half_y)) * o_.height;
      x[size_t(i)] = std::llround(px * unit);
      y[size_t(i)] = std::llround(py * unit);
    }
    for (int i = 1; i + 1 < n; ++i) {
      ScreenTri t;
      const std::array<int, 3> v{0, i, i + 1};
      for (int k = 0; k < 3; ++k) {
        t.x[size_t(k)] = x[size_t(v[size_t(k)])];
        t.y[size_t(k)] = y[size_t(v[size_t(k)])];
        t.inv_z[size_t(k)] = iz[size_t(v[size_t(k)])];
        t.colour[size_t(k)] = poly[size_t(v[size_t(k)])].colour;
      }
      t.area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
      if (t.area2 == 0) continue;
      if (t.area2 < 0) {
        std::swap(t.x[1], t.x[2]), std::swap(t.y[1], t.y[2]);
        std::swap(t.inv_z[1], t.inv_z[2]), std::swap(t.colour[1], t.colour[2]);
        t.area2 = -t.area2;
      }
      sample_range(std::min({t.x[0], t.x[1], t.x[2]}), std::max({t.x[0], t.x[1], t.x[2]}),
                   half_step_, sw_, &t.x_lo, &t.x_hi);
      sample_range(std::min({t.y[0], t.y[1], t.y[2]}), std::max({t.y[0], t.y[1], t.y[2]}),
                   half_step_, sh_, &t.y_lo, &t.y_hi);
      if (t.x_lo > t.x_hi || t.y_lo > t.y_hi) continue;
      tris_.push_back(t);
    }
  }

  Image finish() {
    const int bands = (o_.height + kBandRows - 1) / kBandRows;
    const int64_t band_samples = int64_t(kBandRows) * o_.samples;
    std::vector<std::vector<uint32_t>> bin(static_cast<size_t>(bands));
    for (uint32_t i = 0; i < tris_.size(); ++i) {
      for (int64_t b = tris_[i].y_lo / band_samples; b <= tris_[i].y_hi / band_samples; ++b) {
        bin[size_t(b)].push_back(i);
      }
    }
    Image img(o_.width, o_.height);
    tbb::parallel_for(tbb::blocked_range<int>(0, bands), [&](const tbb::blocked_range<int>& r) {
      for (int b = r.begin(); b < r.end(); ++b) draw_band(b, bin[size_t(b)], img);
    });
    return img;
  }

 private:
  void draw_band(int band, const std::vector<uint32_t>& tris, Image& img) const {
    const int s = o_.samples;
    const int row0 = band * kBandRows, rows = std::min(kBandRows, o_.height - row0);
    const int64_t sy0 = int64_t(row0) * s, sy1 = sy0 + int64_t(rows) * s - 1;
    const size_t stride = size_t(sw_);
    std::vector<float> depth(size_t(rows) * size_t(s) * stride, 0.0f);  // 1/z; 0 = background
    std::vector<Vec3> colour(depth.size(), Vec3(0.0f));
    for (uint32_t ti : tris) {
      const ScreenTri& t = tris_[ti];
      const int64_t y_lo = std::max(t.y_lo, sy0), y_hi = std::min(t.y_hi, sy1);
      // Edge k is the one opposite vertex k: from vertex k+1 to vertex k+2.
      std::array<int64_t, 3> ax, ay, dx, dy, bias;
      for (int k = 0; k < 3; ++k) {
        const size_t a = size_t((k + 1) % 3), e = size_t((k + 2) % 3);
        ax[size_t(k)] = t.x[a], ay[size_t(k)] = t.y[a];
        dx[size_t(k)] = t.x[e] - t.x[a], dy[size_t(k)] = t.y[e] - t.y[a];
        bias[size_t(k)] = owns_edge(dx[size_t(k)], dy[size_t(k)]) ? 0 : -1;
      }
      const double inv_area = 1.0 / double(t.area2);
      const int64_t step = 2 * half_step_;
      const int64_t x0 = (2 * t.x_lo + 1) * half_step_;
      for (int64_t sy = y_lo; sy <= y_hi; ++sy) {
        const int64_t y = (2 * sy + 1) * half_step_;
        std::array<int64_t, 3> e;
        for (size_t k = 0; k < 3; ++k) e[k] = dx[k] * (y - ay[k]) - dy[k] * (x0 - ax[k]);
        const size_t row = size_t(sy - sy0) * stride;
        for (int64_t sx = t.x_lo; sx <= t.x_hi;
             ++sx, e[0] -= dy[0] * step, e[1] -= dy[1] * step, e[2] -= dy[2] * step) {
          if (e[0] + bias[0] < 0 || e[1] + bias[1] < 0 || e[2] + bias[2] < 0) continue;
          const float l0 = float(double(e[0]) * inv_area) * t.inv_z[0];
          const float l1 = float(double(e[1]) * inv_area) * t.inv_z[1];
          const float l2 = float(double(e[2]) * inv_area) * t.inv_z[2];
          const float iz = l0 + l1 + l2;
          const size_t at = row + size_t(sx);
          if (!(iz > depth[at])) continue;
          depth[at] = iz;
          colour[at] = (l0 * t.colour[0] + l1 * t.colour[1] + l2 * t.colour[2]) / iz;
        }
      }
    }
    const float norm = 1.0f / float(s * s);
    for (int r = 0; r < rows; ++r) {
      for (int px = 0; px < o_.width; ++px) {
        Vec3 sum(0.0f);
        for (int j = 0; j < s; ++j) {
          const size_t base = size_t(r * s + j) * stride + size_t(px) * size_t(s);
          for (int i = 0; i < s; ++i) sum += colour[base + size_t(i)];
        }
        img.at(px, row0 + r) = sum * norm;
      }
    }
  }

  RenderOptions o_;
  int64_t sw_, sh_;    // subsamples across and down
  int64_t half_step_;  // fixed-point units from a subsample cell's edge to its centre
  std::vector<ScreenTri> tris_;
};

}  // namespace

Image render_image(std::span<const Vec3> positions, std::span<const Vec3> colours,
                   std::span<const uint32_t> indices, const Camera& camera,
                   const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSize || o.height > kMaxImageSize) {
    throw Error("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
                " is out of range (1 to " + std::to_string(kMaxImageSize) + " pixels a side)");
  }
  if (o.samples < 1 || o.samples > kMaxSamples) {
    throw Error("subsamples per pixel axis must be 1 to " + std::to_string(kMaxSamples));
  }
  const CameraFrame f = camera_frame(camera, float(o.width) / float(o.height));
  const DVec3 right(f.right), up(f.up), forward(f.forward), eye(camera.eye);
  std::vector<DVec3> q(positions.size());
  double far = 0.0;
  for (size_t v = 0; v < positions.size(); ++v) {
    const DVec3 d = DVec3(positions[v]) - eye;
    q[v] = DVec3(glm::dot(d, right), glm::dot(d, up), glm::dot(d, forward));
    far = std::max(far, q[v].z);
  }
  const Clipper clipper(std::max(far * 1e-5, 1e-30), f.tan_half_x, f.tan_half_y);
  Rasterizer raster(o);
  std::array<ClipVertex, 9> poly;
  for (size_t i = 0; i + 2 < indices.size(); i += 3) {
    const uint32_t a = indices[i], b = indices[i + 1], c = indices[i + 2];
    const Vec3 &pa = positions[a], &pb = positions[b], &pc = positions[c];
    const bool front = glm::dot(glm::cross(pb - pa, pc - pa), camera.eye - pa) > 0.0f;
    const std::array<uint32_t, 3> v{a, b, c};
    bool all_in = true, all_out = false;
    for (int k = 0; k < 5 && !all_out; ++k) {
      int outside = 0;
      for (uint32_t j : v) outside += clipper.distance(k, q[j]) < 0.0;
      all_in = all_in && outside == 0;
      all_out = outside == 3;
    }
    if (all_out) continue;
    for (size_t k = 0; k < 3; ++k) poly[k] = {q[v[k]], front ? colours[v[k]] : Vec3(0.0f)};
    const int n = all_in ? 3 : clipper.clip(poly, 3);
    if (n >= 3) raster.add_polygon(poly, n, f);
  }
  return raster.finish();
}

}  // namespace rad
