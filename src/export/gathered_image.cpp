#include "export/gathered_image.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/denormals.h"
#include "core/error.h"
#include "export/image_render.h"
#include "export/polygon_locator.h"
#include "mesh/sample_points.h"
#include "solver/direct_light.h"
#include "solver/shoot.h"
#include "solver/texture_factors.h"

namespace rad {

namespace {

// Sets of shadow-ray ends per source (direct_light.h): a subsample's first rays end at one,
// drawn from its pixel and its place in it, so neighbouring subsamples find a penumbra's edge
// at different points and it shows no step where the rounds begin.
constexpr uint32_t kEndSets = 16;
// Penumbra rounds at a subsample (pixel_gather_settings), whatever the solver's --penumbra-rays:
// a picture shows every penumbra at the pixel.
constexpr uint32_t kPixelPenumbraRounds = 8;
// Rows traced, separated and shaded together: what is held at once is a band's hits.
constexpr int kBandRows = 16;

float unit(uint64_t bits) { return float(bits >> 40) * 0x1p-24f; }

// What a camera subsample met: a polygon and the point on it, or nothing (polygon -1), or a
// face seen from behind (-2).
struct Hit {
  int32_t polygon = -1;
  Vec3 x{0.0f};
  float footprint = 0.0f;  // the area the subsample covers there
};

struct Scratch {
  std::vector<Segment> segments;  // a row's camera rays
  std::vector<SegmentHit> met;
  DirectLightScratch direct;
  std::vector<std::pair<uint32_t, int>> stack;
  VisibilityStats camera;
};

// Barycentric coordinates of x (on or near the triangle's plane) in triangle c, by areas of the
// sub-triangles against the normal, clamped into the triangle.
Vec3 barycentric(const std::array<Vec3, 3>& c, const Vec3& x) {
  const DVec3 a(c[0]), b(c[1]), d(c[2]), y(x);
  const DVec3 n = glm::cross(b - a, d - a);
  const double n2 = glm::dot(n, n);
  if (!(n2 > 0.0)) return Vec3(1.0f / 3.0f);
  DVec3 w(glm::dot(glm::cross(b - y, d - y), n) / n2, glm::dot(glm::cross(d - y, a - y), n) / n2,
          0.0);
  w.z = 1.0 - w.x - w.y;
  w = glm::max(w, DVec3(0.0));
  const double sum = w.x + w.y + w.z;
  return sum > 0.0 ? Vec3(w / sum) : Vec3(1.0f / 3.0f);
}

}  // namespace

GatherSettings pixel_gather_settings(const SolverState& s) {
  GatherSettings g = gather_settings(s);
  g.penumbra_rays = kPixelPenumbraRounds;
  g.penumbra_every_source = true;
  return g;
}

Image render_gathered_image(const SolverState& s, const VisibilityBackend& vis,
                            const Camera& camera, const GatheredImageOptions& o,
                            GatheredImageStats* stats,
                            const std::function<void(double)>& progress) {
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSize || o.height > kMaxImageSize)
    throw Error(SourceLoc{}, "image size out of range");
  if (o.samples < 1 || o.samples > 16) throw Error(SourceLoc{}, "samples out of range (1..16)");
  const auto start = std::chrono::steady_clock::now();
  const Solution& sol = s.solution;
  const Hierarchy& h = *sol.hierarchy;
  const Triangles& tris = h.triangles;
  Image image(o.width, o.height);
  if (o.transparent) image.alpha.assign(image.pixels.size(), 0.0f);
  const CameraFrame f = camera_frame(camera, float(o.width) / float(o.height));
  const DirectLight direct = make_direct_light(s, kEndSets);
  const PolygonLocator locator(tris, h.bounds);
  const GatherSettings base = gather_settings(s);
  const GatherSettings at_pixels = pixel_gather_settings(s);
  // Camera segments reach past the far side of the scene from wherever the eye is.
  const float reach =
      2.0f * (glm::length(camera.eye - h.bounds.center()) + h.bounds.diagonal()) + 1e-30f;
  const int n = o.samples;
  const size_t spp = size_t(n) * size_t(n);
  const size_t w = size_t(o.width);
  const float pixel_angle = 2.0f * f.tan_half_y / float(o.height);

  std::vector<std::vector<Vec3>> bounced(tris.size());
  std::vector<uint8_t> separated(tris.size(), 0);
  std::vector<Hit> hits(size_t(kBandRows) * w * spp);
  std::vector<uint32_t> fresh;
  tbb::enumerable_thread_specific<Scratch> scratch;
  GatheredImageStats st;

  auto set_of = [&](size_t pixel, size_t sub) {
    return uint32_t(splitmix64(uint64_t(pixel) * 131u + sub + 0x5eedull) % kEndSets);
  };

