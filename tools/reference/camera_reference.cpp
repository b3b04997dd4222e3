#include "reference/camera_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>

#include "core/error.h"

namespace rad {

namespace {

// Owen-scrambled Sobol points in blocks of up to 4 dimensions (Burley, "Practical Hash-based
// Owen Scrambling", JCGT 2020): each block's points are the first four Sobol dimensions, its
// index order and digits shuffled by hashes of (pixel, block), so blocks are independent of one
// another and every point is uniform (each pixel's estimate unbiased) while the points of a
// block spread as a (0, m, 2)-net does over any two of its first dimensions. Blocks follow
// the order in which a path draws its numbers (PathTracer::sample_irradiance): the place in
// the pixel and the first bounce's direction (what a pixel's value depends on most, so they
// share a block), then at the point seen, at the next one and the one after it, the emitter
// picked with the point on it, then the bounce direction.
constexpr std::array<int, 6> kBlockDims{4, 3, 3, 2, 3, 2};
// Where each of a path's first numbers comes from: block, dimension in it. The place in the
// pixel (block 0, dimensions 0 and 1) is not among them: the camera ray draws it.
constexpr std::array<std::array<int, 2>, 15> kFirstDraws{{
    {1, 0},
    {1, 1},
    {1, 2},  // depth 0: emitter, point on it
    {0, 2},
    {0, 3},  //          bounce direction
    {2, 0},
    {2, 1},
    {2, 2},  // depth 1
    {3, 0},
    {3, 1},  //
    {4, 0},
    {4, 1},
    {4, 2},  // depth 2 (then Russian roulette and the rest: the path's stream)
    {5, 0},
    {5, 1},  //
}};
constexpr int kFirstDims = int(kFirstDraws.size());

// Direction numbers of Sobol dimensions 1 to 3 (0 is the bit reversal of the index), from the
// primitive polynomials x + 1, x^2 + x + 1, x^3 + x + 1 with initial numbers (1), (1, 3),
// (1, 3, 1) (Joe & Kuo 2008).
std::array<std::array<uint32_t, 32>, 4> sobol_directions() {
  std::array<std::array<uint32_t, 32>, 4> v{};
  for (int k = 0; k < 32; ++k) v[0][size_t(k)] = 1u << (31 - k);
  struct Poly {
    int s;
    uint32_t a;
    std::array<uint32_t, 3> m;
  };
  constexpr std::array<Poly, 3> kPolys{{{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}}};
  for (size_t d = 1; d < 4; ++d) {
    const Poly& p = kPolys[d - 1];
    std::array<uint32_t, 32> m{};
    for (int k = 0; k < 32; ++k) {
      if (k < p.s) {
        m[size_t(k)] = p.m[size_t(k)];
        continue;
      }
      // m_k = 2 a_1 m_(k-1) ^ 4 a_2 m_(k-2) ^ ... ^ 2^s m_(k-s) ^ m_(k-s).
      uint32_t x = m[size_t(k - p.s)] ^ (m[size_t(k - p.s)] << p.s);
      for (int i = 1; i < p.s; ++i) {
        if ((p.a >> (p.s - 1 - i)) & 1u) x ^= m[size_t(k - i)] << i;
      }
      m[size_t(k)] = x;
    }
    for (int k = 0; k < 32; ++k) v[d][size_t(k)] = m[size_t(k)] << (31 - k);
  }
  return v;
}

const std::array<std::array<uint32_t, 32>, 4> kSobol = sobol_directions();

uint32_t sobol(uint32_t index, size_t dim) {
  uint32_t x = 0;
  for (size_t k = 0; index; index >>= 1, ++k) {
    if (index & 1u) x ^= kSobol[dim][k];
  }
  return x;
}

uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0F0F0F0Fu) | ((x & 0x0F0F0F0Fu) << 4);
  x = ((x >> 8) & 0x00FF00FFu) | ((x & 0x00FF00FFu) << 8);
  return (x >> 16) | (x << 16);
}

// Owen scrambling by hashing (Laine & Karras 2011, in Burley's form): each bit flipped by a
// function of the bits above it.
uint32_t owen_scramble(uint32_t x, uint32_t seed) {
  x = reverse_bits(x);
  x += seed;
  x ^= x * 0x6c50b47cu;
  x ^= x * 0xb82f1e52u;
  x ^= x * 0xc7afe638u;
  x ^= x * 0x8d22f6e6u;
  return reverse_bits(x);
}

uint32_t hash_seed(uint64_t seed, uint64_t pixel, uint64_t what) {
  uint64_t s = seed ^ (pixel * 0xD1B54A32D192ED03ull) ^ (what * 0x9E3779B97F4A7C15ull);
  splitmix64_next(s);
  return uint32_t(splitmix64_next(s) >> 32);
}

// Dimension `dim` of point `i` of block `block` of a pixel's points, in [0, 1).
double block_sample(uint32_t i, int block, size_t dim, uint64_t seed, uint64_t pixel) {
  const uint32_t index = owen_scramble(i, hash_seed(seed, pixel, uint64_t(block) * 8));
  const uint32_t x = owen_scramble(sobol(index, dim), hash_seed(seed, pixel, block * 8 + 1 + dim));
  return double(x) * 0x1p-32;
}

// The camera ray through (px, py), in pixels from the image's top left: rad's renderers'
// (export/gathered_image.cpp, export/image_render.cpp) mapping of the image onto the view.
Vec3 ray_direction(const CameraFrame& f, int width, int height, double px, double py) {
  const float u = float(px / width), v = float(py / height);
  return glm::normalize(f.forward + f.right * ((2.0f * u - 1.0f) * f.tan_half_x) +
                        f.up * ((1.0f - 2.0f * v) * f.tan_half_y));
}

