#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "core/base/error.h"
#include "output/atomic_file.h"
#include "output/result_record.h"

namespace ilp {
namespace {

// Keys in the order written, so the file reads top-down like the printed report.
using json = nlohmann::ordered_json;

json line_json(const VerdictLine& g) {
  json line = {{"kind", g.kind},   {"name", g.name},       {"surfaces", g.surfaces}, {"grid", g.grid},
               {"metric", g.metric}, {"unit", g.unit},     {"rule", g.rule},         {"target", g.target}};
  if (g.rule == "in") line["target_max"] = g.target_max;
  line["predicted"] = g.predicted;
  line["verified"] = g.verified ? json(*g.verified) : json(nullptr);
  line["met"] = g.met;
  line["fails_only_on_verification"] = g.fails_only_on_verification;
  line["tolerance"] = g.tolerance;
  line["relative_error"] = g.relative_error ? json(*g.relative_error) : json(nullptr);
  line["margin"] = g.margin;
  return line;
}

json lines_json(const std::vector<VerdictLine>& lines) {
  json out = json::array();
  for (const VerdictLine& l : lines) out.push_back(line_json(l));
  return out;
}

json variant_json(const VariantRecord& v) {
  return {{"product", v.product},     {"rotation_deg", v.rotation_deg}, {"summary", v.summary},
          {"searched", v.searched},   {"chosen", v.chosen},             {"luminaires", v.luminaires},
          {"power_w", v.power_w},     {"all_met", v.all_met},           {"goals", lines_json(v.goals)},
          {"constraints", lines_json(v.constraints)}};
}

json to_json(const ResultRecord& r) {
  json j;
  j["program_version"] = r.program_version;
  j["config"] = r.config;
  j["objective"] = r.objective;
  j["layout"] = {{"family", r.layout_family}, {"arrangement", r.arrangement}, {"spacing_m", {r.spacing_x_m, r.spacing_y_m}}};
  j["luminaires"] = json::array();
  for (const LuminaireRecord& l : r.luminaires)
    j["luminaires"].push_back({{"id", l.id},
                               {"product", l.product},
                               {"x_m", l.x_m},
                               {"y_m", l.y_m},
                               {"z_m", l.z_m},
                               {"rotation_deg", l.rotation_deg},
                               {"tilt_deg", l.tilt_deg},
                               {"flux_lm", l.flux_lm},
                               {"power_w", l.power_w},
                               {"above_floor_m", l.above_floor_m ? json(*l.above_floor_m) : json(nullptr)}});
  for (std::size_t k = 0; k < r.luminaires.size(); ++k)
    if (!r.luminaires[k].group.empty()) j["luminaires"][k]["group"] = r.luminaires[k].group;
  j["bill_of_materials"] = json::array();
  for (const BillLine& b : r.bill_of_materials)
    j["bill_of_materials"].push_back({{"product", b.product},
                                      {"source", b.source},
                                      {"count", b.count},
                                      {"rated_flux_lm", b.rated_flux_lm},
                                      {"unit_power_w", b.unit_power_w},
                                      {"output_fraction", b.output_fraction},
                                      {"total_power_w", b.total_power_w}});
  for (std::size_t k = 0; k < r.bill_of_materials.size(); ++k)
    if (!r.bill_of_materials[k].group.empty()) j["bill_of_materials"][k]["group"] = r.bill_of_materials[k].group;
  j["variants"] = json::array();
  for (const VariantRecord& v : r.variants) j["variants"].push_back(variant_json(v));
  j["files"] = r.files;
  j["goals"] = lines_json(r.goals);
  j["constraints"] = lines_json(r.constraints);
  if (!r.scenarios.empty()) {
    j["scenarios"] = json::array();
    for (const ScenarioRecord& s : r.scenarios)
      j["scenarios"].push_back({{"name", s.name}, {"light", s.light}, {"lit", s.lit}, {"luminaires", s.luminaires},
                                {"power_w", s.power_w}, {"all_met", s.all_met}, {"goals", lines_json(s.goals)}});
  }
  j["margin_floor"] = r.margin_floor;
  j["power_w"] = r.power_w;
  j["mounting_area_m2"] = r.mounting_area_m2;
  j["power_density_w_per_m2"] = r.power_density_w_per_m2;
  j["floor_area_m2"] = r.floor_area_m2;
  j["floor_area_source"] = r.floor_area_source;
  j["power_density_w_per_m2_per_100_lx"] = r.power_density_w_per_m2_per_100_lx;
  j["maintenance_factor"] = r.maintenance_factor;
  j["grids"] = json::array();
  auto values = [](const GridValues& v) {
    return json{{"average_lux", v.average_lux}, {"min_lux", v.min_lux}, {"max_lux", v.max_lux}, {"uniformity", v.uniformity}};
  };
  for (const GridRecord& g : r.grids)
    j["grids"].push_back({{"name", g.name}, {"points", g.points}, {"area_m2", g.area_m2}, {"spacing_m", g.spacing_m},
                          {"inside_solid", g.inside_solid}, {"verified", g.verified}, {"initial", values(g.initial)},
                          {"maintained", values(g.maintained)}});
  if (r.energy) {
    const EnergyRecord& e = *r.energy;
    j["energy"] = {{"building_type", e.building_type},
                   {"assumed", e.assumed},
                   {"hours_day_h", e.hours_day_h},
                   {"hours_night_h", e.hours_night_h},
                   {"occupancy_factor", e.occupancy_factor},
                   {"daylight_factor", e.daylight_factor},
                   {"constant_illuminance_factor", e.constant_illuminance_factor},
                   {"parasitic_kwh_per_m2", e.parasitic_kwh_per_m2},
                   {"installed_power_w", e.installed_power_w},
                   {"area_m2", e.area_m2},
                   {"lighting_kwh", e.lighting_kwh},
                   {"parasitic_kwh", e.parasitic_kwh},
                   {"total_kwh", e.total_kwh},
                   {"leni_kwh_per_m2", e.leni_kwh_per_m2}};
  }
  if (r.room) {
    json surfaces = json::array();
    for (const SurfaceRecord& s : r.room->surfaces)
      surfaces.push_back({{"name", s.name}, {"area_m2", s.area_m2}, {"reflectance", s.reflectance},
                          {"bottom_m", s.bottom_m}, {"top_m", s.top_m}});
    j["room"] = {{"mesh", r.room->mesh},
                 {"size_m", {r.room->length_x_m, r.room->width_y_m, r.room->height_z_m}},
                 {"floor_z_m", r.room->floor_z_m ? json(*r.room->floor_z_m) : json(nullptr)},
                 {"surfaces", surfaces}};
  }
  j["fixed_flux_lm"] = r.fixed_flux_lm;
  j["feasible"] = r.feasible;
  j["all_met"] = r.all_met;
  if (!r.no_layout.empty()) j["no_layout"] = r.no_layout;
  j["flux_correction"] = r.flux_correction;
  j["flux_correction_limited"] = r.flux_correction_limited;
  j["verification"] = {{"method", r.verification}, {"rays_per_patch", r.verification_rays_per_patch}};
  if (r.verification_indirect_rays_per_patch > 0) {
    j["verification"]["indirect_rays_per_patch"] = r.verification_indirect_rays_per_patch;
    j["verification"]["first_indirect_rays"] = r.verification_first_indirect_rays;
    j["verification"]["refinement_change"] = r.verification_refinement_change;
  }
  if (r.verification_decisive_points > 0) {
    j["verification"]["decisive_points"] = r.verification_decisive_points;
    j["verification"]["decisive_rays"] = r.verification_decisive_rays;
    j["verification"]["dominant_patches"] = r.verification_dominant_patches;
    j["verification"]["dominant_rays"] = r.verification_dominant_rays;
  }
  j["sample_size"] = r.sample_size;
  j["population"] = r.population;
  j["patches"] = r.patches;
  j["candidates"] = r.candidates;
  j["seed"] = r.seed;
  j["optimizer_seed"] = r.optimizer_seed;
  j["evaluations"] = r.evaluations;
  j["searches"] = r.searches;
  j["direct_checks"] = r.direct_checks;
  j["direct_check_note"] = r.direct_check_note;
  j["calibration"] = r.calibration;
  j["time_limited"] = r.time_limited;
  j["search_max_seconds"] = r.search_max_seconds > 0.0 ? json(r.search_max_seconds) : json(nullptr);
  j["depends_on_machine"] = r.search_max_seconds > 0.0;
  j["attempts"] = json::array();
  for (const AttemptRecord& a : r.attempts)
    j["attempts"].push_back({{"luminaires", a.luminaires}, {"evaluations", a.evaluations}, {"feasible", a.feasible},
                             {"power_w", a.power_w}, {"global_stop", a.global_stop}, {"local_stop", a.local_stop},
                             {"arrangement", a.arrangement}});
  return j;
}

json timings_to_json(const ResultRecord& r) {
  json j;
  j["timings_s"] = json::object();
  for (const auto& [phase, seconds] : r.timings_s) j["timings_s"][phase] = seconds;
  if (!r.verification_parts_s.empty()) {
    j["verification_parts_s"] = json::object();
    for (const auto& [part, seconds] : r.verification_parts_s) j["verification_parts_s"][part] = seconds;
  }
  j["attempts_s"] = json::array();
  for (const AttemptRecord& a : r.attempts) j["attempts_s"].push_back(a.seconds);
  return j;
}

// Times from `j` (timings.json, or an older result.json that held them) into r.
void read_timings(const json& j, ResultRecord& r) {
  if (j.contains("timings_s")) {
    r.timings_s.clear();
    for (const auto& [phase, seconds] : j.at("timings_s").items()) r.timings_s.emplace_back(phase, seconds.get<double>());
  }
  if (j.contains("verification_parts_s")) {
    r.verification_parts_s.clear();
    for (const auto& [part, seconds] : j.at("verification_parts_s").items())
      r.verification_parts_s.emplace_back(part, seconds.get<double>());
  }
  if (j.contains("attempts_s")) {
    const json& seconds = j.at("attempts_s");
    for (std::size_t a = 0; a < std::min(seconds.size(), r.attempts.size()); ++a) r.attempts[a].seconds = seconds[a].get<double>();
  }
}

// A goal or constraint line; files before constraints and margins lack their keys.
VerdictLine line_from_json(const json& g) {
  VerdictLine goal;
  goal.kind = g.value("kind", std::string("goal"));
  goal.name = g.at("name").get<std::string>();
  goal.surfaces = g.value("surfaces", std::vector<std::string>());
  goal.grid = g.value("grid", std::string());
  goal.metric = g.at("metric").get<std::string>();
  goal.unit = g.at("unit").get<std::string>();
  goal.rule = g.value("rule", std::string());
  goal.target = g.at("target").get<double>();
  goal.target_max = g.value("target_max", 0.0);
  goal.predicted = g.at("predicted").get<double>();
  if (!g.at("verified").is_null()) goal.verified = g.at("verified").get<double>();
  goal.met = g.at("met").get<bool>();
  goal.fails_only_on_verification = g.value("fails_only_on_verification", false);
  goal.tolerance = g.at("tolerance").get<double>();
  if (g.contains("relative_error") && g.at("relative_error").is_number())
    goal.relative_error = g.at("relative_error").get<double>();
  goal.margin = g.value("margin", 0.0);
  return goal;
}

std::vector<VerdictLine> lines_from_json(const json& j, const char* key) {
  std::vector<VerdictLine> out;
  if (j.contains(key))
    for (const json& l : j.at(key)) out.push_back(line_from_json(l));
  return out;
}

// A variant: an object, or (files before variant tables) its summary line alone.
VariantRecord variant_from_json(const json& v) {
  VariantRecord out;
  if (v.is_string()) {
    out.summary = v.get<std::string>();
    return out;
  }
  out.product = v.at("product").get<std::string>();
  out.rotation_deg = v.at("rotation_deg").get<double>();
  out.summary = v.at("summary").get<std::string>();
  out.searched = v.at("searched").get<bool>();
  out.chosen = v.at("chosen").get<bool>();
  out.luminaires = v.at("luminaires").get<int>();
  out.power_w = v.at("power_w").get<double>();
  out.all_met = v.at("all_met").get<bool>();
  out.goals = lines_from_json(v, "goals");
  out.constraints = lines_from_json(v, "constraints");
  return out;
}

ResultRecord from_json(const json& j) {
  ResultRecord r;
  r.program_version = j.at("program_version").get<std::string>();
  r.config = j.at("config").get<std::string>();
  r.objective = j.at("objective").get<std::string>();
  if (j.contains("layout")) {
    const json& layout = j.at("layout");
    r.layout_family = layout.value("family", std::string());
    r.arrangement = layout.value("arrangement", std::string());
    const std::vector<double> spacing = layout.value("spacing_m", std::vector<double>{0.0, 0.0});
    if (spacing.size() == 2) {
      r.spacing_x_m = spacing[0];
      r.spacing_y_m = spacing[1];
    }
  }
  for (const json& l : j.at("luminaires"))
    r.luminaires.push_back({l.at("id").get<std::string>(), l.at("x_m").get<double>(), l.at("y_m").get<double>(),
                            l.at("z_m").get<double>(), l.at("flux_lm").get<double>(), l.at("power_w").get<double>(),
                            l.value("product", std::string()), l.value("rotation_deg", 0.0),
                            l.contains("above_floor_m") && l.at("above_floor_m").is_number()
                                ? std::optional<double>(l.at("above_floor_m").get<double>())
                                : std::nullopt,
                            l.value("tilt_deg", 0.0), l.value("group", std::string())});
  if (j.contains("bill_of_materials"))
    for (const json& b : j.at("bill_of_materials"))
      r.bill_of_materials.push_back({b.at("product").get<std::string>(), b.at("source").get<std::string>(),
                                     b.at("count").get<int>(), b.at("rated_flux_lm").get<double>(),
                                     b.at("unit_power_w").get<double>(), b.at("output_fraction").get<double>(),
                                     b.at("total_power_w").get<double>(), b.value("group", std::string())});
  if (j.contains("variants"))
    for (const json& v : j.at("variants")) r.variants.push_back(variant_from_json(v));
  r.files = j.value("files", std::vector<std::string>());
  (void)j.at("goals");  // a result has goals (the error names the key)
  r.goals = lines_from_json(j, "goals");
  r.constraints = lines_from_json(j, "constraints");
  if (j.contains("scenarios"))
    for (const json& s : j.at("scenarios"))
      r.scenarios.push_back({s.at("name").get<std::string>(), s.at("light").get<std::string>(), s.at("lit").get<int>(),
                             s.at("luminaires").get<int>(), s.at("power_w").get<double>(), s.at("all_met").get<bool>(),
                             lines_from_json(s, "goals")});
  r.margin_floor = j.value("margin_floor", 0.0);
  r.power_w = j.at("power_w").get<double>();
  r.mounting_area_m2 = j.at("mounting_area_m2").get<double>();
  r.power_density_w_per_m2 = j.at("power_density_w_per_m2").get<double>();
  // Results written before calculation grids lack these keys.
  r.floor_area_m2 = j.value("floor_area_m2", r.mounting_area_m2);
  r.floor_area_source = j.value("floor_area_source", std::string("mounting surface"));
  r.power_density_w_per_m2_per_100_lx = j.value("power_density_w_per_m2_per_100_lx", 0.0);
  r.maintenance_factor = j.value("maintenance_factor", 1.0);
  auto values = [](const json& v) {
    return GridValues{v.at("average_lux").get<double>(), v.at("min_lux").get<double>(), v.at("max_lux").get<double>(),
                      v.at("uniformity").get<double>()};
  };
  if (j.contains("grids"))
    for (const json& g : j.at("grids"))
      r.grids.push_back({g.at("name").get<std::string>(), g.at("points").get<int>(), g.at("area_m2").get<double>(),
                         g.at("spacing_m").get<double>(), g.at("inside_solid").get<int>(), g.at("verified").get<bool>(),
                         values(g.at("initial")), values(g.at("maintained"))});
  if (j.contains("energy")) {
    const json& e = j.at("energy");
    r.energy = EnergyRecord{e.at("building_type").get<std::string>(), e.at("assumed").get<bool>(),
                            e.at("hours_day_h").get<double>(), e.at("hours_night_h").get<double>(),
                            e.at("occupancy_factor").get<double>(), e.at("daylight_factor").get<double>(),
                            e.at("constant_illuminance_factor").get<double>(), e.at("parasitic_kwh_per_m2").get<double>(),
                            e.at("installed_power_w").get<double>(), e.at("area_m2").get<double>(),
                            e.at("lighting_kwh").get<double>(), e.at("parasitic_kwh").get<double>(),
                            e.at("total_kwh").get<double>(), e.at("leni_kwh_per_m2").get<double>()};
  }
  if (j.contains("room")) {
    const json& room = j.at("room");
    RoomRecord rr;
    rr.mesh = room.at("mesh").get<std::string>();
    rr.length_x_m = room.at("size_m").at(0).get<double>();
    rr.width_y_m = room.at("size_m").at(1).get<double>();
    rr.height_z_m = room.at("size_m").at(2).get<double>();
    if (room.at("floor_z_m").is_number()) rr.floor_z_m = room.at("floor_z_m").get<double>();
    for (const json& s : room.at("surfaces"))
      rr.surfaces.push_back({s.at("name").get<std::string>(), s.at("area_m2").get<double>(),
                             s.at("reflectance").get<double>(), s.at("bottom_m").get<double>(),
                             s.at("top_m").get<double>()});
    r.room = rr;
  }
  r.fixed_flux_lm = j.at("fixed_flux_lm").get<double>();
  r.feasible = j.at("feasible").get<bool>();
  r.all_met = j.at("all_met").get<bool>();
  r.no_layout = j.value("no_layout", std::string());
  r.flux_correction = j.at("flux_correction").get<double>();
  r.flux_correction_limited = j.at("flux_correction_limited").get<bool>();
  r.verification = j.at("verification").at("method").get<std::string>();
  r.verification_rays_per_patch = j.at("verification").at("rays_per_patch").get<int>();
  r.verification_indirect_rays_per_patch = j.at("verification").value("indirect_rays_per_patch", 0);
  r.verification_first_indirect_rays = j.at("verification").value("first_indirect_rays", 0);
  r.verification_refinement_change = j.at("verification").value("refinement_change", 0.0);
  r.verification_decisive_points = j.at("verification").value("decisive_points", 0);
  r.verification_decisive_rays = j.at("verification").value("decisive_rays", 0);
  r.verification_dominant_patches = j.at("verification").value("dominant_patches", 0);
  r.verification_dominant_rays = j.at("verification").value("dominant_rays", 0);
  r.sample_size = j.at("sample_size").get<int>();
  r.population = j.at("population").get<int>();
  r.patches = j.at("patches").get<int>();
  r.candidates = j.at("candidates").get<int>();
  r.seed = j.at("seed").get<unsigned long long>();
  r.optimizer_seed = j.at("optimizer_seed").get<unsigned long long>();
  r.evaluations = j.at("evaluations").get<int>();
  r.searches = j.at("searches").get<int>();
  if (j.contains("direct_checks")) r.direct_checks = j.at("direct_checks").get<int>();
  if (j.contains("direct_check_note")) r.direct_check_note = j.at("direct_check_note").get<std::string>();
  r.calibration = j.at("calibration").get<std::vector<std::string>>();
  r.time_limited = j.at("time_limited").get<bool>();
  if (j.contains("search_max_seconds") && j.at("search_max_seconds").is_number())
    r.search_max_seconds = j.at("search_max_seconds").get<double>();
  for (const json& a : j.at("attempts"))
    r.attempts.push_back({a.at("luminaires").get<int>(), a.at("evaluations").get<int>(), a.value("seconds", 0.0),
                          a.at("feasible").get<bool>(), a.at("power_w").get<double>(),
                          a.at("global_stop").get<std::string>(), a.at("local_stop").get<std::string>(),
                          a.value("arrangement", std::string())});
  read_timings(j, r);  // a result.json written before timings.json
  return r;
}

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

// Lux and lumens with one decimal, metres and ratios (uniformity) with three, whole
// numbers (counts) as they are.
std::string line_number(const VerdictLine& g, double v) {
  if (g.unit.empty() && v == std::round(v) && std::abs(v) < 1e9 && (g.kind == "constraint" || v == 0.0))
    return fixed(v, 0);
  return fixed(v, g.unit == "lx" || g.unit == "lm" ? 1 : 3);
}
std::string goal_value(const GoalRecord& g, double v) { return line_number(g, v); }

// A line's rule, for files written before lines had one: a maximum is an upper bound.
std::string rule_of(const VerdictLine& g) {
  if (!g.rule.empty()) return g.rule;
  return g.metric == "maximum" ? "<=" : ">=";
}

std::string with_unit(const VerdictLine& g, double v) { return line_number(g, v) + (g.unit.empty() ? "" : " " + g.unit); }

// "goal metric" for goals, the key for constraints.
std::string line_label(const VerdictLine& g) { return g.kind == "constraint" ? g.name : g.name + " " + g.metric; }

// The target column: ">= 2.000", "<= 0", "8 .. 12", "= 500.0".
std::string target_text(const VerdictLine& g) {
  const std::string rule = rule_of(g);
  if (rule == "in")
    return g.target == g.target_max ? line_number(g, g.target) : line_number(g, g.target) + " .. " + line_number(g, g.target_max);
  return rule + " " + line_number(g, g.target);
}

}  // namespace

std::string verdict_value_text(const VerdictLine& line, double value) {
  return with_unit(line, value);
}
std::string verdict_target_text(const VerdictLine& line) {
  return target_text(line) + (line.unit.empty() ? "" : " " + line.unit);
}

std::string failing_line_text(const VerdictLine& g) {
  const std::string rule = rule_of(g);
  const double v = g.value();
  std::string text = line_label(g) + " " + with_unit(g, v);
  auto by = [&](const char* relation, double bound) {
    text += std::string(" ") + relation + " " + with_unit(g, bound) + " (by " + with_unit(g, std::abs(v - bound));
    if (g.unit == "lx" && bound > 0.0) text += ", " + fixed(100.0 * std::abs(v - bound) / bound, 1) + " %";
    text += ")";
  };
  if (rule == "=") {
    text += ", " + fixed(g.target > 0.0 ? 100.0 * std::abs(v - g.target) / g.target : 0.0, 1) + " % off " +
            with_unit(g, g.target) + " (tolerance " + fixed(100.0 * g.tolerance, 1) + " %)";
  } else if (rule == "<=" || (rule == "in" && v > g.target_max)) {
    by(">", rule == "in" ? g.target_max : g.target);
  } else {
    by("<", g.target);
  }
  if (g.fails_only_on_verification) text += " on verification only";
  return text;
}

std::string failing_lines_text(const ResultRecord& r) {
  std::string out;
  for (const std::vector<VerdictLine>* lines : {&r.goals, &r.constraints})
    for (const VerdictLine& l : *lines)
      if (!l.met) out += (out.empty() ? "" : "; ") + failing_line_text(l);
  for (const ScenarioRecord& s : r.scenarios)  // named by their scenario
    for (const VerdictLine& l : s.goals)
      if (!l.met) out += (out.empty() ? "" : "; ") + ("scenario '" + s.name + "': ") + failing_line_text(l);
  return out;
}

void write_result_json(const std::string& path, const ResultRecord& result) {
  const json j = to_json(result);
  // Invalid UTF-8 (a name from a file) is replaced, not a throw after the whole run.
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2, ' ', false, json::error_handler_t::replace) << "\n"; });
}

