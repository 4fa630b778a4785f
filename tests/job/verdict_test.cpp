// The verdict: every constraint a line with target, value and met (job/constraint_check.h),
// and the margin the verification keeps above a scaled goal's target
// (job/verification_margin.h), checked with rays independent of the verification's.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "job/constraint_check.h"
#include "job/plan.h"
#include "job/job_runner.h"
#include "job/result_mapping.h"
#include "job/verification_margin.h"
#include "tests/optimizer/optimizer_test_scenes.h"
#include "tests/test_support.h"
#include "job/config.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

PlacedLuminaire at(double x, double y, double flux_lm = 1000.0) {
  PlacedLuminaire l;
  l.position_m = V(x, y, 2.4);
  l.flux_lm = flux_lm;
  return l;
}

SearchSpec two_panel_spec() {
  SearchSpec spec;
  spec.luminaire.type = LuminaireType::square_lambertian(0.3);
  spec.luminaire.flux_min_lm = 100.0;
  spec.luminaire.flux_max_lm = 2000.0;
  spec.layout.count_min = 1;
  spec.layout.count_max = 4;
  spec.layout.min_distance_m = 2.0;
  return spec;
}

const ConstraintOutcome* line_named(const std::vector<ConstraintOutcome>& lines, const std::string& name) {
  auto it = std::find_if(lines.begin(), lines.end(), [&](const ConstraintOutcome& c) { return c.name == name; });
  return it == lines.end() ? nullptr : &*it;
}

const Eigen::AlignedBox2d kRoom(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(4.0, 4.0));

// Issue 20: two luminaires 1.965 m apart under min_distance_m: 2.0, every goal met,
// exited 2 with "NOT MET" and no line saying why. The distance is now a line.
TEST(ConstraintLines, TwoLuminaires1965ApartMissMinDistanceByTheGap) {
  const std::vector<ConstraintOutcome> lines = check_constraints(two_panel_spec(), kRoom, 0.0, {at(1.0, 2.0), at(2.965, 2.0)});
  const ConstraintOutcome* d = line_named(lines, "min_distance_m");
  ASSERT_NE(d, nullptr);
  EXPECT_FALSE(d->met);
  EXPECT_NEAR(d->value, 1.965, 1e-12);
  EXPECT_EQ(d->target, 2.0);
  EXPECT_EQ(d->unit, "m");
  // The line as the report names it.
  JobOutcome outcome;
  outcome.constraints = lines;
  const VerdictLines verdict = verdict_lines(JobGoals{}, outcome);
  EXPECT_FALSE(verdict.all_met());
  const auto it = std::find_if(verdict.constraints.begin(), verdict.constraints.end(),
                               [](const VerdictLine& l) { return l.name == "min_distance_m"; });
  ASSERT_NE(it, verdict.constraints.end());
  EXPECT_EQ(it->kind, "constraint");
  EXPECT_EQ(failing_line_text(*it), "min_distance_m 1.965 m < 2.000 m (by 0.035 m)");
  // 2.0 m apart, and 2.0 less the search's own round-off, are met.
  EXPECT_TRUE(line_named(check_constraints(two_panel_spec(), kRoom, 0.0, {at(1.0, 2.0), at(3.0, 2.0)}), "min_distance_m")->met);
  EXPECT_TRUE(line_named(check_constraints(two_panel_spec(), kRoom, 0.0, {at(1.0, 2.0), at(2.99985, 2.0)}), "min_distance_m")->met);
  EXPECT_FALSE(line_named(check_constraints(two_panel_spec(), kRoom, 0.0, {at(1.0, 2.0), at(2.999, 2.0)}), "min_distance_m")->met);
}

