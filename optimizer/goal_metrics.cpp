#include "optimizer/goal_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/glare/ugr.h"

namespace ilp {
namespace {

constexpr double kMaxLux = 1e7;

// Each metric's rule: what the stages do with it (docs/config.md lists the keys).
constexpr MetricDomain kInstant = MetricDomain::instant;
constexpr LightCounted kTotal = LightCounted::total;
const std::vector<MetricRule> kRules = {
    {GoalMetric::average, "average_lux", "average", "lx", true, true, true, false, kMaxLux, AreaKind::illuminance, 0.0,
     kInstant, kTotal, "illuminance"},
    {GoalMetric::minimum, "min_lux", "minimum", "lx", true, true, true, true, kMaxLux, AreaKind::illuminance, 0.0,
     kInstant, kTotal, "illuminance"},
    {GoalMetric::maximum, "max_lux", "maximum", "lx", false, true, false, false, kMaxLux, AreaKind::illuminance, 0.0,
     kInstant, kTotal, "illuminance"},
    {GoalMetric::uniformity, "uniformity", "uniformity", "", true, false, false, false, 1.0, AreaKind::illuminance, 0.0,
     kInstant, kTotal, "illuminance ratio"},
    {GoalMetric::ugr, "ugr_max", "UGR", "", false, false, false, false, 30.0, AreaKind::glare, 10.0, kInstant, kTotal,
     "glare rating"},
    {GoalMetric::cylindrical, "cylindrical_lux", "cylindrical", "lx", true, true, true, false, kMaxLux,
     AreaKind::cylindrical, 0.0, kInstant, kTotal, "cylindrical illuminance"},
    {GoalMetric::cylindrical_uniformity, "cylindrical_uniformity", "cylindrical U0", "", true, false, false, false, 1.0,
     AreaKind::cylindrical, 0.0, kInstant, kTotal, "cylindrical illuminance ratio"},
    {GoalMetric::modelling, "modelling", "modelling", "", true, false, false, false, 5.0, AreaKind::cylindrical, 0.0,
     kInstant, kTotal, "cylindrical over horizontal illuminance"},
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
  if (metric == GoalMetric::ugr) return target >= r.min_target && target <= r.max_target ? "" : "must be in [10, 30]";
  if (metric == GoalMetric::modelling) return target > 0.0 && target <= r.max_target ? "" : "must be in (0, 5]";
  if (!r.lux) return target > 0.0 && target <= r.max_target ? "" : "must be in (0, 1]";
  if (r.zero_allowed ? !(target >= 0.0) : !(target > 0.0)) return r.zero_allowed ? "must be >= 0" : "must be > 0";
  return target <= r.max_target ? "" : "must be at most 1e+07 lx";
}

namespace {

// Ez per point (the mean of its vertical rows), Ez,m by the area's weights, Eh,m from the up rows.
AreaStatistics cylindrical_statistics(const GoalArea& area, const Eigen::VectorXd& lux) {
  AreaStatistics s;
  constexpr std::size_t kRowsPerPoint = kCylinderPlanes + 1;
  const std::size_t points = area.rows.size() / kRowsPerPoint;
  if (points == 0) return s;
  s.min_lux = std::numeric_limits<double>::infinity();
  s.max_lux = -s.min_lux;
  double horizontal = 0.0;
  for (std::size_t q = 0; q < points; ++q) {
    double ez = 0.0;
    for (std::size_t k = 0; k < kCylinderPlanes; ++k) ez += lux[area.rows[q * kRowsPerPoint + k]];
    ez /= kCylinderPlanes;
    s.min_lux = std::min(s.min_lux, ez);
    s.max_lux = std::max(s.max_lux, ez);
    horizontal += lux[area.rows[q * kRowsPerPoint + kCylinderPlanes]];
  }
  s.average_lux = weighted_average(area, lux);
  s.uniformity = s.average_lux > 0.0 ? s.min_lux / s.average_lux : 0.0;
  horizontal /= static_cast<double>(points);
  s.modelling = horizontal > 0.0 ? s.average_lux / horizontal : 0.0;
  return s;
}

}  // namespace

AreaStatistics area_statistics(const GoalArea& area, const Eigen::VectorXd& lux) {
  if (area.kind == AreaKind::cylindrical) return cylindrical_statistics(area, lux);
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
    case GoalMetric::cylindrical: return s.average_lux;
    case GoalMetric::cylindrical_uniformity: return s.uniformity;
    case GoalMetric::modelling: return s.modelling;
    case GoalMetric::ugr: break;  // not a statistic of illuminance: goal_value
  }
  throw std::invalid_argument("metric_value: " + std::string(metric_rule(metric).name) + " is not a statistic of illuminance");
}

double ugr_value(double glare_sum, double eye_indirect_lux) {
  if (!(glare_sum > 0.0)) return 0.0;
  if (!(eye_indirect_lux > 0.0)) return kUgrWithoutBackground;
  return std::min(kUgrWithoutBackground, ugr_from_terms(glare_sum, eye_indirect_lux / std::numbers::pi));
}

double goal_value(GoalMetric metric, const GoalArea& area, const GoalLight& light) {
  if (metric_rule(metric).area != area.kind)
    throw std::invalid_argument("goal_value: " + std::string(metric_rule(metric).name) + " is not measured over area '" +
                                area.name + "'");
  if (metric != GoalMetric::ugr) return metric_value(metric, area_statistics(area, light.lux));
  double highest = -std::numeric_limits<double>::infinity();
  for (const int o : area.observers) highest = std::max(highest, ugr_value(light.glare[o], light.eye_indirect_lux[o]));
  return highest;
}

double least_flux_scale(GoalMetric metric, const GoalArea& area, const Eigen::VectorXd& fixed,
                        const Eigen::VectorXd& gain, double target) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  double scale = 0.0;
  if (metric == GoalMetric::average || metric == GoalMetric::cylindrical) {
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

std::optional<double> largest_flux_scale(GoalMetric metric, double value, double target) {
  switch (metric) {
    case GoalMetric::maximum:
      if (value > 0.0) return target / value;
      return std::nullopt;
    case GoalMetric::ugr:
      // Below 10 no source counts (0) and at kUgrWithoutBackground nothing scales.
      if (value > 0.0 && value < kUgrWithoutBackground) return std::pow(10.0, (target - value) / 8.0);
      return std::nullopt;
    case GoalMetric::average:  // lower bounds, and ratios a common scale leaves unchanged
    case GoalMetric::minimum:
    case GoalMetric::uniformity:
    case GoalMetric::cylindrical:
    case GoalMetric::cylindrical_uniformity:
    case GoalMetric::modelling:
      return std::nullopt;
  }
  return std::nullopt;
}

double relative_violation(GoalMetric metric, double value, double target, bool two_sided_average) {
  if (!(target > 0.0)) return 0.0;
  if (two_sided_average && metric == GoalMetric::average) return std::abs(value - target) / target;
  return metric_rule(metric).lower_bound ? std::max(0.0, (target - value) / target)
                                         : std::max(0.0, (value - target) / target);
}

}  // namespace ilp
