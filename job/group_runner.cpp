#include "job/group_runner.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/base/error.h"
#include "core/glare/ugr.h"
#include "optimizer/group_search.h"
#include "optimizer/goal_metrics.h"

namespace ilp {
namespace {

// Every arrangement of every variant of one group, with its light.
struct GroupLights {
  std::vector<RegularLights> per_variant;  // in the group's prepared order
  std::vector<const PreparedJob*> variants;
};

std::string located_group(const PreparedGroups& groups, std::size_t g, const std::string& what) {
  const GroupName& group = groups.names[g];
  return located(group.loc, "luminaires.groups[" + std::to_string(g) + "] ('" + group.name + "'): " + what);
}

// Share of a goal's target a group must give some point of the goal's area directly,
// from one candidate at full output, to serve that goal.
constexpr double kServesShare = 0.01;

// Does the group serve a goal: does one of its candidates (any variant), at full output,
// light some row of a lux goal's area (average, minimum, cylindrical) directly with at
// least kServesShare of the goal's target? Light that reaches the goals only after
// reflection, or a trace of stray light, is not service.
bool serves_a_goal(const GroupLights& lights) {
  for (const PreparedJob* p : lights.variants) {
    const LightingModel& model = p->model;
    if (model.candidate_direct_lux_per_lm.size() == 0) continue;
    for (const GoalSpec& goal : p->plan.search.goals) {
      const MetricRule& rule = metric_rule(goal.metric);
      if (!rule.lux || !rule.lower_bound || !(goal.target > 0.0)) continue;
      const int a = find_goal_area(model, goal.name, rule.area);
      if (a < 0) continue;
      for (const Eigen::Index r : model.areas[static_cast<std::size_t>(a)].rows)
        if (model.candidate_direct_lux_per_lm.row(r).maxCoeff() * p->plan.search.luminaire.flux_max_lm >=
            kServesShare * goal.target)
          return true;
    }
  }
  return false;
}

std::vector<GroupLights> arrangement_lights(const PreparedGroups& groups) {
  std::vector<GroupLights> out(groups.names.size());
  for (std::size_t k = 0; k < groups.prepared.size(); ++k) {
    const PreparedJob& p = groups.prepared[k];
    GroupLights& g = out[groups.group[k]];
    g.variants.push_back(&p);
    g.per_variant.push_back(regular_arrangement_lights(p.model, p.plan.search));
  }
  for (std::size_t g = 0; g < out.size(); ++g) {
    if (!serves_a_goal(out[g]))
      throw ConfigError(located_group(groups, g, "serves no goal: none of its candidates, at full output, lights any point of a "
                                              "goal's area directly with 1 % of its target (move its zone or mounting toward "
                                              "the goals, or leave it out)"));
    bool any = false;
    for (const RegularLights& l : out[g].per_variant) any = any || !l.arrangements.empty();
    if (!any)
      throw ConfigError(located_group(groups, g, "no arrangement can be mounted or built; " +
                                                  out[g].per_variant.front().first_refusal));
  }
  return out;
}

std::vector<GroupChoices> group_choices(const PreparedGroups& groups, const std::vector<GroupLights>& lights) {
  std::vector<GroupChoices> out;
  for (std::size_t g = 0; g < lights.size(); ++g) {
    GroupChoices c{groups.names[g].name, {}};
    for (std::size_t v = 0; v < lights[g].variants.size(); ++v) {
      const SearchLuminaire& s = lights[g].variants[v]->plan.search.luminaire;
      const Eigen::Vector2d extent_m = 2.0 * s.type.half_footprint_m(s.rotation_deg, s.tilt_deg);
      for (const ArrangementLight& a : lights[g].per_variant[v].arrangements)
        c.options.push_back({static_cast<int>(v), &a, s.flux_min_lm, s.flux_max_lm, s.efficacy_lm_per_w, extent_m});
    }
    out.push_back(std::move(c));
  }
  return out;
}

// The outcome's luminaires and groups from the search's pair.
void place_groups(FoundLayout& out, const PreparedGroups& groups, const std::vector<GroupLights>& lights,
                  const std::vector<GroupChoices>& choices, const GroupSearchResult& found) {
  for (std::size_t g = 0; g < choices.size(); ++g) {
    const GroupPick& pick = found.groups[g];
    const GroupOption& option = choices[g].options[static_cast<std::size_t>(pick.option)];
    OutcomeGroup group;
    group.name = groups.names[g].name;
    group.label_prefix = std::string(1, static_cast<char>('A' + g));
    group.plan = lights[g].variants[static_cast<std::size_t>(option.variant)]->plan;
    group.first = out.luminaires.size();
    group.count = option.light->luminaires.size();
    group.arrangement = option.light->label;
    group.spacing_m = option.light->spacing_m;
    for (PlacedLuminaire l : option.light->luminaires) {
      l.flux_lm = pick.flux_lm;
      l.power_w = pick.flux_lm / option.efficacy_lm_per_w;
      out.luminaires.push_back(l);
    }
    out.groups.push_back(std::move(group));
  }
}

// The prepared variant a group of the outcome placed.
const PreparedJob& group_variant(const GroupLights& lights, const OutcomeGroup& group) {
  for (const PreparedJob* v : lights.variants)
    if (v->plan.product.product == group.plan.product.product &&
        v->plan.product.rotation_deg == group.plan.product.rotation_deg)
      return *v;
  throw std::logic_error("solve_groups: group '" + group.name + "' placed a variant it does not have");
}

// The layout's direct light at the goal rows as predicted: each luminaire through its
// own group's candidates' direct columns, plus the fixed sources'.
Eigen::VectorXd predicted_direct(const FoundLayout& out, const std::vector<GroupLights>& lights, const LightingModel& primary) {
  Eigen::VectorXd a = primary.fixed_direct_lux;
  for (std::size_t g = 0; g < out.groups.size(); ++g) {
    const LightingModel& model = group_variant(lights[g], out.groups[g]).model;
    for (std::size_t j = out.groups[g].first; j < out.groups[g].first + out.groups[g].count; ++j) {
      const PlacedLuminaire& l = out.luminaires[j];
      for (int k = 0; k < GridPoint::kMaxCandidates; ++k)
        if (l.blend.candidates[k] >= 0)
          a += (l.flux_lm * l.blend.weights[k]) * model.candidate_direct_lux_per_lm.col(l.blend.candidates[k]);
    }
  }
  return a.cwiseMax(0.0);
}

// Each group's constraint lines (count, distances, flux range), named by the group, and
// the power density of all groups together.
std::vector<ConstraintOutcome> group_constraints(const JobOutcome& out, const std::vector<GroupLights>& lights,
                                                 const PowerDensityCap& cap) {
  std::vector<ConstraintOutcome> lines;
  for (std::size_t g = 0; g < out.groups.size(); ++g) {
    const OutcomeGroup& group = out.groups[g];
    const PreparedJob* p = &group_variant(lights[g], group);
    const std::vector<PlacedLuminaire> own(out.luminaires.begin() + static_cast<std::ptrdiff_t>(group.first),
                                           out.luminaires.begin() + static_cast<std::ptrdiff_t>(group.first + group.count));
    for (ConstraintOutcome c : check_constraints(p->plan.search, p->model.grid.surface_box_m(),
                                                 p->plan.model.candidates.wall_distance_m, own)) {
      c.name = group.name + "." + c.name;
      lines.push_back(c);
    }
  }
  if (cap.max_w_per_m2) {
    double total_w = 0.0;
    for (const PlacedLuminaire& l : out.luminaires) total_w += l.power_w;
    const double value = cap.area_m2 > 0.0 ? total_w / cap.area_m2 : 0.0;
    ConstraintOutcome c{"max_power_density_w_per_m2", "power density of every group", "W/m²", ConstraintRule::at_most,
                        *cap.max_w_per_m2, 0.0, value, kConstraintLineTolerance, false};
    c.met = constraint_met(c.rule, c.target, 0.0, value, c.tolerance);
    lines.push_back(c);
  }
  return lines;
}

std::string search_line(const GroupSearchResult& r, const std::vector<GroupChoices>& choices) {
  std::ostringstream line;
  line << std::fixed << std::setprecision(2) << "groups searched together: ";
  for (std::size_t g = 0; g < choices.size(); ++g)
    line << (g ? " x " : "") << choices[g].options.size() << " arrangements of '" << choices[g].name << "'";
  std::size_t arrangements = 0;
  for (const GroupChoices& c : choices) arrangements += c.options.size();
  const char* what = choices.size() == 2 ? " pairs" : " combinations";
  line << " = " << r.pairs << what << "; " << arrangements << " arrangement lights, " << r.solved
       << " output solves (evaluations), " << r.pruned << what << " pruned by their least power, " << r.colliding
       << " colliding (a luminaire of one group on another's); " << r.seconds << " s";
  return line.str();
}

}  // namespace

PreparedGroups prepare_groups(const JobPlan& job, const RunOptions& run, const ProgressCallback& progress,
                              const std::string& cache_dir, const LogSink& log,
                              const std::function<void(const PreparedJob&)>& prepared_log) {
  PreparedGroups out;
  if (job.groups.empty()) return out;
  // The groups share the room: the model is read and its BVH built once, and every
  // group's variants costed on it first, so that the whole run's estimate comes before
  // any operator is built.
  SharedScene shared = load_shared_scene(job.scene, job.threads, run);
  log_shared_scene(shared, run, log);
  for (const GroupPlan& group : job.groups) require_search_surfaces(group.surfaces, job.scene.mesh_path, shared.loaded->scene);
  std::vector<std::vector<CostedGeometry>> costed;
  std::vector<std::vector<CostEstimate>> estimates;
  for (const GroupPlan& group : job.groups) {
    costed.push_back(cost_variants(shared, group.variants, run));
    estimates.push_back(estimates_of(costed.back()));
  }
  if (log) {
    std::ostringstream line;
    line << "estimate: the whole run, building every group's operators, searching them together and verifying "
            "once: about "
         << std::fixed << std::setprecision(1) << groups_run_seconds(estimates) << " s for its " << job.groups.size()
         << " groups";
    log(line.str());
  }
  for (std::size_t g = 0; g < job.groups.size(); ++g) {
    const GroupPlan& group = job.groups[g];
    out.names.push_back({group.name, group.loc});
    if (log) log("group '" + group.name + "'");
    for (PreparedJob& p : prepare_costed(shared, g + 1 == job.groups.size(), std::move(costed[g]), job.scene,
                                         group.variants, run, progress, cache_dir, log, prepared_log)) {
      out.prepared.push_back(std::move(p));
      out.group.push_back(g);
    }
  }
  return out;
}

VariantChoice solve_groups(const PreparedGroups& groups, const JobGoals& goals, const ProgressCallback& progress,
                           const LogSink& log) {
  const PreparedJob& primary = groups.prepared.front();
  if (!objective_rule(goals.objective).minimises_power)
    throw ConfigError(primary.plan.source + ": objective: luminaires.groups are searched for min_power only");
  const double mf = primary.plan.maintenance_factor;
  for (const PreparedJob& p : groups.prepared) {
    if (std::abs(p.plan.maintenance_factor - mf) > 1e-12)
      throw ConfigError(located_group(groups, groups.group[static_cast<std::size_t>(&p - groups.prepared.data())],
                                      "product '" + p.plan.product.product +
                                          "' has its own maintenance factor: every group's products must share one"));
    if (p.model.goal_rows() != primary.model.goal_rows())
      throw std::logic_error("solve_groups: the groups' models have different goal rows");
  }
  const std::vector<GroupLights> lights = arrangement_lights(groups);
  const std::vector<GroupChoices> choices = group_choices(groups, lights);
  const SearchSpec spec = search_at(primary.plan, goals);  // the goals at initial targets
  PowerDensityCap cap;
  std::tie(cap.area_m2, cap.area_source) = power_density_area(primary);
  cap.max_w_per_m2 = goals.max_power_density_w_per_m2;
  const GroupSearchResult found = search_groups(primary.model, {spec.goals, cap.max_power_w()}, choices);
  if (log) log(search_line(found, choices));
  if (found.groups.empty())
    throw ConfigError(primary.plan.source + ": luminaires.groups: no pair of arrangements can be placed together (in every pair a "
                                 "luminaire of one group lies on one of the other's; give the groups separate zones)");

  FoundLayout found_layout;
  place_groups(found_layout, groups, lights, choices, found);
  found_layout.light = {found.lux, found.eye_indirect_lux, found.glare};
  found_layout.direct_lux = predicted_direct(found_layout, lights, primary.model);
  found_layout.as_searched = found.goals;
  found_layout.feasible = found.feasible;
  for (std::size_t g = 0; g < found_layout.groups.size(); ++g)
    found_layout.models.insert(found_layout.models.end(), found_layout.groups[g].count,
                               &group_variant(lights[g], found_layout.groups[g]).model);
  VariantChoice choice;
  choice.outcome = verify_found(
      primary, spec, std::move(found_layout), cap,
      [&](const JobOutcome& o) { return group_constraints(o, lights, cap); }, progress);
  JobOutcome& out = choice.outcome;
  out.search.evaluations = static_cast<int>(found.solved);
  out.search.seconds = found.seconds;
  choice.variant = 0;
  choice.search_seconds = found.seconds;
  choice.verify_seconds = out.verify_seconds;
  return choice;
}

}  // namespace ilp