void write_timings_json(const std::string& path, const ResultRecord& result) {
  const json j = timings_to_json(result);
  write_file_atomically(path, [&](std::ostream& out) { out << j.dump(2) << "\n"; });
}

std::string result_record_bytes(const ResultRecord& result) {
  json j;
  j["result"] = to_json(result);
  j["timings"] = timings_to_json(result);
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

ResultRecord result_record_from_bytes(const std::string& bytes) {
  try {
    const json j = json::parse(bytes);
    ResultRecord r = from_json(j.at("result"));
    read_timings(j.at("timings"), r);
    return r;
  } catch (const json::exception& e) {
    throw std::runtime_error(std::string("a room's record as received: ") + e.what());
  }
}

namespace {

// The JSON document at `path` (`what`: "result" or "timings", for messages) given to `use`.
template <class Use>
void read_json_file(const std::string& path, const char* what, const Use& use) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw std::runtime_error(path + ": is a folder, not a " + what + " file");
  if (const std::string why = not_a_regular_file(path, what); !why.empty()) throw std::runtime_error(why);
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the " + std::string(what) + " file");
  try {
    use(json::parse(in));
  } catch (const json::parse_error& e) {
    throw std::runtime_error(path + ": not valid JSON (byte " + std::to_string(e.byte) + "): " + e.what());
  } catch (const json::exception& e) {
    throw std::runtime_error(path + ": not an ilp " + std::string(what) + " file (" + std::string(e.what()) + ")");
  }
}

}  // namespace

