// The verification's indirect rows (issue 21): patches that are not goals carry only
// reflected light, so their rows cast verification.indirect_rays_per_patch rays and
// their direct light is the cheap estimate. What the goals get must stay within 0.5 %
// of the verification with every row at rays_per_patch and every patch's direct light
// precise (as it was before).
#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <vector>

#include "core/exact/exact_solver.h"
#include "core/exact/point_illuminance.h"
#include "core/transport/ray_caster.h"
#include "job/config.h"
#include "job/job_runner.h"
#include "job/plan.h"

namespace ilp {
namespace {

// The office job (a grid and the floor's patches as goals) with a 3 x 2 field at
// 3000 lm: the goal rows' values, by verify_layout as configured, and by a full exact
// solve (every row at rays_per_patch, every patch's direct light precise, the points'
// gathers as the verification casts them).
TEST(Verification, IndirectRowsKeepEveryGoalWithinHalfAPercentOfTheFullSolve) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office.yaml");
  job.verification.method = VerificationMethod::exact;
  job.verification.rays_per_patch = 1024;
  job.verification.indirect_rays_per_patch = 128;
  job.sample.fraction = 0.02;  // the operator is not what is tested
  const std::vector<VariantPlan> plans = plan_job(job).variants;
  ASSERT_EQ(plans.size(), 1u);
  const PreparedJob prepared = prepare_job(scene_spec(job), plans[0]);
  std::vector<PlacedLuminaire> layout;
  for (double x : {1.0, 3.0, 5.0})
    for (double y : {1.25, 2.75}) layout.push_back({{x, y, 2.93}, 3000.0, 0.0, {}});

  const Verification v = verify_layout(prepared, layout);
  ASSERT_EQ(v.method, "exact");
  // Progressive (verification.first_indirect_rays 16): doubled at least once, and
  // stopped before the cap once no goal moved by more than its error allows.
  EXPECT_EQ(v.first_indirect_rays, 16);
  EXPECT_GE(v.indirect_rays_per_patch, 32);
  EXPECT_LT(v.indirect_rays_per_patch, 128);
  EXPECT_GT(v.refinement_change, 0.0);
  EXPECT_TRUE(v.bvh_reused) << "the job scene's BVH, the luminaires' alone built";
  // Where its time went (timings.json's verification_parts_s): every part, adding up.
  ASSERT_EQ(v.parts_s.size(), 6u);
  EXPECT_EQ(v.parts_s.front().first, "BVH");
  EXPECT_EQ(v.parts_s.back().first, "the rest");
  double parts = 0.0;
  for (const auto& [name, seconds] : v.parts_s) {
    EXPECT_GE(seconds, 0.0) << name;
    parts += seconds;
  }
  EXPECT_NEAR(parts, v.seconds, 1e-9 + 1e-9 * v.seconds);
  const Eigen::VectorXd fast = verified_goal_lux(prepared.model, v);

  Scene scene = prepared.loaded.scene;
  add_layout(scene, plans[0].search.luminaire, layout);
  ExactSolveOptions full = exact_options(job, {});
  full.form_factors.rays_per_patch = 1024;
  full.form_factors.seed = job.form_factors.seed ^ 0x5EED5EEDull;  // the verification's own rays
  full.direct_light.seed = full.form_factors.seed;
  const ExactSolution solution = solve_exact(scene, full);
  const RayCaster caster(scene, 0);
  const PointIlluminance at = exact_point_illuminance(scene, caster, solution.radiosity, prepared.model.goal_points,
                                                      full.form_factors, full.direct_light);
  Verification reference = v;
  reference.patches = scene.all_patches();
  reference.lux = solution.radiosity.total_lux;
  reference.point_lux = at.total_lux;
  const Eigen::VectorXd exact = verified_goal_lux(prepared.model, reference);

