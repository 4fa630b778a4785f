#include "job/config.h"
#include "job/plan.h"

#include <sstream>

#include "core/base/key_hash.h"
#include "job/goal_rules.h"
#include "job/products.h"

namespace ilp {
namespace {

// The plain panel of luminaires.size_m at the flux_lm range and efficacy keys, as a
// product whose luminaires each take their own flux.
ProductVariant plain_panel(const JobConfig& job) {
  const LuminaireSearch& s = *job.search;
  ProductVariant p;
  p.product = "square Lambertian panel " + (std::ostringstream() << job.luminaire_size_m).str() + " m";
  p.source = "square_lambertian";
  p.type = LuminaireType::square_lambertian(job.luminaire_size_m);
  p.rated_flux_lm = s.flux_max_lm;
  p.power_w = s.flux_max_lm / s.efficacy_lm_per_w;
  p.dim_min = s.flux_max_lm > 0.0 ? s.flux_min_lm / s.flux_max_lm : 0.0;
  p.dim_max = 1.0;
  return p;
}

CandidateSpec candidate_spec(const LuminaireSearch& s, const ProductVariant& product) {
  CandidateSpec c;
  c.mounting_surface = s.mounting_surface;
  c.type = product.type;
  c.rotation_deg = product.rotation_deg;
  c.tilt_deg = product.tilt_deg;
  c.spacing_m = s.candidate_spacing_m;
  c.wall_distance_m = s.wall_distance_m;
  c.ceiling_module_m = s.ceiling_module_m;
  c.mount_offset_m = product.mount_offset_m.value_or(s.mount_offset_m);
  c.mounting_loc = s.mounting_loc;
  c.spacing_loc = s.spacing_loc;
  c.offset_loc = product.mount_offset_m ? product.mount_offset_loc : s.offset_loc;
  c.zone_m = s.zone_m;
  // An array's offsets count from the surface's corner: it keeps the whole surface
  // unless a zone is given.
  if (s.layout != LayoutFamily::array || s.zone_set) c.zone_margin_m = s.zone_margin_m;
  else c.zone_margin_m.reset();
  c.zone_loc = s.zone_loc;
  c.suspended_height_m = s.suspended_height_m;
  c.suspended_loc = s.suspended_loc;
  c.wall = s.on_wall;
  c.floor_surface = s.floor_surface;
  c.floor_loc = s.floor_loc;
  return c;
}

// One area per goal name and kind of area its metrics are measured over, in the goals'
// order, with the first goal's facing (and for cylinders and observers, the first goal's eyes).
std::vector<GoalAreaSpec> area_specs(const JobConfig& job) {
  std::vector<GoalAreaSpec> out;
  for (const GoalSetting& goal : job.goals) {
    const AreaKind kind = metric_rule(goal.metric).area;
    bool seen = false;
    for (const GoalAreaSpec& a : out) seen = seen || (a.name == goal.name && a.kind == kind);
    if (seen) continue;
    GoalAreaSpec area{goal.name, goal.surfaces, goal.facing, -1};
    area.kind = kind;
    area.loc = goal.loc;
    if (goal.eye_height_m) area.eye_height_m = *goal.eye_height_m;
    if (kind == AreaKind::glare) area.observers = goal.observers;
    if (!goal.grid.empty()) {
      area.grid = find_grid(job, goal.grid);
      if (area.grid < 0) throw std::invalid_argument("goal '" + goal.name + "': no grid '" + goal.grid + "'");
    }
    out.push_back(area);
  }
  return out;
}

ModelSpec model_spec(const JobConfig& job, const ProductVariant& product, const RunOptions& run) {
  ModelSpec m;
  m.candidates = candidate_spec(*job.search, product);
  m.areas = area_specs(job);
  m.grids = job.grids;
  m.operator_options = operator_options(job, run);
  m.operator_options.share = run.operator_share;
  m.sample_size = job.sample.rule();
  m.reflected_stride = job.sample.reflected_stride;
  m.probe_flux_lm = product.dim_max * product.rated_flux_lm;
  m.threads = worker_threads(job, run);
  return m;
}

SearchSpec search_spec(const JobConfig& job, const VariantPlan& plan, const RunOptions& run) {
  const LuminaireSearch& s = *job.search;
  const ProductVariant& p = plan.product;
  SearchSpec spec;
  if (plan.listed)  // one output for all, within the product's dimming range
    spec.luminaire = {p.type, p.rotation_deg, p.tilt_deg, p.product, true, p.dim_min * p.rated_flux_lm,
                      p.dim_max * p.rated_flux_lm, p.rated_flux_lm / p.power_w};
  else  // the plain panel in the flux_lm range: one output for all unless output: individual
    spec.luminaire = {p.type, p.rotation_deg, p.tilt_deg, std::string(), !s.individual_output, s.flux_min_lm,
                      s.flux_max_lm, s.efficacy_lm_per_w};
  LayoutSpec& layout = spec.layout;
  layout.family = s.layout;
  layout.count_min = s.count_min;
  layout.count_max = job.constraints.max_luminaires ? std::min(s.count_max, *job.constraints.max_luminaires) : s.count_max;
  layout.array_rows = s.array_rows;
  layout.array_columns = s.array_columns;
  layout.array_spacing_m = s.array_spacing_m;
  layout.array_offset_m = s.array_offset_m;
  layout.regular = s.regular;
  layout.ceiling_module_m = s.ceiling_module_m;
  layout.min_distance_m = job.constraints.min_distance_m;
  layout.mounting_surface = s.suspended_height_m ? "the suspension plane" : s.mounting_surface;
  layout.loc = s.layout_loc;
  spec.options = job.optimizer;
  spec.options.threads = worker_threads(job, run);
  return spec;
}

JobGoals job_goals(const JobConfig& job) {
  JobGoals out;
  for (const GoalSetting& g : job.goals) out.lines.push_back({g.name, g.metric, g.target, g.surfaces, g.grid});
  out.objective = job.objective;
  out.max_power_density_w_per_m2 = job.constraints.max_power_density_w_per_m2;
  return out;
}

// Every line at its initial target (GoalSpec, as the search and the verification judge).
std::vector<GoalSpec> initial_goals(const JobGoals& goals, double maintenance_factor) {
  std::vector<GoalSpec> out;
  for (const GoalLine& g : goals.lines) out.push_back({g.name, g.metric, initial_target(g.metric, g.target, maintenance_factor)});
  return out;
}

// What the outputs cost, from output.formats.
OutputWork output_work(const OutputSettings& output) {
  OutputWork work;
  for (const std::string& key : output.formats) {
    const OutputFormat& f = *find_output_format(key);
    work.patch_files = work.patch_files || f.per_patch;
    work.renders = work.renders || f.rendered;
    work.plan_render = work.plan_render || f.renders_plan;
  }
  return work;
}

// The variants of a job with one search (a single-search job, or one group's job).
std::vector<VariantPlan> plan_variants(const JobConfig& job, const RunOptions& run) {
  if (!job.search) {
    // A forward job (every luminaire placed, light computed, nothing chosen) is for
    // `ilp solve` and `ilp accuracy`: the message says so rather than only what is missing.
    const std::string forward = !job.luminaires.empty() || !job.emitting_surfaces.empty()
                                    ? "; this job's light is all given (luminaires.placed or emitting_surfaces): "
                                      "compute it with `ilp solve` (or check it with `ilp accuracy`)"
                                    : "";
    throw ConfigError(job.path + ": luminaires.mounting_surface is missing: an inverse job says where luminaires may "
                                 "go (see docs/user-guide.md)" + forward);
  }
  if (job.goals.empty()) throw ConfigError(job.path + ": goals are missing: an inverse job says what surfaces must receive");
  const bool listed = !job.products.empty();
  const bool on_wall = job.search->on_wall.has_value();
  const std::vector<ProductVariant> products =
      listed ? product_variants(job.products, on_wall) : std::vector{plain_panel(job)};
  std::vector<VariantPlan> out;
  for (const ProductVariant& product : products) {
    VariantPlan plan;
    plan.product = product;
    if (on_wall) {  // C0 into the room, the product's rotation added to the wall's facing
      double r = product.rotation_deg + wall_facing_deg(job.search->on_wall->facing);
      while (r > 180.0) r -= 360.0;
      while (r <= -180.0) r += 360.0;
      plan.product.rotation_deg = r;
    }
    plan.listed = listed;
    plan.maintenance_factor = product.maintenance_factor.value_or(job.maintenance_factor);
    plan.goals = job_goals(job);
    plan.verification = {job.verification, exact_options(job, run), operator_options(job, run), worker_threads(job, run)};
    plan.outputs = output_work(job.output);
    plan.source = job.path;
    plan.model = model_spec(job, plan.product, run);
    plan.search = search_spec(job, plan, run);
    plan.search = search_at(plan, plan.goals);
    plan.scenarios = job.scenarios;
    for (ScenarioSpec& s : plan.scenarios)
      for (GoalSpec& g : s.goals)
        g.target = initial_target(g.metric, g.target, plan.maintenance_factor);
    out.push_back(std::move(plan));
  }
  return out;
}

SearchSurfaces search_surfaces(const LuminaireSearch& s) {
  return {s.mounting_surface, s.mounting_loc, s.suspended_height_m.has_value(), s.floor_surface, s.floor_loc};
}

}  // namespace

int worker_threads(const JobConfig& job, const RunOptions& run) { return run.threads.value_or(job.form_factors.threads); }

SampleOperatorOptions operator_options(const JobConfig& job, const RunOptions& run) {
  SampleOperatorOptions options;
  options.strategy = job.sample.strategy;
  options.sample_seed = job.sample.seed;
  options.indirect = job.sample.indirect;
  options.hit_block_patches = job.sample.hit_block_patches;
  options.form_factors = job.form_factors;
  options.direct_light = job.direct_light;
  options.form_factors.threads = options.direct_light.threads = worker_threads(job, run);
  return options;
}

ExactSolveOptions exact_options(const JobConfig& job, const RunOptions& run) {
  ExactSolveOptions options;
  options.form_factors = job.form_factors;
  options.direct_light = job.direct_light;
  options.radiosity = job.radiosity;
  options.form_factors.threads = options.direct_light.threads = options.radiosity.threads = worker_threads(job, run);
  return options;
}

double initial_target(GoalMetric metric, double maintained, double maintenance_factor) {
  return metric_rule(metric).lux ? maintained / maintenance_factor : maintained;
}

SearchSpec search_at(const VariantPlan& variant, const JobGoals& goals) {
  SearchSpec spec = variant.search;
  spec.goals = initial_goals(goals, variant.maintenance_factor);
  spec.objective = goals.objective;
  return spec;
}

void set_goal_target(JobGoals& goals, const std::string& key, double value) {
  goal_rules::apply(
      goals.lines, key, value, [&](const std::string& rule) -> void { throw ConfigError("--set " + key + ": " + rule); },
      [&](const std::string& rule) -> void {
        throw ConfigError("--set " + key + " = " + goal_rules::format_number(value) + ": " + rule);
      });
}

// Each JobConfig field reaches the scene through SceneSpec or is no scene input (the
// comment in hash_scene_inputs, job/job_scene.cpp, and the test CacheKey.SceneInputsCover
// EveryJobConfigField say which).
static_assert(field_count<JobConfig>() == 45,
              "JobConfig changed: if load_job_scene reads the new field, carry it in SceneSpec (and hash it in "
              "hash_scene_inputs); if the operator depends on it otherwise, it must reach it through ModelSpec");
SceneSpec scene_spec(const JobConfig& job) {
  SceneSpec s;
  s.path = job.path;
  s.mesh_path = job.mesh_path;
  s.mesh_loc = job.mesh_loc;
  s.mesh_read = job.mesh_read;
  s.scene = job.scene;
  s.surface_split = job.surface_split;
  s.max_patch_edge_loc = job.max_patch_edge_loc;
  s.up_axis_loc = job.up_axis_loc;
  s.scale_to_m_loc = job.scale_to_m_loc;
  s.reflectance = job.reflectance;
  s.default_reflectance = job.default_reflectance;
  s.emitting_surfaces = job.emitting_surfaces;
  s.add_floors = job.add_floors;
  s.exclude_surfaces = job.exclude_surfaces;
  s.exclude_surface_locs = job.exclude_surface_locs;
  s.two_sided_surfaces = job.two_sided_surfaces;
  s.two_sided_locs = job.two_sided_locs;
  s.two_sided_all = job.two_sided_all;
  s.luminaire_size_m = job.luminaire_size_m;
  s.luminaires = job.luminaires;
  s.ignore_material_kd = job.ignore_material_kd;
  s.keep_surfaces = job.keep_surfaces;
  s.report_surfaces = job.report_surfaces;
  s.report_surface_locs = job.report_surface_locs;
  for (const GoalSetting& g : job.goals) s.goals.push_back({g.name, g.surfaces, g.surfaces_loc});
  if (job.search) s.search = search_surfaces(*job.search);
  return s;
}

JobPlan plan_job(const JobConfig& job, const RunOptions& run) {
  JobPlan out;
  out.source = job.path;
  out.threads = worker_threads(job, run);
  out.goals = job_goals(job);
  if (job.groups.empty()) {
    out.scene = scene_spec(job);
    out.variants = plan_variants(job, run);
    return out;
  }
  // The groups share the room (group_job changes only the search and the products); the
  // scene is read through the first group's job, which has a search.
  for (std::size_t g = 0; g < job.groups.size(); ++g) {
    const JobConfig one = group_job(job, g);
    if (g == 0) out.scene = scene_spec(one);
    out.groups.push_back({job.groups[g].name, job.groups[g].loc, search_surfaces(*one.search), plan_variants(one, run)});
  }
  return out;
}

}  // namespace ilp
