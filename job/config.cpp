#include "job/setting_keys.h"
#include "job/config.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <utility>

#include "core/energy/leni.h"
#include "job/config_yaml.h"
#include "job/goal_rules.h"
#include "job/products.h"

namespace ilp {
namespace {

using namespace config_yaml;

// scene.regions: [{name, facing, height_m: [low, high], min_area_m2}, ...]
void read_regions(const Value& list, JobConfig& job) {
  std::set<std::string> names;
  for (const Value& item : list.list()) {
    const Map rule(item, {"name", "facing", "height_m", "min_area_m2"});
    RegionRule r;
    const Value name = rule.require("name");
    r.name = name.text();
    if (r.name.empty()) name.fail("must not be empty");
    if (!names.insert(r.name).second) name.fail("is used by another region");
    if (auto v = rule.get("facing")) {
      const std::string f = v->text();
      if (f == "up") r.facing = Facing::up;
      else if (f == "down") r.facing = Facing::down;
      else if (f == "vertical") r.facing = Facing::vertical;
      else if (f != "any") v->fail("must be up, down, vertical or any");
    }
    if (auto v = rule.get("height_m")) {
      if (!v->node().IsSequence() || v->node().size() != 2) v->fail("must be a list [low, high] in metres");
      r.height_m = {v->element(0).number(), v->element(1).number()};
      if (!(r.height_m->second >= r.height_m->first)) v->element(1).fail("must be >= height_m[0]");
    }
    if (auto v = rule.get("min_area_m2")) {
      r.min_area_m2 = v->number();
      if (r.min_area_m2 < 0.0) v->fail("must be >= 0");
    }
    r.loc = item.loc();
    job.surface_split.regions.push_back(r);
  }
  if (job.surface_split.regions.empty()) list.fail("must list at least one region");
}

// ---- scene

void read_scene(const Map& scene, JobConfig& job) {
  const Value mesh = scene.require("mesh");
  const std::filesystem::path base = std::filesystem::path(job.path).parent_path();
  job.mesh_path = (base / mesh.path()).lexically_normal().string();
  job.mesh_loc = mesh.loc();
  if (auto v = scene.get("up_axis")) {
    const std::string axis = Value::lower(v->text());
    if (axis == "y") job.scene.up_axis = UpAxis::y;
    else if (axis == "z") job.scene.up_axis = UpAxis::z;
    else v->fail("must be y or z");
    job.up_axis_loc = v->loc();
  }
  if (auto v = scene.get("scale_to_m")) {
    job.scene.scale_to_m = v->bounded(kMinScale, kMaxScale, " (metres per file unit)");
    job.scale_to_m_loc = v->loc();
  }
  if (auto v = scene.get("max_patch_edge_m")) {
    job.scene.max_patch_edge_m = v->bounded(kMinPatchEdge_m, kMaxLength_m, " m");
    job.max_patch_edge_loc = v->loc();
  }
  if (auto v = scene.get("surfaces_from")) {
    const std::string from = Value::lower(v->text());
    if (from == "group") job.mesh_read.surface_naming = SurfaceNaming::group;
    else if (from == "object") job.mesh_read.surface_naming = SurfaceNaming::object;
    else if (from == "material") job.mesh_read.surface_naming = SurfaceNaming::material;
    else if (from == "connected") job.surface_split.connected = true;  // groups, split into connected pieces
    else v->fail("must be group, object, material or connected");
  }
  if (auto v = scene.get("weld_tolerance_m")) job.surface_split.weld_tolerance_m = v->positive();
  if (auto v = scene.get("regions")) read_regions(*v, job);
  if (auto v = scene.get("reflectance")) {
    if (!v->node().IsMap()) v->fail("must map surface names to reflectances");
    reject_duplicate_keys(*v);
    for (const auto& item : v->node()) {
      const std::string surface = item.first.Scalar();
      const Value rho(item.second, v->key() + "." + surface, job.path);
      job.reflectance.push_back({surface, rho.reflectance(), rho.loc()});
    }
  }
  if (auto v = scene.get("default_reflectance")) job.default_reflectance = v->reflectance();
  if (auto v = scene.get("add_floor"))
    for (const Value& item : v->list()) {
      const Map floor(item, {"name", "rectangle_m", "z_m", "reflectance"});
      FloorSetting f;
      f.loc = item.loc();
      const Value name = floor.require("name");
      f.name = name.text();
      if (f.name.empty()) name.fail("must not be empty");
      for (const FloorSetting& other : job.add_floors)
        if (other.name == f.name) name.fail("a floor of this name is already added");
      const Value rect = floor.require("rectangle_m");
      if (!rect.node().IsSequence() || rect.node().size() != 2) rect.fail("must be two corners [[x0, y0], [x1, y1]]");
      const Eigen::Vector2d a = pair_of(rect.element(0), [](const Value& x) { return x.number(); });
      const Eigen::Vector2d b = pair_of(rect.element(1), [](const Value& x) { return x.number(); });
      f.lo = a.cwiseMin(b);
      f.hi = a.cwiseMax(b);
      if (!((f.hi - f.lo).minCoeff() > 0.0)) rect.fail("the corners must differ in x and in y");
      if (auto z = floor.get("z_m")) f.z_m = z->number();
      f.rgb = floor.require("reflectance").reflectance();
      job.add_floors.push_back(f);
    }
  if (auto v = scene.get("exclude_surfaces"))
    for (const Value& item : v->list()) {
      job.exclude_surfaces.push_back(item.text());
      job.exclude_surface_locs.push_back(item.loc());
    }
  if (auto v = scene.get("two_sided")) {
    if (v->node().IsScalar()) {
      if (v->text() != "all") v->fail("must be all or a list of surface names");
      job.two_sided_all = true;
    } else {
      for (const Value& item : v->list()) {
        job.two_sided_surfaces.push_back(item.text());
        job.two_sided_locs.push_back(item.loc());
      }
    }
  }
  if (auto v = scene.get("emitting_surfaces")) {
    for (const Value& item : v->list()) {
      const Map emitter(item, {"surface", "exitance_lm_per_m2"});
      const Value surface = emitter.require("surface");
      const Value exitance = emitter.require("exitance_lm_per_m2");
      const double e = exitance.bounded(0.0, kMaxExitance_lm_per_m2, " lm/m²");
      job.emitting_surfaces.push_back({surface.text(), e, surface.loc()});
    }
  }
}

using goal_rules::format_number;

void read_constraints(const Map& constraints, JobConfig& job) {
  if (auto v = constraints.get("max_luminaires")) {
    const int cap = static_cast<int>(v->integer(1, 100'000'000));
    if (job.search && job.search->layout == LayoutFamily::free && cap < job.search->count_min)
      v->fail("is below the least luminaires.count (" + std::to_string(job.search->count_min) + ")");
    if (job.search && job.search->layout == LayoutFamily::array &&
        cap < job.search->array_rows * job.search->array_columns)
      v->fail("is below the array's rows x columns (" +
              std::to_string(job.search->array_rows * job.search->array_columns) + ")");
    job.constraints.max_luminaires = cap;
    job.constraints.max_luminaires_loc = v->loc();
  }
  if (auto v = constraints.get("min_distance_m")) {
    job.constraints.min_distance_m = v->bounded(0.0, kMaxLength_m, " m");
  }
  if (auto v = constraints.get("max_power_density_w_per_m2")) {
    job.constraints.max_power_density_w_per_m2 = v->bounded(1e-6, 1e6, " W/m²");
    job.constraints.max_power_density_loc = v->loc();
  }
}

void read_objective(const Value& v, JobConfig& job) {
  const ObjectiveRule* rule = objective_rule_for_key(v.text());
  if (!rule) v.fail("must be min_power or closest_to_target");
  job.objective = rule->objective;
  if (rule->averages_are_targets &&
      std::none_of(job.goals.begin(), job.goals.end(),
                   [](const GoalSetting& g) { return g.metric == GoalMetric::average; }))
    v.fail("needs at least one goal with average_lux");
}

// The text of `v`, which must be one of `names` (else the error lists them).
std::string one_of(const Value& v, std::initializer_list<const char*> names) {
  const std::string text = v.text();
  std::string list;
  for (const char* n : names) {
    if (text == n) return text;
    list += std::string(list.empty() ? "" : ", ") + n;
  }
  v.fail("must be one of " + list);
}

void read_optimizer(const Map& optimizer, JobConfig& job) {
  SearchOptions& o = job.optimizer;
  if (auto v = optimizer.get("global_algorithm"))
    o.global_algorithm = one_of(*v, {"GN_CRS2_LM", "GN_ISRES", "GN_ESCH", "GN_DIRECT_L", "GN_DIRECT_L_RAND", "none"});
  if (auto v = optimizer.get("local_algorithm")) {
    o.local_algorithm = one_of(*v, {"LN_SBPLX", "LN_COBYLA", "LN_BOBYQA", "LN_NELDERMEAD", "LN_PRAXIS", "none"});
    if (o.local_algorithm == "none" && o.global_algorithm == "none")
      v->fail("global_algorithm and local_algorithm cannot both be none");
  }
  if (auto v = optimizer.get("max_evaluations")) o.max_evaluations = static_cast<int>(v->integer(1, 100'000'000));
  if (auto v = optimizer.get("local_max_evaluations"))
    o.local_max_evaluations = static_cast<int>(v->integer(1, 100'000'000));
  if (auto v = optimizer.get("max_seconds")) {
    o.max_seconds = v->positive();
    if (o.max_seconds > kMaxSeconds) v->fail("must be at most 1e+07 s");
  }
  if (auto v = optimizer.get("seed")) o.seed = static_cast<std::uint64_t>(v->integer(0, (1ll << 53)));
}

void read_verification(const Map& verification, JobConfig& job) {
  VerificationSettings& s = job.verification;
  if (auto v = verification.get("method")) {
    const std::string m = v->text();
    if (m == "auto") s.method = VerificationMethod::automatic;
    else if (m == "exact") s.method = VerificationMethod::exact;
    else if (m == "sample") s.method = VerificationMethod::sample;
    else if (m == "none") s.method = VerificationMethod::none;
    else v->fail("must be auto, exact, sample or none");
  }
  if (auto v = verification.get("rays_per_patch")) s.rays_per_patch = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = verification.get("indirect_rays_per_patch"))
    s.indirect_rays_per_patch = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = verification.get("first_indirect_rays"))
    s.first_indirect_rays = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = verification.get("decisive_rays")) s.decisive_rays = static_cast<int>(v->integer(0, 1 << 24));
  if (auto v = verification.get("rounds")) s.rounds = static_cast<int>(v->integer(1, 10));
  if (auto v = verification.get("margin")) s.margin = v->number_in(0.0, 0.2, false, "[0, 0.2]");
  if (auto v = verification.get("max_exact_patches"))
    s.max_exact_patches = static_cast<std::size_t>(v->integer(1, 100'000'000));
  if (auto v = verification.get("sample_fraction")) {
    s.sample_fraction = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (s.sample_fraction <= 0.0) v->fail("must be in (0, 1]");
  }
}

