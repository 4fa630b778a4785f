// What a goal is, for every stage that judges one: its metric and the one table of
// metric rules (key, name, unit, bound, range of a valid target), the goal line the
// search and the verification judge (its target already initial), and the objective.
// The job file's goal keys and objective names are read from these tables.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ilp {

enum class GoalMetric {
  average,     // area-weighted average illuminance >= target lux (closest_to_target: = target)
  minimum,     // lowest patch illuminance >= target lux
  maximum,     // highest patch illuminance <= target lux
  uniformity,  // U0 = Emin / Eavg >= target (a ratio in (0, 1])
  ugr,                     // unified glare rating (CIE 117), the highest over the observers <= target
  cylindrical,             // mean cylindrical illuminance Ez,m >= target lux (at eye height over a grid)
  cylindrical_uniformity,  // U0 of the cylindrical illuminance, Ez,min / Ez,m >= target
  modelling,               // modelling Ez,m / Eh,m >= target (EN 12464-1 recommends 0.30 to 0.60)
};

// What a goal area is made of, by the metric measured over it (its rule's `area`):
// - illuminance: patches of surfaces, or the points of a grid (one row each);
// - cylindrical: a grid's points lifted to eye height, each as kCylinderPlanes
//   vertical receivers (their mean is Ez) and one facing up (Eh);
// - glare: observers' eyes, each one vertical receiver facing its line of sight (its
//   indirect illuminance gives the background luminance) with the luminaires' glare terms.
enum class AreaKind { illuminance, cylindrical, glare };

// Which patches of a goal's surfaces count: all, or only those facing up (a desk's top
// without its edges and underside) or down, within about 25 degrees of vertical.
enum class GoalFacing { any, up, down };

enum class Objective {
  min_power,          // least electric power meeting every goal
  closest_to_target,  // average goals hit their targets (least squared relative deviation); others are constraints
};

// What an objective means for the stages: its key in the job file, whether the search
// and the choice between layouts minimise electric power (feasible layouts ranked by
// watts, counts and products bounded by the power already found), and whether average
// goals are targets to hit (least squared relative deviation, two-sided) instead of
// lower bounds.
struct ObjectiveRule {
  Objective objective;
  std::string_view key;     // min_power, closest_to_target
  bool minimises_power;
  bool averages_are_targets;
};
const ObjectiveRule& objective_rule(Objective objective);
// The rule of an objective's key, or nullptr.
const ObjectiveRule* objective_rule_for_key(std::string_view key);
// Is a goal of this metric a target to hit under the objective (an average goal of
// closest_to_target), rather than a bound?
bool is_target_goal(Objective objective, GoalMetric metric);

// Which light a metric counts: all of it (every reflection), or only what comes straight
// from the sources (EN 1838's emergency values: reflected light does not count).
enum class LightCounted { total, direct };
// Over what time a metric is judged: one state of the lighting (an instant), or every
// hour of a year (climate-based daylight metrics, annual energy).
enum class MetricDomain { instant, year };

struct MetricRule {
  GoalMetric metric;
  std::string_view key;   // in goals entries and sweep keys: average_lux, min_lux, max_lux, uniformity,
                          // ugr_max, cylindrical_lux, cylindrical_uniformity, modelling
  std::string_view name;  // average, minimum, maximum, uniformity, UGR, cylindrical, cylindrical U0, modelling
  std::string_view unit;  // "lx", or "" for ratios and UGR
  bool lower_bound;       // value >= target (else value <= target)
  bool lux;               // in lux: linear in flux and maintained = initial x MF (U0 is neither)
  bool scale_closed_form; // the least flux scale meeting it is a closed form (average, minimum)
  bool zero_allowed;      // a target of 0 is valid (minimum); every other must be > 0
  double max_target;      // the largest valid target (1e7 lx; 1 for U0)
  AreaKind area = AreaKind::illuminance;  // what the metric is measured over
  double min_target = 0.0;  // the least valid target (exclusive unless zero_allowed; inclusive for UGR)
  MetricDomain domain = MetricDomain::instant;  // every metric so far: one lighting state
  LightCounted light = LightCounted::total;     // every metric so far counts reflected light
  std::string_view quantity = "illuminance";    // what is measured: illuminance, glare rating, cylindrical illuminance, ratio
};

// Every metric, in GoalMetric order.
const std::vector<MetricRule>& metric_rules();
const MetricRule& metric_rule(GoalMetric metric);
// The rule of a goals entry's key, or nullptr for a key that is no metric.
const MetricRule* metric_rule_for_key(std::string_view key);
// The rule a target breaks ("" when none), e.g. "must be > 0" or "must be in (0, 1]".
std::string target_rule(GoalMetric metric, double target);

inline std::string_view to_string(GoalMetric metric) { return metric_rule(metric).name; }
inline std::string_view goal_key(GoalMetric metric) { return metric_rule(metric).key; }

// One goal line as the search and the verification judge it: a metric over the goal
// area of that name (optimizer/lighting_model.h), at an initial target (lux metrics:
// the job's maintained target / maintenance factor; U0 as given).
struct GoalSpec {
  std::string name;
  GoalMetric metric = GoalMetric::average;
  double target = 0.0;
};

}  // namespace ilp