ResultRecord read_result_json(const std::string& path) {
  ResultRecord r;
  read_json_file(path, "result", [&](const json& j) { r = from_json(j); });
  const std::filesystem::path timings = std::filesystem::path(path).parent_path() / "timings.json";
  std::error_code ec;
  if (std::filesystem::exists(timings, ec))
    read_json_file(timings.string(), "timings", [&](const json& j) { read_timings(j, r); });
  return r;
}

namespace {

// A regular layout's arrangements: the feasible ones, least power first (the cheapest
// eight), then the rest summed up by why, with the first of each (result.json keeps
// every one).
void print_arrangements(std::ostream& os, const std::vector<AttemptRecord>& attempts) {
  std::vector<const AttemptRecord*> feasible;
  std::vector<std::pair<std::string, std::pair<int, std::string>>> others;  // why, (count, first)
  for (const AttemptRecord& a : attempts) {
    if (a.arrangement.empty()) continue;
    if (a.evaluations > 0 && a.feasible) {
      feasible.push_back(&a);
      continue;
    }
    const std::string why = a.evaluations > 0 ? "infeasible as predicted" : a.global_stop.substr(0, a.global_stop.find(':'));
    const std::string first = a.arrangement + (a.evaluations > 0 ? "" : ": " + a.global_stop);
    auto it = std::find_if(others.begin(), others.end(), [&](const auto& o) { return o.first == why; });
    if (it == others.end()) others.push_back({why, {1, first}});
    else ++it->second.first;
  }
  std::stable_sort(feasible.begin(), feasible.end(), [](const AttemptRecord* a, const AttemptRecord* b) {
    return a->power_w < b->power_w;
  });
  constexpr std::size_t kShown = 8;
  for (std::size_t i = 0; i < std::min(kShown, feasible.size()); ++i)
    os << "  " << feasible[i]->arrangement << " (" << feasible[i]->luminaires << "): " << fixed(feasible[i]->power_w, 1)
       << " W as predicted\n";
  if (feasible.size() > kShown) os << "  ... and " << feasible.size() - kShown << " more meeting every goal as predicted\n";
  for (const auto& [why, first] : others)
    os << "  " << first.first << (first.first == 1 ? " arrangement " : " arrangements ") << why << ", e.g. "
       << first.second << "\n";
}

// Not met: the lines that fail, by name and by how much, then what kind of miss it is.
// Met exactly when every line is (result_mapping), so a "NOT MET" always names a line.
void print_verdict(std::ostream& os, const ResultRecord& r) {
  if (r.all_met) return;
  bool missed_as_predicted = false, scenario_missed = false;
  for (const std::vector<VerdictLine>* lines : {&r.goals, &r.constraints})
    for (const VerdictLine& l : *lines) missed_as_predicted = missed_as_predicted || (!l.met && !l.fails_only_on_verification);
  for (const ScenarioRecord& s : r.scenarios) scenario_missed = scenario_missed || !s.all_met;
  const std::string failing = failing_lines_text(r);
  os << "NOT MET: "
     << (failing.empty() ? "the result says not met, but every line is met (a result written by an older ilp?)" : failing)
     << "\n";
  if (!missed_as_predicted && scenario_missed)
    os << "NOT MET in a scenario: the layout meets its goals, but not every scenario's (the search places the layout "
          "for the goals; the scenarios are judged on it)\n";
  else if (!missed_as_predicted)
    os << "NOT MET on verification: the layout meets every goal as predicted, but not every goal as verified\n";
  else if (r.objective == "min_power")
    os << "INFEASIBLE: no layout found meets every goal and constraint; the closest found is shown\n";
  else
    os << "no layout found comes within the tolerance of every target and meets every constraint; the closest found "
          "is shown\n";
}

// The lines of one table: goals (target, predicted, verified, margin) or constraints
// (target, value).
void print_lines(std::ostream& os, const std::vector<VerdictLine>& lines, bool goals) {
  if (lines.empty()) return;
  if (goals)
    os << std::left << std::setw(30) << "goal" << std::right << std::setw(12) << "target" << std::setw(11) << "predicted"
       << std::setw(10) << "verified" << std::setw(9) << "margin" << "  status\n";
  else
    os << std::left << std::setw(30) << "constraint" << std::right << std::setw(16) << "target" << std::setw(12)
       << "value" << "  status\n";
  for (const VerdictLine& g : lines) {
    const std::string label = line_label(g) + (g.unit.empty() ? "" : " (" + g.unit + ")");
    std::string status = g.met ? "met" : "MISSED";
    const double value = g.value();
    if (!g.met && g.target > 0.0 && rule_of(g) != "in")
      status += " by " + fixed(100.0 * std::abs(value - g.target) / g.target, 1) + " %";
    else if (!g.met)
      status += ": " + failing_line_text(g);
    if (g.fails_only_on_verification) status += " (fails on verification only)";
    if (!goals) {
      os << std::left << std::setw(30) << label << std::right << std::setw(16) << target_text(g) << std::setw(12)
         << line_number(g, value) << "  " << status << "\n";
      continue;
    }
    const std::string margin = g.margin > 0.0 ? fixed(100.0 * g.margin, 2) + " %" : std::string("-");
    os << std::left << std::setw(30) << label << std::right << std::setw(12) << target_text(g) << std::setw(11)
       << goal_value(g, g.predicted) << std::setw(10) << (g.verified ? goal_value(g, *g.verified) : std::string("-"))
       << std::setw(9) << margin << "  " << status << "\n";
  }
}

// Each product variant tried, and for one not reported that was searched and missed, why.
void print_variants(std::ostream& os, const std::vector<VariantRecord>& variants) {
  if (variants.empty()) return;
  os << "\nvariants:\n";
  for (const VariantRecord& v : variants) {
    os << "  " << (v.chosen ? "* " : "  ") << v.summary << "\n";
    if (!v.searched || v.chosen || v.all_met) continue;
    for (const std::vector<VerdictLine>* lines : {&v.goals, &v.constraints})
      for (const VerdictLine& l : *lines)
        if (!l.met) os << "      not met: " << failing_line_text(l) << "\n";
  }
}

void print_result_text(std::ostream& os, const ResultRecord& r) {
  if (!r.no_layout.empty()) {
    os << "NO LAYOUT: " << r.no_layout << "\n";
    for (const VariantRecord& v : r.variants) os << "  " << v.summary << "\n";
    return;
  }
  print_verdict(os, r);
  os << (r.all_met ? "Optimal layout (" : "Closest layout found (") << r.objective << ", " << r.luminaires.size()
     << " luminaires";
  if (!r.arrangement.empty()) os << ": " << r.arrangement;
  if (!r.arrangement.empty() && (r.spacing_x_m > 0.0 || r.spacing_y_m > 0.0))  // (groups: in each group's arrangement)
    os << ", spacing " << fixed(r.spacing_x_m, 2) << " x " << fixed(r.spacing_y_m, 2) << " m";
  os << ")\n";
  bool products = false, heights = false;
  for (const LuminaireRecord& l : r.luminaires) {
    products = products || !l.product.empty();
    heights = heights || l.above_floor_m.has_value();
  }
  os << std::right << std::setw(6) << "id" << std::setw(9) << "x m" << std::setw(9) << "y m" << std::setw(9) << "z m";
  if (heights) os << std::setw(13) << "h floor m";
  os << std::setw(11) << "flux lm" << std::setw(10) << "power W";
  if (products) os << std::setw(7) << "rot °" << "  product";
  os << "\n";
  double flux = 0.0;
  for (const LuminaireRecord& l : r.luminaires) {
    os << std::setw(6) << l.id << std::setw(9) << fixed(l.x_m, 3) << std::setw(9) << fixed(l.y_m, 3) << std::setw(9)
       << fixed(l.z_m, 3);
    if (heights) os << std::setw(13) << (l.above_floor_m ? fixed(*l.above_floor_m, 3) : std::string("-"));
    os << std::setw(11) << fixed(l.flux_lm, 1) << std::setw(10) << fixed(l.power_w, 2);
    if (products) os << std::setw(7) << fixed(l.rotation_deg, 0) << "  " << l.product;
    os << "\n";
    flux += l.flux_lm;
  }
  if (!r.bill_of_materials.empty()) {
    os << "Bill of materials:\n";
    for (const BillLine& b : r.bill_of_materials)
      os << "  " << (b.group.empty() ? "" : "group " + b.group + ": ") << b.count << " x " << b.product << " (" << fixed(b.rated_flux_lm, 0) << " lm, "
         << fixed(b.unit_power_w, 1) << " W each" << (b.output_fraction < 1.0 - 1e-9 ? ", set to " + fixed(100.0 * b.output_fraction, 1) + " %" : "")
         << "; " << b.source << "): " << fixed(b.total_power_w, 1) << " W\n";
  }
  os << "Total power " << fixed(r.power_w, 1) << " W for " << fixed(flux, 0) << " lm; power density "
     << fixed(r.power_density_w_per_m2, 2) << " W/m² over " << fixed(r.floor_area_m2, 2) << " m² ("
     << r.floor_area_source << ")";
  if (r.power_density_w_per_m2_per_100_lx > 0.0)
    os << ", " << fixed(r.power_density_w_per_m2_per_100_lx, 2) << " W/m² per 100 lx";
  os << "\n";
  if (r.energy) {
    const EnergyRecord& e = *r.energy;
    os << "LENI " << fixed(e.leni_kwh_per_m2, 2) << " kWh/(m²·a) (EN 15193-1: " << fixed(e.total_kwh, 0)
       << " kWh/a over " << fixed(e.area_m2, 2) << " m²; " << e.building_type << (e.assumed ? " assumed" : "") << ", t_D "
       << fixed(e.hours_day_h, 0) << " h, t_N " << fixed(e.hours_night_h, 0) << " h, F_O " << fixed(e.occupancy_factor, 2)
       << ", F_D " << fixed(e.daylight_factor, 2) << ", F_C " << fixed(e.constant_illuminance_factor, 2) << ", parasitic "
       << fixed(e.parasitic_kwh_per_m2, 1) << " kWh/(m²·a))\n";
  }
  if (r.maintenance_factor != 1.0)
    os << "maintenance factor " << fixed(r.maintenance_factor, 2)
       << ": targets are maintained values; the luminaires are designed for initial = target / MF\n";
  if (r.fixed_flux_lm > 0.0)
    os << "(plus " << fixed(r.fixed_flux_lm, 0) << " lm of luminaires placed in the config, not counted above)\n";

  os << "\n";
  print_lines(os, r.goals, true);
  if (!r.constraints.empty()) os << "\n";
  print_lines(os, r.constraints, false);
  for (const ScenarioRecord& s : r.scenarios) {
    os << "\nScenario '" << s.name << "' (" << s.light << " light, " << s.lit << " of " << s.luminaires
       << " luminaires lit, " << fixed(s.power_w, 1) << " W): " << (s.all_met ? "met" : "NOT MET") << "\n";
    print_lines(os, s.goals, true);
  }
  if (!r.grids.empty()) os << "\n";
  print_grid_table(os, r.grids);
  os << "\nverification: ";
  if (r.verification == "none") os << "none (predicted values only)";
  else os << r.verification << ", " << r.verification_rays_per_patch << " rays per patch";
  if (r.verification_indirect_rays_per_patch > 0 && r.verification_indirect_rays_per_patch < r.verification_rays_per_patch) {
    os << " at goals, " << r.verification_indirect_rays_per_patch << " on the other patches' rows";
    if (r.verification_indirect_rays_per_patch > r.verification_first_indirect_rays)
      os << " (refined from " << r.verification_first_indirect_rays << ": the goals' values moved by at most "
         << fixed(100.0 * r.verification_refinement_change, 3) << " % at the last doubling)";
  }
  if (r.verification_decisive_points > 0)
    os << "; the " << r.verification_decisive_points << " grid points deciding a minimum or maximum gathered again with "
       << r.verification_decisive_rays << " rays, the " << r.verification_dominant_patches
       << " patches they gather most from solved with precise direct light and " << r.verification_dominant_rays
       << "-ray rows";
  if (r.flux_correction != 1.0)
    os << "; every flux scaled by " << fixed(r.flux_correction, 4) << " after verification";
  if (r.flux_correction_limited)
    os << " (the flux range allowed no more: the goals wanted another scale)";
  if (r.verification != "none" && r.margin_floor > 0.0)
    os << "\nmargin: each average and minimum goal the flux scale meets is kept at least " << fixed(100.0 * r.margin_floor, 2)
       << " % above its target (verification.margin), more where the verification's own error estimate (2 standard "
          "errors) is larger";
  os << "\noperator: k = " << r.sample_size << " of " << r.population << " reflecting patches (" << r.patches
     << " patches), " << r.candidates << " candidate positions, seed " << r.seed << "\n";
  os << "search: " << r.evaluations << " evaluations in " << r.searches << (r.searches == 1 ? " round" : " rounds")
     << ", optimizer seed " << r.optimizer_seed;
  if (r.search_max_seconds > 0.0)
    os << "; wall-clock limit " << fixed(r.search_max_seconds, 1) << " s (optimizer.max_seconds): the layout may depend on "
       << "the machine's speed and load" << (r.time_limited ? ", and the limit ended a stage" : "");
  os << "\n";
  if (r.direct_checks > 0)
    os << "  " << r.direct_checks << (r.direct_checks == 1 ? " arrangement" : " arrangements")
       << " checked against the luminaires' own direct light at the grid points"
       << (r.direct_check_note.empty() ? " (the blend's prediction held)" : "; first missed: " + r.direct_check_note)
       << "\n";
  for (const std::string& line : r.calibration) os << "  " << line << "\n";
  print_arrangements(os, r.attempts);
  for (const AttemptRecord& a : r.attempts) {
    if (!a.arrangement.empty()) continue;
    if (a.evaluations == 0 && a.global_stop == a.local_stop) {  // left out before any search: why
      os << "  " << a.luminaires << " luminaires: " << a.global_stop << "\n";
      continue;
    }
    os << "  " << a.luminaires << " luminaires: "
       << (a.feasible ? fixed(a.power_w, 1) + " W as searched" : std::string("infeasible as searched"))
       << ", " << a.evaluations << " evaluations" << (a.seconds > 0.0 ? " in " + fixed(a.seconds, 2) + " s" : "")
       << " (global: " << a.global_stop
       << "; local: " << a.local_stop << ")\n";
  }
  print_variants(os, r.variants);
  if (r.timings_s.empty()) return;  // a result.json without its timings.json
  os << "timings:";
  for (std::size_t k = 0; k < r.timings_s.size(); ++k)
    os << (k ? ", " : " ") << r.timings_s[k].first << " " << fixed(r.timings_s[k].second, 2) << " s";
  os << "\n";
}

}  // namespace

