// The sample-based operator against the exact solve, conservation and its own shortcuts.
#include "core/operator/sample_operator.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <string_view>

#include "job/config.h"
#include "job/plan.h"
#include "core/base/error.h"
#include "core/exact/exact_solver.h"
#include "job/job_scene.h"
#include "core/scene/reference_scenes.h"
#include "core/operator/sample_error.h"

namespace ilp {
namespace {

// The shipped office, meshed coarsely (about 1,900 patches) so that k = n stays cheap.
Scene coarse_office(double max_edge_m = 0.6) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  job.scene.max_patch_edge_m = max_edge_m;
  return load_job_scene(scene_spec(job)).scene;
}

SampleOperatorOptions options_with(int k, int rays = 256) {
  SampleOperatorOptions o;
  o.sample_size = k;
  o.form_factors.rays_per_patch = rays;
  return o;
}

SampleOperator build(const Scene& scene, std::span<const int> goals, const SampleOperatorOptions& o) {
  const RayCaster caster(scene);
  const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
  return build_sample_operator(scene, caster, rows, o);
}

TEST(SampleOperator, CensusReproducesTheExactSolve) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = scene.patches_of({"desk_1", "desk_2", "floor", "walls"});
  for (IndirectMethod method : {IndirectMethod::sample_gather, IndirectMethod::exact_second_bounce}) {
    SampleOperatorOptions o = options_with(static_cast<int>(scene.patches.size()));
    o.indirect = method;
    const SampleOperator op = build(scene, goals, o);
    ASSERT_TRUE(op.stats.census);
    ExactSolveOptions exact;
    exact.radiosity.relative_residual = 1e-12;
    const ExactSolution reference = solve_exact(scene, exact);
    const Eigen::VectorXd H = op.illuminance_lux(source_flux_lm(scene, op.sources));
    const Eigen::VectorXd direct = op.direct_lux(source_flux_lm(scene, op.sources));
    for (std::size_t g = 0; g < goals.size(); ++g) {
      const Eigen::Index i = goals[g];
      ASSERT_NEAR(direct[g], reference.radiosity.direct_lux[i], 1e-9 * reference.radiosity.direct_lux[i] + 1e-12)
          << "patch " << i;
      ASSERT_NEAR(H[g], reference.radiosity.total_lux[i], 1e-8 * reference.radiosity.total_lux[i])
          << "patch " << i << " with " << to_string(method);
    }
  }
}


// The error against the census (the exact solve with the same rows) falls as k
// grows, for both indirect methods, averaged over seeds; the census itself is exact.
TEST(SampleOperator, ErrorShrinksAsTheSampleGrows) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = scene.patches_of({"desk_1", "desk_2", "floor"});
  const RayCaster caster(scene);
  for (IndirectMethod method : {IndirectMethod::sample_gather, IndirectMethod::exact_second_bounce}) {
    SampleOperatorOptions o = options_with(1);
    o.indirect = method;
    const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
    const Eigen::VectorXd flux = source_flux_lm(scene, rows.sources);
    o.sample_size = static_cast<int>(scene.patches.size());
    const SampleOperator census = build_sample_operator(scene, caster, rows, o);
    const Eigen::VectorXd exact = census.illuminance_lux(flux), exact_direct = census.direct_lux(flux);
    std::vector<double> errors;
    for (double fraction : {0.01, 0.05, 0.25}) {
      double sum = 0.0;
      for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        o.sample_size = static_cast<int>(fraction * static_cast<double>(scene.patches.size()));
        o.sample_seed = seed;
        const SampleOperator op = build_sample_operator(scene, caster, rows, o);
        sum += compare_illuminance(scene, goals, op.illuminance_lux(flux), op.direct_lux(flux), exact, exact_direct)
                   .rms_relative_indirect;
      }
      errors.push_back(sum / 4);
    }
    for (std::size_t m = 1; m < errors.size(); ++m)
      EXPECT_LT(errors[m], 0.8 * errors[m - 1]) << to_string(method) << ": errors " << errors[0] << ", " << errors[1]
                                                << ", " << errors[2];
    EXPECT_GT(errors.front(), 1e-3) << "a 1 % sample cannot be exact";
  }
}

