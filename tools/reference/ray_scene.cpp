#include "reference/ray_scene.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "core/error.h"
#include "scene/texture.h"

namespace rad {

namespace {

// The cut-out triangles' masks and texture coordinates, for the geometry's filter (its user
// data): per triangle, its mask (null: opaque throughout).
struct Cutouts {
  std::vector<const AlphaMask*> mask;
  std::vector<std::array<Vec2, 3>> uv;
};

// Rejects a hit on a cut-out triangle where its mask is a hole, at the texture coordinates of
// Embree's barycentrics (u weights corner b, v corner c).
void through_holes(const RTCFilterFunctionNArguments* args) {
  const auto* c = static_cast<const Cutouts*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned t = RTCHitN_primID(args->hit, args->N, i);
    const AlphaMask* mask = c->mask[t];
    if (!mask) continue;
    const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
    const std::array<Vec2, 3>& uv = c->uv[t];
    if (!opaque_at(*mask, uv[0] * (1.0f - u - v) + uv[1] * u + uv[2] * v)) args->valid[i] = 0;
  }
}

}  // namespace

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<Vec3> normals;  // per triangle, for the front-faces-only filter
  Cutouts cutouts;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
  void check(const char* what) const {
    const RTCError e = rtcGetDeviceError(device);
    if (e != RTC_ERROR_NONE) throw Error(fmt::format("Embree error {} while {}", int(e), what));
  }
};

RayScene::RayScene(const Hierarchy& h) : impl_(std::make_unique<Impl>()) {
  const Triangles& triangles = h.triangles;
  impl_->normals = triangles.normal;
  bool any_cutout = false;
  for (size_t i = 0; i < triangles.size() && i < triangles.uv.size(); ++i) {
    const AlphaMask& mask = h.objects[size_t(triangles.object[i])].cutout;
    if (!mask || !std::isfinite(triangles.uv[i][0].x)) continue;
    if (!any_cutout) {
      impl_->cutouts.mask.assign(triangles.size(), nullptr);
      impl_->cutouts.uv.assign(triangles.size(), {});
      any_cutout = true;
    }
    impl_->cutouts.mask[i] = &mask;
    impl_->cutouts.uv[i] = triangles.uv[i];
  }
  FlushDenormals denormals;
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) {
    throw Error(
        fmt::format("cannot create the Embree device (error {})", int(rtcGetDeviceError(nullptr))));
  }
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  RTCGeometry g = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n = triangles.size();
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  impl_->check("allocating the geometry");
  for (size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = triangles.corners[i][size_t(k)];
      vertices[9 * i + 3 * k + 0] = p.x;
      vertices[9 * i + 3 * k + 1] = p.y;
      vertices[9 * i + 3 * k + 2] = p.z;
      indices[3 * i + size_t(k)] = unsigned(3 * i + size_t(k));
    }
  }
  if (any_cutout) {
    rtcSetGeometryUserData(g, &impl_->cutouts);
    rtcSetGeometryIntersectFilterFunction(g, through_holes);
    rtcSetGeometryOccludedFilterFunction(g, through_holes);
  }
  rtcCommitGeometry(g);
  rtcAttachGeometry(impl_->scene, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(impl_->scene);
  impl_->check("building the BVH");
}

RayScene::~RayScene() = default;

namespace {
// Masks are enabled in this Embree build: mask 0 would hit nothing.
void fill_ray(RTCRay& ray, const Vec3& origin, const Vec3& dir, float tfar) {
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.tnear = 0.0f;
  ray.dir_x = dir.x;
  ray.dir_y = dir.y;
  ray.dir_z = dir.z;
  ray.time = 0.0f;
  ray.tfar = tfar;
  ray.mask = ~0u;
  ray.id = 0;
  ray.flags = 0;
}

// The nearest hit that `context` (and its filter, if any) accepts.
RayHit closest_hit(RTCScene scene, RTCIntersectContext* context, const Vec3& origin,
                   const Vec3& dir, float tfar) {
  RTCRayHit rh;
  fill_ray(rh.ray, origin, dir, tfar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, context, &rh);
  RayHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.triangle = int32_t(rh.hit.primID);
  hit.t = rh.ray.tfar;
  hit.u = rh.hit.u;
  hit.v = rh.hit.v;
  return hit;
}
}  // namespace

RayHit RayScene::intersect(const Vec3& origin, const Vec3& dir, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  return closest_hit(impl_->scene, &context, origin, dir, tfar);
}

namespace {

// An intersection context that also carries the triangles' normals for its filter.
struct FrontContext {
  RTCIntersectContext context;
  const Vec3* normals;
};

// Rejects hits on a triangle's back face.
void front_faces_only(const RTCFilterFunctionNArguments* args) {
  const auto* c = reinterpret_cast<const FrontContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3& n = c->normals[RTCHitN_primID(args->hit, args->N, i)];
    const Vec3 d(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                 RTCRayN_dir_z(args->ray, args->N, i));
    if (glm::dot(n, d) >= 0.0f) args->valid[i] = 0;
  }
}

}  // namespace

RayHit RayScene::intersect_front(const Vec3& origin, const Vec3& dir, float tfar) const {
  FrontContext fc;
  rtcInitIntersectContext(&fc.context);
  fc.context.filter = front_faces_only;
  fc.normals = impl_->normals.data();
  return closest_hit(impl_->scene, &fc.context, origin, dir, tfar);
}

bool RayScene::occluded(const Vec3& origin, const Vec3& dir, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  fill_ray(ray, origin, dir, tfar);
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

}  // namespace rad
