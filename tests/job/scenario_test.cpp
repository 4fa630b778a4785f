// Scenarios (issue 38): other lighting states of the layout found, evaluated through the
// same operator columns and verified on the same verification rows as the layout's own
// state, in the one outcome assembly. Checked against linearity on those rows (an
// independent law: the exact solve is linear in the exitances) and against the layout's
// own verified direct light.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "job/config.h"
#include "job/group_runner.h"
#include "job/job_runner.h"
#include "job/plan.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

ScenarioSpec scenario(const std::string& name, LightCounted light, double fraction, std::vector<ScenarioLevel> levels,
                      std::vector<GoalSpec> goals) {
  ScenarioSpec s;
  s.name = name;
  s.light = light;
  s.fraction = fraction;
  s.levels = std::move(levels);
  s.goals = std::move(goals);
  return s;
}

double relative_gap(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-12, b.cwiseAbs().maxCoeff());
}

TEST(Scenarios, HalfTheOfficesLuminairesAt30PercentDirectLightOnlyAreVerifiedOnTheSameRows) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office.yaml");
  const std::vector<GoalSpec> min_goal{{"work_plane", GoalMetric::minimum, 1.0}};
  const std::vector<GoalSpec> average_goal{{"work_plane", GoalMetric::average, 100.0}};
  job.scenarios = {
      scenario("odd at 30 %", LightCounted::direct, 0.0, {{"", ScenarioPick::odd, 0.3}}, min_goal),
      scenario("even at 30 %", LightCounted::direct, 0.0, {{"", ScenarioPick::even, 0.3}}, min_goal),
      scenario("all at 30 %", LightCounted::direct, 0.3, {}, average_goal),
      scenario("all, total", LightCounted::total, 1.0, {}, average_goal),
  };
  const VariantPlan plan = plan_job(job).variants.front();
  ASSERT_EQ(plan.scenarios.size(), 4u);
  EXPECT_NEAR(plan.scenarios[2].goals[0].target, 100.0 / 0.8, 1e-12);  // initial = maintained / MF
  const PreparedJob prepared = prepare_job(scene_spec(job), plan);
  const JobOutcome outcome = solve_prepared(prepared, plan_job(job).goals);
  ASSERT_EQ(outcome.verification.method, "exact");
  ASSERT_EQ(outcome.scenarios.size(), 4u);
  ASSERT_EQ(outcome.verification.state_lux.size(), 4u);
  const std::size_t n = outcome.luminaires.size();
  ASSERT_GE(n, 2u);
  const ScenarioOutcome &odd = outcome.scenarios[0], &even = outcome.scenarios[1], &all = outcome.scenarios[2],
                        &total = outcome.scenarios[3];
  // L1, L3, ... and L2, L4, ...: every luminaire in exactly one half.
  EXPECT_EQ(odd.lit, (n + 1) / 2);
  EXPECT_EQ(even.lit, n / 2);
  for (std::size_t j = 0; j < n; ++j) {
    EXPECT_DOUBLE_EQ(odd.fractions[j] + even.fractions[j], 0.3);
    EXPECT_DOUBLE_EQ(odd.fractions[j], j % 2 == 0 ? 0.3 : 0.0);
  }
  double power_w = 0.0;
  for (const PlacedLuminaire& l : outcome.luminaires) power_w += l.power_w;
  EXPECT_NEAR(odd.power_w + even.power_w, 0.3 * power_w, 1e-9 * power_w);

  // Verified: the two halves add up to all at 30 % (the same rows, exitances linear), and
  // that is 0.3 of the layout's own verified direct light at the goal rows.
  EXPECT_LT(relative_gap(odd.verified_lux + even.verified_lux, all.verified_lux), 1e-9);
  const LightingModel& model = prepared.model;
  Eigen::VectorXd direct(model.goal_rows());
  const Verification& v = outcome.verification;
  for (std::size_t r = 0; r < model.goal_patches.size(); ++r) {
    const auto k = std::lower_bound(v.patches.begin(), v.patches.end(), model.goal_patches[r]) - v.patches.begin();
    direct[static_cast<Eigen::Index>(r)] = v.direct_lux[k];
  }
  direct.tail(v.point_direct_lux.size()) = v.point_direct_lux;
  EXPECT_LT(relative_gap(all.verified_lux, 0.3 * direct), 1e-9);
  // All at full output with every reflection: the layout's own state again (its decisive
  // points were gathered with more rays: within their error).
  const double own = outcome.goals[0].verified->value;  // work_plane average, initial
  ASSERT_EQ(outcome.goals[0].predicted.metric, GoalMetric::average);
  EXPECT_NEAR(total.goals[0].verified->value, own, 0.005 * own);

  // Predicted through the operator's direct columns: close to the verified direct light.
  EXPECT_NEAR(all.goals[0].predicted.value, all.goals[0].verified->value, 0.03 * all.goals[0].verified->value);
  EXPECT_NEAR(odd.goals[0].predicted.value, odd.goals[0].verified->value, 0.1 * odd.goals[0].verified->value);
  // Judged: minimum 1 lx met by either half, 100 lx maintained by all at 30 % as measured.
  EXPECT_TRUE(odd.all_met);
  EXPECT_TRUE(even.all_met);
  EXPECT_EQ(all.all_met, all.goals[0].verified->value >= 100.0 / 0.8 * (1 - 1e-9));
}

