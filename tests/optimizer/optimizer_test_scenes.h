// Small inverse-lighting jobs written to a temporary folder: a 4 x 4 x 2.5 m room
// (floor, walls, ceiling) with square target mats on the floor, and the YAML job
// around it. Tests change the YAML text to make the case they need.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <sstream>
#include <string>
#include <vector>

#include "job/job_runner.h"
#include "job/plan.h"
#include "tests/test_support.h"
#include "job/config.h"

namespace ilp::test {

struct Mat {
  std::string name;
  Eigen::Vector2d centre_m;
  double size_m = 0.4;
};

// OBJ of the room: every face a quad, wound so its front faces `normal`.
inline std::string room_obj(const std::vector<Mat>& mats, double height_m = 2.5, double side_m = 4.0) {
  std::ostringstream obj;
  int vertices = 0;
  auto quad = [&](const std::string& group, std::vector<Eigen::Vector3d> v, const Eigen::Vector3d& normal) {
    if ((v[1] - v[0]).cross(v[2] - v[0]).dot(normal) < 0.0) std::swap(v[1], v[3]);
    obj << "g " << group << "\n";
    for (const auto& p : v) obj << "v " << p.x() << " " << p.y() << " " << p.z() << "\n";
    obj << "f " << vertices + 1 << " " << vertices + 2 << " " << vertices + 3 << " " << vertices + 4 << "\n";
    vertices += 4;
  };
  const double s = side_m, h = height_m;
  using V = Eigen::Vector3d;
  quad("floor", {V(0, 0, 0), V(s, 0, 0), V(s, s, 0), V(0, s, 0)}, V::UnitZ());
  quad("ceiling", {V(0, 0, h), V(s, 0, h), V(s, s, h), V(0, s, h)}, -V::UnitZ());
  quad("walls", {V(0, 0, 0), V(0, s, 0), V(0, s, h), V(0, 0, h)}, V::UnitX());
  quad("walls", {V(s, 0, 0), V(s, s, 0), V(s, s, h), V(s, 0, h)}, -V::UnitX());
  quad("walls", {V(0, 0, 0), V(s, 0, 0), V(s, 0, h), V(0, 0, h)}, V::UnitY());
  quad("walls", {V(0, s, 0), V(s, s, 0), V(s, s, h), V(0, s, h)}, -V::UnitY());
  for (const Mat& m : mats) {
    const double r = 0.5 * m.size_m, z = 0.01;
    const Eigen::Vector2d c = m.centre_m;
    quad(m.name, {V(c.x() - r, c.y() - r, z), V(c.x() + r, c.y() - r, z), V(c.x() + r, c.y() + r, z),
                  V(c.x() - r, c.y() + r, z)},
         V::UnitZ());
  }
  return obj.str();
}

// The job: luminaires, goals and the rest as YAML blocks the test supplies.
// `reflectance`: one number for every surface, in [0, 1).
inline std::string room_job(const std::string& reflectance, const std::string& luminaires, const std::string& goals,
                            const std::string& rest = "") {
  return "scene:\n  mesh: room.obj\n  max_patch_edge_m: 0.25\n  default_reflectance: " + reflectance + "\n" +
         "luminaires:\n" + luminaires + "goals:\n" + goals +
         "solver:\n  rays_per_patch: 64\n  seed: 3\n  sample_fraction: 0.2\n"
         "verification:\n  rays_per_patch: 256\n" +
         rest;
}

// The job's first variant as the runner plans it: prepared (scene, model, operator),
// its search spec, its model spec.
inline PreparedJob prepare(const JobConfig& job, const std::string& cache_dir = "") {
  return prepare_job(scene_spec(job), plan_job(job).variants.front(), {}, {}, cache_dir);
}
inline SearchSpec spec(const JobConfig& job) { return plan_job(job).variants.front().search; }
inline ModelSpec model_spec(const JobConfig& job) { return plan_job(job).variants.front().model; }

}  // namespace ilp::test