// The same sample, rays and seeds give bit-identical operators with 1 and 2 threads.
TEST(SampleOperator, DeterministicWhateverTheThreadCount) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = scene.patches_of({"desk_1", "floor"});
  SampleOperatorOptions one = options_with(60), two = one;
  one.form_factors.threads = one.direct_light.threads = 1;
  two.form_factors.threads = two.direct_light.threads = 2;
  const SampleOperator a = build(scene, goals, one), b = build(scene, goals, two);
  EXPECT_EQ(a.sample.patches, b.sample.patches);
  EXPECT_EQ(a.total_lux_per_lm, b.total_lux_per_lm);
  const SampleOperatorOptions other_seed = [&] { auto o = one; o.sample_seed = 2; return o; }();
  EXPECT_NE(build(scene, goals, other_seed).total_lux_per_lm, a.total_lux_per_lm);
}

// Sample rows of K sum to rho_i s_i: I - K is strictly diagonally dominant.
TEST(SampleOperator, StatsAndLogDescribeTheBuild) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = scene.patches_of({"desk_1", "desk_2"});
  const SampleOperator op = build(scene, goals, options_with(100));
  EXPECT_EQ(op.stats.goal_patches, goals.size());
  EXPECT_EQ(op.stats.sample_patches, 100u);
  EXPECT_EQ(op.stats.population, scene.patches.size() - 8);  // 4 luminaires x 2 patches do not reflect
  EXPECT_GT(op.stats.condition_estimate, 1.0);
  EXPECT_LT(op.stats.condition_estimate, 1e3);
  EXPECT_EQ(op.stats.rays_cast, (100 + goals.size()) * 256u);
  std::string log;
  for (const std::string& line : op.log) log += line + "\n";
  EXPECT_NE(log.find("condition estimate"), std::string::npos) << log;
  EXPECT_NE(log.find("100 distinct patches"), std::string::npos) << log;
  // Row sums of K are rho_a s_a: at most the ceiling's 0.7, and near it in a closed
  // room (s_a is 1 less what the luminaires and back faces take).
  EXPECT_LE(op.stats.max_row_sum, 0.7);
  EXPECT_GT(op.stats.max_row_sum, 0.6);
  EXPECT_DOUBLE_EQ(op.stats.condition_bound_inf, (1 + op.stats.max_row_sum) / (1 - op.stats.max_row_sum));
  EXPECT_NE(log.find("infinity-norm condition is at most"), std::string::npos) << log;
}

// The k x k solve and the first-reflection gathers ran on TBB's default arena, so
// solver.threads = 1 still used every core there; they now run in the build's own
// arena of form_factors.threads (seen from the solve's progress callback).
TEST(SampleOperator, TheSolveHonoursTheThreadCount) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = scene.patches_of({"desk_1", "desk_2"});
  SampleOperatorOptions o = options_with(100);
  o.form_factors.threads = o.direct_light.threads = 1;
  const RayCaster caster(scene, 1);
  const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
  int solve_concurrency = 0;
  const ProgressCallback progress = [&](std::string_view phase, std::size_t, std::size_t) {
    if (phase == "k x k solve") solve_concurrency = std::max(solve_concurrency, tbb::this_task_arena::max_concurrency());
  };
  build_sample_operator(scene, caster, rows, o, progress);
  EXPECT_EQ(solve_concurrency, 1);
}

// The goal rows' time is part of the build's phases (it was left at 0: `ilp bench` and
// the run log printed "goal rows 0.000 s" while the rows took most of the build).
TEST(SampleOperator, TheBuildsPhasesIncludeTheGoalRows) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = scene.patches_of({"desk_1", "desk_2", "floor"});
  const RayCaster caster(scene);
  const SampleOperatorOptions o = options_with(100);
  const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
  ASSERT_GT(rows.seconds, 0.0);
  const SampleOperator op = build_sample_operator(scene, caster, rows, o);
  EXPECT_EQ(op.stats.goal_seconds, rows.seconds);
  const SampleOperatorStats& st = op.stats;
  EXPECT_DOUBLE_EQ(st.build_seconds(),
                   st.goal_seconds + st.sample_row_seconds + st.direct_seconds + st.solve_seconds + st.response_seconds);
}

