// The closed-form direct term against Howell's point-to-rectangle factor, and its
// shadow rays against blockers of known size.
#include "core/direct_light.h"

#include <gtest/gtest.h>

#include <numbers>

#include "core/ray_caster.h"
#include "core/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

// An a x b emitting rectangle facing down at height c, corner above the origin.
Scene rectangle_above_origin(double a, double b, double c) {
  return reference::make_quad_scene({{"emitter", V(0, 0, c), V(0, b, c), V(a, b, c), V(a, 0, c)}}, 0.0);
}

TEST(DirectLight, PointToTriangleFormFactorsSumToTheRectangleClosedForm) {
  for (double c : {0.25, 1.0, 3.0}) {
    const Scene scene = rectangle_above_origin(1.0, 0.5, c);
    double sum = 0.0;
    for (const Patch& p : scene.patches) sum += point_to_triangle_form_factor(V::Zero(), V::UnitZ(), p);
    EXPECT_NEAR(sum, reference::point_to_corner_rectangle_form_factor(1.0, 0.5, c), 1e-12) << "height " << c;
  }
}

TEST(DirectLight, ClipsToTheReceiversHemisphereAndIgnoresTheEmittersBack) {
  const Scene scene = rectangle_above_origin(1.0, 1.0, 1.0);  // [0, 1] x [0, 1] at z = 1, facing down
  double facing_away = 0.0, above_emitter = 0.0, tilted = 0.0;
  for (const Patch& p : scene.patches) {
    facing_away += point_to_triangle_form_factor(V::Zero(), -V::UnitZ(), p);
    above_emitter += point_to_triangle_form_factor(V(0.5, 0.5, 2.0), V::UnitZ(), p);  // sees its back
    // A vertical receiver at x = 0.5 facing +x sees only the half x > 0.5.
    tilted += point_to_triangle_form_factor(V(0.5, 0.0, 0.0), V::UnitX(), p);
  }
  EXPECT_EQ(facing_away, 0.0);
  EXPECT_EQ(above_emitter, 0.0);
  // Independent value: (1/pi) * integral over the half of cos1 cos2 / r^2, where from
  // (0.5, 0, 0) to (x, y, 1): cos1 = (x - 0.5) / r, cos2 = 1 / r. Midpoint rule.
  constexpr int kCells = 1000;
  double integral = 0.0;
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const double dx = 0.5 * (i + 0.5) / kCells, y = (j + 0.5) / kCells;
      const double r2 = dx * dx + y * y + 1.0;
      integral += dx / (r2 * r2) * (0.5 / kCells) * (1.0 / kCells);
    }
  EXPECT_NEAR(tilted, integral / std::numbers::pi, 1e-6);
}

TEST(DirectLight, CoplanarPatchesIncludingTheEmitterItselfReceiveNothing) {
  // A 2 x 2 emitting square far from the origin, meshed into 32 coplanar patches.
  const Scene scene = reference::make_quad_scene(
      {{"panel", V(100, 200, 3), V(100, 202, 3), V(102, 202, 3), V(102, 200, 3)}}, 0.5);
  const RayCaster caster(scene);
  std::vector<int> all(scene.patches.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
  const Eigen::MatrixXd F = compute_emitter_form_factors(scene, caster, all, all, {});
  EXPECT_EQ(F.cwiseAbs().maxCoeff(), 0.0);
  for (const Patch& p : scene.patches) EXPECT_EQ(point_to_triangle_form_factor(p.centroid_m, p.normal, p), 0.0);
}

TEST(DirectLight, PatchToSquareMatchesParallelPlatesClosedForm) {
  // Receiver: unit square at z = 0 facing up; emitter: unit square at z = 1 facing down.
  const Scene scene = reference::make_quad_scene({{"receiver", V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)},
                                             {"emitter", V(0, 0, 1), V(0, 1, 1), V(1, 1, 1), V(1, 0, 1)}},
                                            0.0);
  const RayCaster caster(scene);
  DirectLightOptions options;
  options.receiver_points = 256;
  const auto receivers = reference::patches_of(scene, "receiver");
  const auto emitters = reference::patches_of(scene, "emitter");
  const Eigen::MatrixXd F = compute_emitter_form_factors(scene, caster, receivers, emitters, options);
  double weighted = 0.0, area = 0.0;
  for (std::size_t r = 0; r < receivers.size(); ++r) {
    weighted += scene.patches[receivers[r]].area_m2 * F.row(static_cast<Eigen::Index>(r)).sum();
    area += scene.patches[receivers[r]].area_m2;
  }
  // Only the quadrature over receiver points is approximate: no rays are blocked.
  EXPECT_NEAR(weighted / area, 0.199825, 2e-3);
}

TEST(DirectLight, ShadowRaysSeeBlockersOfKnownSize) {
  // A small receiver under a unit emitter; a blocker between them covering all of
  // the emitter as seen from the receiver, then one covering exactly half of it.
  auto scene_with_blocker = [](double blocker_x1) {
    return reference::make_quad_scene(
        {{"receiver", V(0.49, 0.49, 0), V(0.51, 0.49, 0), V(0.51, 0.51, 0), V(0.49, 0.51, 0)},
         {"emitter", V(0, 0, 1), V(0, 1, 1), V(1, 1, 1), V(1, 0, 1)},
         {"blocker", V(-1, -1, 0.5), V(blocker_x1, -1, 0.5), V(blocker_x1, 2, 0.5), V(-1, 2, 0.5)}},
        0.0);
  };
  DirectLightOptions options;
  options.receiver_points = 4;
  options.shadow_rays = 256;
  auto direct = [&](const Scene& scene) {
    const RayCaster caster(scene);
    const auto receivers = reference::patches_of(scene, "receiver");
    const auto emitters = reference::patches_of(scene, "emitter");
    return compute_emitter_form_factors(scene, caster, receivers, emitters, options).sum();
  };
  EXPECT_EQ(direct(scene_with_blocker(2.0)), 0.0);
  // Blocker edge at x = 0.5 straight above the receiver: the rays to x < 0.5 are
  // blocked, half of the emitter's points; the unoccluded factor stays the whole square's.
  const double half = direct(scene_with_blocker(0.5));
  const double open = direct(reference::make_quad_scene(
      {{"receiver", V(0.49, 0.49, 0), V(0.51, 0.49, 0), V(0.51, 0.51, 0), V(0.49, 0.51, 0)},
       {"emitter", V(0, 0, 1), V(0, 1, 1), V(1, 1, 1), V(1, 0, 1)}},
      0.0));
  EXPECT_NEAR(half / open, 0.5, 0.05);
}

}  // namespace
}  // namespace ilp
