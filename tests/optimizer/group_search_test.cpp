// The joint output solve of two luminaire groups (optimizer/group_search.h) against a
// brute-force search over a fine grid of the two groups' fluxes, on small synthetic
// models whose goal rows the test writes itself (no scene).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "optimizer/group_search.h"

namespace ilp {
namespace {

// A model of `rows` goal rows and two goal areas: "task" (rows 0 .. 5, equal weights)
// and "edge" (rows 6 .. 7), with a small fixed light.
LightingModel synthetic_model() {
  LightingModel m;
  m.goal_points.resize(8);
  m.fixed_lux = Eigen::VectorXd::Constant(8, 20.0);
  m.fixed_direct_lux = m.fixed_lux;
  GoalArea task;
  task.name = "task";
  for (Eigen::Index r = 0; r < 6; ++r) task.rows.push_back(r);
  task.area_weights = Eigen::VectorXd::Constant(6, 1.0 / 6.0);
  GoalArea edge;
  edge.name = "edge";
  edge.rows = {6, 7};
  edge.area_weights = Eigen::VectorXd::Constant(2, 0.5);
  m.areas = {task, edge};
  return m;
}

ArrangementLight random_light(std::mt19937& rng, int luminaires, double scale) {
  std::uniform_real_distribution<double> u(0.05, 1.0);
  ArrangementLight a;
  a.label = std::to_string(luminaires) + " luminaires";
  a.luminaires.resize(static_cast<std::size_t>(luminaires));
  a.lux_per_lm.resize(8);
  for (Eigen::Index r = 0; r < 8; ++r) a.lux_per_lm[r] = scale * luminaires * u(rng);
  return a;
}

const std::vector<GoalSpec> kGoals = {
    {"task", GoalMetric::average, 500.0},
    {"task", GoalMetric::uniformity, 0.6},
    {"task", GoalMetric::maximum, 1400.0},
    {"edge", GoalMetric::minimum, 150.0},
};

// The goals judged by the test's own arithmetic, not the library's.
bool meets_goals(const LightingModel& m, const ArrangementLight& a, const ArrangementLight& b, double s0, double s1) {
  const Eigen::VectorXd e = m.fixed_lux + s0 * a.lux_per_lm + s1 * b.lux_per_lm;
  const Eigen::VectorXd task = e.head(6);
  const double mean = task.mean();
  return mean >= 500.0 * (1 - 1e-9) && task.minCoeff() >= 0.6 * mean * (1 - 1e-9) && task.maxCoeff() <= 1400.0 * (1 + 1e-9) &&
         e.tail(2).minCoeff() >= 150.0 * (1 - 1e-9);
}

struct Brute {
  bool found = false;
  double power_w = 0.0;
};

// Least power over an (n + 1) x (n + 1) grid of the two fluxes.
Brute brute_force(const LightingModel& m, const GroupOption& a, const GroupOption& b, int n) {
  Brute out;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double s0 = a.flux_min_lm + (a.flux_max_lm - a.flux_min_lm) * i / n;
      const double s1 = b.flux_min_lm + (b.flux_max_lm - b.flux_min_lm) * j / n;
      if (!meets_goals(m, *a.light, *b.light, s0, s1)) continue;
      const double p = s0 * a.count() / a.efficacy_lm_per_w + s1 * b.count() / b.efficacy_lm_per_w;
      if (!out.found || p < out.power_w) out = {true, p};
    }
  return out;
}

TEST(GroupSearch, TwoGroupOutputsMatchABruteForceGridOverBothFluxes) {
  const LightingModel m = synthetic_model();
  std::mt19937 rng(7);
  int compared = 0, infeasible = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const ArrangementLight la = random_light(rng, 4, 0.1), lb = random_light(rng, 3, 0.1);
    const GroupOption a{0, &la, 300.0, 3000.0, 100.0}, b{0, &lb, 600.0, 2000.0, 120.0};
    const GroupSearchResult joint = search_groups(m, {kGoals}, {{"A", {a}}, {"B", {b}}});
    constexpr int kCells = 600;
    const Brute brute = brute_force(m, a, b, kCells);
    if (!brute.found) {
      ++infeasible;
      // The grid may miss a thin feasible sliver; the solve may not invent one.
      if (joint.feasible) {
        EXPECT_TRUE(meets_goals(m, la, lb, joint.groups[0].flux_lm, joint.groups[1].flux_lm));
      }
      continue;
    }
    ++compared;
    ASSERT_TRUE(joint.feasible) << "trial " << trial;
    const double s0 = joint.groups[0].flux_lm, s1 = joint.groups[1].flux_lm;
    EXPECT_TRUE(meets_goals(m, la, lb, s0, s1)) << "trial " << trial;
    // The exact optimum is no worse than any grid point, and within a grid cell of the best one.
    const double cell_w = (2700.0 / kCells) * 4 / 100.0 + (1400.0 / kCells) * 3 / 120.0;
    EXPECT_LE(joint.power_w, brute.power_w + 1e-6) << "trial " << trial;
    EXPECT_GE(joint.power_w, brute.power_w - cell_w) << "trial " << trial;
    EXPECT_NEAR(joint.power_w, s0 * 4 / 100.0 + s1 * 3 / 120.0, 1e-9);
  }
  EXPECT_GE(compared, 10);  // the random cases exercise both outcomes
  EXPECT_GE(compared + infeasible, 40);
}