// Text from the job and vendors' files (names, keywords) reaches the terminal here:
// its control characters are shown escaped, never obeyed.
void print_result(std::ostream& os, const ResultRecord& r) {
  std::ostringstream text;
  print_result_text(text, r);
  os << printable(text.str(), true);
}

void print_grid_table(std::ostream& os, const std::vector<GridRecord>& grids, const std::string& basis) {
  if (grids.empty()) return;
  os << std::left << std::setw(20) << "grid" << std::right << std::setw(7) << "points" << std::setw(9)
     << "Em lx" << std::setw(9) << "Emin lx" << std::setw(9) << "Emax lx" << std::setw(7) << "U0" << "   maintained:"
     << std::setw(8) << "Em lx" << std::setw(9) << "Emin lx" << std::setw(9) << "Emax lx" << "\n";
  for (const GridRecord& g : grids)
    os << std::left << std::setw(20) << g.name << std::right << std::setw(7) << g.points << std::setw(9)
       << fixed(g.initial.average_lux, 1) << std::setw(9) << fixed(g.initial.min_lux, 1) << std::setw(9)
       << fixed(g.initial.max_lux, 1) << std::setw(7) << fixed(g.initial.uniformity, 3) << std::setw(21)
       << fixed(g.maintained.average_lux, 1) << std::setw(9) << fixed(g.maintained.min_lux, 1) << std::setw(9)
       << fixed(g.maintained.max_lux, 1) << "  (" << (basis.empty() ? (g.verified ? "verified" : "predicted") : basis) << ", initial | maintained)\n";
}

}  // namespace ilp
