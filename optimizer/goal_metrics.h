// Goal metrics in one place: per metric its key, name, unit, rule (a lower or an upper
// bound), whether it is in lux (linear in flux, scaled by the maintenance factor), its
// value over a goal area's rows (Em, Emin, Emax, U0) and the closed-form least flux
// scale that meets it. The search, the verification's flux correction, the statistics
// and the report read this table instead of each keeping its own if-chain.
#pragma once

#include <Eigen/Core>
#include <string_view>

#include "job/config.h"
#include "optimizer/lighting_model.h"

namespace ilp {

struct MetricRule {
  GoalMetric metric;
  std::string_view key;   // in goals entries and sweep keys: average_lux, min_lux, max_lux, uniformity
  std::string_view name;  // average, minimum, maximum, uniformity
  std::string_view unit;  // "lx", or "" for the U0 ratio
  bool lower_bound;       // value >= target (else value <= target)
  bool lux;               // in lux: linear in flux and maintained = initial x MF (U0 is neither)
  bool scale_closed_form; // the least flux scale meeting it is a closed form (average, minimum)
};

const MetricRule& metric_rule(GoalMetric metric);

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
