// scene.exclude_surfaces and scene.two_sided: what real models need (a ground plane
// around a room, faces wound the wrong way), checked on a floor wound upside down.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "job/config.h"
#include "job/plan.h"
#include "core/exact/exact_solver.h"
#include "job/job_scene.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::TempDir;

// A 2 x 2 m floor at z = 0 wound to face DOWN (the defect), a 40 x 40 m ground
// plane 1 m below facing up, a black post 3 m high beside the floor (so the scene
// reaches the luminaire), and one 0.2 m luminaire 2 m above the floor's centre.
const char* kObj =
    "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\n"
    "v -19 -19 -1\nv 21 -19 -1\nv 21 21 -1\nv -19 21 -1\n"
    "v -0.5 0 0\nv -0.5 0.1 0\nv -0.5 0.1 3\nv -0.5 0 3\n"
    "g floor\nf 1 4 3 2\n"
    "g ground\nf 5 6 7 8\n"
    "g post\nf 9 10 11 12\n";

std::string job_yaml(const std::string& extra) {
  return "scene:\n  mesh: scene.obj\n  default_reflectance: 0\n" + extra +
         "luminaires:\n  size_m: 0.2\n  placed:\n    - {name: L, position_m: [1, 1, 2], flux_lm: 1000}\n"
         "solver:\n  rays_per_patch: 16\n";
}

double centre_lux(const Scene& scene, const Eigen::VectorXd& lux, bool facing_up) {
  double sum = 0.0, area = 0.0;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (scene.surfaces[p.surface].name != "floor" || (p.normal.z() > 0.0) != facing_up) continue;
    sum += lux[static_cast<Eigen::Index>(i)] * p.area_m2;
    area += p.area_m2;
  }
  return area > 0.0 ? sum / area : -1.0;
}

TEST(SceneOptions, OneSidedFloorWoundDownwardsStaysDark) {
  TempDir dir;
  dir.write("scene.obj", kObj);
  const JobScene loaded = load_job_scene(scene_spec(load_job_config(dir.write("job.yaml", job_yaml("")))));
  const ExactSolution s = solve_exact(loaded.scene, {});
  EXPECT_EQ(centre_lux(loaded.scene, s.radiosity.total_lux, false), 0.0) << "its front faces away from the light";
  EXPECT_EQ(centre_lux(loaded.scene, s.radiosity.total_lux, true), -1.0) << "no patch faces up";
}

TEST(SceneOptions, TwoSidedFloorIsLitOnItsUpperSide) {
  TempDir dir;
  dir.write("scene.obj", kObj);
  const JobScene one = load_job_scene(scene_spec(load_job_config(dir.write("one.yaml", job_yaml("")))));
  const JobScene two = load_job_scene(scene_spec(load_job_config(dir.write("two.yaml", job_yaml("  two_sided: [floor]\n")))));
  EXPECT_EQ(two.scene.patches_of({"floor"}).size(), 2 * one.scene.patches_of({"floor"}).size());
  EXPECT_EQ(two.scene.patches_of({"ground"}).size(), one.scene.patches_of({"ground"}).size());
  bool logged = false;
  for (const std::string& line : two.log) logged = logged || line.find("scene.two_sided: 2 triangles doubled") == 0;
  EXPECT_TRUE(logged);
  const ExactSolution s = solve_exact(two.scene, {});
  // The upward twin sees the luminaire: E = (flux / pi) cos^3 / h^2 averaged over the
  // 2 m floor 2 m below a 0.2 m panel, against the point source's 79.6 lx at the centre.
  const double up = centre_lux(two.scene, s.radiosity.total_lux, true);
  const double point_source_centre = 1000.0 / std::numbers::pi / 4.0;
  EXPECT_GT(up, 0.7 * point_source_centre);
  EXPECT_LT(up, point_source_centre);
  EXPECT_EQ(centre_lux(two.scene, s.radiosity.total_lux, false), 0.0);
}

TEST(SceneOptions, AllSurfacesTwoSidedAndExcludedGroundPlane) {
  TempDir dir;
  dir.write("scene.obj", kObj);
  const JobScene loaded =
      load_job_scene(scene_spec(load_job_config(dir.write("job.yaml", job_yaml("  two_sided: all\n  exclude_surfaces: [ground]\n")))));
  EXPECT_TRUE(loaded.scene.patches_of({"ground"}).empty());
  EXPECT_EQ(loaded.scene.patches_of({"floor"}).size(), 4u);  // 2 triangles, doubled
  EXPECT_EQ(loaded.scene.patches_of({"post"}).size(), 4u);
  EXPECT_NEAR(loaded.scene.bounds_m.max().x(), 2.0, 1e-12) << "the ground plane no longer sets the bounds";
  EXPECT_NEAR(loaded.scene.bounds_m.min().z(), 0.0, 1e-12);
  bool logged = false;
  for (const std::string& line : loaded.log)
    logged = logged || line == "scene.exclude_surfaces: 2 triangles of 1 surfaces left out";
  EXPECT_TRUE(logged);
}

TEST(SceneOptions, BadNamesAndValuesPointAtTheConfig) {
  TempDir dir;
  dir.write("scene.obj", kObj);
  const std::string unknown = dir.write("a.yaml", job_yaml("  exclude_surfaces: [grund]\n"));
  EXPECT_TRUE(test::Contains(test::error_of<ConfigError>([&] { load_job_scene(scene_spec(load_job_config(unknown))); }),
                             unknown + ":4:22: scene.exclude_surfaces: unknown surface 'grund'"));
  const std::string bad = dir.write("b.yaml", job_yaml("  two_sided: some\n"));
  EXPECT_TRUE(test::Contains(test::error_of<ConfigError>([&] { load_job_config(bad); }),
                             bad + ":4:14: scene.two_sided = some: must be all or a list of surface names"));
}

}  // namespace
}  // namespace ilp