TEST(GroupSearch, ThePairChosenIsTheLeastPowerOverEveryPairAndPruningSkipsNone) {
  const LightingModel m = synthetic_model();
  std::mt19937 rng(11);
  std::vector<ArrangementLight> lights_a, lights_b;
  for (int n = 1; n <= 5; ++n) lights_a.push_back(random_light(rng, n, 0.08));
  for (int n = 1; n <= 4; ++n) lights_b.push_back(random_light(rng, n, 0.08));
  GroupChoices a{"A", {}}, b{"B", {}};
  for (const ArrangementLight& l : lights_a) a.options.push_back({0, &l, 300.0, 3000.0, 100.0});
  for (const ArrangementLight& l : lights_b) b.options.push_back({0, &l, 600.0, 2000.0, 120.0});
  const GroupSearchResult joint = search_groups(m, {kGoals}, {a, b});
  double best_w = std::numeric_limits<double>::infinity();
  for (const GroupOption& x : a.options)
    for (const GroupOption& y : b.options) {
      const GroupSearchResult one = search_groups(m, {kGoals}, {{"A", {x}}, {"B", {y}}});
      if (one.feasible) best_w = std::min(best_w, one.power_w);
    }
  ASSERT_TRUE(std::isfinite(best_w));
  ASSERT_TRUE(joint.feasible);
  EXPECT_NEAR(joint.power_w, best_w, 1e-9);
  EXPECT_EQ(joint.pairs, 20);
  EXPECT_EQ(joint.solved + joint.pruned, 20);
  EXPECT_GT(joint.pruned, 0);  // the bound leaves some pairs out
}

TEST(GroupSearch, TheLinearProgrammeIsExactOnAKnownTriangle) {
  // s0 + s1 >= 10, s0 - s1 >= -4, in [0, 20]^2, cost (1, 3): the optimum is (10, 0).
  const std::vector<OutputConstraint> c{{{1.0, 1.0}, 10.0}, {{1.0, -1.0}, -4.0}};
  const auto s = least_cost_outputs(c, {0.0, 0.0}, {20.0, 20.0}, {1.0, 3.0});
  ASSERT_TRUE(s);
  EXPECT_NEAR(s->x(), 10.0, 1e-9);
  EXPECT_NEAR(s->y(), 0.0, 1e-9);
  // cost (3, 1): the vertex (3, 7) where both bind.
  const auto t = least_cost_outputs(c, {0.0, 0.0}, {20.0, 20.0}, {3.0, 1.0});
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->x(), 3.0, 1e-9);
  EXPECT_NEAR(t->y(), 7.0, 1e-9);
  // Nothing left: s0 + s1 >= 50 in [0, 20]^2.
  EXPECT_FALSE(least_cost_outputs({{{1.0, 1.0}, 50.0}}, {0.0, 0.0}, {20.0, 20.0}, {1.0, 1.0}));
}