TEST(SampleError, ComparesAreaWeightedAndSkipsZeroReferences) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = {0, 1, 2};
  const double a0 = scene.patches[0].area_m2, a1 = scene.patches[1].area_m2;
  const Eigen::Vector3d reference(100, 200, 0), reference_direct(50, 100, 0);
  const Eigen::Vector3d total(110, 180, 5), direct(50, 100, 0);  // total off by +10 %, -10 %; patch 2 has no reference
  const IlluminanceError e = compare_illuminance(scene, goals, total, direct, reference, reference_direct);
  EXPECT_NEAR(e.rms_relative_total, 0.1, 1e-12);
  EXPECT_NEAR(e.max_relative_total, 0.1, 1e-12);
  // Indirect: 60 vs 50 (+20 %) and 80 vs 100 (-20 %).
  EXPECT_NEAR(e.max_relative_indirect, 0.2, 1e-12);
  EXPECT_NEAR(e.rms_relative_indirect, 0.2, 1e-12);
  const IlluminanceError skewed =
      compare_illuminance(scene, goals, Eigen::Vector3d(110, 200, 0), direct, reference, reference_direct);
  EXPECT_NEAR(skewed.rms_relative_total, 0.1 * std::sqrt(a0 / (a0 + a1)), 1e-12);
  const std::vector<int> two_goals = {0, 1};
  EXPECT_THROW(compare_illuminance(scene, two_goals, total, direct, reference, reference_direct), std::invalid_argument);
}

TEST(SampleError, PredictionScalesWithSampleSizeAndReachesZeroAtTheCensus) {
  ErrorPrediction p;
  p.pilot_size = 100;
  p.population = 1'000'000;
  p.rms_relative_spread_total = 0.08;
  EXPECT_NEAR(p.predicted_rms_error(100), 0.08, 1e-12);
  EXPECT_NEAR(p.predicted_rms_error(400), 0.04, 1e-4);  // 1/sqrt(k) while k << n
  EXPECT_EQ(p.predicted_rms_error(1'000'000), 0.0);
  for (double target : {0.05, 0.02, 0.005}) {
    const int k = p.recommended_sample_size(target);
    EXPECT_LE(p.predicted_rms_error(k), target);
    EXPECT_GT(p.predicted_rms_error(k - 1), target);
  }
  p.population = 500;  // the finite-population correction: the census is exact
  const int k = p.recommended_sample_size(1e-6);
  EXPECT_LE(k, 500);
  EXPECT_LE(p.predicted_rms_error(k), 1e-6);
  EXPECT_THROW(p.recommended_sample_size(0.0), std::invalid_argument);
}

// The spread of pilot samples predicts the error against the census within a factor 2.
TEST(SampleError, PilotSpreadPredictsTheMeasuredError) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = scene.patches_of({"desk_1", "desk_2", "floor"});
  const RayCaster caster(scene);
  SampleOperatorOptions o = options_with(1);
  const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
  const Eigen::VectorXd flux = source_flux_lm(scene, rows.sources);
  o.sample_size = static_cast<int>(scene.patches.size());
  const SampleOperator census = build_sample_operator(scene, caster, rows, o);
  const int pilot = 40, k = 160;
  const ErrorPrediction prediction = predict_sample_error(scene, caster, rows, flux, o, pilot, 6);
  EXPECT_GT(prediction.rms_relative_spread_total, 0.0);
  double measured = 0.0;
  for (std::uint64_t seed = 50; seed < 56; ++seed) {
    o.sample_size = k;
    o.sample_seed = seed;
    const SampleOperator op = build_sample_operator(scene, caster, rows, o);
    const double e = compare_illuminance(scene, goals, op.illuminance_lux(flux), op.direct_lux(flux),
                                         census.illuminance_lux(flux), census.direct_lux(flux))
                         .rms_relative_total;
    measured += e * e;
  }
  measured = std::sqrt(measured / 6);
  EXPECT_GT(prediction.predicted_rms_error(k), 0.5 * measured);
  EXPECT_LT(prediction.predicted_rms_error(k), 2.0 * measured);
  EXPECT_THROW(predict_sample_error(scene, caster, rows, flux, o, pilot, 1), std::invalid_argument);
}

}  // namespace
}  // namespace ilp