TEST(Scenarios, AScenarioTheLayoutMissesIsAGoalNotMetOfTheWholeJob) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office.yaml");
  job.scenarios = {scenario("dimmed to nothing", LightCounted::total, 0.0, {}, {{"work_plane", GoalMetric::average, 50.0}})};
  const JobOutcome outcome = solve_prepared(prepare_job(scene_spec(job), plan_job(job).variants.front()), plan_job(job).goals);
  ASSERT_EQ(outcome.scenarios.size(), 1u);
  EXPECT_FALSE(outcome.scenarios[0].all_met);
  EXPECT_EQ(outcome.scenarios[0].lit, 0u);
  EXPECT_NEAR(outcome.scenarios[0].goals[0].verified->value, 0.0, 1e-9);
  EXPECT_FALSE(outcome.all_met);
}

TEST(Scenarios, TheSectionIsReadWithItsTargetsAndBadEntriesNameTheirKey) {
  test::TempDir dir;
  const std::string office = test::read_file(ILP_SOURCE_DIR "/configs/office.yaml");
  auto with = [&](const std::string& section) {
    std::string text = office;
    const std::string data = std::string(ILP_SOURCE_DIR) + "/data/";
    for (std::size_t at = text.find("../data/"); at != std::string::npos; at = text.find("../data/", at))
      text.replace(at, 8, data);
    return dir.write("job.yaml", text + "\nscenarios:\n" + section);
  };
  const JobConfig job = load_job_config(with(
      "  - name: emergency\n    light: direct\n    fraction: 0\n    levels: [{select: even, fraction: 0.1}]\n"
      "    fixed_fraction: 0\n    goals: [{goal: work_plane, min_lux: 1, average_lux: 5}]\n"));
  ASSERT_EQ(job.scenarios.size(), 1u);
  const ScenarioSpec& s = job.scenarios[0];
  EXPECT_EQ(s.light, LightCounted::direct);
  EXPECT_EQ(s.fraction, 0.0);
  EXPECT_EQ(s.fixed_fraction, 0.0);
  ASSERT_EQ(s.levels.size(), 1u);
  EXPECT_EQ(s.levels[0].pick, ScenarioPick::even);
  EXPECT_EQ(s.levels[0].fraction, 0.1);
  ASSERT_EQ(s.goals.size(), 2u);
  auto error = [&](const std::string& section) {
    return test::error_of<ConfigError>([&] { (void)load_job_config(with(section)); });
  };
  auto says = [](const std::string& message, std::vector<std::string> parts) {
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << "\nlacks: " << part;
  };
  says(error("  - name: x\n    goals: [{goal: desks, min_lux: 1}]\n"),
       {"job.yaml:", "scenarios[0].goals[0].goal", "no goal of this name"});
  says(error("  - name: x\n    goals: [{goal: work_plane, ugr_max: 19}]\n"), {"UGR is judged for the normal lighting"});
  says(error("  - name: x\n    levels: [{group: A, fraction: 0.5}]\n    goals: [{goal: work_plane, min_lux: 1}]\n"),
       {"this job has none"});
  says(error("  - name: x\n    fraction: 1.5\n    goals: [{goal: work_plane, min_lux: 1}]\n"),
       {"scenarios[0].fraction", "[0, 1]"});
  says(error("  - name: x\n    light: reflected\n    goals: [{goal: work_plane, min_lux: 1}]\n"), {"must be total"});
  says(error("  - name: x\n    goals: [{goal: floor, cylindrical_lux: 50}]\n"), {"name a goal with a cylindrical metric"});
  // The office's work plane has its preset's Ez,m: a scenario may judge its cylinders too.
  EXPECT_EQ(load_job_config(with("  - name: x\n    goals: [{goal: work_plane, average_lux: 100, cylindrical_lux: 30}]\n"))
                .scenarios[0].goals.size(), 2u);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// Three luminaire groups (issue 38: any number): the shipped two-group office with a third
// group, a row on the west wall aimed across the room, searched together through GLPK's
// simplex and verified once with every group placed.
TEST(Groups, AJobOfThreeLuminaireGroupsRunsAndMeetsItsGoals) {
  std::string text = test::read_file(ILP_SOURCE_DIR "/configs/office_two_groups.yaml");
  for (std::size_t at; (at = text.find("../data/")) != std::string::npos;) text.replace(at, 8, ILP_SOURCE_DIR "/data/");
  const std::size_t grids = text.find("\ngrids:");
  ASSERT_NE(grids, std::string::npos);
  text.insert(grids, "\n    - name: west wash\n      products: [wall linear LED]\n"
                     "      on_wall: {surface: walls, height_m: 2.6, facing: +x}\n      floor_surface: floor\n"
                     "      mount_offset_m: 0.05\n      candidate_spacing_m: 0.25\n      layout: rows\n"
                     "      rows: {per_row: [1, 2]}\n      wall_distance_m: 0.3\n");
  const std::size_t verification = text.find("  rays_per_patch: 1024");
  if (verification != std::string::npos) text.replace(verification, 21, "  rays_per_patch: 256");
  test::TempDir dir;
  const JobConfig job = load_job_config(dir.write("three.yaml", text));
  ASSERT_EQ(job.groups.size(), 3u);
  const PreparedGroups groups = prepare_groups(plan_job(job), {}, {}, "", {});
  const VariantChoice choice = solve_groups(groups, plan_job(job).goals, {}, {});
  const JobOutcome& out = choice.outcome;
  ASSERT_EQ(out.groups.size(), 3u);
  EXPECT_EQ(out.groups[2].name, "west wash");
  EXPECT_EQ(out.groups[2].label_prefix, "C");
  std::size_t placed = 0;
  for (const OutcomeGroup& g : out.groups) {
    EXPECT_EQ(g.first, placed);
    placed += g.count;
  }
  EXPECT_EQ(placed, out.luminaires.size());
  EXPECT_NE(out.verification.method, "none");
  double power_w = 0.0;
  for (const OutcomeGroup& g : out.groups) power_w += g.power_w;
  EXPECT_NEAR(power_w, out.power_w, 1e-9 * out.power_w);
  for (const GoalOutcome& g : out.goals) EXPECT_TRUE(g.met) << g.predicted.name << " " << to_string(g.predicted.metric);
}

}  // namespace
}  // namespace ilp
