#include "core/transport/ray_caster.h"

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

// One Embree BVH over patches [first_patch, first_patch + normals.size()) of a scene, in
// coordinates relative to `center` (converted to float).
struct Bvh {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3f> normals;  // per patch, to tell front from back hits
  const float* vertices = nullptr;       // Embree's copy: 9 floats a patch
  std::size_t first_patch = 0;
  std::string last_error;

  Bvh() = default;
  Bvh(const Bvh&) = delete;
  Bvh& operator=(const Bvh&) = delete;
  ~Bvh() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void build(const Scene& scene, std::size_t first, const Eigen::Vector3d& centre, int threads);
  // Closest hit with t < t_max (patch -1: none).
  RayHit first_hit(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction, float t_max) const;
  bool occluded(const Eigen::Vector3d& from_m, const Eigen::Vector3d& dir, float t_near, float t_far) const;
  // Whether patches [0, size) of `scene` are the ones this BVH holds, to the float.
  bool holds_first_patches_of(const Scene& scene) const;
};

void Bvh::build(const Scene& s, std::size_t first, const Eigen::Vector3d& centre, int threads) {
  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
  device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!device) throw IlpError("Embree: cannot create a device (error " +
                              std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
  rtcSetDeviceErrorFunction(device, record_error, &last_error);
  center = centre;
  first_patch = first;
  scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  const std::size_t n = s.patches.size() - first;
  if (n == 0) {  // nothing appended to a reused base (Embree has no buffer of size 0)
    rtcCommitScene(scene);
    return;
  }
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), 3 * n));
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                 RTC_FORMAT_UINT3, 3 * sizeof(unsigned), n));
  if (!v || !indices) throw IlpError("Embree: cannot allocate geometry buffers: " + last_error);
  for (std::size_t i = 0; i < n; ++i) {
    const Patch& p = s.patches[first + i];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d x = p.vertices_m[k] - center;
      if (!x.allFinite()) throw NumericalError("patch " + std::to_string(first + i) + " has a non-finite vertex");
      for (int c = 0; c < 3; ++c) v[9 * i + 3 * k + c] = static_cast<float>(x[c]);
      indices[3 * i + k] = static_cast<unsigned>(3 * i + k);
    }
    normals.push_back(p.normal.cast<float>());
  }
  vertices = v;
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene);
  if (!last_error.empty()) throw IlpError("building the BVH: " + last_error);
}

bool Bvh::holds_first_patches_of(const Scene& s) const {
  if (first_patch != 0 || normals.size() > s.patches.size()) return false;
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d x = s.patches[i].vertices_m[k] - center;
      for (int c = 0; c < 3; ++c)
        if (vertices[9 * i + 3 * k + c] != static_cast<float>(x[c])) return false;
    }
  return true;
}

RayHit Bvh::first_hit(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction, float t_max) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  const Eigen::Vector3d o = origin_m - center;
  rh.ray.org_x = static_cast<float>(o.x());
  rh.ray.org_y = static_cast<float>(o.y());
  rh.ray.org_z = static_cast<float>(o.z());
  rh.ray.dir_x = static_cast<float>(direction.x());
  rh.ray.dir_y = static_cast<float>(direction.y());
  rh.ray.dir_z = static_cast<float>(direction.z());
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = t_max;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.ray.time = 0.0f;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene, &context, &rh);
  RayHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return hit;
  hit.patch = static_cast<int>(first_patch + rh.hit.primID);
  hit.t = rh.ray.tfar;
  hit.front = normals[rh.hit.primID].dot(direction.cast<float>()) < 0.0f;
  return hit;
}

bool Bvh::occluded(const Eigen::Vector3d& from_m, const Eigen::Vector3d& dir, float t_near, float t_far) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  const Eigen::Vector3d o = from_m - center;
  ray.org_x = static_cast<float>(o.x());
  ray.org_y = static_cast<float>(o.y());
  ray.org_z = static_cast<float>(o.z());
  ray.dir_x = static_cast<float>(dir.x());
  ray.dir_y = static_cast<float>(dir.y());
  ray.dir_z = static_cast<float>(dir.z());
  ray.tnear = t_near;
  ray.tfar = t_far;
  ray.mask = 0xFFFFFFFFu;
  ray.flags = 0;
  ray.time = 0.0f;
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

}  // namespace

// The scene's own BVH, and a base caster's whose BVH holds the scene's first patches
// (null: none; own then holds every patch).
struct RayCaster::Impl {
  std::shared_ptr<const RayCaster> base;
  Bvh own;
};

RayCaster::ThreadModes::ThreadModes() : saved_(_mm_getcsr()) {
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
}

RayCaster::ThreadModes::~ThreadModes() { _mm_setcsr(saved_); }

RayCaster::RayCaster(const Scene& scene, int threads) : RayCaster(nullptr, scene, threads) {}

RayCaster::RayCaster(std::shared_ptr<const RayCaster> base, const Scene& scene, int threads)
    : impl_(std::make_unique<Impl>()) {
  const ThreadModes modes = prepare_thread();
  const Eigen::Vector3d center = scene.bounds_m.isEmpty() ? Eigen::Vector3d::Zero().eval() : scene.bounds_m.center().eval();
  double max_coordinate = 0.0;
  for (const Patch& p : scene.patches)
    for (const auto& v : p.vertices_m) max_coordinate = std::max(max_coordinate, (v - center).cwiseAbs().maxCoeff());
  const double diagonal = scene.bounds_m.isEmpty() ? 0.0 : scene.bounds_m.diagonal().norm();
  ray_offset_m_ = std::max(kOffsetRelDiagonal * diagonal, kOffsetFloatUlps * FLT_EPSILON * max_coordinate);
  if (base && !base->impl_->base && base->impl_->own.holds_first_patches_of(scene)) impl_->base = std::move(base);
  impl_->own.build(scene, impl_->base ? impl_->base->impl_->own.normals.size() : 0, center, threads);
}

RayCaster::~RayCaster() = default;

bool RayCaster::reuses_base() const { return impl_->base != nullptr; }

RayHit RayCaster::first_hit(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
                            double t_max_m) const {
  float t_max = std::isinf(t_max_m) ? std::numeric_limits<float>::infinity() : static_cast<float>(t_max_m);
  RayHit hit;
  if (impl_->base) {
    hit = impl_->base->impl_->own.first_hit(origin_m, direction, t_max);
    if (hit.patch >= 0) t_max = static_cast<float>(hit.t);
    if (impl_->own.normals.empty()) return hit;
  }
  const RayHit nearer = impl_->own.first_hit(origin_m, direction, t_max);
  return nearer.patch >= 0 ? nearer : hit;
}

bool RayCaster::occluded(const Eigen::Vector3d& from_m, const Eigen::Vector3d& to_m) const {
  const Eigen::Vector3d d = to_m - from_m;
  const double length = d.norm();
  if (!(length > 2.0 * ray_offset_m_)) return false;
  const Eigen::Vector3d dir = d / length;
  const auto t_near = static_cast<float>(ray_offset_m_), t_far = static_cast<float>(length - ray_offset_m_);
  if (impl_->base && impl_->base->impl_->own.occluded(from_m, dir, t_near, t_far)) return true;
  return !impl_->own.normals.empty() && impl_->own.occluded(from_m, dir, t_near, t_far);
}

}  // namespace ilp