TEST(ConstraintLines, CountOverlapWallDistanceAndFluxAreJudgedOnTheLayout) {
  SearchSpec spec = two_panel_spec();
  spec.layout.min_distance_m = 0.0;
  // Outlines 0.3 m wide, centres 0.2 m apart along x: a third of one overlaps.
  const std::vector<ConstraintOutcome> lines = check_constraints(spec, kRoom, 0.5, {at(0.5, 2.0, 50.0), at(0.7, 2.0, 50.0)});
  EXPECT_EQ(line_named(lines, "min_distance_m"), nullptr) << "no line for a constraint the job does not state";
  const ConstraintOutcome* count = line_named(lines, "count");
  ASSERT_NE(count, nullptr);
  EXPECT_TRUE(count->met);
  EXPECT_EQ(count->value, 2.0);
  EXPECT_EQ(count->target_max, 4.0);
  const ConstraintOutcome* overlap = line_named(lines, "outline_overlap");
  ASSERT_NE(overlap, nullptr);
  EXPECT_NEAR(overlap->value, 1.0 / 3.0, 1e-12);
  EXPECT_FALSE(overlap->met);
  // The left outline's edge is at 0.35 m from the wall at x = 0: 0.15 m short of 0.5 m.
  const ConstraintOutcome* wall = line_named(lines, "wall_distance_m");
  ASSERT_NE(wall, nullptr);
  EXPECT_NEAR(wall->value, 0.35, 1e-12);
  EXPECT_FALSE(wall->met);
  // 50 lm each, below the 100 lm the range allows.
  const ConstraintOutcome* flux = line_named(lines, "flux_lm");
  ASSERT_NE(flux, nullptr);
  EXPECT_EQ(flux->rule, ConstraintRule::within);
  EXPECT_FALSE(flux->met);
  // Five luminaires where at most four may be.
  std::vector<PlacedLuminaire> five;
  for (int k = 0; k < 5; ++k) five.push_back(at(0.5 + 0.7 * k, 2.0));
  EXPECT_FALSE(line_named(check_constraints(spec, kRoom, 0.0, five), "count")->met);
  // Individual outputs: the lowest and the highest flux each get a line.
  spec.luminaire.uniform_output = false;
  const std::vector<ConstraintOutcome> own = check_constraints(spec, kRoom, 0.0, {at(1.0, 1.0, 150.0), at(3.0, 3.0, 2500.0)});
  ASSERT_EQ(std::count_if(own.begin(), own.end(), [](const ConstraintOutcome& c) { return c.name == "flux_lm"; }), 2);
  for (const ConstraintOutcome& c : own)
    if (c.name == "flux_lm") {
      EXPECT_EQ(c.met, c.rule == ConstraintRule::at_least) << c.what;
    }
}

TEST(ConstraintLines, TheRuleHoldsUpToItsRelativeTolerance) {
  EXPECT_TRUE(constraint_met(ConstraintRule::at_least, 2.0, 0.0, 1.9999, 1e-4));
  EXPECT_FALSE(constraint_met(ConstraintRule::at_least, 2.0, 0.0, 1.9997, 1e-4));
  EXPECT_TRUE(constraint_met(ConstraintRule::at_most, 0.0, 0.0, 5e-5, 1e-4)) << "absolute at a target of 0";
  EXPECT_FALSE(constraint_met(ConstraintRule::at_most, 0.0, 0.0, 2e-4, 1e-4));
  EXPECT_TRUE(constraint_met(ConstraintRule::within, 8.0, 8.0, 8.0, 1e-4));
  EXPECT_FALSE(constraint_met(ConstraintRule::within, 8.0, 8.0, 9.0, 1e-4));
  EXPECT_FALSE(constraint_met(ConstraintRule::within, 8.0, 12.0, 7.0, 1e-4));
}

// A room lit through a grid (whose points carry the gather's error estimate) and a mat
// (a patch goal: the floor alone), verified exactly.
std::string margin_job(const test::TempDir& dir, double margin) {
  dir.write("room.obj", test::room_obj({{"mat", {1.3, 1.7}, 0.8}}));
  const std::string luminaires =
      "  size_m: 0.3\n  flux_lm: [10, 20000]\n  efficacy_lm_per_w: 100\n  mounting_surface: ceiling\n"
      "  candidate_spacing_m: 0.5\n  count: [1, 4]\n";
  const std::string goals =
      "  - grid: plane\n    average_lux: 300\n    min_lux: 150\n"
      "  - surface: mat\n    average_lux: 250\n";
  const std::string rest = "grids:\n  - name: plane\n    over_surface: floor\n    height_m: 0.8\n    spacing_m: 0.5\n"
                           "optimizer:\n  max_evaluations: 600\n  local_max_evaluations: 300\n";
  std::string text = test::room_job("0.5", luminaires, goals, rest);
  const std::string verification = "verification:\n  rays_per_patch: 256\n";
  text.replace(text.find(verification), verification.size(),
               verification + "  method: exact\n  margin: " + std::to_string(margin) + "\n");
  return dir.write("job.yaml", text);
}

