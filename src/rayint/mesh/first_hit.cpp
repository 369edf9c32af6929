// Embree-backed first hit on the mesh boundary (see first_hit.hpp).
#include "rayint/mesh/first_hit.hpp"

#include "rayint/mesh/embree_ray.hpp"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace rayint {

struct BoundaryFirstHit::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  LocalFrame frame;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

struct FilterContext {
  RTCIntersectContext base;  // first member: Embree passes a pointer to it
  BoundaryFirstHit::Filter filter;
  const void* const* users;  // the filter's user of each ray, by the ray's id
};

void intersect_filter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const FilterContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned face = RTCHitN_primID(args->hit, args->N, i);
    const unsigned id = RTCRayN_id(args->ray, args->N, i);
    if (!ctx->filter(ctx->users[id], face)) args->valid[i] = 0;
  }
}

float embree_t_far(double t_far) {
  return std::isfinite(t_far) && t_far < 3e38 ? static_cast<float>(t_far) : std::numeric_limits<float>::infinity();
}

[[noreturn]] void embree_failed(RTCDevice device, const char* what) {
  throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                           std::to_string(static_cast<int>(rtcGetDeviceError(device))) + ")");
}

}  // namespace

BoundaryFirstHit::BoundaryFirstHit(const std::vector<Vec3>& points,
                                   const std::vector<std::array<std::int32_t, 3>>& faces, const Vec3& box_min,
                                   const Vec3& box_max)
    : impl_(std::make_unique<Impl>()) {
  impl_->frame = LocalFrame::of(box_min, box_max);
  impl_->device = rtcNewDevice("threads=1");  // build only; queries run on the caller's threads
  if (!impl_->device) throw std::runtime_error("Embree: rtcNewDevice failed");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  if (!faces.empty()) {
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), points.size()));
    if (!v) embree_failed(impl_->device, "vertex buffer");
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec3 p = impl_->frame.point(points[i]);
      for (int k = 0; k < 3; ++k) v[3 * i + static_cast<std::size_t>(k)] = static_cast<float>(p[k]);
    }
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), faces.size()));
    if (!idx) embree_failed(impl_->device, "index buffer");
    for (std::size_t f = 0; f < faces.size(); ++f)
      for (std::size_t k = 0; k < 3; ++k) idx[3 * f + k] = static_cast<unsigned>(faces[f][k]);
    rtcSetGeometryIntersectFilterFunction(geom, intersect_filter);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(impl_->scene);
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE) embree_failed(impl_->device, "scene build");
}

BoundaryFirstHit::~BoundaryFirstHit() = default;

LocalFrame LocalFrame::of(const Vec3& lo, const Vec3& hi) {
  LocalFrame f;
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0) || !std::isfinite(diagonal)) return f;
  f.centre = 0.5 * (lo + hi);
  f.scale = std::ldexp(1.0, -std::ilogb(diagonal));
  return f;
}

void init_ray_hit(RTCRayHit& rh, const LocalFrame& frame, const Vec3& origin, const Vec3& direction, double t_near,
                  float t_far) {
  const Vec3 o = frame.point(origin);
  rh.ray.org_x = static_cast<float>(o.x());
  rh.ray.org_y = static_cast<float>(o.y());
  rh.ray.org_z = static_cast<float>(o.z());
  rh.ray.dir_x = static_cast<float>(direction.x());
  rh.ray.dir_y = static_cast<float>(direction.y());
  rh.ray.dir_z = static_cast<float>(direction.z());
  rh.ray.tnear = static_cast<float>(frame.length(std::max(0.0, t_near)));
  rh.ray.tfar = t_far;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
}

std::int64_t BoundaryFirstHit::first(const Vec3& origin, const Vec3& direction, double t_near,
                                     double t_far, Filter filter, const void* user) const {
  FilterContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.filter = filter;
  ctx.users = &user;  // init_ray_hit gives the ray id 0
  RTCRayHit rh;
  init_ray_hit(rh, impl_->frame, origin, direction, t_near, embree_t_far(impl_->frame.length(t_far)));
  rtcIntersect1(impl_->scene, &ctx.base, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
  return static_cast<std::int64_t>(rh.hit.primID);
}

void BoundaryFirstHit::first_packet(const Vec3* origins, const Vec3* directions, const double* t_near,
                                    const double* t_far, const bool* active, int n, Filter filter,
                                    const void* const* users, std::int64_t* result) const {
  if (n < 0 || n > kPacket) throw std::invalid_argument("BoundaryFirstHit::first_packet: n must be in [0, 8]");
  FilterContext ctx;
  rtcInitIntersectContext(&ctx.base);
  ctx.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  ctx.filter = filter;
  ctx.users = users;
  alignas(32) RTCRayHit8 rh;
  alignas(32) int valid[kPacket];
  // Each lane as init_ray_hit fills a single ray (the same single-precision values).
  for (int i = 0; i < kPacket; ++i) {
    RTCRayHit one;
    const bool on = i < n && active[i];
    valid[i] = on ? -1 : 0;
    if (on) init_ray_hit(one, impl_->frame, origins[i], directions[i], t_near[i], embree_t_far(impl_->frame.length(t_far[i])));
    else init_ray_hit(one, LocalFrame{}, Vec3::Zero(), Vec3::UnitZ(), 0.0, 0.0f);
    rh.ray.org_x[i] = one.ray.org_x;
    rh.ray.org_y[i] = one.ray.org_y;
    rh.ray.org_z[i] = one.ray.org_z;
    rh.ray.dir_x[i] = one.ray.dir_x;
    rh.ray.dir_y[i] = one.ray.dir_y;
    rh.ray.dir_z[i] = one.ray.dir_z;
    rh.ray.tnear[i] = one.ray.tnear;
    rh.ray.tfar[i] = one.ray.tfar;
    rh.ray.time[i] = one.ray.time;
    rh.ray.mask[i] = one.ray.mask;
    rh.ray.id[i] = static_cast<unsigned>(i);  // the filter's user: users[i]
    rh.ray.flags[i] = one.ray.flags;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect8(valid, impl_->scene, &ctx.base, &rh);
  for (int i = 0; i < n; ++i)
    result[i] = valid[i] && rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID ? static_cast<std::int64_t>(rh.hit.primID[i]) : -1;
}

}  // namespace rayint
