// The exact solve refined in steps (ProgressiveExactSolve, for the verification): rows
// outside the precise patches start at a few rays and are doubled by new, independent
// rays. Merged rows keep every conservation law of a row, the ray count is what the
// steps cast, and the refined answer agrees with a plain solve at the final count.
#include "core/exact/exact_solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/light/luminaire.h"
#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

// A furnace: a closed box whose every face emits E with reflectance rho has
// B = E / (1 - rho) everywhere, for any rays, exactly when each row sums to 1. After
// every doubling it still does (a merged row that lost or doubled a share would not).
TEST(ProgressiveExactSolve, AFurnaceStaysExactAtEveryStep) {
  constexpr double kRho = 0.6, kE = 100.0, kB0 = kE / (1.0 - kRho);
  Scene scene = reference::make_closed_box(V::Zero(), V(3.0, 2.0, 2.5), kRho, 0.5);
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) set_surface_exitance(scene, static_cast<int>(s), kE);
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = 64;
  options.radiosity.relative_residual = 1e-12;
  options.precise_patches = std::vector<int>{0, 5};
  options.other_rays_per_patch = 32;
  ProgressiveExactSolve solve(scene, options, 4);
  const auto n = static_cast<std::uint64_t>(scene.patches.size());
  std::vector<int> steps;
  while (true) {
    steps.push_back(solve.other_rays());
    const Eigen::MatrixXd& B = solve.solution().radiosity.radiosity_lm_per_m2;
    for (Eigen::Index i = 0; i < B.rows(); ++i) ASSERT_NEAR(B(i, 0), kB0, 1e-8 * kB0) << "patch " << i << " at " << steps.back();
    if (!solve.can_refine()) break;
    solve.refine();
  }
  EXPECT_EQ(steps, (std::vector<int>{4, 8, 16, 32}));
  // The precise rows once at 64, the others 4 + 4 + 8 + 16 = 32 each.
  EXPECT_EQ(solve.solution().summary.rays_cast, 2u * 64u + (n - 2u) * 32u);
}

// A box lit by its ceiling (rho 0.5): the floor's illuminance after refining 8 -> 128
// agrees with one solve at 128 rays within the rays' noise, and the first step (8 rays)
// is further from it than the last (the refinement converges).
TEST(ProgressiveExactSolve, RefiningConvergesToThePlainSolve) {
  Scene scene = reference::make_closed_box(V::Zero(), V(4.0, 3.0, 2.5), 0.5, 0.4);
  const std::vector<int> ceiling = reference::patches_of(scene, "ceiling");
  ASSERT_FALSE(ceiling.empty());
  set_surface_exitance(scene, scene.patches[static_cast<std::size_t>(ceiling.front())].surface, 1000.0);
  const std::vector<int> floor = reference::patches_of(scene, "floor");
  ASSERT_FALSE(floor.empty());
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = 128;
  options.precise_patches = floor;
  options.other_rays_per_patch = 128;
  const ExactSolution plain = solve_exact(scene, options);
  auto floor_mean = [&](const ExactSolution& s) {
    double sum = 0.0, area = 0.0;
    for (int p : floor) {
      sum += scene.patches[static_cast<std::size_t>(p)].area_m2 * s.radiosity.total_lux[p];
      area += scene.patches[static_cast<std::size_t>(p)].area_m2;
    }
    return sum / area;
  };
  ProgressiveExactSolve solve(scene, options, 8);
  const double first = floor_mean(solve.solution());
  while (solve.can_refine()) solve.refine();
  EXPECT_EQ(solve.other_rays(), 128);
  const double last = floor_mean(solve.solution()), reference = floor_mean(plain);
  EXPECT_NEAR(last / reference, 1.0, 0.005);
  EXPECT_NE(first, last) << "the steps must change the answer";
}

// Patches made precise after a few steps (the verification's decisive points' patches):
// their rows are replaced, not merged, so every row still sums to 1 (the furnace stays
// exact), they are cast once at the count asked for, and later doublings leave them.
TEST(ProgressiveExactSolve, MakePreciseReplacesRowsAndKeepsTheFurnaceExact) {
  constexpr double kRho = 0.6, kE = 100.0, kB0 = kE / (1.0 - kRho);
  Scene scene = reference::make_closed_box(V::Zero(), V(3.0, 2.0, 2.5), kRho, 0.5);
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s) set_surface_exitance(scene, static_cast<int>(s), kE);
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = 64;
  options.radiosity.relative_residual = 1e-12;
  options.precise_patches = std::vector<int>{0};
  options.other_rays_per_patch = 32;
  ProgressiveExactSolve solve(scene, options, 4);
  const auto n = static_cast<std::uint64_t>(scene.patches.size());
  EXPECT_EQ(solve.precise_count(), 1u);
  EXPECT_EQ(solve.make_precise({7, 3, 0, 7}, 256), 2u);  // 0 was precise; 7 named twice
  EXPECT_EQ(solve.make_precise({3}, 256), 0u);
  EXPECT_EQ(solve.precise_count(), 3u);
  const Eigen::MatrixXd& B = solve.solution().radiosity.radiosity_lm_per_m2;
  for (Eigen::Index i = 0; i < B.rows(); ++i) ASSERT_NEAR(B(i, 0), kB0, 1e-8 * kB0) << "patch " << i;
  while (solve.can_refine()) solve.refine();
  for (Eigen::Index i = 0; i < B.rows(); ++i) ASSERT_NEAR(B(i, 0), kB0, 1e-8 * kB0) << "patch " << i;
  // Patch 0 once at 64; 3 and 7 at 4 first, then 256; the others 4 + 4 + 8 + 16.
  EXPECT_EQ(solve.solution().summary.rays_cast, 64u + 2u * (4u + 256u) + (n - 3u) * 32u);
}

