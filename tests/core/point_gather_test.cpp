// dominant_patches (core/exact/point_illuminance.h): the patches a grid point gathers a given
// share of its reflected light from, which the verification solves precisely for the
// points deciding a minimum (job_runner.cpp).
#include "core/exact/point_illuminance.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

// Row 0 gathers from a (0.5 of its rays, B 100), b (0.3, B 200), c (0.0015, B 100) and a
// luminaire (0.1): light 50, 60 and 0.15 of 110.15, the luminaire's left out (it is
// direct light). Row 1 gathers nothing (every ray escaped).
TEST(DominantPatches, ThePatchesCarryingTheShareOfAPointsReflectedLight) {
  Scene scene = reference::make_closed_box(V::Zero(), V(3.0, 2.0, 2.5), 0.5, 0.5);
  const int luminaire_surface = add_square_luminaire(scene, "panel", V(1.5, 1.0, 2.45), 0.6, 1000.0);
  int lum = -1;
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    if (scene.patches[i].surface == luminaire_surface) lum = static_cast<int>(i);
  ASSERT_GE(lum, 0);
  const int a = 2, b = 9, c = 5;
  const auto n = static_cast<Eigen::Index>(scene.patches.size());
  FormFactorRows rows;
  rows.row_patches = {-1, -2};
  rows.F = SparseRows(2, n);
  std::vector<Eigen::Triplet<double>> at = {{0, a, 0.5}, {0, b, 0.3}, {0, c, 0.0015}, {0, lum, 0.1}};
  rows.F.setFromTriplets(at.begin(), at.end());
  RadiositySolution solution;
  solution.radiosity_lm_per_m2 = Eigen::MatrixXd::Constant(n, 1, 100.0);
  solution.radiosity_lm_per_m2(b, 0) = 200.0;
  solution.radiosity_lm_per_m2(lum, 0) = 1e6;  // far above all: never chosen, never counted

  EXPECT_EQ(dominant_patches(scene, rows, solution, std::vector<int>{0}, 0.002), (std::vector<int>{a, b}));
  EXPECT_EQ(dominant_patches(scene, rows, solution, std::vector<int>{0}, 0.001), (std::vector<int>{a, c, b}))
      << "0.15 of 110.15 is 0.14 %: ascending patch order";
  EXPECT_EQ(dominant_patches(scene, rows, solution, std::vector<int>{0}, 0.5), (std::vector<int>{b})) << "60 of 110.15";
  EXPECT_TRUE(dominant_patches(scene, rows, solution, std::vector<int>{1}, 0.002).empty()) << "nothing gathered";
  EXPECT_THROW(dominant_patches(scene, rows, solution, std::vector<int>{2}, 0.002), std::invalid_argument);
}

}  // namespace
}  // namespace ilp