TEST(VerificationMargin, TheBindingGoalIsKeptAboveItsTargetAndStaysMetWithOtherRays) {
  test::TempDir dir;
  const JobConfig job = load_job_config(margin_job(dir, 0.01));
  EXPECT_EQ(job.verification.margin, 0.01);
  PreparedJob prepared = test::prepare(job);
  const JobOutcome outcome = solve_prepared(prepared, plan_job(job).goals);
  ASSERT_TRUE(outcome.all_met);
  ASSERT_EQ(outcome.goals.size(), 3u);
  // Every average and minimum goal is scaled to: at least target x (1 + margin), and
  // the binding one exactly (the flux range is wide enough).
  double binding = 0.0;
  for (const GoalOutcome& g : outcome.goals) {
    ASSERT_TRUE(g.verified);
    EXPECT_GE(g.margin, 0.01) << g.predicted.name;
    EXPECT_GE(g.verified->value, g.verified->target * (1.0 + g.margin) * (1.0 - 1e-9)) << g.predicted.name;
    binding = std::max(binding, g.verified->target * (1.0 + g.margin) / g.verified->value);
  }
  EXPECT_NEAR(binding, 1.0, 1e-9);
  // The grid's goals carry the verification's own error estimate, the mat's none.
  ASSERT_TRUE(outcome.goals[0].relative_error && outcome.goals[1].relative_error);
  EXPECT_GT(*outcome.goals[1].relative_error, 0.0);
  EXPECT_LT(*outcome.goals[1].relative_error, 0.05);
  EXPECT_GE(outcome.goals[1].margin, 2.0 * *outcome.goals[1].relative_error - 1e-15);
  EXPECT_FALSE(outcome.goals[2].relative_error);
  EXPECT_EQ(outcome.goals[2].margin, 0.01) << "no estimate: the floor";
  // Independent check: the layout solved again with other rays still meets every goal.
  prepared.plan.verification.exact.form_factors.seed += 1009;  // the verification's rays
  prepared.plan.verification.sample.form_factors.seed += 1009;
  const Verification other = verify_layout(prepared, outcome.luminaires);
  SearchSpec real = prepared.plan.search;
  real.goals = search_at(prepared.plan, plan_job(job).goals).goals;
  const std::vector<GoalJudgement> judged = judge_goals(prepared.model, real, verified_goal_lux(prepared.model, other));
  for (std::size_t g = 0; g < judged.size(); ++g) {
    EXPECT_NE(judged[g].value, outcome.goals[g].verified->value) << "other rays, another value";
    EXPECT_GE(judged[g].value, judged[g].target) << judged[g].name << " " << to_string(judged[g].metric);
  }
}

// With no floor the margin is the error estimate alone: 2 standard errors on the grid's
// goals, none on the mat's (no estimate), and the binding goal sits exactly there.
TEST(VerificationMargin, WithoutAFloorTheMarginIsTheErrorEstimateAlone) {
  test::TempDir dir;
  const JobConfig job = load_job_config(margin_job(dir, 0.0));
  const JobOutcome outcome = solve_prepared(test::prepare(job), plan_job(job).goals);
  double binding = 0.0;
  for (const GoalOutcome& g : outcome.goals) {
    EXPECT_EQ(g.margin, kMarginStandardErrors * g.relative_error.value_or(0.0)) << g.predicted.name;
    binding = std::max(binding, g.verified->target * (1.0 + g.margin) / g.verified->value);
  }
  EXPECT_NEAR(binding, 1.0, 1e-9);
  EXPECT_EQ(outcome.goals[2].margin, 0.0);
}

