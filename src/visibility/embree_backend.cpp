#include "visibility/embree_backend.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "core/denormals.h"
#include "core/error.h"
#include "visibility/triangle_test.h"

namespace rad {

namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();
constexpr size_t kPacket = 16;

// The shared contract: a segment is blocked exactly when segment_hits_triangle (the test brute
// force and the grid use) says so for some triangle. Embree only proposes candidates: it traces
// each segment lengthened by `margin` at both ends against triangles grown by `margin` in their
// plane, so every triangle the shared test hits is among the candidates despite rounding, and
// an occlusion filter keeps a candidate only if the shared test, on the original segment, hits
// it. (Without this the backends disagreed on ~1 ray in 1e6 of a solve, all passing within
// 2e-7 of an edge, enough to subdivide an element differently.)
struct TraceContext {
  RTCIntersectContext embree;  // first: Embree hands the filter a pointer to it
  const Vec3* origin;          // per ray id: the original segment
  const Vec3* direction;
  const TriangleRecord* records;
  const Cutouts* cutouts;
  float clearance;  // margin + a distance far above either test's rounding (see below)
};

struct GeometryData {
  uint32_t first_triangle;
  float longest_edge;  // of the grown triangles: bounds their altitudes from below
  bool cutout;         // a cut-out Pure: no hit is sure before its mask is read
};

// A hit the shared test is certain to confirm needs no test (and no read of its record, the
// filter's cost): Embree's point lies `clearance` inside the grown triangle (so clearance -
// margin inside the original) and from both ends of the segment, and the ray meets the plane
// at more than 11.5 degrees (below that both tests' errors grow as 1 / cos). Distances from
// Embree's own data: the altitude to edge k is |Ng| / |edge k| >= |Ng| / longest_edge.
bool surely_hit(const RTCFilterFunctionNArguments* args, unsigned i, float clearance,
                float longest_edge) {
  RTCHitN* h = args->hit;
  RTCRayN* r = args->ray;
  const unsigned n = args->N;
  const float u = RTCHitN_u(h, n, i), v = RTCHitN_v(h, n, i), w = 1.0f - u - v;
  const Vec3 ng(RTCHitN_Ng_x(h, n, i), RTCHitN_Ng_y(h, n, i), RTCHitN_Ng_z(h, n, i));
  const Vec3 d(RTCRayN_dir_x(r, n, i), RTCRayN_dir_y(r, n, i), RTCRayN_dir_z(r, n, i));
  const float t = RTCRayN_tfar(r, n, i);
  const float ng2 = glm::dot(ng, ng), d2 = glm::dot(d, d), nd = glm::dot(ng, d);
  const float edge = clearance * longest_edge;
  const float lo = std::min({u, v, w});
  return nd * nd >= 0.04f * ng2 * d2 && lo > 0.0f && lo * lo * ng2 >= edge * edge &&
         t * t * d2 >= clearance * clearance &&
         (1.0f - t) * (1.0f - t) * d2 >= clearance * clearance;
}

void keep_shared_test_hits(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const TraceContext*>(args->context);
  const auto* geometry = static_cast<const GeometryData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    if (!geometry->cutout && surely_hit(args, i, context->clearance, geometry->longest_edge))
      continue;
    const unsigned id = RTCRayN_id(args->ray, args->N, i);
    const uint32_t t = geometry->first_triangle + RTCHitN_primID(args->hit, args->N, i);
    if (!segment_blocked(context->records[t], *context->cutouts, context->origin[id],
                         context->direction[id])) {
      args->valid[i] = 0;
    }
  }
}

// first_hit, in two passes over the same candidates. First Embree's own nearest among the
// triangles the shared test hits (`accept`: a candidate stands when the shared test, on the
// original segment, hits it), which bounds where the shared test's nearest can lie. Then every
// candidate up to that bound is measured with the shared test and the nearest kept; all are
// rejected, so Embree goes on to the next. The second pass alone, over the whole segment, would
// give the same answer, after visiting every triangle along it.
struct NearestContext {
  RTCIntersectContext embree;  // first: Embree hands the filter a pointer to it
  Vec3 origin, direction;
  const TriangleRecord* records;
  const Cutouts* cutouts;
  bool accept = false;
  SegmentHitRecord best;
  uint64_t tests = 0;
};

void keep_nearest_shared_test_hit(const RTCFilterFunctionNArguments* args) {
  auto* context = reinterpret_cast<NearestContext*>(args->context);
  const auto* geometry = static_cast<const GeometryData*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const uint32_t t = geometry->first_triangle + RTCHitN_primID(args->hit, args->N, i);
    ++context->tests;
    const float distance = segment_block_distance(context->records[t], *context->cutouts,
                                                  context->origin, context->direction);
    if (context->accept) {
      if (!(distance < std::numeric_limits<float>::infinity())) args->valid[i] = 0;
      continue;
    }
    keep_nearer(context->best, distance, t);
    args->valid[i] = 0;
  }
}

