#include "optimizer/illuminance_metrics.h"

#include <gtest/gtest.h>

#include <sstream>

namespace ilp {
namespace {

using V = Eigen::Vector3d;

// Two patches of one surface with areas 1 and 3, one of another surface.
Scene three_patch_scene() {
  Scene scene;
  scene.surfaces = {{"desk"}, {"floor"}};
  for (auto [area, surface] : {std::pair{1.0, 0}, std::pair{3.0, 0}, std::pair{2.0, 1}}) {
    Patch p;
    p.area_m2 = area;
    p.surface = surface;
    scene.patches.push_back(p);
  }
  return scene;
}

TEST(IlluminanceMetrics, AverageIsAreaWeightedAndUniformityIsMinOverAverage) {
  const Scene scene = three_patch_scene();
  const Eigen::VectorXd lux = Eigen::Vector3d(100.0, 500.0, 42.0);
  const SurfaceIlluminance desk = surface_illuminance(scene, lux, 0);
  EXPECT_EQ(desk.patches, 2u);
  EXPECT_DOUBLE_EQ(desk.area_m2, 4.0);
  EXPECT_DOUBLE_EQ(desk.average_lux, (100.0 * 1 + 500.0 * 3) / 4.0);  // not the plain mean 300
  EXPECT_DOUBLE_EQ(desk.min_lux, 100.0);
  EXPECT_DOUBLE_EQ(desk.max_lux, 500.0);
  EXPECT_DOUBLE_EQ(desk.uniformity, 100.0 / 400.0);
  const SurfaceIlluminance floor = surface_illuminance(scene, lux, 1);
  EXPECT_DOUBLE_EQ(floor.average_lux, 42.0);
  EXPECT_DOUBLE_EQ(floor.uniformity, 1.0);
}

TEST(IlluminanceMetrics, TableFollowsRequestedSurfacesAndPrintsUnits) {
  const Scene scene = three_patch_scene();
  const Eigen::VectorXd lux = Eigen::Vector3d(100.0, 500.0, 42.0);
  const auto rows = surface_illuminance_table(scene, lux, {"floor"});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].surface, "floor");
  std::ostringstream os;
  print_illuminance_table(os, rows);
  EXPECT_NE(os.str().find("Eavg lux"), std::string::npos);
  EXPECT_NE(os.str().find("42.0"), std::string::npos);
  EXPECT_THROW(surface_illuminance_table(scene, lux, {"ceiling"}), std::invalid_argument);
  EXPECT_THROW(surface_illuminance(scene, Eigen::VectorXd::Zero(2), 0), std::invalid_argument);
}

TEST(IlluminanceMetrics, UnlitSurfaceHasZeroUniformity) {
  const Scene scene = three_patch_scene();
  EXPECT_EQ(surface_illuminance(scene, Eigen::VectorXd::Zero(3), 0).uniformity, 0.0);
}

}  // namespace
}  // namespace ilp
