#include "job/round_calibration.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "optimizer/goal_metrics.h"

namespace ilp {

std::optional<double> next_search_target(GoalMetric metric, double real_target, double current_target,
                                         double predicted, double verified) {
  if (!(predicted > 0.0) || !(verified > 0.0)) return std::nullopt;
  constexpr double kMargin = 0.002;  // aim just past the target, not at it
  const double ratio = predicted / verified;
  double next = !metric_rule(metric).lower_bound ? std::min(current_target, real_target * ratio * (1.0 - kMargin))
                                              : std::max(current_target, real_target * ratio * (1.0 + kMargin));
  if (metric == GoalMetric::uniformity) next = std::min(next, 1.0);
  if (next == current_target) return std::nullopt;
  return next;
}

std::string calibration_line(int round, double maintenance_factor, const GoalLine& goal, double predicted,
                             double verified, double next_target) {
  const MetricRule& rule = metric_rule(goal.metric);
  std::string unit;  // " lx", or none for U0 (appended: GCC 12 warns falsely on " " + string)
  if (!rule.unit.empty()) unit.append(" ").append(rule.unit);
  std::ostringstream line;
  line << std::setprecision(4) << "round " << round + 1 << ": " << goal.name << " " << to_string(goal.metric)
       << " predicted " << predicted << unit << ", verified " << verified << unit;
  const double initial = initial_target(goal.metric, goal.target, maintenance_factor);
  if (rule.lux && initial != goal.target) line << " (initial, for " << initial << unit << ")";
  line << "; the next search aims at " << next_target << unit << " for " << goal.target << unit;
  return line.str();
}

}  // namespace ilp