// The points deciding a grid's minimum (and so its U0) or maximum, for the verification's
// second look: those within the band of the lowest or highest, or within 3 of their own
// standard errors of it; none for an average, none over patches (no points).
TEST(DecisivePoints, ThePointsNearTheLowestOrHighestOfAGridGoal) {
  LightingModel model;
  model.goal_patches = {10};
  model.goal_points.resize(5);
  GoalArea desk;
  desk.name = "desk";
  desk.grid = 0;
  desk.rows = {1, 2, 3, 4, 5};
  desk.area_weights = Eigen::VectorXd::Constant(5, 0.2);
  GoalArea mat;
  mat.name = "mat";
  mat.rows = {0};
  mat.area_weights = Eigen::VectorXd::Ones(1);
  model.areas = {desk, mat};
  Eigen::VectorXd lux(6);
  lux << 50.0, 100.0, 104.0, 106.0, 300.0, 290.0;  // the mat's patch, then the desk's points 0 to 4
  const Eigen::VectorXd none;
  auto decisive = [&](GoalMetric metric, const std::string& name, const Eigen::VectorXd& errors) {
    return decisive_points(model, {GoalSpec{name, metric, 1.0}}, lux, errors, 0.05, 3.0);
  };
  EXPECT_EQ(decisive(GoalMetric::uniformity, "desk", none), (std::vector<int>{0, 1})) << "100 and 104 of <= 105";
  EXPECT_EQ(decisive(GoalMetric::minimum, "desk", none), (std::vector<int>{0, 1}));
  Eigen::VectorXd errors(5);
  errors << 1.0, 1.0, 0.4, 1.0, 1.0;
  EXPECT_EQ(decisive(GoalMetric::minimum, "desk", errors), (std::vector<int>{0, 1, 2}))
      << "106 - 3 x 0.4 = 104.8: within the band";
  errors[2] = 0.3;
  EXPECT_EQ(decisive(GoalMetric::minimum, "desk", errors), (std::vector<int>{0, 1})) << "106 - 0.9 > 105";
  errors[2] = 0.4;
  EXPECT_EQ(decisive(GoalMetric::maximum, "desk", none), (std::vector<int>{3, 4})) << "300 and 290 of >= 285";
  EXPECT_TRUE(decisive(GoalMetric::average, "desk", none).empty());
  EXPECT_TRUE(decisive(GoalMetric::minimum, "mat", none).empty()) << "patches: no points";
  EXPECT_TRUE(decisive(GoalMetric::minimum, "stairs", none).empty()) << "no such area";
  const std::vector<int> both = decisive_points(
      model, {GoalSpec{"desk", GoalMetric::uniformity, 0.6}, GoalSpec{"desk", GoalMetric::maximum, 500.0}}, lux, none,
      0.05, 3.0);
  EXPECT_EQ(both, (std::vector<int>{0, 1, 3, 4})) << "ascending, each once";
}

// The margin column says what was kept, not what was asked: a flux correction held back
// by a UGR limit (or the flux range) leaves a lower bound less above its target than it
// asked, and the line printed what it asked. search_and_verify now reports kept_margin.
TEST(VerificationMargin, TheMarginReportedIsWhatTheVerifiedValueKeeps) {
  EXPECT_DOUBLE_EQ(kept_margin(0.005, 503.0, 500.0), 0.005) << "more than asked: the asked margin";
  EXPECT_NEAR(kept_margin(0.005, 501.0, 500.0), 0.002, 1e-12) << "held back: what the value keeps";
  EXPECT_DOUBLE_EQ(kept_margin(0.005, 495.0, 500.0), 0.0) << "below the target: none (the line is missed)";
  EXPECT_DOUBLE_EQ(kept_margin(0.0, 510.0, 500.0), 0.0) << "a goal without a margin keeps none";
}

TEST(VerificationMargin, TheFloorIsCheckedAsAKey) {
  test::TempDir dir;
  const std::string path = margin_job(dir, 0.5);
  try {
    load_job_config(path);
    FAIL() << "a margin of 50 % is refused";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path), std::string::npos) << what;
    EXPECT_NE(what.find("verification.margin"), std::string::npos) << what;
    EXPECT_NE(what.find("[0, 0.2]"), std::string::npos) << what;
  }
}

