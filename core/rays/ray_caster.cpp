#include "core/rays/ray_caster.h"

#include <embree3/rtcore.h>
#include <pmmintrin.h>
#include <xmmintrin.h>

#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

#include "core/base/error.h"

namespace ilp {
namespace {

// Relative size of the ray-origin offset against the scene diagonal: 1e-6 of a
// 10 m room is 10 um, far below any patch yet well above float round-off there.
constexpr double kOffsetRelDiagonal = 1e-6;
// Float round-off of coordinates scales with their magnitude: keep the offset above
// this many float epsilons of the largest (recentred) coordinate.
constexpr double kOffsetFloatUlps = 64.0;

void record_error(void* user, RTCError code, const char* message) {
  auto* last = static_cast<std::string*>(user);
  *last = "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
}

}  // namespace

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3f> normals;  // per patch, to tell front from back hits
  std::string last_error;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

RayCaster::ThreadModes::ThreadModes() : saved_(_mm_getcsr()) {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

RayCaster::ThreadModes::~ThreadModes() { _mm_setcsr(saved_); }

RayCaster::RayCaster(const Scene& scene, int threads) : impl_(std::make_unique<Impl>()) {
  const ThreadModes modes = prepare_thread();
  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
  impl_->device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!impl_->device) throw IlpError("Embree: cannot create a device (error " +
                                     std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(impl_->device, record_error, &impl_->last_error);

  impl_->center = scene.bounds_m.isEmpty() ? Eigen::Vector3d::Zero().eval() : scene.bounds_m.center().eval();
  double max_coordinate = 0.0;
  for (const Patch& p : scene.patches)
    for (const auto& v : p.vertices_m) max_coordinate = std::max(max_coordinate, (v - impl_->center).cwiseAbs().maxCoeff());
  const double diagonal = scene.bounds_m.isEmpty() ? 0.0 : scene.bounds_m.diagonal().norm();
  ray_offset_m_ = std::max(kOffsetRelDiagonal * diagonal, kOffsetFloatUlps * FLT_EPSILON * max_coordinate);

  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const std::size_t n = scene.patches.size();
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                 RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  if (!vertices || !indices) throw IlpError("Embree: cannot allocate geometry buffers: " + impl_->last_error);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d v = scene.patches[i].vertices_m[k] - impl_->center;
      if (!v.allFinite()) throw NumericalError("patch " + std::to_string(i) + " has a non-finite vertex");
      for (int c = 0; c < 3; ++c) vertices[9 * i + 3 * k + c] = static_cast<float>(v[c]);
      indices[3 * i + k] = static_cast<unsigned>(3 * i + k);
    }
    impl_->normals.push_back(scene.patches[i].normal.cast<float>());
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
  if (!impl_->last_error.empty()) throw IlpError("building the BVH: " + impl_->last_error);
}

RayCaster::~RayCaster() = default;

RayHit RayCaster::first_hit(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
                            double t_max_m) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  const Eigen::Vector3d o = origin_m - impl_->center;
  rh.ray.org_x = static_cast<float>(o.x());
  rh.ray.org_y = static_cast<float>(o.y());
  rh.ray.org_z = static_cast<float>(o.z());
  rh.ray.dir_x = static_cast<float>(direction.x());
  rh.ray.dir_y = static_cast<float>(direction.y());
  rh.ray.dir_z = static_cast<float>(direction.z());
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = std::isinf(t_max_m) ? std::numeric_limits<float>::infinity() : static_cast<float>(t_max_m);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.ray.time = 0.0f;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &context, &rh);
  RayHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.patch = static_cast<int>(rh.hit.primID);
  hit.t = rh.ray.tfar;
  hit.front = impl_->normals[hit.patch].dot(direction.cast<float>()) < 0.0f;
  return hit;
}

bool RayCaster::occluded(const Eigen::Vector3d& from_m, const Eigen::Vector3d& to_m) const {
  const Eigen::Vector3d d = to_m - from_m;
  const double length = d.norm();
  if (!(length > 2.0 * ray_offset_m_)) return false;
  const Eigen::Vector3d dir = d / length;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  const Eigen::Vector3d o = from_m - impl_->center;
  ray.org_x = static_cast<float>(o.x());
  ray.org_y = static_cast<float>(o.y());
  ray.org_z = static_cast<float>(o.z());
  ray.dir_x = static_cast<float>(dir.x());
  ray.dir_y = static_cast<float>(dir.y());
  ray.dir_z = static_cast<float>(dir.z());
  ray.tnear = static_cast<float>(ray_offset_m_);
  ray.tfar = static_cast<float>(length - ray_offset_m_);
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  ray.time = 0.0f;
  rtcOccluded1(impl_->scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace ilp
