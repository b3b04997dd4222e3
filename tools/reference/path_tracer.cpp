#include "reference/path_tracer.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>

#include "solver/texture_factors.h"

namespace rad {

namespace {

constexpr double kPi = std::numbers::pi;

// Orthonormal basis around a unit normal (Duff et al., "Building an Orthonormal Basis,
// Revisited", JCGT 2017).
void basis(const Vec3& n, Vec3& t, Vec3& b) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  t = Vec3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = Vec3(c, sign + n.y * n.y * a, -n.y);
}

// Cosine-weighted direction about n (Malley's method): pdf = cos / pi.
Vec3 cosine_direction(const Vec3& n, Pcg32& rng) {
  const double u1 = rng.uniform(), u2 = rng.uniform();
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  Vec3 t, b;
  basis(n, t, b);
  const float x = float(r * std::cos(phi)), y = float(r * std::sin(phi));
  const float z = float(std::sqrt(std::max(0.0, 1.0 - u1)));
  return glm::normalize(t * x + b * y + n * z);
}

// Uniform point on a triangle (Shirley & Chiu warp).
Vec3 uniform_on_triangle(const std::array<Vec3, 3>& c, Pcg32& rng) {
  const double s = std::sqrt(rng.uniform()), r2 = rng.uniform();
  const float u = float(s * (1.0 - r2)), v = float(s * r2);
  return c[0] + u * (c[1] - c[0]) + v * (c[2] - c[0]);
}

DVec3 to_d(const Vec3& v) { return DVec3(v); }

}  // namespace

PathTracer::PathTracer(const Hierarchy& h, int roulette_depth, bool next_event, int max_bounces)
    : h_(&h),
      scene_(h),
      // Far above float rounding of coordinates (~1e-7 of the scene) and far below features.
      offset_(1e-5f * std::max(h.bounds.diagonal(), 1e-20f)),
      roulette_depth_(roulette_depth),
      next_event_(next_event),
      max_bounces_(max_bounces) {
  const Triangles& t = h.triangles;
  textured_.resize(t.size());
  for (size_t i = 0; i < t.size(); ++i) {
    textured_[i] = is_textured(t, i, h.objects[size_t(t.object[i])]) ? 1 : 0;
  }
  double total = 0.0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double power = double(t.area[i]) * mean_component(material(int32_t(i)).emission);
    if (power <= 0.0) continue;
    total += power;
    emitters_.push_back(int32_t(i));
    emitter_cdf_.push_back(total);
  }
  area_pdf_.assign(t.size(), 0.0);
  for (size_t e = 0; e < emitters_.size(); ++e) {
    const size_t i = size_t(emitters_[e]);
    area_pdf_[i] = mean_component(material(int32_t(i)).emission) / total;  // power / total / area
  }
  for (double& c : emitter_cdf_) c /= total;
  if (!emitter_cdf_.empty()) emitter_cdf_.back() = 1.0;
}

const Material& PathTracer::material(int32_t triangle) const {
  return h_->objects[size_t(h_->triangles.object[size_t(triangle)])].material;
}

TexelSurface surface_at(const Hierarchy& h, size_t tri, const Vec3& x) {
  const SceneObject& o = h.objects[size_t(h.triangles.object[tri])];
  if (!is_textured(h.triangles, tri, o))
    return {false, o.material.reflectance, o.material.emission};
  const TextureFactors f = texture_factor(h.triangles, tri, o, x, 0.0f);
  return {true, o.material.reflectance * f.reflectance, o.material.emission * f.emission};
}

TexelSurface PathTracer::surface_at(int32_t triangle, const Vec3& x) const {
  if (!textured_[size_t(triangle)]) {
    const Material& m = material(triangle);
    return {false, m.reflectance, m.emission};
  }
  return rad::surface_at(*h_, size_t(triangle), x);
}

double PathTracer::light_pdf(int32_t tri, double r2, double cos_y) const {
  return area_pdf_[size_t(tri)] * r2 / cos_y;
}

namespace {
// Power heuristic (beta = 2) weight of the technique with pdf a against the one with pdf b.
double power_heuristic(double a, double b) { return a * a / (a * a + b * b); }
}  // namespace