// What a probe ray of the interior test met: a front face (triangle >= 0) or not.
struct Probe {
  int32_t triangle = -1;
  Vec3 position{0.0f};
};

Probe probe(const PathTracer& tracer, const Triangles& t, const Vec3& eye, const Vec3& dir) {
  const RayHit hit = tracer.first_hit(eye, dir, std::numeric_limits<float>::max());
  if (hit.triangle < 0 || !(glm::dot(t.normal[size_t(hit.triangle)], dir) < 0.0f)) return {};
  return {hit.triangle, eye + dir * hit.t};
}

bool same_surface(const Triangles& t, const Probe& a, const Probe& b, float plane_tolerance) {
  if (a.triangle < 0 || b.triangle < 0) return false;
  if (t.object[size_t(a.triangle)] != t.object[size_t(b.triangle)]) return false;
  const Vec3& na = t.normal[size_t(a.triangle)];
  const Vec3& nb = t.normal[size_t(b.triangle)];
  constexpr float kCosTolerance = 0.9999985f;  // cos(0.1 degree)
  if (glm::dot(na, nb) < kCosTolerance) return false;
  return std::abs(glm::dot(na, b.position - a.position)) <= plane_tolerance;
}

}  // namespace

CameraReference render_camera_reference(const Hierarchy& h, const CameraReferenceOptions& o,
                                        const std::function<void(int, int)>& progress) {
  if (o.width < 1 || o.height < 1) throw Error("the reference image has no pixels");
  if (o.pixel_samples < 1) throw Error("--pixel-samples must be at least 1");
  const auto start = std::chrono::steady_clock::now();
  const PathTracer tracer(h, o.trace.roulette_depth, o.trace.next_event, o.trace.max_bounces);
  const Triangles& t = h.triangles;
  const CameraFrame f = camera_frame(o.camera, float(o.width) / float(o.height));
  const Vec3 eye = o.camera.eye;
  const int k = o.pixel_samples;
  const uint32_t n = uint32_t(k) * uint32_t(k);
  const float plane_tolerance = 1e-5f * h.bounds.diagonal();

  CameraReference ref;
  ref.width = o.width, ref.height = o.height;
  ref.radiosity.assign(size_t(o.width) * size_t(o.height), DVec3(0.0));
  ref.interior.assign(ref.radiosity.size(), 0);
  std::atomic<uint64_t> paths{0};
  std::atomic<int> rows_done{0};
  std::mutex progress_mutex;

  tbb::parallel_for(
      tbb::blocked_range<int>(0, o.height, 1),
      [&](const tbb::blocked_range<int>& rows) {
        FlushDenormals denormals;
        std::array<double, kFirstDims> first{};
        uint64_t traced = 0;
        for (int y = rows.begin(); y < rows.end(); ++y) {
          for (int x = 0; x < o.width; ++x) {
            const size_t pixel = size_t(y) * size_t(o.width) + size_t(x);
            Pcg32 path_rng(o.trace.seed, pixel);
            DVec3 sum(0.0);
            for (uint32_t j = 0; j < n; ++j) {
              const double sx = block_sample(j, 0, 0, o.trace.seed, pixel);
              const double sy = block_sample(j, 0, 1, o.trace.seed, pixel);
              const Vec3 dir = ray_direction(f, o.width, o.height, x + sx, y + sy);
              const RayHit hit = tracer.first_hit(eye, dir, std::numeric_limits<float>::max());
              if (hit.triangle < 0) continue;
              const Vec3& normal = t.normal[size_t(hit.triangle)];
              if (!(glm::dot(normal, dir) < 0.0f)) continue;  // from behind: black
              for (size_t d = 0; d < first.size(); ++d) {
                first[d] = block_sample(j, kFirstDraws[d][0], size_t(kFirstDraws[d][1]),
                                        o.trace.seed, pixel);
              }
              const auto& c = t.corners[size_t(hit.triangle)];
              const Vec3 p = c[0] + hit.u * (c[1] - c[0]) + hit.v * (c[2] - c[0]);
              const TexelSurface mat = tracer.surface_at(hit.triangle, p);
              DVec3 b(mat.emission);
              if (max_component(mat.reflectance) > 0.0f) {
                path_rng.draw_first(first.data(), first.size());
                b += DVec3(mat.reflectance) * tracer.sample_irradiance(p, normal, path_rng);
                ++traced;
              }
              sum += b;
            }
            ref.radiosity[pixel] = sum / double(n);

            const double cx = x + 0.5, cy = y + 0.5;
            const Probe centre = probe(tracer, t, eye, ray_direction(f, o.width, o.height, cx, cy));
            bool interior = centre.triangle >= 0;
            constexpr std::array<std::array<double, 2>, 4> kSides{
                {{-0.5, 0.0}, {0.5, 0.0}, {0.0, -0.5}, {0.0, 0.5}}};
            for (const auto& s : kSides) {
              if (!interior) break;
              const Vec3 dir = ray_direction(f, o.width, o.height, cx + s[0], cy + s[1]);
              interior = same_surface(t, centre, probe(tracer, t, eye, dir), plane_tolerance);
            }
            ref.interior[pixel] = interior ? 1 : 0;
          }
          const int done = ++rows_done;
          if (progress) {
            std::lock_guard lock(progress_mutex);
            progress(done, o.height);
          }
        }
        paths += traced;
      },
      tbb::simple_partitioner());
  ref.paths = paths;
  ref.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return ref;
}

}  // namespace rad