// A patch made precise gets the precise direct light, the same bits as a solve that had
// it precise from the start (a patch's light depends only on it and the options), and
// the patches left alone keep the cheap estimate (one point of the patch against eight:
// under a panel the two differ).
TEST(ProgressiveExactSolve, MakePreciseGivesThePreciseDirectLight) {
  Scene scene = reference::make_closed_box(V::Zero(), V(4.0, 3.0, 2.5), 0.5, 0.5);
  add_square_luminaire(scene, "panel", V(2.0, 1.5, 2.45), 0.6, 3000.0);
  const std::vector<int> floor = reference::patches_of(scene, "floor");
  ASSERT_GE(floor.size(), 4u);
  const std::vector<int> chosen = {floor[1], floor[floor.size() / 2]};
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = 64;
  options.precise_patches = std::vector<int>{};
  options.other_rays_per_patch = 16;
  ProgressiveExactSolve late(scene, options, 16);
  const Eigen::VectorXd cheap = late.solution().radiosity.direct_lux;
  ASSERT_EQ(late.make_precise(chosen, 64), 2u);
  options.precise_patches = chosen;
  const ExactSolution early = solve_exact(scene, options);
  const Eigen::VectorXd& now = late.solution().radiosity.direct_lux;
  for (int p : chosen) EXPECT_EQ(now[p], early.radiosity.direct_lux[p]) << "patch " << p;
  for (int p : floor) {
    if (std::find(chosen.begin(), chosen.end(), p) == chosen.end()) {
      EXPECT_EQ(now[p], cheap[p]) << "patch " << p;
    }
  }
  double moved = 0.0;
  for (int p : chosen) moved = std::max(moved, std::abs(now[p] - cheap[p]) / early.radiosity.direct_lux[p]);
  EXPECT_GT(moved, 1e-6) << "the cheap and precise estimates should differ somewhere";
}

// The verification's steps before its last solve only to a loose residual: tighten()
// then goes on from the loose solution to the tolerance set, and reaches the solve that
// was tight from the start (the same system, solved twice to 1e-12).
TEST(ProgressiveExactSolve, ALooseStepTightenedReachesTheTightSolve) {
  Scene scene = reference::make_closed_box(V::Zero(), V(4.0, 3.0, 2.5), 0.7, 0.4);
  add_square_luminaire(scene, "panel", V(2.0, 1.5, 2.45), 0.6, 3000.0);
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = 32;
  options.precise_patches = std::vector<int>{};
  options.other_rays_per_patch = 16;
  options.radiosity.relative_residual = 1e-12;
  const ExactSolution tight = solve_exact(scene, options);
  options.radiosity.relative_residual = 1e-3;
  ProgressiveExactSolve solve(scene, options, 16);
  const ExactSolveSummary& s = solve.solution().summary;
  EXPECT_LE(s.relative_residual, 1e-3);
  EXPECT_GT(s.relative_residual, 1e-12) << "the loose step should stop before the tight tolerance";
  const int loose_sweeps = s.iterations;
  EXPECT_FALSE(solve.tighten()) << "already within its own tolerance";
  solve.set_relative_residual(1e-12);
  EXPECT_TRUE(solve.tighten());
  EXPECT_LE(s.relative_residual, 1e-12);
  EXPECT_LT(s.iterations, tight.summary.iterations) << "from the loose solution, fewer sweeps than from the start";
  EXPECT_GT(loose_sweeps, 0);
  const Eigen::MatrixXd& B = solve.solution().radiosity.radiosity_lm_per_m2;
  const Eigen::MatrixXd& reference = tight.radiosity.radiosity_lm_per_m2;
  EXPECT_LE((B - reference).norm(), 1e-10 * reference.norm());
  EXPECT_FALSE(solve.tighten());
}

// Merged rows (a doubling, patches made precise) are built on the solve's threads, each
// row by one thread: the same radiosity, to the bit, on one thread or two.
TEST(ProgressiveExactSolve, TheStepsGiveTheSameBitsOnAnyThreadCount) {
  auto run = [](int threads) {
    Scene scene = reference::make_closed_box(V::Zero(), V(4.0, 3.0, 2.5), 0.6, 0.4);
    add_square_luminaire(scene, "panel", V(2.0, 1.5, 2.45), 0.6, 3000.0);
    ExactSolveOptions options;
    options.form_factors.rays_per_patch = 64;
    options.form_factors.threads = threads;
    options.direct_light.threads = threads;
    options.radiosity.threads = threads;
    options.precise_patches = std::vector<int>{};
    options.other_rays_per_patch = 32;
    ProgressiveExactSolve solve(scene, options, 8);
    while (solve.can_refine()) solve.refine();
    solve.make_precise({1, 4, 9}, 256);
    return solve.solution().radiosity.radiosity_lm_per_m2;
  };
  const Eigen::MatrixXd one = run(1), two = run(2);
  ASSERT_EQ(one.rows(), two.rows());
  for (Eigen::Index i = 0; i < one.rows(); ++i) ASSERT_EQ(one(i, 0), two(i, 0)) << "patch " << i;
}

}  // namespace
}  // namespace ilp