DVec3 PathTracer::direct(const Vec3& p, const Vec3& n, Pcg32& rng) const {
  if (emitters_.empty()) return DVec3(0.0);
  const double pick = rng.uniform();
  const size_t k = size_t(std::upper_bound(emitter_cdf_.begin(), emitter_cdf_.end(), pick) -
                          emitter_cdf_.begin());
  const int32_t tri = emitters_[std::min(k, emitters_.size() - 1)];
  const Triangles& t = h_->triangles;
  const Vec3 y = uniform_on_triangle(t.corners[size_t(tri)], rng);
  const Vec3& ny = t.normal[size_t(tri)];
  const Vec3 d = y - p;
  const double r2 = double(glm::dot(d, d));
  if (r2 <= 0.0) return DVec3(0.0);
  const double r = std::sqrt(r2);
  const double cos_x = double(glm::dot(n, d)) / r, cos_y = -double(glm::dot(ny, d)) / r;
  if (cos_x <= 0.0 || cos_y <= 0.0) return DVec3(0.0);
  const Vec3 emission = surface_at(tri, y).emission;
  if (max_component(emission) <= 0.0f) return DVec3(0.0);  // a dark texel, or a hole
  const Vec3 from = p + n * offset_, to = y + ny * offset_;
  if (scene_.occluded(from, to - from, 1.0f)) return DVec3(0.0);
  // Irradiance integrand (E / pi) cos_x over the solid-angle pdf of this point.
  const double pdf = light_pdf(tri, r2, cos_y);
  const double weight = power_heuristic(pdf, cos_x / kPi);
  return to_d(emission) * (weight * cos_x / (kPi * pdf));
}

RayHit PathTracer::first_hit(const Vec3& from, const Vec3& w, float tfar) const {
  RayHit hit = scene_.intersect(from, w, tfar);
  if (hit.triangle >= 0 && glm::dot(h_->triangles.normal[size_t(hit.triangle)], w) >= 0.0f) {
    // A back face, unless a front face lies at the same distance: two rooms' walls back to
    // back are coincident, and which of two coplanar triangles Embree reports is arbitrary
    // (taking the back one made every building's reference up to 25% too dark).
    const RayHit front = scene_.intersect_front(from, w, hit.t * (1.0f + 1e-5f) + offset_);
    if (front.triangle >= 0) hit = front;
  }
  return hit;
}

DVec3 PathTracer::sample_irradiance(const Vec3& p0, const Vec3& n0, Pcg32& rng) const {
  const Triangles& t = h_->triangles;
  DVec3 irradiance(0.0), throughput(1.0);
  Vec3 p = p0, n = n0;
  for (int depth = 0;; ++depth) {
    if (next_event_) irradiance += throughput * direct(p, n, rng);
    const Vec3 w = cosine_direction(n, rng);
    const Vec3 from = p + n * offset_;
    const RayHit hit = first_hit(from, w, std::numeric_limits<float>::max());
    if (hit.triangle < 0) break;  // escaped
    const Vec3& nh = t.normal[size_t(hit.triangle)];
    const float cos_y = -glm::dot(nh, w);
    if (cos_y <= 0.0f) break;  // back face: black
    const auto& c = t.corners[size_t(hit.triangle)];
    const Vec3 y = c[0] + hit.u * (c[1] - c[0]) + hit.v * (c[2] - c[0]);
    const TexelSurface m = surface_at(hit.triangle, y);
    if (area_pdf_[size_t(hit.triangle)] > 0.0) {
      // The emission seen along w, weighted against next-event estimation's chance of it.
      const double cos_x = double(glm::dot(n, w));
      const double r = double(hit.t);
      const double weight =
          next_event_ ? power_heuristic(cos_x / kPi, light_pdf(hit.triangle, r * r, double(cos_y)))
                      : 1.0;
      irradiance += throughput * to_d(m.emission) * weight;
    }
    if (max_bounces_ >= 0 && depth >= max_bounces_) break;
    double survive = 1.0;
    if (depth + 1 >= roulette_depth_) {
      survive = std::min(0.95, double(max_component(m.reflectance)));
      if (survive <= 0.0 || rng.uniform() >= survive) break;
    } else if (max_component(m.reflectance) <= 0.0f) {
      break;
    }
    throughput *= to_d(m.reflectance) / survive;
    p = y;
    n = nh;
  }
  return irradiance;
}