// Two groups on one ceiling: an arrangement of B whose luminaire lies on one of A's is
// never chosen, however cheap; one beside it (outlines touching) may be.
TEST(GroupSearch, PairsWhoseLuminairesShareAPlaceAreLeftOut) {
  const LightingModel m = synthetic_model();
  std::mt19937 rng(5);
  ArrangementLight la = random_light(rng, 1, 0.5), on = random_light(rng, 1, 0.5), beside = on;
  la.luminaires[0].position_m = {2.0, 2.0, 2.9};
  on.luminaires[0].position_m = {2.3, 2.0, 2.9};       // 0.3 m apart, outlines 1.2 x 0.1 m: overlapping
  beside.luminaires[0].position_m = {2.0, 2.1, 2.9};   // 0.1 m apart across: touching
  ArrangementLight below = on;
  below.luminaires[0].position_m.z() = 2.5;            // under it, 0.4 m lower: no collision
  const Eigen::Vector2d extent{1.2, 0.1};
  const GroupOption a{0, &la, 300.0, 3000.0, 100.0, extent};
  EXPECT_TRUE(groups_collide(a, {0, &on, 300.0, 3000.0, 100.0, extent}));
  EXPECT_FALSE(groups_collide(a, {0, &beside, 300.0, 3000.0, 100.0, extent}));
  EXPECT_FALSE(groups_collide(a, {0, &below, 300.0, 3000.0, 100.0, extent}));
  const GroupSearchResult r = search_groups(m, {{{"task", GoalMetric::average, 100.0}}},
                                            {{"A", {a}}, {"B", {{0, &on, 300.0, 3000.0, 100.0, extent}}}});
  EXPECT_EQ(r.colliding, 1);
  EXPECT_EQ(r.solved, 0);
  EXPECT_FALSE(r.feasible);
}

