#include "visibility/embree_backend.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <atomic>
#include <cassert>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>

#include "core/denormals.h"
#include "core/error.h"

namespace rad {

namespace {

constexpr float kNegInf = -std::numeric_limits<float>::infinity();
constexpr size_t kPacket = 16;

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
  EmbreeBackend(const Hierarchy& h, const VisibilityOptions& options) : packets_(options.packets) {
    const ScopedFlushDenormals denormals;
    device_ = rtcNewDevice(nullptr);
    if (!device_) {
      throw Error(fmt::format("cannot create the Embree device (error {})",
                              int(rtcGetDeviceError(nullptr))));
    }
    rtcSetDeviceErrorFunction(device_, &ErrorSink::callback, &errors_);
    scene_ = rtcNewScene(device_);
    check("creating the scene");
    // ROBUST (watertight edges) although it is slower: without it Embree let through rays that
    // cross a shared edge of two triangles (a block's vertical edge), which brute force and the
    // grid see blocked, and a Cornell box vertex came out 1% off the other backends.
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    // One geometry per Pure over the flattened world triangles: as fast as one big mesh, and no
    // instances (only one instancing level in this build, and coherent packets on instanced
    // scenes hung on this machine's AVX-512 path).
    for (const SceneObject& o : h.objects) {
      if (o.kind != ObjectKind::Pure || o.triangle_count == 0) continue;
      RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      check("creating a geometry");
      auto* vertices = static_cast<float*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                  3 * sizeof(float), 3 * size_t(o.triangle_count)));
      auto* indices = static_cast<unsigned*>(
          rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                  3 * sizeof(unsigned), o.triangle_count));
      check("allocating geometry buffers");
      for (uint32_t i = 0; i < o.triangle_count; ++i) {
        const auto& corners = h.triangles.corners[o.first_triangle + i];
        for (int k = 0; k < 3; ++k) {
          vertices[9 * i + 3 * k + 0] = corners[k].x;
          vertices[9 * i + 3 * k + 1] = corners[k].y;
          vertices[9 * i + 3 * k + 2] = corners[k].z;
          indices[3 * i + k] = 3 * i + k;
        }
      }
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

  // Single rays: tnear = 0, tfar = 1 over the unnormalised direction; mask ~0u (masks are on in
  // this build and mask 0 hits nothing). Occluded ⇔ Embree set tfar to -inf.
  void trace_single(std::span<const Segment> segments, std::span<uint8_t> out) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t i = 0; i < segments.size(); ++i) {
      const Segment& s = segments[i];
      RTCRay ray;
      ray.org_x = s.origin.x;
      ray.org_y = s.origin.y;
      ray.org_z = s.origin.z;
      ray.tnear = 0.0f;
      ray.dir_x = s.direction.x;
      ray.dir_y = s.direction.y;
      ray.dir_z = s.direction.z;
      ray.time = 0.0f;
      ray.tfar = 1.0f;
      ray.mask = ~0u;
      ray.id = 0;
      ray.flags = 0;
      rtcOccluded1(scene_, &context, &ray);
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
  // set_lane(k, i) writes ray i's lane-k fields that vary (the rest of `rays` is set already).
  template <typename SetLane, typename Single>
  void trace_in_packets(size_t n, RTCRay16& rays, SetLane set_lane, Single single,
                        std::span<uint8_t> out) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) int valid[kPacket];
    for (size_t begin = 0; begin < n; begin += kPacket) {
      const size_t count = std::min(kPacket, n - begin);
      if (count == 1) {
        single(begin);
        continue;
      }
      for (size_t k = 0; k < kPacket; ++k) {
        valid[k] = k < count ? -1 : 0;
        set_lane(k, begin + (k < count ? k : 0));
        rays.tfar[k] = 1.0f;
      }
      rtcOccluded16(valid, scene_, &context, &rays);
      for (size_t k = 0; k < count; ++k) out[begin + k] = rays.tfar[k] == kNegInf ? 1 : 0;
    }
  }

  void trace_packets(std::span<const Segment> segments, std::span<uint8_t> out) const {
    alignas(64) RTCRay16 rays;
    fill_constant_fields(rays);
    trace_in_packets(
        segments.size(), rays,
        [&](size_t k, size_t i) {
          const Segment& s = segments[i];
          rays.org_x[k] = s.origin.x;
          rays.org_y[k] = s.origin.y;
          rays.org_z[k] = s.origin.z;
          rays.dir_x[k] = s.direction.x;
          rays.dir_y[k] = s.direction.y;
          rays.dir_z[k] = s.direction.z;
        },
        [&](size_t i) { trace_single(segments.subspan(i, 1), out.subspan(i, 1)); }, out);
  }

  // A fan: the origin fills the packet once, each packet then takes only the far ends,
  // straight from the fan's arrays (no Segment copies to transpose).
  void trace_fan_packets(const SegmentFan& fan, std::span<uint8_t> out) const {
    alignas(64) RTCRay16 rays;
    fill_constant_fields(rays);
    for (size_t k = 0; k < kPacket; ++k) {
      rays.org_x[k] = fan.origin.x;
      rays.org_y[k] = fan.origin.y;
      rays.org_z[k] = fan.origin.z;
    }
    trace_in_packets(
        fan.size, rays,
        [&](size_t k, size_t i) {
          rays.dir_x[k] = fan.x[i] - fan.origin.x;
          rays.dir_y[k] = fan.y[i] - fan.origin.y;
          rays.dir_z[k] = fan.z[i] - fan.origin.z;
        },
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
};

}  // namespace

std::unique_ptr<VisibilityBackend> make_embree_backend(const Hierarchy& h,
                                                       const VisibilityOptions& options) {
  return std::make_unique<EmbreeBackend>(h, options);
}

}  // namespace rad