// building: a job of rooms, whose grids are each room's (a room without grids writes no grid files).
void read_output(const Map& output, JobConfig& job, bool building) {
  OutputSettings& o = job.output;
  if (auto v = output.get("directory")) {
    o.directory = v->path();
    if (o.directory.empty()) v->fail("must not be empty");
  }
  if (auto v = output.get("formats")) {
    const std::string names = output_format_keys();
    const std::vector<Value> formats = v->list();
    if (formats.empty()) v->fail("must list at least one of " + names);
    std::vector<std::string> listed;
    for (const Value& item : formats) {
      const std::string name = item.text();
      const OutputFormat* f = find_output_format(name);
      if (!f) item.fail("must be one of " + names);
      if (f->needs_grids && job.grids.empty() && !building) item.fail("needs calculation grids (the job has no grids section)");
      if (std::find(listed.begin(), listed.end(), name) != listed.end()) item.fail("is listed twice");
      listed.push_back(name);
    }
    o.formats.clear();  // in registry order, the order they are written
    for (const OutputFormat& f : output_formats())
      if (std::find(listed.begin(), listed.end(), f.key) != listed.end()) o.formats.emplace_back(f.key);
  }
  if (auto v = output.get("plan_cut_height_m")) o.plan_cut_height_m = v->bounded(0.001, 1000.0, " m");
}