// Up to kMaxSearchedGroups groups are searched (issue 38); one more is refused, as are
// three or more groups whose product of arrangement counts is over kMaxGroupCombinations.
TEST(GroupSearch, MoreThanTheMostGroupsAreRefused) {
  const LightingModel m = synthetic_model();
  std::mt19937 rng(3);
  const ArrangementLight l = random_light(rng, 2, 0.1);
  const GroupChoices g{"A", {{0, &l, 100.0, 1000.0, 100.0}}};
  EXPECT_NO_THROW(search_groups(m, {kGoals}, {g, g, g}));
  EXPECT_THROW(search_groups(m, {kGoals}, std::vector<GroupChoices>(kMaxSearchedGroups + 1, g)), std::invalid_argument);
  // Three groups of 200 arrangements: 8,000,000 combinations, refused before any is solved
  // (two groups keep every pair, as before).
  GroupChoices many{"B", std::vector<GroupOption>(200, {0, &l, 100.0, 1000.0, 100.0})};
  EXPECT_THROW(search_groups(m, {kGoals}, {many, many, many}), std::invalid_argument);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// Three groups: the joint solve (GLPK's simplex beyond two) against a brute-force grid
// over all three fluxes, judged by the test's own arithmetic.
TEST(GroupSearch, ThreeGroupOutputsMatchABruteForceGridOverEveryFlux) {
  const LightingModel m = synthetic_model();
  std::mt19937 rng(23);
  int compared = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const ArrangementLight la = random_light(rng, 4, 0.06), lb = random_light(rng, 3, 0.06), lc = random_light(rng, 2, 0.06);
    const GroupOption a{0, &la, 300.0, 3000.0, 100.0}, b{0, &lb, 600.0, 2000.0, 120.0}, c{0, &lc, 200.0, 2500.0, 90.0};
    const GroupSearchResult joint = search_groups(m, {kGoals}, {{"A", {a}}, {"B", {b}}, {"C", {c}}});
    constexpr int kCells = 80;
    bool found = false;
    double best_w = 0.0;
    for (int i = 0; i <= kCells; ++i)
      for (int j = 0; j <= kCells; ++j)
        for (int l = 0; l <= kCells; ++l) {
          const double s0 = 300.0 + 2700.0 * i / kCells, s1 = 600.0 + 1400.0 * j / kCells, s2 = 200.0 + 2300.0 * l / kCells;
          const Eigen::VectorXd e = m.fixed_lux + s0 * la.lux_per_lm + s1 * lb.lux_per_lm + s2 * lc.lux_per_lm;
          const Eigen::VectorXd task = e.head(6);
          const double mean = task.mean();
          if (!(mean >= 500.0 * (1 - 1e-9) && task.minCoeff() >= 0.6 * mean * (1 - 1e-9) &&
                task.maxCoeff() <= 1400.0 * (1 + 1e-9) && e.tail(2).minCoeff() >= 150.0 * (1 - 1e-9)))
            continue;
          const double p = s0 * 4 / 100.0 + s1 * 3 / 120.0 + s2 * 2 / 90.0;
          if (!found || p < best_w) best_w = p, found = true;
        }
    if (!found) continue;
    ++compared;
    ASSERT_TRUE(joint.feasible) << "trial " << trial;
    ASSERT_EQ(joint.groups.size(), 3u);
    const double s0 = joint.groups[0].flux_lm, s1 = joint.groups[1].flux_lm, s2 = joint.groups[2].flux_lm;
    const Eigen::VectorXd e = m.fixed_lux + s0 * la.lux_per_lm + s1 * lb.lux_per_lm + s2 * lc.lux_per_lm;
    EXPECT_GE(e.head(6).mean(), 500.0 * (1 - 1e-6)) << "trial " << trial;
    EXPECT_GE(e.tail(2).minCoeff(), 150.0 * (1 - 1e-6)) << "trial " << trial;
    const double cell_w = (2700.0 / kCells) * 4 / 100.0 + (1400.0 / kCells) * 3 / 120.0 + (2300.0 / kCells) * 2 / 90.0;
    EXPECT_LE(joint.power_w, best_w + 1e-6) << "trial " << trial;
    EXPECT_GE(joint.power_w, best_w - cell_w) << "trial " << trial;
  }
  EXPECT_GE(compared, 4);
}

TEST(GroupSearch, TheSimplexIsExactOnAKnownCornerAndRefusesAnEmptyBox) {
  // s0 + s1 + s2 >= 10, s0 >= 2, cost (1, 3, 2) in [0, 20]^3: the optimum is (10, 0, 0).
  const std::vector<OutputConstraintN> c{{Eigen::Vector3d(1.0, 1.0, 1.0), 10.0}, {Eigen::Vector3d(1.0, 0.0, 0.0), 2.0}};
  const auto s = least_cost_outputs_n(c, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(20.0), Eigen::Vector3d(1.0, 3.0, 2.0));
  ASSERT_TRUE(s);
  EXPECT_NEAR((*s)[0], 10.0, 1e-9);
  EXPECT_NEAR((*s)[1], 0.0, 1e-9);
  EXPECT_NEAR((*s)[2], 0.0, 1e-9);
  // At most 20 each: s0 + s1 + s2 >= 61 cannot be met.
  const std::vector<OutputConstraintN> none{{Eigen::Vector3d(1.0, 1.0, 1.0), 61.0}};
  EXPECT_FALSE(least_cost_outputs_n(none, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(20.0), Eigen::Vector3d::Ones()));
  // Two groups through the same entry point: the plane's exact enumeration.
  const std::vector<OutputConstraintN> two{{Eigen::Vector2d(1.0, 1.0), 10.0}, {Eigen::Vector2d(1.0, -1.0), -4.0}};
  const auto p = least_cost_outputs_n(two, Eigen::Vector2d::Zero(), Eigen::Vector2d::Constant(20.0), Eigen::Vector2d(1.0, 3.0));
  ASSERT_TRUE(p);
  EXPECT_NEAR((*p)[0], 10.0, 1e-9);
}

}  // namespace
}  // namespace ilp