DVec3 PathTracer::sample_radiosity(const ReferencePoint& point, Pcg32& rng) const {
  const TexelSurface m = surface_at(point.triangle, point.position);
  if (max_component(m.reflectance) <= 0.0f) return to_d(m.emission);
  return to_d(m.emission) +
         to_d(m.reflectance) * sample_irradiance(point.position, point.normal, rng);
}

namespace {

// A point's running sums: everything needed to continue sampling it and to report it. Sums
// are of B - shift (shift = the point's emission, which every sample contains) so the variance
// does not cancel against a large mean.
struct Accumulator {
  Pcg32 rng;
  DVec3 shift{0.0};
  DVec3 sum{0.0}, sum_sq{0.0};
  uint64_t n = 0;

  DVec3 mean() const { return shift + sum / double(n); }
  // Standard error of the mean, per channel.
  DVec3 standard_error() const {
    const DVec3 m = sum / double(n);
    const DVec3 var = glm::max(sum_sq / double(n) - m * m, DVec3(0.0)) * (double(n) / (n - 1));
    return glm::sqrt(var / double(n));
  }
};

void run(const PathTracer& tracer, const ReferencePoint& point, Accumulator& a, uint64_t count) {
  for (uint64_t i = 0; i < count; ++i) {
    const DVec3 b = tracer.sample_radiosity(point, a.rng) - a.shift;
    a.sum += b;
    a.sum_sq += b * b;
  }
  a.n += count;
}

}  // namespace

std::vector<ReferenceValue> estimate_radiosity(
    const Hierarchy& h, std::span<const ReferencePoint> points, const TraceOptions& options,
    TraceStats* stats, const std::function<void(size_t, size_t)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const PathTracer tracer(h, options.roulette_depth, options.next_event, options.max_bounces);
  std::vector<Accumulator> acc;
  acc.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    acc.push_back({Pcg32(options.seed, i), DVec3(tracer.material(points[i].triangle).emission)});
  }

  // Pilot: a fixed number of samples per point gives the mean radiosity that sets the target.
  const uint64_t pilot = std::max<uint64_t>(options.pilot_samples, 2);
  tbb::parallel_for(size_t(0), points.size(), [&](size_t i) {
    FlushDenormals denormals;
    run(tracer, points[i], acc[i], pilot);
  });
  DVec3 mean(0.0);
  for (const Accumulator& a : acc) mean += a.mean();
  mean /= double(std::max<size_t>(points.size(), 1));
  const DVec3 target = options.target_stderr * glm::max(mean, DVec3(1e-300));

  // Then each point on its own until its standard error meets the target: the samples still
  // needed are extrapolated from its own variance (1/sqrt(n)), 10% over, at least min_batch.
  std::atomic<size_t> done{0};
  std::mutex progress_mutex;
  tbb::parallel_for(
      size_t(0), points.size(),
      [&](size_t i) {
        FlushDenormals denormals;
        Accumulator& a = acc[i];
        while (a.n < options.max_samples) {
          const DVec3 ratio = a.standard_error() / target;
          const double worst = std::max({ratio.x, ratio.y, ratio.z});
          if (worst <= 1.0) break;
          const double wanted =
              std::min(1.1 * double(a.n) * worst * worst, double(options.max_samples));
          const uint64_t more = std::min(std::max(options.min_batch, uint64_t(wanted) - a.n),
                                         options.max_samples - a.n);
          run(tracer, points[i], a, more);
        }
        const size_t finished = ++done;
        if (progress) {
          std::lock_guard lock(progress_mutex);
          progress(finished, points.size());
        }
      },
      tbb::simple_partitioner());

  std::vector<ReferenceValue> values(points.size());
  TraceStats s;
  s.mean_radiosity = DVec3(0.0);
  for (size_t i = 0; i < points.size(); ++i) {
    values[i].radiosity = acc[i].mean();
    values[i].standard_error = acc[i].standard_error();
    values[i].samples = acc[i].n;
    s.samples += acc[i].n;
    s.mean_radiosity += values[i].radiosity;
    const DVec3 rel = values[i].standard_error / glm::max(mean, DVec3(1e-300));
    s.worst_relative_stderr = std::max({s.worst_relative_stderr, rel.x, rel.y, rel.z});
    if (acc[i].n >= options.max_samples) ++s.points_at_max_samples;
  }
  s.mean_radiosity /= double(std::max<size_t>(points.size(), 1));
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = s;
  return values;
}

}  // namespace rad