  for (int y0 = 0; y0 < o.height; y0 += kBandRows) {
    const int y1 = std::min(o.height, y0 + kBandRows);
    // The camera rays of the band: what each subsample sees.
    tbb::parallel_for(tbb::blocked_range<int>(y0, y1), [&](const tbb::blocked_range<int>& r) {
      const ScopedFlushDenormals ftz;
      Scratch& sc = scratch.local();
      for (int y = r.begin(); y < r.end(); ++y) {
        // The row's segments, traced in one call.
        sc.segments.resize(w * spp);
        sc.met.resize(w * spp);
        for (size_t x = 0; x < w; ++x) {
          const size_t pixel = size_t(y) * w + x;
          for (size_t k = 0; k < spp; ++k) {
            const uint64_t bits = splitmix64(uint64_t(pixel) * 0x9e37u + k);
            const float u =
                (float(x) + (float(k % size_t(n)) + unit(bits)) / float(n)) / float(o.width);
            const float v =
                (float(y) + (float(k / size_t(n)) + unit(splitmix64(bits))) / float(n)) /
                float(o.height);
            const Vec3 dir =
                glm::normalize(f.forward + f.right * ((2.0f * u - 1.0f) * f.tan_half_x) +
                               f.up * ((1.0f - 2.0f * v) * f.tan_half_y));
            sc.segments[x * spp + k] = {camera.eye, dir * reach};
          }
        }
        vis.first_hits(sc.segments, sc.met, sc.camera);
        for (size_t i = 0; i < w * spp; ++i) {
          const SegmentHit& met = sc.met[i];
          const Vec3 dir = sc.segments[i].direction / reach;
          Hit& hit = hits[size_t(y - y0) * w * spp + i];
          hit = Hit{};
          if (!met.hit) continue;
          hit.x = camera.eye + sc.segments[i].direction * met.t;
          if (!(glm::dot(met.normal, dir) < 0.0f)) {
            hit.polygon = -2;
            continue;
          }
          hit.polygon = locator.locate(hit.x, met.normal, sc.stack);
          if (hit.polygon >= 0) {
            const float d = reach * met.t * pixel_angle / float(n);
            const float cosine =
                std::max(std::abs(glm::dot(tris.normal[size_t(hit.polygon)], dir)), 0.05f);
            hit.footprint = d * d / cosine;
          }
        }
      }
    });
    // The polygons seen for the first time: each vertex's bounced light, H less what the
    // emitters give it directly, gathered where the vertex gathers.
    fresh.clear();
    for (size_t i = 0; i < size_t(y1 - y0) * w * spp; ++i) {
      const int32_t p = hits[i].polygon;
      if (p >= 0 && !separated[size_t(p)] && !sol.mesh.polygons[size_t(p)].elements.empty()) {
        separated[size_t(p)] = 1;
        fresh.push_back(uint32_t(p));
      }
    }
    st.polygons_seen += fresh.size();
    tbb::parallel_for(tbb::blocked_range<size_t>(0, fresh.size(), 1), [&](const auto& r) {
      const ScopedFlushDenormals ftz;
      Scratch& sc = scratch.local();
      for (size_t i = r.begin(); i < r.end(); ++i) {
        const size_t p = fresh[i];
        const PolygonMesh& m = sol.mesh.polygons[p];
        const GatherSettings g = receiver_settings(base, s, p);
        std::vector<Vec3>& b = bounced[p];
        b.resize(m.vertex_count());
        for (uint32_t v = 0; v < m.vertex_count(); ++v) {
          const Vec3 at = s.scene.buried.gather_point(p, v, m.positions[v]);
          const Vec3 d = direct_gain(s, direct, p, at, tris.normal[p], 0, vis, g, sc.direct);
          b[v] = glm::max(sol.vertex_states[p][v].irradiance - d, Vec3(0.0f));
        }
      }
    });
    // Shading.
    tbb::parallel_for(tbb::blocked_range<int>(y0, y1), [&](const tbb::blocked_range<int>& r) {
      const ScopedFlushDenormals ftz;
      Scratch& sc = scratch.local();
      for (int y = r.begin(); y < r.end(); ++y) {
        for (size_t x = 0; x < w; ++x) {
          const size_t pixel = size_t(y) * w + x;
          DVec3 sum(0.0);
          size_t covered = 0;
          for (size_t k = 0; k < spp; ++k) {
            const Hit& hit = hits[(size_t(y - y0) * w + x) * spp + k];
            if (hit.polygon == -1) {
              if (!o.transparent) sum += DVec3(o.background);
              continue;
            }
            ++covered;
            if (hit.polygon < 0) continue;
            const size_t p = size_t(hit.polygon);
            const PolygonMesh& m = sol.mesh.polygons[p];
            if (m.elements.empty()) continue;
            const SceneObject& obj = sol.object_of(p);
            const Material& mat = sol.material_of(p);
            TextureFactors tf;
            if (is_textured(tris, p, obj)) tf = texture_factor(tris, p, obj, hit.x, hit.footprint);
            const Vec3 rho = mat.reflectance * tf.reflectance;
            const Vec3 e = mat.emission * tf.emission;
            const Vec3 bary = barycentric(tris.corners[p], hit.x);
            const Vec3 indirect = interpolate_at(
                                      m, [&](uint32_t v) { return bounced[p][v]; }, bary) +
                                  o.ambient;
            const GatherSettings g = receiver_settings(at_pixels, s, p);
            const Vec3 d = direct_gain(s, direct, p, hit.x, tris.normal[p], set_of(pixel, k), vis,
                                       g, sc.direct);
            sum += DVec3(e + rho * (d + indirect));
          }
          image.pixels[pixel] = Vec3(sum / double(spp));
          if (o.transparent) image.alpha[pixel] = float(covered) / float(spp);
        }
      }
    });
    if (progress) progress(double(y1) / double(o.height));
  }
  for (const Scratch& sc : scratch) {
    st.camera_rays += sc.camera.rays;
    st.shadow_rays += sc.direct.gather.stats.rays.rays;
  }
  st.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = st;
  return image;
}

}  // namespace rad
