#include "job/result_mapping.h"

#include "job/config.h"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <filesystem>
#include <limits>
#include <map>
#include <string_view>

#include "core/energy/leni.h"
#include "optimizer/goal_metrics.h"

namespace ilp {

RoomRecord room_record(const Scene& scene, std::optional<double> floor_z_m, const std::string& mesh_path) {
  RoomRecord room;
  room.mesh = std::filesystem::path(mesh_path).filename().string();
  room.floor_z_m = floor_z_m;
  const double base_z = floor_z_m.value_or(0.0);
  Eigen::AlignedBox3d bounds;
  struct Sums {
    double area = 0.0, weighted = 0.0;
    double bottom = std::numeric_limits<double>::infinity(), top = -std::numeric_limits<double>::infinity();
  };
  std::vector<Sums> sums(scene.surfaces.size());
  for (const Patch& p : scene.patches) {
    const Surface& surface = scene.surfaces[static_cast<std::size_t>(p.surface)];
    if (surface.is_luminaire() || surface.is_virtual) continue;
    Sums& s = sums[static_cast<std::size_t>(p.surface)];
    s.area += p.area_m2;
    s.weighted += p.area_m2 * p.reflectance.dot(kLuminanceWeights);
    for (const Eigen::Vector3d& v : p.vertices_m) {
      bounds.extend(v);
      s.bottom = std::min(s.bottom, v.z() - base_z);
      s.top = std::max(s.top, v.z() - base_z);
    }
  }
  if (!bounds.isEmpty()) {
    const Eigen::Vector3d size = bounds.sizes();
    room.length_x_m = size.x();
    room.width_y_m = size.y();
    room.height_z_m = size.z();
  }
  for (std::size_t k = 0; k < scene.surfaces.size(); ++k)
    if (sums[k].area > 0.0)
      room.surfaces.push_back({scene.surfaces[k].name, sums[k].area, sums[k].weighted / sums[k].area, sums[k].bottom,
                               sums[k].top});
  return room;
}

std::optional<EnergyRecord> energy_record(const EnergySettings& settings, double power_w, double area_m2,
                                          double maintenance_factor) {
  if (!(area_m2 > 0.0)) return std::nullopt;
  const std::optional<BuildingHours> row = find_building_type(settings.building_type);
  if (!row) throw std::invalid_argument("energy.building_type " + settings.building_type + ": unknown");
  LeniInputs in;
  in.installed_power_w = power_w;
  in.floor_area_m2 = area_m2;
  in.day_h = settings.hours_day.value_or(row->day_h);
  in.night_h = settings.hours_night.value_or(row->night_h);
  in.occupancy_factor = settings.occupancy_factor;
  in.daylight_factor = settings.daylight_factor;
  in.constant_illuminance = settings.constant_illuminance ? constant_illuminance_factor(maintenance_factor) : 1.0;
  in.parasitic_kwh_per_m2 = settings.parasitic_kwh_per_m2;
  const LeniResult r = compute_leni(in);
  return EnergyRecord{settings.building_type, !settings.given, in.day_h, in.night_h, in.occupancy_factor,
                      in.daylight_factor, in.constant_illuminance, in.parasitic_kwh_per_m2, power_w, area_m2,
                      r.lighting_kwh, r.parasitic_kwh, r.total_kwh, r.leni_kwh_per_m2};
}

// Product x count, watts each and in all.
std::vector<BillLine> bill_of_materials(const VariantPlan& plan, const JobOutcome& outcome) {
  if (outcome.luminaires.empty()) return {};
  if (!outcome.groups.empty()) {  // one line per group: its product at its one output
    std::vector<BillLine> lines;
    for (const OutcomeGroup& g : outcome.groups) {
      const ProductVariant& p = g.plan.product;
      BillLine line{p.product, std::filesystem::path(p.source).filename().string(), static_cast<int>(g.count),
                    p.rated_flux_lm, p.power_w, outcome.luminaires[g.first].flux_lm / p.rated_flux_lm, g.power_w, g.name};
      lines.push_back(line);
    }
    return lines;
  }
  const ProductVariant& p = plan.product;
  const SearchLuminaire& s = plan.search.luminaire;
  BillLine line;
  line.count = static_cast<int>(outcome.luminaires.size());
  line.total_power_w = outcome.power_w;
  line.product = p.product;
  // The file's name only: a report never shows the folders of the machine it ran on.
  line.source = std::filesystem::path(p.source).filename().string();
  line.rated_flux_lm = p.rated_flux_lm;
  line.unit_power_w = p.power_w;
  line.output_fraction = s.uniform_output ? outcome.luminaires.front().flux_lm / p.rated_flux_lm : 1.0;
  if (!s.uniform_output) line.product += " (each at its own flux)";
  return {line};
}

namespace {

std::string_view rule_text(ConstraintRule rule) {
  switch (rule) {
    case ConstraintRule::at_least: return ">=";
    case ConstraintRule::at_most: return "<=";
    case ConstraintRule::within: return "in";
  }
  return "";
}

}  // namespace

bool VerdictLines::all_met() const {
  auto met = [](const VerdictLine& l) { return l.met; };
  return std::all_of(goals.begin(), goals.end(), met) && std::all_of(constraints.begin(), constraints.end(), met);
}

VerdictLines verdict_lines(const JobGoals& goals, const JobOutcome& outcome) {
  VerdictLines out;
  for (std::size_t g = 0; g < outcome.goals.size(); ++g) {
    const GoalOutcome& o = outcome.goals[g];
    const MetricRule& rule = metric_rule(o.predicted.metric);
    VerdictLine rec;
    rec.name = o.predicted.name;
    rec.surfaces = goals.lines[g].surfaces;
    rec.grid = goals.lines[g].grid;
    rec.metric = std::string(rule.name);
    rec.unit = std::string(rule.unit);
    // The report shows maintained values, as the job states its targets.
    const double mf = rule.lux ? outcome.maintenance_factor : 1.0;
    rec.target = goals.lines[g].target;
    rec.predicted = o.predicted.value * mf;
    if (o.verified) rec.verified = o.verified->value * mf;
    rec.met = o.met;
    rec.fails_only_on_verification = o.fails_only_on_verification;
    rec.tolerance = o.tolerance;
    rec.rule = is_target_goal(goals.objective, o.predicted.metric) ? "=" : rule.lower_bound ? ">=" : "<=";
    rec.relative_error = o.relative_error;
    rec.margin = o.margin;
    out.goals.push_back(rec);
  }
  for (const ConstraintOutcome& c : outcome.constraints) {
    VerdictLine rec;
    rec.kind = "constraint";
    rec.name = c.name;
    rec.metric = c.what;
    rec.unit = c.unit;
    rec.rule = std::string(rule_text(c.rule));
    rec.target = c.target;
    rec.target_max = c.target_max;
    rec.predicted = c.value;
    rec.met = c.met;
    rec.tolerance = c.tolerance;
    out.constraints.push_back(rec);
  }
  return out;
}

std::vector<ScenarioRecord> scenario_records(const JobConfig& job, const JobOutcome& outcome) {
  std::vector<ScenarioRecord> out;
  for (std::size_t s = 0; s < outcome.scenarios.size(); ++s) {
    const ScenarioOutcome& o = outcome.scenarios[s];
    ScenarioRecord rec{o.name, o.light == LightCounted::direct ? "direct" : "total", static_cast<int>(o.lit),
                       static_cast<int>(outcome.luminaires.size()), o.power_w, o.all_met, {}};
    for (std::size_t g = 0; g < o.goals.size(); ++g) {
      const GoalOutcome& line = o.goals[g];
      const MetricRule& rule = metric_rule(line.predicted.metric);
      VerdictLine v;
      v.name = line.predicted.name;
      for (const GoalSetting& goal : job.goals)
        if (goal.name == v.name) {
          v.surfaces = goal.surfaces;
          v.grid = goal.grid;
          break;
        }
      v.metric = std::string(rule.name);
      v.unit = std::string(rule.unit);
      const double mf = rule.lux ? outcome.maintenance_factor : 1.0;
      v.target = job.scenarios.at(s).goals.at(g).target;
      v.predicted = line.predicted.value * mf;
      if (line.verified) v.verified = line.verified->value * mf;
      v.met = line.met;
      v.fails_only_on_verification = line.fails_only_on_verification;
      v.tolerance = line.tolerance;
      v.rule = rule.lower_bound ? ">=" : "<=";
      rec.goals.push_back(v);
    }
    out.push_back(std::move(rec));
  }
  return out;
}

VariantRecord variant_record(const PreparedJob& prepared, const JobGoals& goals, const JobOutcome& outcome,
                             const std::string& summary, bool chosen) {
  VariantRecord v;
  v.product = prepared.plan.product.product;
  v.rotation_deg = prepared.plan.product.rotation_deg;
  v.summary = summary;
  v.chosen = chosen;
  v.searched = !outcome.search.beaten;
  if (!v.searched) return v;
  v.luminaires = static_cast<int>(outcome.luminaires.size());
  v.power_w = outcome.power_w;
  const VerdictLines lines = verdict_lines(goals, outcome);
  v.all_met = lines.all_met();
  v.goals = lines.goals;
  v.constraints = lines.constraints;
  return v;
}

ResultRecord make_record(const std::string& program_version, const PreparedJob& prepared, const JobConfig& job, const JobOutcome& outcome,
                         const std::vector<GridRecord>& grids, const std::vector<std::pair<std::string, double>>& timings) {
  ResultRecord r;
  r.program_version = program_version;
  r.config = job.path;
  r.objective = std::string(objective_rule(job.objective).key);
  r.layout_family = std::string(layout_family_key(prepared.plan.search.layout.family));
  r.arrangement = outcome.search.best.arrangement;
  r.spacing_x_m = outcome.search.best.spacing_m.x();
  r.spacing_y_m = outcome.search.best.spacing_m.y();
  if (!outcome.groups.empty()) {  // "A: 4 x 3 field; B: 1 row of 3", the families likewise
    r.layout_family.clear();
    r.arrangement.clear();
    for (const OutcomeGroup& g : outcome.groups) {
      const std::string sep = r.arrangement.empty() ? "" : "; ";
      r.layout_family += sep + g.name + ": " + std::string(layout_family_key(g.plan.search.layout.family));
      std::ostringstream spacing;
      spacing << std::fixed << std::setprecision(2) << ", spacing " << g.spacing_m.x() << " x " << g.spacing_m.y() << " m";
      r.arrangement += sep + g.name + ": " + g.arrangement + spacing.str();
    }
    r.spacing_x_m = r.spacing_y_m = 0.0;
  }
  for (std::size_t j = 0; j < outcome.luminaires.size(); ++j) {
    const PlacedLuminaire& l = outcome.luminaires[j];
    const SearchLuminaire& luminaire = outcome_plan(prepared, outcome, j).search.luminaire;
    const OutcomeGroup* group = outcome_group(outcome, j);
    const std::optional<double> floor_z = prepared.model.floor_z_m;
    r.luminaires.push_back({outcome_luminaire_name(outcome, j), l.position_m.x(), l.position_m.y(), l.position_m.z(),
                            l.flux_lm, l.power_w, luminaire.product, luminaire.rotation_deg,
                            floor_z ? std::optional<double>(l.position_m.z() - *floor_z) : std::nullopt,
                            luminaire.tilt_deg, group ? group->name : std::string()});
  }
  const VerdictLines lines = verdict_lines(prepared.plan.goals, outcome);
  r.goals = lines.goals;
  r.constraints = lines.constraints;
  r.scenarios = scenario_records(job, outcome);
  r.margin_floor = outcome.margin_floor;
  r.power_w = outcome.power_w;
  r.mounting_area_m2 = outcome.mounting_area_m2;
  r.power_density_w_per_m2 = outcome.power_density_w_per_m2;
  r.floor_area_m2 = outcome.floor_area_m2;
  r.floor_area_source = outcome.floor_area_source;
  r.power_density_w_per_m2_per_100_lx = outcome.power_density_w_per_m2_per_100_lx;
  r.maintenance_factor = outcome.maintenance_factor;
  r.room = room_record(prepared.loaded.scene, prepared.model.floor_z_m, job.mesh_path);
  if (!outcome.luminaires.empty())
    r.energy = energy_record(job.energy, outcome.power_w, outcome.floor_area_m2, outcome.maintenance_factor);
  r.grids = grids;
  r.fixed_flux_lm = outcome.fixed_flux_lm;
  r.feasible = outcome.feasible;
  // Met exactly when every line is: never "not met" without a line that says why.
  r.all_met = lines.all_met() && std::all_of(r.scenarios.begin(), r.scenarios.end(),
                                             [](const ScenarioRecord& s) { return s.all_met; });
  r.flux_correction = outcome.flux_correction;
  r.flux_correction_limited = outcome.flux_correction_limited;
  r.verification = outcome.verification.method;
  r.verification_rays_per_patch = outcome.verification.rays_per_patch;
  r.verification_indirect_rays_per_patch = outcome.verification.indirect_rays_per_patch;
  r.verification_first_indirect_rays = outcome.verification.first_indirect_rays;
  r.verification_refinement_change = outcome.verification.refinement_change;
  r.verification_decisive_points = static_cast<int>(outcome.verification.decisive_points);
  r.verification_decisive_rays = outcome.verification.decisive_rays;
  r.verification_dominant_patches = static_cast<int>(outcome.verification.precise_patches);
  r.verification_dominant_rays = outcome.verification.precise_rays;
  r.sample_size = prepared.model.sample_size;
  r.population = static_cast<int>(prepared.model.stats.population);
  r.patches = static_cast<int>(prepared.loaded.scene.patches.size());
  r.candidates = static_cast<int>(prepared.model.grid.size());
  r.seed = job.form_factors.seed;
  r.optimizer_seed = job.optimizer.seed;
  r.evaluations = outcome.search.evaluations;
  r.searches = outcome.searches;
  r.direct_checks = outcome.search.direct_checks;
  r.direct_check_note = outcome.search.direct_check_note;
  r.calibration = outcome.calibration;
  r.time_limited = outcome.search.time_limited;
  r.search_max_seconds = job.optimizer.max_seconds;
  r.timings_s = timings;
  r.verification_parts_s = outcome.verification.parts_s;
  for (const CountAttempt& a : outcome.search.attempts)
    r.attempts.push_back(
        {a.luminaires, a.evaluations, a.seconds, a.feasible, a.power_w, a.global_stop, a.local_stop, a.arrangement});
  return r;
}

}  // namespace ilp
