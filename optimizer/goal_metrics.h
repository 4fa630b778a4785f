// Goal metrics on illuminance: a metric's value over a goal area's rows (Em, Emin,
// Emax, U0), the closed-form least flux scale that meets it, and how far a value
// violates a target. The rule table itself (keys, units, bounds) is optimizer/goal_spec.h.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string_view>

#include "optimizer/goal_spec.h"
#include "optimizer/lighting_model.h"

namespace ilp {


// Em (weighted average), Emin, Emax and U0 = Emin / Em (0 when Em is 0) over an area's rows.
// A cylindrical area's (GoalArea): Ez,m, Ez,min, Ez,max and their U0 over its points (each
// the mean of its vertical rows), and modelling = Ez,m / Eh,m (0 when Eh,m is 0).
struct AreaStatistics {
  double average_lux = 0.0, min_lux = 0.0, max_lux = 0.0, uniformity = 0.0;
  double modelling = 0.0;
};
AreaStatistics area_statistics(const GoalArea& area, const Eigen::VectorXd& lux);
double metric_value(GoalMetric metric, const AreaStatistics& statistics);

// A layout's light as the metrics read it: the illuminance at the goal rows and, per
// observer of the model (LightingModel::observers), the indirect illuminance at the eye
// and the sum of the luminaires' glare terms L^2 omega / p^2.
struct GoalLight {
  const Eigen::VectorXd& lux;
  const Eigen::VectorXd& eye_indirect_lux;
  const Eigen::VectorXd& glare;
};

// UGR reported when luminaires are in view but no light reaches the eye indirectly
// (Lb = 0: the rating is unbounded).
inline constexpr double kUgrWithoutBackground = 99.0;
// CIE 117's UGR = 8 log10(0.25 / Lb sum) with Lb = E_ind / pi; 0 when no luminaire is
// in view (CIE 117 reports anything under 10 as "< 10").
double ugr_value(double glare_sum, double eye_indirect_lux);

// The metric's value over the area: statistics of its rows, or for a glare area the
// highest UGR of its observers.
double goal_value(GoalMetric metric, const GoalArea& area, const GoalLight& light);

// The least scale alpha >= 0 with metric(fixed + alpha gain) >= target, for metrics with
// scale_closed_form: 0 when met already, infinity when no scale meets it.
double least_flux_scale(GoalMetric metric, const GoalArea& area, const Eigen::VectorXd& fixed,
                        const Eigen::VectorXd& gain, double target);

// The largest common scale s of every flux (no fixed sources) at which an upper-bound
// goal whose value is `value` at s = 1 still meets `target`: a maximum scales with s
// (target / value), a UGR rises by 8 log10(s) (both the sources' luminance and the
// background's scale with s). Nothing for lower bounds and scale-free ratios, or a UGR
// without background light (kUgrWithoutBackground does not scale).
std::optional<double> largest_flux_scale(GoalMetric metric, double value, double target);

// Relative violation of `target` by `value` under the metric's rule (>= 0); for an average
// goal with objective closest_to_target, the relative deviation |value - target| / target.
double relative_violation(GoalMetric metric, double value, double target, bool two_sided_average);

}  // namespace ilp