// energy: {building_type, hours_day, hours_night, occupancy_factor, daylight_factor,
// constant_illuminance, parasitic_kwh_per_m2}.
void read_energy(const Value& section, JobConfig& job) {
  const Map energy(section, {"building_type", "hours_day", "hours_night", "occupancy_factor", "daylight_factor",
                             "constant_illuminance", "parasitic_kwh_per_m2"});
  EnergySettings& e = job.energy;
  e.given = true;
  e.loc = section.loc();
  if (auto v = energy.get("building_type")) {
    e.building_type = v->text();
    if (!find_building_type(e.building_type)) {
      std::string names;
      for (const BuildingHours& b : building_types()) names += (names.empty() ? "" : ", ") + std::string(b.key);
      v->fail("must be one of " + names);
    }
  }
  constexpr double kHoursPerYear = 8760.0;
  if (auto v = energy.get("hours_day")) e.hours_day = v->number_in(0.0, kHoursPerYear, false, "[0, 8760] h");
  if (auto v = energy.get("hours_night")) e.hours_night = v->number_in(0.0, kHoursPerYear, false, "[0, 8760] h");
  const BuildingHours row = *find_building_type(e.building_type);
  if (e.hours_day.value_or(row.day_h) + e.hours_night.value_or(row.night_h) > kHoursPerYear)
    (energy.get("hours_night") ? *energy.get("hours_night") : *energy.get("hours_day"))
        .fail("hours_day + hours_night must be at most 8760 h (a year)");
  if (auto v = energy.get("occupancy_factor")) {
    e.occupancy_factor = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (e.occupancy_factor <= 0.0) v->fail("must be in (0, 1]");
  }
  if (auto v = energy.get("daylight_factor")) e.daylight_factor = v->number_in(0.0, 1.0, false, "[0, 1]");
  if (auto v = energy.get("constant_illuminance")) {
    const std::string flag = Value::lower(v->text());
    if (flag == "true") e.constant_illuminance = true;
    else if (flag == "false") e.constant_illuminance = false;
    else v->fail("must be true or false");
  }
  if (auto v = energy.get("parasitic_kwh_per_m2")) e.parasitic_kwh_per_m2 = v->number_in(0.0, 1000.0, false, "[0, 1000] kWh/(m²·a)");
}

