#include "job/verification_margin.h"

#include <algorithm>
#include <cmath>

#include "optimizer/goal_metrics.h"

namespace ilp {
namespace {

// The relative standard error of a goal's value from its rows' errors, or nothing when
// a row has no estimate (a patch) or the value is 0.
std::optional<double> relative_error(const LightingModel& model, const GoalArea& area, GoalMetric metric,
                                     const Eigen::VectorXd& lux, const Eigen::VectorXd& point_error_lux) {
  const auto patches = static_cast<Eigen::Index>(model.goal_patches.size());
  if (point_error_lux.size() == 0 || area.rows.empty()) return std::nullopt;
  double variance = 0.0, average = 0.0;
  Eigen::Index lowest = area.rows.front();
  for (std::size_t r = 0; r < area.rows.size(); ++r) {
    const Eigen::Index row = area.rows[r];
    if (row < patches) return std::nullopt;
    const double w = area.area_weights[static_cast<Eigen::Index>(r)], se = point_error_lux[row - patches];
    variance += w * w * se * se;
    average += w * lux[row];
    if (lux[row] < lux[lowest]) lowest = row;
  }
  const double average_error = average > 0.0 ? std::sqrt(variance) / average : 0.0;
  const double minimum_error = lux[lowest] > 0.0 ? point_error_lux[lowest - patches] / lux[lowest] : 0.0;
  switch (metric) {
    case GoalMetric::average: return average > 0.0 ? std::optional(average_error) : std::nullopt;
    case GoalMetric::minimum: return lux[lowest] > 0.0 ? std::optional(minimum_error) : std::nullopt;
    case GoalMetric::uniformity:
      if (!(average > 0.0 && lux[lowest] > 0.0)) return std::nullopt;
      return std::hypot(average_error, minimum_error);
    case GoalMetric::maximum:  // its highest point's; not needed for a margin
    case GoalMetric::ugr:      // the others are not scaled by the flux correction
    case GoalMetric::cylindrical:
    case GoalMetric::cylindrical_uniformity:
    case GoalMetric::modelling:
      return std::nullopt;
  }
  return std::nullopt;
}

// The relative change of a goal's value from `before` to `after` (the same rows), for
// the goals whose value is an average, a minimum or their ratio; nothing for others.
std::optional<double> relative_change(const GoalArea& area, GoalMetric metric, const Eigen::VectorXd& before,
                                      const Eigen::VectorXd& after) {
  if (area.rows.empty()) return std::nullopt;
  double average_before = 0.0, average_after = 0.0;
  Eigen::Index lowest = area.rows.front();
  for (std::size_t r = 0; r < area.rows.size(); ++r) {
    const Eigen::Index row = area.rows[r];
    const double w = area.area_weights[static_cast<Eigen::Index>(r)];
    average_before += w * before[row];
    average_after += w * after[row];
    if (after[row] < after[lowest]) lowest = row;
  }
  const double average = average_after > 0.0 ? std::abs(average_after - average_before) / average_after : 0.0;
  const double minimum = after[lowest] > 0.0 ? std::abs(after[lowest] - before[lowest]) / after[lowest] : 0.0;
  switch (metric) {
    case GoalMetric::average: return average;
    case GoalMetric::minimum: return minimum;
    case GoalMetric::uniformity: return std::hypot(average, minimum);
    case GoalMetric::maximum:  // neither an average, a minimum nor their ratio
    case GoalMetric::ugr:
    case GoalMetric::cylindrical:
    case GoalMetric::cylindrical_uniformity:
    case GoalMetric::modelling:
      return std::nullopt;
  }
  return std::nullopt;
}

}  // namespace

double largest_goal_change(const LightingModel& model, const std::vector<GoalSpec>& goals, const Eigen::VectorXd& before,
                           const Eigen::VectorXd& after) {
  double largest = 0.0;
  for (const GoalSpec& g : goals)
    if (const int a = find_goal_area(model, g.name); a >= 0)
      largest = std::max(largest, relative_change(model.areas[static_cast<std::size_t>(a)], g.metric, before, after).value_or(0.0));
  return largest;
}

bool refinement_settled(const LightingModel& model, const std::vector<GoalSpec>& goals, const Eigen::VectorXd& before,
                        const Eigen::VectorXd& after, const Eigen::VectorXd& point_error_lux, double margin_floor) {
  const double floor_share = margin_floor / (2.0 * kMarginStandardErrors);
  for (const GoalSpec& g : goals) {
    const int a = find_goal_area(model, g.name);
    if (a < 0) continue;
    const GoalArea& area = model.areas[static_cast<std::size_t>(a)];
    const std::optional<double> change = relative_change(area, g.metric, before, after);
    if (!change) continue;
    const double own = relative_error(model, area, g.metric, after, point_error_lux).value_or(0.0);
    if (*change > std::max(own, floor_share)) return false;
  }
  return true;
}

std::vector<GoalMargin> goal_margins(const LightingModel& model, const std::vector<GoalJudgement>& verified,
                                     const Eigen::VectorXd& lux, const Eigen::VectorXd& point_error_lux,
                                     double margin_floor, bool averages_are_targets) {
  std::vector<GoalMargin> out;
  for (const GoalJudgement& g : verified) {
    GoalMargin m;
    const int a = find_goal_area(model, g.name);
    if (a >= 0) m.relative_error = relative_error(model, model.areas[static_cast<std::size_t>(a)], g.metric, lux, point_error_lux);
    const MetricRule& rule = metric_rule(g.metric);
    m.applies = rule.scale_closed_form && rule.lower_bound && g.target > 0.0 &&
                !(averages_are_targets && g.metric == GoalMetric::average);
    m.margin = m.applies ? std::max(margin_floor, kMarginStandardErrors * m.relative_error.value_or(0.0)) : 0.0;
    out.push_back(m);
  }
  return out;
}

std::vector<int> decisive_points(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                 const Eigen::VectorXd& lux, const Eigen::VectorXd& point_error_lux, double band,
                                 double standard_errors) {
  const auto patches = static_cast<Eigen::Index>(model.goal_patches.size());
  std::vector<int> out;
  for (const GoalSpec& g : goals) {
    const bool lowest = g.metric == GoalMetric::minimum || g.metric == GoalMetric::uniformity;
    if (!lowest && g.metric != GoalMetric::maximum) continue;
    const int a = find_goal_area(model, g.name);
    if (a < 0) continue;
    const GoalArea& area = model.areas[static_cast<std::size_t>(a)];
    if (area.grid < 0 || area.rows.empty()) continue;
    double extreme = lux[area.rows.front()];
    for (Eigen::Index row : area.rows) extreme = lowest ? std::min(extreme, lux[row]) : std::max(extreme, lux[row]);
    for (Eigen::Index row : area.rows) {
      if (row < patches) continue;
      const Eigen::Index q = row - patches;
      const double error = q < point_error_lux.size() ? standard_errors * point_error_lux[q] : 0.0;
      const bool near = lowest ? lux[row] - error <= extreme * (1.0 + band)
                               : lux[row] + error >= extreme * (1.0 - band);
      if (near) out.push_back(static_cast<int>(row - patches));
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double kept_margin(double asked, double verified_value, double target) {
  if (!(asked > 0.0) || !(target > 0.0)) return asked;
  // Kept to round-off (the correction scales the binding goal to exactly target x (1 + asked)).
  if (verified_value >= target * (1.0 + asked) * (1.0 - 1e-9)) return asked;
  return std::clamp(verified_value / target - 1.0, 0.0, asked);
}

}  // namespace ilp
