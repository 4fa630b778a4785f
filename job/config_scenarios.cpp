// The scenarios section: the installation's other lighting states (optimizer/scenario_spec.h).
#include <algorithm>

#include "job/config_yaml.h"

namespace ilp::config_yaml {
namespace {

ScenarioPick read_pick(const Value& v) {
  const std::string text = v.text();
  for (ScenarioPick p : {ScenarioPick::all, ScenarioPick::odd, ScenarioPick::even})
    if (scenario_pick_key(p) == text) return p;
  v.fail("must be all, odd or even");
}

std::vector<ScenarioLevel> read_levels(const Value& section, const JobConfig& job) {
  std::vector<ScenarioLevel> out;
  for (const Value& item : section.list()) {
    const Map entry(item, {"group", "select", "fraction"});
    ScenarioLevel level;
    if (auto v = entry.get("group")) {
      level.group = v->text();
      const bool known = std::any_of(job.groups.begin(), job.groups.end(),
                                     [&](const LuminaireGroup& g) { return g.name == level.group; });
      if (!known)
        v->fail(job.groups.empty() ? "names a luminaire group, and this job has none (leave group out: every luminaire)"
                                   : "no luminaire group of this name in luminaires.groups");
    }
    if (auto v = entry.get("select")) level.pick = read_pick(*v);
    level.fraction = entry.require("fraction").number_in(0.0, 1.0, false, "[0, 1]");
    out.push_back(level);
  }
  return out;
}

// A scenario's goal lines: each names an area of the job's goals (its name) and one or
// more illuminance metrics, targets maintained as every goal's.
void read_scenario_goals(const Value& section, const JobConfig& job, ScenarioSpec& scenario) {
  const std::vector<Value> entries = section.list();
  if (entries.empty()) section.fail("must list at least one goal");
  for (const Value& item : entries) {
    std::vector<std::string> keys{"goal"};
    for (const MetricRule& r : metric_rules()) keys.emplace_back(r.key);
    const Map entry(item, keys);
    const Value area = entry.require("goal");
    const std::string name = area.text();
    const auto goal = std::find_if(job.goals.begin(), job.goals.end(), [&](const GoalSetting& g) { return g.name == name; });
    if (goal == job.goals.end()) area.fail("no goal of this name in goals (a scenario's goal is judged over a goal's area)");
    bool any = false;
    for (const MetricRule& rule : metric_rules()) {
      auto v = entry.get(std::string(rule.key));
      if (!v) continue;
      if (rule.area == AreaKind::glare) v->fail("a scenario judges illuminance; UGR is judged for the normal lighting");
      // The goal's name must have an area of the kind this metric is measured over.
      const bool laid = std::any_of(job.goals.begin(), job.goals.end(), [&](const GoalSetting& g) {
        return g.name == name && metric_rule(g.metric).area == rule.area;
      });
      if (!laid && rule.area == AreaKind::cylindrical)
        v->fail("is measured over a goal's cylinders: name a goal with a cylindrical metric");
      if (!laid) v->fail("goal '" + name + "' has no illuminance area (only cylinders or observers)");
      const double target = v->number();
      if (const std::string broken = target_rule(rule.metric, target); !broken.empty()) v->fail(broken);
      scenario.goals.push_back({name, rule.metric, target});
      any = true;
    }
    if (!any) item.fail("needs at least one of average_lux, min_lux, max_lux, uniformity, cylindrical_lux");
  }
}

}  // namespace

void read_scenarios(const Value& section, JobConfig& job) {
  const std::vector<Value> entries = section.list();
  if (entries.empty()) section.fail("must list at least one scenario");
  if (!job.search && job.groups.empty()) section.fail("scenarios are states of the layout a job searches (luminaires.mounting_surface or groups)");
  for (const Value& item : entries) {
    const Map entry(item, {"name", "light", "fraction", "levels", "fixed_fraction", "goals"});
    ScenarioSpec s;
    s.loc = item.loc();
    const Value name = entry.require("name");
    s.name = name.text();
    if (s.name.empty()) name.fail("must not be empty");
    for (const ScenarioSpec& other : job.scenarios)
      if (other.name == s.name) name.fail("scenario '" + s.name + "' is already defined");
    if (auto v = entry.get("light")) {
      const std::string light = v->text();
      if (light == "total") s.light = LightCounted::total;
      else if (light == "direct") s.light = LightCounted::direct;
      else v->fail("must be total (every reflection) or direct (straight from the luminaires)");
    }
    if (auto v = entry.get("fraction")) s.fraction = v->number_in(0.0, 1.0, false, "[0, 1]");
    if (auto v = entry.get("levels")) s.levels = read_levels(*v, job);
    if (auto v = entry.get("fixed_fraction")) s.fixed_fraction = v->number_in(0.0, 1.0, false, "[0, 1]");
    read_scenario_goals(entry.require("goals"), job, s);
    job.scenarios.push_back(std::move(s));
  }
}

}  // namespace ilp::config_yaml
