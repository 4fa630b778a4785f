// The automatic verification method chosen by the cost model: exact while its sparse
// rows fit, else a sample that fits in memory (issue 12: a 25 % sample of
// 398K patches, 79,000 x 79,000 dense, ran out of memory after 12 minutes).
#include "job/config.h"
#include "job/job_cost.h"

#include <gtest/gtest.h>

namespace ilp {
namespace {

TEST(JobCost, AutomaticVerificationNeverChoosesADenseSystemThatDoesNotFit) {
  JobConfig job;  // verification.method auto, 1024 rays, sample_fraction 0.25
  const std::size_t n = 398000;
  const double budget = 4e9;
  const VerificationPlan plan = plan_verification(job.verification, n, n, 60000, 8, budget);
  ASSERT_EQ(plan.method, VerificationMethod::sample);  // exact rows: 398K x 1024 rays, about 8 GB
  EXPECT_LE(plan.sample_size, kAutoVerificationMaxSample);
  EXPECT_LE(sample_verification_bytes(static_cast<std::size_t>(plan.sample_size), 60000, 9, 1024), 0.5 * budget);
  // With a tiny budget the sample shrinks further instead of failing later.
  const VerificationPlan small = plan_verification(job.verification, n, n, 100, 8, 5e7);
  EXPECT_LT(small.sample_size, plan.sample_size);
  EXPECT_LE(sample_verification_bytes(static_cast<std::size_t>(small.sample_size), 100, 9, 1024), 2.5e7);
}

TEST(JobCost, AutomaticVerificationIsExactWhenItsRowsFit) {
  JobConfig job;
  job.verification.rays_per_patch = 128;
  EXPECT_EQ(plan_verification(job.verification, 20000, 20000, 100, 8, 1e9).method, VerificationMethod::exact);  // <= max_exact_patches
  // 398K rows at 128 rays: about 1.3 GB, within half of 24 GB.
  EXPECT_EQ(plan_verification(job.verification, 398000, 398000, 100, 8, 24e9).method, VerificationMethod::exact);
  EXPECT_EQ(plan_verification(job.verification, 398000, 398000, 100, 8, 2e9).method, VerificationMethod::sample);
}

TEST(JobCost, ExplicitMethodsAreKept) {
  JobConfig job;
  job.verification.method = VerificationMethod::sample;
  job.verification.sample_fraction = 0.25;
  const VerificationPlan plan = plan_verification(job.verification, 398000, 398000, 100, 8, 1e9);
  EXPECT_EQ(plan.method, VerificationMethod::sample);
  EXPECT_EQ(plan.sample_size, 99500);  // as asked: the job's estimate refuses it (verification.sample_fraction)
  job.verification.method = VerificationMethod::exact;
  EXPECT_EQ(plan_verification(job.verification, 398000, 398000, 100, 8, 1e9).method, VerificationMethod::exact);
}

// The whole run's estimate from its variants' own: the model is read and its BVH built
// once (the variants share them), the outputs written once, and a later variant's
// verification counted at half under min_power (it is verified only when predicted to
// beat the one found).
TEST(JobCost, TheWholeRunCountsTheSceneAndTheOutputsOnceAndLaterVerificationsAtHalf) {
  CostEstimate variant;
  variant.phases = {{kScenePhase, 1.0}, {"sample rows (k = 100)", 2.0}, {"verification (exact, ...)", 4.0},
                    {kOutputPhase, 0.5}};
  JobConfig job;
  job.objective = Objective::min_power;
  EXPECT_DOUBLE_EQ(whole_run_seconds(job.objective, {variant}), 7.5);
  EXPECT_DOUBLE_EQ(whole_run_seconds(job.objective, {variant, variant}), 7.5 + 2.0 + 2.0);
  EXPECT_DOUBLE_EQ(whole_run_seconds(job.objective, {variant, variant, variant}), 7.5 + 2 * (2.0 + 2.0));
  job.objective = Objective::closest_to_target;  // every variant verified
  EXPECT_DOUBLE_EQ(whole_run_seconds(job.objective, {variant, variant}), 7.5 + 2.0 + 4.0);
  EXPECT_DOUBLE_EQ(whole_run_seconds(job.objective, {}), 0.0);
}

// A job of luminaire groups: every group's variants built and searched, the model read and
// the outputs written once, and one verification of the groups together (the largest).
TEST(JobCost, GroupsReadTheModelWriteTheOutputsAndVerifyOnce) {
  CostEstimate a, b;
  a.phases = {{kScenePhase, 1.0, 0.0, ""}, {"search (10 evaluations)", 2.0, 0.0, ""},
              {"verification (exact, ...)", 3.0, 0.0, ""}, {kOutputPhase, 0.5, 0.0, ""}};
  b.phases = {{kScenePhase, 1.0, 0.0, ""}, {"search (10 evaluations)", 4.0, 0.0, ""},
              {"verification (exact, ...)", 5.0, 0.0, ""}, {kOutputPhase, 0.5, 0.0, ""}};
  EXPECT_DOUBLE_EQ(groups_run_seconds({{a}}), 6.5);
  EXPECT_DOUBLE_EQ(groups_run_seconds({{a}, {b}}), 1.0 + 2.0 + 4.0 + 0.5 + 5.0);
  EXPECT_DOUBLE_EQ(groups_run_seconds({{a, b}, {a}}), 1.0 + 2.0 + 4.0 + 2.0 + 0.5 + 5.0);
  EXPECT_DOUBLE_EQ(groups_run_seconds({}), 0.0);
}

}  // namespace
}  // namespace ilp