  ASSERT_GT(prepared.model.goal_patches.size(), 0u);
  ASSERT_GT(prepared.model.goal_points.size(), 0u);
  for (const GoalArea& area : prepared.model.areas) {
    double mean_fast = 0.0, mean_exact = 0.0, min_fast = 1e300, min_exact = 1e300;
    for (Eigen::Index r = 0; r < static_cast<Eigen::Index>(area.rows.size()); ++r) {
      const Eigen::Index row = area.rows[static_cast<std::size_t>(r)];
      mean_fast += area.area_weights[r] * fast[row];
      mean_exact += area.area_weights[r] * exact[row];
      min_fast = std::min(min_fast, fast[row]);
      min_exact = std::min(min_exact, exact[row]);
    }
    EXPECT_NEAR(mean_fast / mean_exact, 1.0, 0.005) << area.name << " average";
    EXPECT_NEAR(min_fast / min_exact, 1.0, 0.005) << area.name << " minimum";
    EXPECT_NEAR((min_fast / mean_fast) / (min_exact / mean_exact), 1.0, 0.005) << area.name << " U0";
  }
}

// The grid goals' lowest point and U0 (the office's work plane and its surrounding band),
// from the verification as a job runs it with rays_per_patch 128 (the classroom's), with
// and without the decisive points' second look, against a reference with every row at
// 1024 rays, every patch's direct light precise and each point's gather at 16384 rays.
// With it the minimum and U0 are within 0.4 % (measured: 0.07 % and 0.05 %); without it
// (decisive_rays 0, the verification before) 0.64 % and 0.59 %. The test prints both.
struct GridExtremes {
  std::vector<double> minimum, uniformity;
};

GridExtremes grid_extremes(const LightingModel& model, const Eigen::VectorXd& lux) {
  GridExtremes out;
  for (const GoalArea& area : model.areas) {
    if (area.grid < 0 || area.kind != AreaKind::illuminance) continue;
    double mean = 0.0, low = 1e300;
    for (Eigen::Index r = 0; r < static_cast<Eigen::Index>(area.rows.size()); ++r) {
      mean += area.area_weights[r] * lux[area.rows[static_cast<std::size_t>(r)]];
      low = std::min(low, lux[area.rows[static_cast<std::size_t>(r)]]);
    }
    out.minimum.push_back(low);
    out.uniformity.push_back(low / mean);
  }
  return out;
}

TEST(Verification, TheDecisivePointsKeepEveryMinimumWithinHalfAPercentOfAFineReference) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office.yaml");
  job.verification.method = VerificationMethod::exact;
  job.verification.rays_per_patch = 128;
  job.sample.fraction = 0.02;  // the operator is not what is tested
  const std::vector<VariantPlan> plans = plan_job(job).variants;
  ASSERT_EQ(plans.size(), 1u);
  PreparedJob prepared = prepare_job(scene_spec(job), plans[0]);
  std::vector<PlacedLuminaire> layout;
  for (double x : {1.0, 3.0, 5.0})
    for (double y : {1.25, 2.75}) layout.push_back({{x, y, 2.93}, 3000.0, 0.0, {}});
  const Verification with = verify_layout(prepared, layout);
  EXPECT_GT(with.decisive_points, 0u);
  EXPECT_GT(with.precise_patches, 0u);
  EXPECT_EQ(with.decisive_rays, 16384);
  EXPECT_EQ(with.precise_rays, 1024);
  prepared.plan.verification.settings.decisive_rays = 0;
  const Verification without = verify_layout(prepared, layout);
  EXPECT_EQ(without.decisive_points, 0u);

  Scene scene = prepared.loaded.scene;
  add_layout(scene, plans[0].search.luminaire, layout);
  ExactSolveOptions fine = exact_options(job, {});
  fine.form_factors.rays_per_patch = 1024;
  fine.form_factors.seed = 77;  // rays of its own
  fine.direct_light.seed = fine.form_factors.seed;
  const ExactSolution solution = solve_exact(scene, fine);
  const RayCaster caster(scene, 0);
  fine.form_factors.rays_per_patch = 16384;
  const PointIlluminance at = exact_point_illuminance(scene, caster, solution.radiosity, prepared.model.goal_points,
                                                      fine.form_factors, fine.direct_light);
  Verification reference = with;
  reference.patches = scene.all_patches();
  reference.lux = solution.radiosity.total_lux;
  reference.point_lux = at.total_lux;

  const GridExtremes exact = grid_extremes(prepared.model, verified_goal_lux(prepared.model, reference));
  const GridExtremes now = grid_extremes(prepared.model, verified_goal_lux(prepared.model, with));
  const GridExtremes before = grid_extremes(prepared.model, verified_goal_lux(prepared.model, without));
  ASSERT_GE(exact.minimum.size(), 1u) << "the work plane";
  for (std::size_t g = 0; g < exact.minimum.size(); ++g) {
    std::cout << "grid goal " << g << ": minimum " << exact.minimum[g] << " lx; with " << now.minimum[g]
              << ", without " << before.minimum[g] << "; U0 " << exact.uniformity[g] << ", with "
              << now.uniformity[g] << ", without " << before.uniformity[g] << "\n";
    EXPECT_NEAR(now.minimum[g] / exact.minimum[g], 1.0, 0.004) << "grid goal " << g;
    EXPECT_NEAR(now.uniformity[g] / exact.uniformity[g], 1.0, 0.004) << "grid goal " << g;
  }
}

}  // namespace
}  // namespace ilp
