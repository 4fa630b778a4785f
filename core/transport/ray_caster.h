// Ray queries against all patches of a Scene through one Embree BVH. This file and
// its source are the only Embree users. Geometry is recentred on the scene before
// it is converted to float, and ray origins are pushed off their patch by an offset
// scaled to the scene (see ray_offset_m), so behaviour does not depend on units or
// on where the model sits in space.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <memory>

#include "core/scene/scene.h"

namespace ilp {

struct RayHit {
  int patch = -1;      // -1: the ray left the scene
  bool front = true;   // hit the patch's front side (against its normal)
  double t = 0.0;      // distance along the unit direction, m
};

class RayCaster {
 public:
  // threads = 0: Embree uses every core for the BVH build. The BVH is built here.
  explicit RayCaster(const Scene& scene, int threads = 0);
  // `scene`'s BVH reusing `base`'s for its first patches: when base was built on exactly
  // those (the job scene, to which a layout's luminaires were appended; checked vertex by
  // vertex), only the patches after them get a BVH of their own and every query asks
  // both, with the ray offset of `scene` as a whole: the same hits as a BVH of the whole
  // scene. Otherwise (base null, or another scene) the whole scene's BVH is built.
  RayCaster(std::shared_ptr<const RayCaster> base, const Scene& scene, int threads = 0);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  // Closest hit along origin + t * direction (direction unit), t in (0, t_max).
  RayHit first_hit(const Eigen::Vector3d& origin_m, const Eigen::Vector3d& direction,
                   double t_max_m = std::numeric_limits<double>::infinity()) const;

  // True if anything lies strictly between the two points, ignoring the last
  // ray_offset_m() of the segment at either end (so the end patches do not occlude).
  bool occluded(const Eigen::Vector3d& from_m, const Eigen::Vector3d& to_m) const;

  // Distance a ray origin is pushed along its patch normal: large enough to clear
  // float round-off at the scene's coordinates, small against any patch.
  double ray_offset_m() const { return ray_offset_m_; }

  // Whether the BVH of a base caster is reused (the second constructor's check passed).
  bool reuses_base() const;

  // Flush-to-zero and denormals-are-zero for the calling thread while the returned
  // guard lives, as Embree asks of every thread that casts rays; the guard restores the
  // thread's modes (a TBB body also runs on the caller's thread, whose later arithmetic,
  // reading a file's subnormal numbers say, must not flush).
  class [[nodiscard]] ThreadModes {
   public:
    ThreadModes();
    ~ThreadModes();
    ThreadModes(const ThreadModes&) = delete;
    ThreadModes& operator=(const ThreadModes&) = delete;

   private:
    unsigned int saved_;
  };
  static ThreadModes prepare_thread() { return {}; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double ray_offset_m_ = 0.0;
};

}  // namespace ilp
