#include "optimizer/goal_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace ilp {
namespace {

constexpr double kMaxLux = 1e7;

const std::vector<MetricRule> kRules = {
    {GoalMetric::average, "average_lux", "average", "lx", true, true, true, false, kMaxLux},
    {GoalMetric::minimum, "min_lux", "minimum", "lx", true, true, true, true, kMaxLux},
    {GoalMetric::maximum, "max_lux", "maximum", "lx", false, true, false, false, kMaxLux},
    {GoalMetric::uniformity, "uniformity", "uniformity", "", true, false, false, false, 1.0},
};

double weighted_average(const GoalArea& area, const Eigen::VectorXd& v) {
  double sum = 0.0;
  for (std::size_t r = 0; r < area.rows.size(); ++r) sum += area.area_weights[static_cast<Eigen::Index>(r)] * v[area.rows[r]];
  return sum;
}

}  // namespace

const std::vector<MetricRule>& metric_rules() { return kRules; }

const ObjectiveRule& objective_rule(Objective objective) {
  static constexpr ObjectiveRule kObjectives[] = {{Objective::min_power, "min_power", true, false},
                                                  {Objective::closest_to_target, "closest_to_target", false, true}};
  for (const ObjectiveRule& r : kObjectives)
    if (r.objective == objective) return r;
  throw std::invalid_argument("objective_rule: unknown objective");
}

const ObjectiveRule* objective_rule_for_key(std::string_view key) {
  for (Objective o : {Objective::min_power, Objective::closest_to_target})
    if (objective_rule(o).key == key) return &objective_rule(o);
  return nullptr;
}

bool is_target_goal(Objective objective, GoalMetric metric) {
  return objective_rule(objective).averages_are_targets && metric == GoalMetric::average;
}

const MetricRule& metric_rule(GoalMetric metric) {
  for (const MetricRule& r : kRules)
    if (r.metric == metric) return r;
  throw std::invalid_argument("metric_rule: unknown goal metric");
}

const MetricRule* metric_rule_for_key(std::string_view key) {
  for (const MetricRule& r : kRules)
    if (r.key == key) return &r;
  return nullptr;
}

std::string target_rule(GoalMetric metric, double target) {
  const MetricRule& r = metric_rule(metric);
  if (!r.lux) return target > 0.0 && target <= r.max_target ? "" : "must be in (0, 1]";
  if (r.zero_allowed ? !(target >= 0.0) : !(target > 0.0)) return r.zero_allowed ? "must be >= 0" : "must be > 0";
  return target <= r.max_target ? "" : "must be at most 1e+07 lx";
}

AreaStatistics area_statistics(const GoalArea& area, const Eigen::VectorXd& lux) {
  AreaStatistics s;
  if (area.rows.empty()) return s;
  s.min_lux = std::numeric_limits<double>::infinity();
  s.max_lux = -s.min_lux;
  for (Eigen::Index r : area.rows) {
    s.min_lux = std::min(s.min_lux, lux[r]);
    s.max_lux = std::max(s.max_lux, lux[r]);
  }
  s.average_lux = weighted_average(area, lux);
  s.uniformity = s.average_lux > 0.0 ? s.min_lux / s.average_lux : 0.0;
  return s;
}

double metric_value(GoalMetric metric, const AreaStatistics& s) {
  switch (metric) {
    case GoalMetric::average: return s.average_lux;
    case GoalMetric::minimum: return s.min_lux;
    case GoalMetric::maximum: return s.max_lux;
    case GoalMetric::uniformity: return s.uniformity;
  }
  return 0.0;
}

double least_flux_scale(GoalMetric metric, const GoalArea& area, const Eigen::VectorXd& fixed,
                        const Eigen::VectorXd& gain, double target) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double scale = 0.0;
  if (metric == GoalMetric::average) {
    const double deficit = target - weighted_average(area, fixed), g = weighted_average(area, gain);
    if (deficit > 0.0) scale = g > 0.0 ? deficit / g : kInfinity;
  } else if (metric == GoalMetric::minimum) {
    for (Eigen::Index r : area.rows) {
      const double deficit = target - fixed[r];
      if (deficit > 0.0) scale = std::max(scale, gain[r] > 0.0 ? deficit / gain[r] : kInfinity);
    }
  } else {
    throw std::invalid_argument("least_flux_scale: " + std::string(metric_rule(metric).name) + " has no closed form");
  }
  return scale;
}

double relative_violation(GoalMetric metric, double value, double target, bool two_sided_average) {
  if (!(target > 0.0)) return 0.0;
  if (two_sided_average && metric == GoalMetric::average) return std::abs(value - target) / target;
  return metric_rule(metric).lower_bound ? std::max(0.0, (target - value) / target)
                                         : std::max(0.0, (value - target) / target);
}

}  // namespace ilp