// The power density's area: a rectangle grid over no floor surface gave the mounting
// surface's plan area (38 W/m² "over 56.74 m²" for a 116 m² nave grid); it is the
// grid's own area now, named, unless the job names its floor.
std::string rectangle_grid_job(const test::TempDir& dir, const std::string& floor_surface) {
  dir.write("room.obj", test::room_obj({}));
  const std::string luminaires =
      "  size_m: 0.3\n  flux_lm: [10, 20000]\n  efficacy_lm_per_w: 100\n  mounting_surface: ceiling\n"
      "  candidate_spacing_m: 0.5\n  count: 1\n" + floor_surface;
  const std::string rest = "grids:\n  - name: task\n    rectangle_m: [[0.5, 0.5], [2.5, 3.5]]\n    height_m: 0.8\n"
                           "    border_m: 0\n    spacing_m: 0.5\n"
                           "optimizer:\n  max_evaluations: 200\n  local_max_evaluations: 100\n";
  return dir.write("job.yaml", test::room_job("0.4", luminaires, "  - grid: task\n    average_lux: 100\n", rest));
}

TEST(PowerDensity, ARectangleGridOverNoFloorGivesItsOwnAreaNamed) {
  test::TempDir dir;
  const JobConfig job = load_job_config(rectangle_grid_job(dir, ""));
  const PreparedJob prepared = test::prepare(job);
  const JobOutcome outcome = solve_prepared(prepared, plan_job(job).goals);
  ASSERT_EQ(prepared.model.grids.size(), 1u);
  EXPECT_NEAR(prepared.model.grids[0].area_m2, 6.0, 1e-9) << "2 x 3 m in 0.5 m cells";
  EXPECT_NEAR(outcome.mounting_area_m2, 16.0, 1e-9);
  EXPECT_NEAR(outcome.floor_area_m2, 6.0, 1e-9);
  EXPECT_EQ(outcome.floor_area_source, "area of grid 'task' (no floor surface known)");
  EXPECT_NEAR(outcome.power_density_w_per_m2, outcome.power_w / 6.0, 1e-12);
}

TEST(PowerDensity, TheFloorTheJobNamesIsTheArea) {
  test::TempDir dir;
  const JobConfig job = load_job_config(rectangle_grid_job(dir, "  floor_surface: floor\n"));
  const JobOutcome outcome = solve_prepared(test::prepare(job), plan_job(job).goals);
  EXPECT_NEAR(outcome.floor_area_m2, 16.0, 1e-9);
  EXPECT_EQ(outcome.floor_area_source, "floor 'floor' (luminaires.floor_surface)");
}

// The immediate surrounding area as a goal the search honours: a 1 x 1 m task area at
// 500 lx under one panel; its band (1 m wide, 450 lx, U0 0.40) needs the light spread
// wider, so the layout found without it does not do and more power is drawn with it.
std::string task_job(const test::TempDir& dir, const std::string& surrounding, const std::string& constraints = "") {
  dir.write("room.obj", test::room_obj({}));
  const std::string luminaires =
      "  size_m: 0.3\n  flux_lm: [10, 20000]\n  efficacy_lm_per_w: 100\n  mounting_surface: ceiling\n"
      "  candidate_spacing_m: 0.5\n  count: [1, 4]\n";
  const std::string rest = "grids:\n  - name: task\n    rectangle_m: [[1.5, 1.5], [2.5, 2.5]]\n    height_m: 0.8\n"
                           "    border_m: 0\n    spacing_m: 0.25\n"
                           "optimizer:\n  max_evaluations: 600\n  local_max_evaluations: 300\n" + constraints;
  return dir.write("job.yaml", test::room_job("0.4", luminaires, "  - grid: task\n    average_lux: 500\n" + surrounding, rest));
}

