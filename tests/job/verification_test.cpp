// The verification's indirect rows (issue 21): patches that are not goals carry only
// reflected light, so their rows cast verification.indirect_rays_per_patch rays and
// their direct light is the cheap estimate. What the goals get must stay within 0.5 %
// of the verification with every row at rays_per_patch and every patch's direct light
// precise (as it was before).
#include <gtest/gtest.h>

#include <vector>

#include "core/exact/exact_solver.h"
#include "core/rays/point_gather.h"
#include "core/rays/ray_caster.h"
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
  const std::vector<VariantPlan> plans = plan_job(job);
  ASSERT_EQ(plans.size(), 1u);
  const PreparedJob prepared = prepare_job(job, plans[0]);
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

}  // namespace
}  // namespace ilp
