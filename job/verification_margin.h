// The margin the verification keeps above a goal's target, so that a goal reported met
// stays met under an independent check (another simulator, other rays). The flux
// correction after verification scales every flux so that each lower-bound goal it can
// scale (average, minimum) reaches target x (1 + margin), not the target itself.
//
// The margin of a goal is kMarginStandardErrors times the verification's own estimate of
// its relative error, and never less than a floor (verification.margin, default 0.5 %)
// that stands for what the estimate leaves out. The estimate: each grid point's gather
// of the verified radiosity carries the spread of its rays (core/exact/point_illuminance.h);
// an average over points carries sqrt(sum w_i^2 se_i^2), a minimum its lowest point's.
// Goals over patches, and every goal of a sample verification, have no estimate: the
// floor alone.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "optimizer/layout_search.h"
#include "optimizer/lighting_model.h"

namespace ilp {

// How many of the estimate's standard errors the margin holds (one-sided, about 98 %
// for a normal error).
inline constexpr double kMarginStandardErrors = 2.0;

struct GoalMargin {
  std::optional<double> relative_error;  // the verification's relative standard error of the value, when estimated
  double margin = 0.0;                   // relative: max(floor, kMarginStandardErrors x relative_error)
  bool applies = false;                  // a goal the flux scale can meet (average or minimum, a lower bound)
};

// Per goal of `verified` (judged on `lux`, the model's goal rows), with `point_error_lux`
// the standard error of each goal point's verified value (empty: no estimate).
std::vector<GoalMargin> goal_margins(const LightingModel& model, const std::vector<GoalJudgement>& verified,
                                     const Eigen::VectorXd& lux, const Eigen::VectorXd& point_error_lux,
                                     double margin_floor, bool averages_are_targets);

// The exact verification's progressive refinement (job_runner.cpp): `before` and
// `after` are the goal rows' lux at two steps, the second with twice the rays on the
// rows of the patches that are not goals; their difference estimates the second's error
// from those rows' noise (the error halves in variance with each doubling). Settled
// when every average, minimum and uniformity goal changed by at most the larger of its
// gather's own relative error and a quarter of the margin floor (so the refinement's
// error never raises a margin above the floor by much). Past that, more rays on those
// rows cannot decide a verdict that the gather's own error leaves open (a uniformity
// at its target): only rays_per_patch can. largest_goal_change: the largest such change, for the run log.
bool refinement_settled(const LightingModel& model, const std::vector<GoalSpec>& goals, const Eigen::VectorXd& before,
                        const Eigen::VectorXd& after, const Eigen::VectorXd& point_error_lux, double margin_floor);
double largest_goal_change(const LightingModel& model, const std::vector<GoalSpec>& goals, const Eigen::VectorXd& before,
                           const Eigen::VectorXd& after);

// The goal points that decide a minimum, uniformity or maximum goal over a grid: for
// each such goal, the points whose verified value (`lux`, the goal rows) lies within
// `band` (relative) of the grid's lowest (minimum, uniformity) or highest (maximum)
// point, or whose value `standard_errors` of its own error (`point_error_lux`, when
// given) would bring there. Indices into LightingModel::goal_points, ascending, each once. A grid's
// minimum is one point: its value carries that point's noise whole, where an average
// shares it with the others, so these points are verified with more rays
// (job_runner.cpp, verify_exact_progressively).
std::vector<int> decisive_points(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                 const Eigen::VectorXd& lux, const Eigen::VectorXd& point_error_lux, double band,
                                 double standard_errors);

// The margin a lower-bound goal kept after the flux correction: the one it asked for,
// unless the correction gave less (held back by an upper bound such as UGR, or the flux
// range), then what its verified value holds above the target (never below 0).
double kept_margin(double asked, double verified_value, double target);

}  // namespace ilp