TEST(Surrounding, TheBandsGoalBindsAndTheSearchMeetsIt) {
  test::TempDir dir;
  const JobConfig plain = load_job_config(task_job(dir, ""));
  const JobOutcome without = solve_prepared(test::prepare(plain), plan_job(plain).goals);
  ASSERT_TRUE(without.all_met);
  const JobConfig banded = load_job_config(task_job(dir, "    surrounding: {width_m: 1.0, average_lux: 450}\n"));
  ASSERT_EQ(banded.goals.size(), 3u);
  const PreparedJob prepared = test::prepare(banded);
  const JobOutcome with = solve_prepared(prepared, plan_job(banded).goals);
  // The band's points: the 3 x 3 m grown square less the task, in cells of 1/3 m (p(3 m) = 0.431 m).
  ASSERT_EQ(prepared.model.grids.size(), 2u);
  EXPECT_EQ(prepared.model.grids[1].name, "task_surrounding");
  EXPECT_EQ(prepared.model.grids[1].points.size(), 81u - 9u);
  ASSERT_EQ(with.goals.size(), 3u);
  for (const GoalOutcome& g : with.goals) EXPECT_TRUE(g.met) << g.predicted.name << " " << to_string(g.predicted.metric);
  EXPECT_TRUE(with.all_met);
  ASSERT_TRUE(with.goals[1].verified.has_value());
  EXPECT_GE(with.goals[1].verified->value, 450.0) << "the band's Em as verified (initial = maintained, MF 1)";
  EXPECT_GT(with.power_w, 1.05 * without.power_w) << "the band binds: " << with.power_w << " W against " << without.power_w;
}

// The power-density cap: a cap on the layout's power (cap x the area the power density is
// taken over) that the search honours, judged as a line of its own.
TEST(PowerDensityCap, ALayoutOverTheCapIsInfeasibleAndItsLineSaysByHowMuch) {
  test::TempDir dir;
  const JobConfig plain = load_job_config(task_job(dir, ""));
  const PreparedJob prepared = test::prepare(plain);
  const JobOutcome unlimited = solve_prepared(prepared, plan_job(plain).goals);
  ASSERT_TRUE(unlimited.all_met);
  EXPECT_EQ(unlimited.floor_area_source, "area of grid 'task' (no floor surface known)");
  const double density = unlimited.power_density_w_per_m2;
  // Half the density the goals need: every goal still met, the cap's line missed.
  JobConfig capped = plain;
  capped.constraints.max_power_density_w_per_m2 = 0.5 * density;
  const JobOutcome over = solve_prepared(prepared, plan_job(capped).goals);
  EXPECT_FALSE(over.all_met);
  EXPECT_FALSE(over.feasible);
  const auto line = std::find_if(over.constraints.begin(), over.constraints.end(),
                                 [](const ConstraintOutcome& c) { return c.name == "max_power_density_w_per_m2"; });
  ASSERT_NE(line, over.constraints.end());
  EXPECT_FALSE(line->met);
  EXPECT_EQ(line->unit, "W/m²");
  EXPECT_NEAR(line->value, over.power_w / over.floor_area_m2, 1e-12);
  EXPECT_EQ(line->what, "power density over the area of grid 'task' (no floor surface known)");
  for (const ConstraintOutcome& c : over.constraints) EXPECT_EQ(c.met, c.name != "max_power_density_w_per_m2") << c.name;
  for (const GoalOutcome& g : over.goals) EXPECT_TRUE(g.met);
  // Above what the layout draws: met, and the same layout.
  capped.constraints.max_power_density_w_per_m2 = 2.0 * density;
  const JobOutcome under = solve_prepared(prepared, plan_job(capped).goals);
  EXPECT_TRUE(under.all_met);
  EXPECT_NEAR(under.power_w, unlimited.power_w, 1e-9 * unlimited.power_w);
  // The search: a layout above the cap is infeasible; closest_to_target holds the scale to it.
  SearchSpec spec = prepared.plan.search;
  spec.goals = search_at(prepared.plan, plan_job(plain).goals).goals;  // MF 1
  spec.layout.max_power_w = 0.5 * unlimited.power_w;
  const std::vector<Eigen::Vector2d> xy{Eigen::Vector2d(2.0, 2.0)};
  const LayoutEvaluation capped_eval = evaluate_layout(prepared.model, spec, xy, {1.0});
  EXPECT_FALSE(capped_eval.feasible);
  EXPECT_GT(capped_eval.power_w, spec.layout.max_power_w);
  spec.objective = Objective::closest_to_target;
  const LayoutEvaluation fit = evaluate_layout(prepared.model, spec, xy, {1.0});
  EXPECT_LE(fit.power_w, spec.layout.max_power_w * (1.0 + 1e-12));
}

}  // namespace
}  // namespace ilp