// The triangle grown by `margin` in its plane: scaled about its incentre so each edge moves out
// by `margin` (a sliver, whose inradius is below the margin, at most doubles).
std::array<Vec3, 3> grown(const std::array<Vec3, 3>& t, double margin) {
  const DVec3 a(t[0]), b(t[1]), c(t[2]);
  const double la = glm::length(b - c), lb = glm::length(c - a), lc = glm::length(a - b);
  const double perimeter = la + lb + lc;
  const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
  if (!(perimeter > 0.0)) return t;
  const DVec3 incentre = (a * la + b * lb + c * lc) / perimeter;
  const double inradius = 2.0 * area / perimeter;
  const double scale = inradius > margin ? 1.0 + margin / inradius : 2.0;
  std::array<Vec3, 3> out;
  for (int k = 0; k < 3; ++k)
    out[size_t(k)] = Vec3(incentre + (DVec3(t[size_t(k)]) - incentre) * scale);
  return out;
}

// Embree reports errors through a callback. During construction they become rad::Error; during
// tracing (inside the caller's TBB loops, where throwing is not allowed) they are recorded,
// printed once, and asserted on.
struct ErrorSink {
  std::mutex mutex;
  std::string first;
  std::atomic<bool> failed{false};

  static void callback(void* user, RTCError code, const char* message) {
    auto* sink = static_cast<ErrorSink*>(user);
    std::lock_guard lock(sink->mutex);
    if (!sink->failed.exchange(true)) {
      sink->first = fmt::format("Embree error {}: {}", int(code), message ? message : "");
    }
  }
};

