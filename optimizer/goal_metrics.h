// Goal metrics on illuminance: a metric's value over a goal area's rows (Em, Emin,
// Emax, U0), the closed-form least flux scale that meets it, and how far a value
// violates a target. The rule table itself (keys, units, bounds) is optimizer/goal_spec.h.
#pragma once

#include <Eigen/Core>
#include <string_view>

#include "optimizer/goal_spec.h"
#include "optimizer/lighting_model.h"

namespace ilp {


// Em (weighted average), Emin, Emax and U0 = Emin / Em (0 when Em is 0) over an area's rows.
struct AreaStatistics {
  double average_lux = 0.0, min_lux = 0.0, max_lux = 0.0, uniformity = 0.0;
};
AreaStatistics area_statistics(const GoalArea& area, const Eigen::VectorXd& lux);
double metric_value(GoalMetric metric, const AreaStatistics& statistics);

// The least scale alpha >= 0 with metric(fixed + alpha gain) >= target, for metrics with
// scale_closed_form: 0 when met already, infinity when no scale meets it.
double least_flux_scale(GoalMetric metric, const GoalArea& area, const Eigen::VectorXd& fixed,
                        const Eigen::VectorXd& gain, double target);

// Relative violation of `target` by `value` under the metric's rule (>= 0); for an average
// goal with objective closest_to_target, the relative deviation |value - target| / target.
double relative_violation(GoalMetric metric, double value, double target, bool two_sided_average);

}  // namespace ilp