// `at`: where the sweep key itself is (the section's value starts a line later).
void read_sweep(const Value& section, const FileLoc& at, JobConfig& job) {
  const Map sweep(section, {"key", "values"});
  if (job.goals.empty()) throw ConfigError(located(at, "sweep: needs goals (it varies one goal parameter)"));
  const Value key = sweep.require("key");
  const Value values = sweep.require("values");
  SweepSetting setting;
  setting.key = key.text();
  setting.loc = key.loc();
  const std::vector<Value> list = values.list();
  if (list.empty()) values.fail("must list at least one number");
  std::vector<GoalSetting> trial = job.goals;  // each value is tried as `ilp sweep` will set it
  for (const Value& item : list) {
    const double v = item.number();
    goal_rules::apply(trial, setting.key, v, [&](const std::string& rule) { key.fail(rule); },
                         [&](const std::string& rule) { item.fail(rule); });
    setting.values.push_back(v);
  }
  job.sweep = setting;
}

void read_solver(const Map& solver, JobConfig& job) {
  if (auto v = solver.get("rays_per_patch")) job.form_factors.rays_per_patch = static_cast<int>(v->integer(1, 1 << 24));
  if (auto v = solver.get("seed")) {
    job.form_factors.seed = static_cast<std::uint64_t>(v->integer(0, (1ll << 53)));
    job.direct_light.seed = job.form_factors.seed;
  }
  if (auto v = solver.get("threads")) {
    job.form_factors.threads = static_cast<int>(v->integer(0, 1024));
    job.direct_light.threads = job.form_factors.threads;
  }
  if (auto v = solver.get("relative_residual")) {
    job.radiosity.relative_residual = v->number_in(0.0, 1.0, true, "(0, 1)");
    if (job.radiosity.relative_residual <= 0.0) v->fail("must be in (0, 1)");
  }
  if (auto v = solver.get("max_iterations")) job.radiosity.max_iterations = static_cast<int>(v->integer(1, 100'000'000));
  if (auto v = solver.get("direct_receiver_points")) job.direct_light.receiver_points = static_cast<int>(v->integer(1, 4096));
  if (auto v = solver.get("direct_shadow_rays")) job.direct_light.shadow_rays = static_cast<int>(v->integer(1, 4096));
  if (auto v = solver.get("method")) {
    const std::string m = v->text();
    if (m == "sample") job.method = SolveMethod::sample;
    else if (m == "exact") job.method = SolveMethod::exact;
    else v->fail("must be sample or exact");
  }
  SampleSettings& sample = job.sample;
  const auto size = solver.get("sample_size"), fraction = solver.get("sample_fraction"),
             target = solver.get("target_error");
  if (size && fraction) fraction->fail("give sample_size or sample_fraction, not both");
  if (size) {
    sample.size = static_cast<int>(size->integer(1, 100'000'000));
    sample.size_loc = size->loc();
  }
  if (fraction) {
    sample.fraction = fraction->number_in(0.0, 1.0, false, "(0, 1]");
    if (sample.fraction <= 0.0) fraction->fail("must be in (0, 1]");
    sample.size_loc = fraction->loc();
  }
  if (target) {
    if (size || fraction) target->fail("give target_error or a sample size (sample_size, sample_fraction), not both");
    sample.target_error = target->number_in(0.0, 1.0, true, "(0, 1)");
    if (*sample.target_error <= 0.0) target->fail("must be in (0, 1)");
    sample.target_error_loc = target->loc();
  }
  if (auto v = solver.get("sampling")) {
    const auto strategy = parse_sample_strategy(v->text());
    if (!strategy) v->fail("must be uniform, area or stratified");
    sample.strategy = *strategy;
  }
  if (auto v = solver.get("sample_seed")) sample.seed = static_cast<std::uint64_t>(v->integer(0, (1ll << 53)));
  if (auto v = solver.get("indirect")) {
    const auto method = parse_indirect_method(v->text());
    if (!method) v->fail("must be sample_gather or exact_second_bounce");
    sample.indirect = *method;
  }
  if (auto v = solver.get("max_sample_size")) {
    sample.max_size_for_target = static_cast<int>(v->integer(1, 100'000'000));
    sample.max_size_loc = v->loc();
  }
  if (auto v = solver.get("reflected_stride")) sample.reflected_stride = static_cast<int>(v->integer(1, 64));
  if (auto v = solver.get("hit_block_patches"))
    sample.hit_block_patches = static_cast<int>(v->integer(1, 1'000'000'000));
  if (auto v = solver.get("error_samples")) sample.error_samples = static_cast<int>(v->integer(2, 64));
  if (auto v = solver.get("pilot_fraction")) {
    sample.pilot_fraction = v->number_in(0.0, 1.0, false, "(0, 1]");
    if (sample.pilot_fraction <= 0.0) v->fail("must be in (0, 1]");
  }
}

}  // namespace

namespace config_yaml {

std::vector<std::string> luminaire_keys() {
  return {"size_m", "placed", "model", "flux_lm", "efficacy_lm_per_w", "mounting_surface", "mount_offset_m",
          "candidate_spacing_m", "count", "layout", "array", "products", "wall_distance_m", "ceiling_module_m", "field",
          "rows", "bays", "zone", "output", "suspended", "on_wall", "floor_surface", "groups"};
}

void read_maintenance_factor(const Value& v, JobConfig& job) {
  job.maintenance_factor = v.number_in(0.1, 1.0, false, "[0.1, 1] (as a product's)");
  job.maintenance_loc = v.loc();
}

// In this order: goals name grids and products, the objective needs the goals.
void read_room_keys(const Map& map, JobConfig& job, bool products_named) {
  if (auto v = map.get("luminaires")) read_luminaires(Map(*v, luminaire_keys()), job, products_named);
  if (auto v = map.get("grids")) read_grids(*v, job);
  if (auto v = map.get("maintenance_factor")) read_maintenance_factor(*v, job);
  if (auto v = map.get("goals")) read_goals(*v, job);
  if (auto v = map.get("scenarios")) read_scenarios(*v, job);
  if (auto v = map.get("constraints")) read_constraints(Map(*v, {"max_luminaires", "min_distance_m", "max_power_density_w_per_m2"}), job);
  if (auto v = map.get("objective")) read_objective(*v, job);
  if (auto v = map.get("energy")) read_energy(*v, job);
}

// A building job's shared keys: the product catalogue, the maintenance factor and the
// energy profile every room starts from; what belongs to one room is refused here.
void read_building_keys(const Map& top, JobConfig& job) {
  for (const char* key : {"goals", "grids", "constraints", "objective", "sweep", "report", "scenarios"})
    if (top.get(key))
      throw ConfigError(located(top.key_loc(key), std::string(key) + ": with rooms, each room states its own (rooms[]." +
                                                      key + "; docs/building.md)"));
  if (auto v = top.get("luminaires")) read_luminaires(Map(*v, {"products", "size_m"}), job, false);
  if (auto v = top.get("maintenance_factor")) read_maintenance_factor(*v, job);
  if (auto v = top.get("energy")) read_energy(*v, job);
}

}  // namespace config_yaml

int find_grid(const JobConfig& job, const std::string& name) {
  for (std::size_t g = 0; g < job.grids.size(); ++g)
    if (job.grids[g].name == name) return static_cast<int>(g);
  return -1;
}

void set_goal_parameter(JobConfig& job, const std::string& key, double value) {
  goal_rules::apply(
      job.goals, key, value, [&](const std::string& rule) -> void { throw ConfigError("--set " + key + ": " + rule); },
      [&](const std::string& rule) -> void {
        throw ConfigError("--set " + key + " = " + format_number(value) + ": " + rule);
      });
}

SampleSizeRule SampleSettings::rule() const {
  return {size, fraction, max_size_for_target, target_error, error_samples, pilot_fraction};
}

int SampleSettings::size_for(std::size_t population) const { return rule().size_for(population); }

JobConfig load_job_config(const std::string& path) {
  name_settings_by_key();  // the stages' messages name their settings as this file does
  JobConfig job;
  job.path = path;
  {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw ConfigError(path + ": is a folder, not a config file");
    if (const std::string why = not_a_regular_file(path, "config"); !why.empty()) throw ConfigError(why);
    std::ifstream probe(path);
    if (!probe) throw ConfigError(path + ": cannot open the config file");
  }
  YAML::Node root;
  try {
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // yaml-cpp stops reading at a NUL byte, and YAML::LoadAll then loops for ever (found by config_fuzz).
    if (const auto nul = text.find('\0'); nul != std::string::npos)
      throw ConfigError(located({path, 1 + static_cast<int>(std::count(text.begin(), text.begin() + nul, '\n'))},
                                "a NUL byte: the config must be a text file"));
    reject_deep_nesting(text, path);
    reject_second_document(text, path);
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(located({path, e.mark.line + 1, e.mark.column + 1}, "malformed YAML: " + e.msg));
  } catch (const YAML::Exception& e) {
    throw ConfigError(path + ": cannot read YAML: " + e.what());
  }
  if (!root.IsMap())
    throw ConfigError(path +
                      ": the config must be a YAML map of sections (scene, luminaires, goals, constraints, objective, "
                      "solver, optimizer, verification, output, energy, sweep, report)");
  try {
    const Map top(Value(root, "", job.path), {"scene", "luminaires", "grids", "maintenance_factor", "goals",
                                              "constraints", "objective", "solver", "optimizer", "verification",
                                              "output", "energy", "sweep", "report", "rooms", "scenarios"});
    read_scene(Map(top.require("scene"), {"mesh", "up_axis", "scale_to_m", "max_patch_edge_m", "surfaces_from",
                                          "reflectance", "default_reflectance", "emitting_surfaces",
                                          "exclude_surfaces", "two_sided", "weld_tolerance_m", "regions", "add_floor"}),
               job);
    if (top.get("rooms")) read_building_keys(top, job);
    else read_room_keys(top, job, false);
    if (auto v = top.get("solver"))
      read_solver(Map(*v, {"method", "rays_per_patch", "seed", "threads", "relative_residual", "max_iterations",
                           "direct_receiver_points", "direct_shadow_rays", "sample_size", "sample_fraction",
                           "sampling", "sample_seed", "indirect", "target_error", "error_samples",
                           "pilot_fraction", "max_sample_size", "reflected_stride",
                           "hit_block_patches"}),
                  job);
    if (auto v = top.get("optimizer"))
      read_optimizer(Map(*v, {"global_algorithm", "local_algorithm", "max_evaluations", "local_max_evaluations",
                              "max_seconds", "seed"}),
                     job);
    if (auto v = top.get("verification"))
      read_verification(Map(*v, {"method", "rays_per_patch", "indirect_rays_per_patch", "first_indirect_rays", "decisive_rays", "rounds", "max_exact_patches", "sample_fraction", "margin"}), job);
    if (auto v = top.get("output")) read_output(Map(*v, {"directory", "formats", "plan_cut_height_m"}), job, top.get("rooms").has_value());
    if (auto v = top.get("sweep")) read_sweep(*v, top.key_loc("sweep"), job);
    if (auto v = top.get("rooms")) read_rooms(*v, job);
    if (auto v = top.get("report")) {
      const Map report(*v, {"surfaces"});
      if (auto s = report.get("surfaces"))
        for (const Value& item : s->list()) {
          job.report_surfaces.push_back(item.text());
          job.report_surface_locs.push_back(item.loc());
        }
    }
  } catch (const YAML::Exception& e) {
    throw ConfigError(located({path, e.mark.line + 1, e.mark.column + 1}, std::string("invalid YAML: ") + e.what()));
  }
  return job;
}

JobConfig group_job(const JobConfig& job, std::size_t g) {
  const LuminaireGroup& group = job.groups.at(g);
  JobConfig out = job;
  out.groups.clear();
  out.search = group.search;
  out.products.clear();
  for (const std::string& name : group.products)
    for (const ProductSetting& p : job.products)
      if (p.name == name) out.products.push_back(p);
  return out;
}

}  // namespace ilp
