// Several luminaire groups searched together (issue 19, item 5; any number since issue
// 38): each group's regular arrangements with their light at 1 lm per luminaire
// (optimizer/layout_search.h, regular_arrangement_lights), and for every combination of
// arrangements (one per group) the groups' outputs set together for the least power.
//
// Illuminance is affine in each group's flux per luminaire s_g (all of a group at one
// output): E = fixed + sum_g s_g u_g. Average, minimum, maximum and U0 goals (and the
// cylindrical average) are therefore linear constraints on s, and the least power
// sum_g s_g n_g / efficacy_g within each group's output range is a linear programme in
// one variable per group: for one or two groups solved exactly (the vertices of the
// output box cut by the constraints), for more by GLPK's simplex method. Goals that are
// not linear in s (UGR, cylindrical U0, modelling) are judged at that solution, as the
// single-group search judges them at its closed-form scale: a combination that misses
// one is infeasible.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "optimizer/layout_search.h"
#include "optimizer/lighting_model.h"

namespace ilp {

// Groups a job may search together (their luminaires are named A1 ... F1), and the
// combinations of arrangements (one per group) a search of three or more may weigh: a
// product of the groups' arrangement counts above it is refused before any is solved.
inline constexpr int kMaxSearchedGroups = 6;
inline constexpr double kMaxGroupCombinations = 2e6;

// coeff . s >= rhs, s = (s_0, s_1) the groups' fluxes per luminaire (lm).
struct OutputConstraint {
  Eigen::Vector2d coeff = Eigen::Vector2d::Zero();
  double rhs = 0.0;
};

// The least cost . s over the box [lo, hi] cut by the constraints, exactly: the least
// over the vertices of the clipped box (cost >= 0; a degenerate box, lo = hi on an
// axis, is a segment). Nothing when no point of the box meets every constraint.
std::optional<Eigen::Vector2d> least_cost_outputs(const std::vector<OutputConstraint>& constraints,
                                                  const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                                  const Eigen::Vector2d& cost);

// coeff . s >= rhs for any number of groups.
struct OutputConstraintN {
  Eigen::VectorXd coeff;
  double rhs = 0.0;
};

// The least cost . s over the box [lo, hi] cut by the constraints, in any dimension: one
// or two groups through least_cost_outputs (exact), more through GLPK's simplex method
// (clamped into the box). Nothing when no point of the box meets every constraint.
std::optional<Eigen::VectorXd> least_cost_outputs_n(const std::vector<OutputConstraintN>& constraints,
                                                    const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                                    const Eigen::VectorXd& cost);

// The goals that are linear in the groups' fluxes as constraints on s: every average
// and cylindrical goal one, every minimum, maximum and U0 goal one per row of its area.
// unit_lux[g]: group g's goal-row lux at 1 lm per luminaire (one or two groups; _n: any number).
std::vector<OutputConstraint> linear_goal_constraints(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                                      const Eigen::VectorXd& fixed_lux,
                                                      const std::vector<const Eigen::VectorXd*>& unit_lux);
std::vector<OutputConstraintN> linear_goal_constraints_n(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                                         const Eigen::VectorXd& fixed_lux,
                                                         const std::vector<const Eigen::VectorXd*>& unit_lux);

// One arrangement a group may take, with its luminaire's output range and efficacy.
struct GroupOption {
  int variant = 0;                         // the group's product variant it is of
  const ArrangementLight* light = nullptr;  // its light at 1 lm per luminaire
  double flux_min_lm = 0.0, flux_max_lm = 0.0;
  double efficacy_lm_per_w = 100.0;
  Eigen::Vector2d extent_m = Eigen::Vector2d::Zero();  // its luminaires' outline in plan (x, y), as placed
  int count() const { return static_cast<int>(light->luminaires.size()); }
};

// Do two arrangements of different groups collide: a luminaire of one whose outline in
// plan overlaps one of the other's by more than 1 mm on both axes, their emitting faces
// within kGroupClearanceM in height (a ceiling field and a ceiling row may not share a
// place; a wall bracket below a ceiling batten may)?
inline constexpr double kGroupClearanceM = 0.1;
bool groups_collide(const GroupOption& a, const GroupOption& b);

struct GroupChoices {
  std::string name;
  std::vector<GroupOption> options;
};

struct GroupSearchSpec {
  std::vector<GoalSpec> goals;  // initial targets, each naming an area of the model
  double max_power_w = std::numeric_limits<double>::infinity();  // all groups together
};

struct GroupPick {
  int option = -1;       // into GroupChoices::options
  double flux_lm = 0.0;  // per luminaire
  double power_w = 0.0;  // the group's
};

struct GroupSearchResult {
  bool feasible = false;           // every goal met as predicted (else the pair that misses least)
  std::vector<GroupPick> groups;   // one per group
  double power_w = 0.0;
  std::vector<GoalJudgement> goals;
  Eigen::VectorXd lux, eye_indirect_lux, glare;  // at the goal rows and the observers, as predicted
  long pairs = 0;      // combinations of arrangements (one per group) in all
  long solved = 0;     // linear programmes solved (the evaluations)
  long pruned = 0;     // combinations left out: their least power could not beat the best found
  long colliding = 0;  // combinations left out: a luminaire of one group on another's (groups_collide)
  double seconds = 0.0;
};

// The least-power combination (min_power). `model` gives the goal areas, the fixed
// sources' light and the observers (every group's model has the same goal rows). Throws
// std::invalid_argument for no group, more than kMaxSearchedGroups, a group without
// options or, for three or more groups, more than kMaxGroupCombinations combinations.
GroupSearchResult search_groups(const LightingModel& model, const GroupSearchSpec& spec,
                                const std::vector<GroupChoices>& groups);

}  // namespace ilp
