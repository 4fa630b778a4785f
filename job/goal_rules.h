// The rules of goal targets that the job file's loader and the plan's edits (a sweep
// point's target) share: the lines are the loader's GoalSetting or the plan's GoalLine,
// anything with a name, a metric and a target. Inside job/ only.
#pragma once

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "optimizer/goal_spec.h"

namespace ilp::goal_rules {

inline std::string format_number(double v) {
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}

// The rule `metric` = v breaks against the other targets of goal `name` in `others`
// ("" when none): min_lux and average_lux may not exceed max_lux. `skip` is left out
// (the line being replaced).
template <class Line>
std::string bound_rule(const std::vector<Line>& others, const std::string& name, GoalMetric metric, double v,
                       const Line* skip = nullptr) {
  for (const Line& g : others) {
    if (&g == skip || g.name != name) continue;
    const bool lower = metric == GoalMetric::minimum || metric == GoalMetric::average;
    const bool other_lower = g.metric == GoalMetric::minimum || g.metric == GoalMetric::average;
    if (lower && g.metric == GoalMetric::maximum && v > g.target)
      return "must be <= max_lux (" + format_number(g.target) + ") of goal '" + name + "'";
    if (metric == GoalMetric::maximum && other_lower && v < g.target)
      return std::string("must be >= ") + std::string(goal_key(g.metric)) + " (" + format_number(g.target) + ") of goal '" + name +
             "'";
  }
  return "";
}

// Every goal parameter of the lines, "goals.desks.average_lux, goals.floor.min_lux".
template <class Line>
std::string parameters(const std::vector<Line>& lines) {
  std::string out;
  for (const Line& g : lines) out += (out.empty() ? "goals." : ", goals.") + g.name + "." + std::string(goal_key(g.metric));
  return out;
}

// Sets the target of the line `key` names ("goals.NAME.average_lux", ...) to `value`, checked
// as the file is; bad_key(rule) or bad_value(rule) is called (and must throw) when the key
// or the value is wrong.
template <class Line, class BadKey, class BadValue>
void apply(std::vector<Line>& lines, const std::string& key, double value, BadKey bad_key, BadValue bad_value) {
  Line* found = nullptr;
  const std::size_t dot = key.rfind('.');
  if (key.rfind("goals.", 0) == 0 && dot != std::string::npos && dot > 6) {
    const std::string name = key.substr(6, dot - 6), metric = key.substr(dot + 1);
    for (Line& g : lines)
      if (g.name == name && metric == std::string(goal_key(g.metric))) found = &g;
  }
  if (!found) {
    bad_key("no goal parameter " + key + "; " +
            (lines.empty() ? std::string("the job has no goals") : "the job has " + parameters(lines)));
    return;
  }
  std::string rule = std::isfinite(value) ? target_rule(found->metric, value) : "must be a finite number";
  if (rule.empty()) rule = bound_rule(lines, found->name, found->metric, value, static_cast<const Line*>(found));
  if (!rule.empty()) {
    bad_value(rule);
    return;
  }
  found->target = value;
}

}  // namespace ilp::goal_rules