class EmbreeBackend final : public VisibilityBackend {
 public:
  EmbreeBackend(const Hierarchy& h, const VisibilityOptions& options)
      : packets_(options.packets),
        records_(make_triangle_records(h, &cutouts_)),
        // 4x the rounding scale of the coordinates (1e-6 of the diagonal, or of the largest
        // coordinate for a scene far from the origin): far above the error of either test, far
        // below the shadow offset (1e-5) and any feature.
        margin_(4e-6f * std::max(h.bounds.magnitude(), 1e-30f)) {
    const ScopedFlushDenormals denormals;
    device_ = rtcNewDevice(nullptr);
    if (!device_) {
      throw Error(fmt::format("cannot create the Embree device (error {})",
                              int(rtcGetDeviceError(nullptr))));
    }
    rtcSetDeviceErrorFunction(device_, &ErrorSink::callback, &errors_);
    scene_ = rtcNewScene(device_);
    check("creating the scene");
    // ROBUST although it is slower: the fast mode's box tests are not conservative, and an
    // axis-aligned triangle's box is flat: an 8-wide packet can then skip a face that the same
    // rays traced singly hit, and the backends would disagree.
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    // One geometry per Pure over the flattened world triangles: as fast as one big mesh, and no
    // instances (Debian's Embree 3 is built with one instancing level, and coherent packets over
    // instanced scenes hang in its AVX-512 path).
    geometry_data_.reserve(h.objects.size());
    for (const SceneObject& o : h.objects) {
      // A Pure that casts no shadows is left out: the shared test would reject its hits anyway.
      if (o.kind != ObjectKind::Pure || o.triangle_count == 0 || !o.casts_shadows) continue;
      RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      check("creating a geometry");
      auto* vertices = static_cast<float*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                  3 * sizeof(float), 3 * size_t(o.triangle_count)));
      auto* indices = static_cast<unsigned*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                  3 * sizeof(unsigned), o.triangle_count));
      check("allocating geometry buffers");
      float longest = 0.0f;
      for (uint32_t i = 0; i < o.triangle_count; ++i) {
        const auto corners = grown(h.triangles.corners[o.first_triangle + i], margin_);
        for (int k = 0; k < 3; ++k)
          longest =
              std::max(longest, glm::length(corners[size_t(k)] - corners[size_t((k + 1) % 3)]));
        for (int k = 0; k < 3; ++k) {
          vertices[9 * i + 3 * k + 0] = corners[k].x;
          vertices[9 * i + 3 * k + 1] = corners[k].y;
          vertices[9 * i + 3 * k + 2] = corners[k].z;
          indices[3 * i + k] = 3 * i + k;
        }
      }
      geometry_data_.push_back({o.first_triangle, longest, bool(o.cutout)});
      rtcSetGeometryUserData(geometry, &geometry_data_.back());
      rtcSetGeometryOccludedFilterFunction(geometry, keep_shared_test_hits);
      rtcSetGeometryIntersectFilterFunction(geometry, keep_nearest_shared_test_hit);
      rtcCommitGeometry(geometry);
      rtcAttachGeometry(scene_, geometry);
      rtcReleaseGeometry(geometry);
      check("committing a geometry");
    }
    rtcCommitScene(scene_);
    check("building the BVH");
  }

  ~EmbreeBackend() override {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
  }

  BackendKind kind() const override { return BackendKind::Embree; }

  void occluded(std::span<const Segment> segments, std::span<uint8_t> out,
                VisibilityStats& stats) const override {
    assert(out.size() == segments.size());
    const ScopedFlushDenormals denormals;
    if (packets_) {
      trace_packets(segments, out);
    } else {
      trace_single(segments, out);
    }
    count(out, stats);
  }

  void occluded_fan(const SegmentFan& fan, std::span<uint8_t> out,
                    VisibilityStats& stats) const override {
    assert(out.size() == fan.size);
    if (!packets_) {
      VisibilityBackend::occluded_fan(fan, out, stats);
      return;
    }
    const ScopedFlushDenormals denormals;
    trace_fan_packets(fan, out);
    count(out, stats);
  }

  void first_hits(std::span<const Segment> segments, std::span<SegmentHit> out,
                  VisibilityStats& stats) const override {
    for (size_t i = 0; i < segments.size(); ++i) out[i] = first_hit(segments[i], stats);
  }

  SegmentHit first_hit(const Segment& s, VisibilityStats& stats) const override {
    const ScopedFlushDenormals denormals;
    NearestContext context;
    rtcInitIntersectContext(&context.embree);
    context.origin = s.origin;
    context.direction = s.direction;
    context.records = records_.data();
    context.cutouts = &cutouts_;
    Vec3 o, d;
    lengthened(s.origin, s.direction, o, d);
    RTCRayHit rh;
    rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
    rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = 1.0f;
    rh.ray.time = 0.0f;
    rh.ray.mask = ~0u;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    context.accept = true;
    rtcIntersect1(scene_, &context.embree, &rh);
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      // Embree's t is on a grown triangle along the lengthened ray: the shared test's nearest
      // lies within a few margins of it.
      const float slack = 8.0f * margin_ / std::max(glm::length(d), 1e-30f);
      context.accept = false;
      rh.ray.tfar = std::min(1.0f, rh.ray.tfar + slack);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene_, &context.embree, &rh);
    }
    stats.rays += 1;
    stats.triangle_tests += context.tests;
    const bool hit = context.best.triangle != ~0u;
    stats.occluded += hit ? 1 : 0;
    if (errors_.failed.load(std::memory_order_relaxed)) report_trace_error();
    return hit_of(context.best, records_);
  }

 private:
  // Adds a traced batch's answers to the caller's counters; reports an error Embree raised.
  void count(std::span<const uint8_t> out, VisibilityStats& stats) const {
    uint64_t blocked = 0;
    for (uint8_t o : out) blocked += o;
    stats.rays += out.size();
    stats.occluded += blocked;
    if (errors_.failed.load(std::memory_order_relaxed)) report_trace_error();
  }

  void check(const char* what) {
    if (errors_.failed.load()) {
      std::string message = fmt::format("{} while {}", errors_.first, what);
      if (scene_) rtcReleaseScene(scene_);
      if (device_) rtcReleaseDevice(device_);
      scene_ = nullptr;
      device_ = nullptr;
      throw Error(message);
    }
  }

  void report_trace_error() const {
    static std::once_flag once;
    std::call_once(once, [&] { std::fprintf(stderr, "error: %s\n", errors_.first.c_str()); });
    assert(!"Embree reported an error while tracing");
  }

  // How far inside a grown triangle, and from the lengthened ray's ends, a hit needs no test:
  // the margin plus 4 margins (40x the coordinates' rounding scale).
  float clearance() const { return 5.0f * margin_; }

  // The ray Embree traces for segment (o, d): `margin` longer at both ends.
  void lengthened(const Vec3& o, const Vec3& d, Vec3& origin, Vec3& direction) const {
    const float len = glm::length(d);
    const float extra = len > 0.0f ? margin_ / len : 0.0f;
    origin = o - d * extra;
    direction = d * (1.0f + 2.0f * extra);
  }

  // Single rays: tnear = 0, tfar = 1 over the unnormalised direction; mask ~0u (masks are on in
  // this build and mask 0 hits nothing). Occluded ⇔ Embree set tfar to -inf.
  void trace_single(std::span<const Segment> segments, std::span<uint8_t> out) const {
    TraceContext context;
    rtcInitIntersectContext(&context.embree);
    context.records = records_.data();
    context.cutouts = &cutouts_;
    context.clearance = clearance();
    for (size_t i = 0; i < segments.size(); ++i) {
      const Segment& s = segments[i];
      context.origin = &s.origin;
      context.direction = &s.direction;
      Vec3 o, d;
      lengthened(s.origin, s.direction, o, d);
      RTCRay ray;
      ray.org_x = o.x;
      ray.org_y = o.y;
      ray.org_z = o.z;
      ray.tnear = 0.0f;
      ray.dir_x = d.x;
      ray.dir_y = d.y;
      ray.dir_z = d.z;
      ray.time = 0.0f;
      ray.tfar = 1.0f;
      ray.mask = ~0u;
      ray.id = 0;
      ray.flags = 0;
      rtcOccluded1(scene_, &context.embree, &ray);
      out[i] = ray.tfar == kNegInf ? 1 : 0;
    }
  }

  // The packet fields Embree does not write (tnear, time, mask, id, flags): filled once per
  // call, not once per packet.
  static void fill_constant_fields(RTCRay16& rays) {
    for (size_t k = 0; k < kPacket; ++k) {
      rays.tnear[k] = 0.0f;
      rays.time[k] = 0.0f;
      rays.mask[k] = ~0u;
      rays.id[k] = unsigned(k);
      rays.flags[k] = 0;
    }
  }

  // Rays [0, n) in coherent packets of up to 16 (the solver's vertex → n samples share an
  // origin); a partial last packet is masked by `valid`, a lone last ray goes alone.
  // segment(i) is ray i's original segment; lane k of the packet traces it lengthened.
  template <typename SegmentOf, typename Single>
  void trace_in_packets(size_t n, SegmentOf segment, Single single, std::span<uint8_t> out) const {
    alignas(64) RTCRay16 rays;
    fill_constant_fields(rays);
    Vec3 origin[kPacket], direction[kPacket];
    TraceContext context;
    rtcInitIntersectContext(&context.embree);
    context.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    context.origin = origin;
    context.direction = direction;
    context.records = records_.data();
    context.cutouts = &cutouts_;
    context.clearance = clearance();
    alignas(64) int valid[kPacket];
    for (size_t begin = 0; begin < n; begin += kPacket) {
      const size_t count = std::min(kPacket, n - begin);
      if (count == 1) {
        single(begin);
        continue;
      }
      for (size_t k = 0; k < kPacket; ++k) {
        valid[k] = k < count ? -1 : 0;
        const Segment s = segment(begin + (k < count ? k : 0));
        origin[k] = s.origin;
        direction[k] = s.direction;
        Vec3 o, d;
        lengthened(s.origin, s.direction, o, d);
        rays.org_x[k] = o.x;
        rays.org_y[k] = o.y;
        rays.org_z[k] = o.z;
        rays.dir_x[k] = d.x;
        rays.dir_y[k] = d.y;
        rays.dir_z[k] = d.z;
        rays.tfar[k] = 1.0f;
      }
      rtcOccluded16(valid, scene_, &context.embree, &rays);
      for (size_t k = 0; k < count; ++k) out[begin + k] = rays.tfar[k] == kNegInf ? 1 : 0;
    }
  }

  void trace_packets(std::span<const Segment> segments, std::span<uint8_t> out) const {
    trace_in_packets(
        segments.size(), [&](size_t i) { return segments[i]; },
        [&](size_t i) { trace_single(segments.subspan(i, 1), out.subspan(i, 1)); }, out);
  }

  // A fan: segments straight from the fan's arrays (no Segment copies to transpose).
  void trace_fan_packets(const SegmentFan& fan, std::span<uint8_t> out) const {
    trace_in_packets(
        fan.size, [&](size_t i) { return fan.segment(i); },
        [&](size_t i) {
          const Segment s = fan.segment(i);
          trace_single(std::span<const Segment>(&s, 1), out.subspan(i, 1));
        },
        out);
  }

  mutable ErrorSink errors_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  bool packets_;
  Cutouts cutouts_;                          // before records_, which names them
  std::vector<TriangleRecord> records_;      // the shared test's triangles, by triangle id
  std::vector<GeometryData> geometry_data_;  // per Embree geometry; reserved, never moves
  float margin_;
};

}  // namespace

std::unique_ptr<VisibilityBackend> make_embree_backend(const Hierarchy& h,
                                                       const VisibilityOptions& options) {
  return std::make_unique<EmbreeBackend>(h, options);
}

}  // namespace rad
