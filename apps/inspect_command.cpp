// ilp inspect: the scene as ilp sees it (metres, z up, after exclusions and surface
// splitting), surface by surface, with suggestions, warnings and, for an inverse job,
// the cost estimate of running it. Takes a job file or a bare mesh.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <sstream>

#include "apps/cli_support.h"
#include "job/building.h"
#include "apps/commands.h"
#include "job/config.h"
#include "core/cost/cost_model.h"
#include "core/cost/machine_speed.h"
#include "job/job_scene.h"
#include "job/plan.h"
#include "core/transport/ray_caster.h"
#include "core/study/scene_inspect.h"
#include "job/job_cost.h"
#include "optimizer/lighting_model.h"

namespace ilp::cli {
namespace {

bool is_config(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".yaml" || ext == ".yml";
}

JobConfig job_for(const InspectArgs& args) {
  JobConfig job;
  if (is_config(args.target)) {
    job = load_job_config(args.target);
  } else {
    job.path = args.target;
    job.mesh_path = args.target;
    job.mesh_loc = {args.target, 0, 0};
    job.default_reflectance = Eigen::Vector3d::Constant(0.5);  // reflectances do not matter here
    job.ignore_material_kd = true;
  }
  // Command-line options override the file.
  // (Set, they override what an imported file states, as the job's keys do.)
  if (args.scale > 0.0) {
    job.scene.scale_to_m = args.scale;
    job.scale_to_m_loc = {"--scale", 0, 0};
  }
  if (args.up == "y" || args.up == "z") {
    job.scene.up_axis = args.up == "y" ? UpAxis::y : UpAxis::z;
    job.up_axis_loc = {"--up", 0, 0};
  }
  if (args.patch_edge_m > 0.0) job.scene.max_patch_edge_m = args.patch_edge_m;
  if (args.connected) job.surface_split.connected = true;
  if (args.weld_m > 0.0) job.surface_split.weld_tolerance_m = args.weld_m;
  return job;
}

std::string fixed(double v, int digits) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << v;
  return os.str();
}

void print_surfaces(const SceneInspection& in, std::size_t limit) {
  std::vector<std::size_t> order(in.surfaces.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return in.surfaces[a].area_m2 > in.surfaces[b].area_m2; });
  const std::size_t shown = std::min(limit, order.size());
  std::cout << "surfaces, largest first (" << shown << " of " << in.surfaces.size() << " shown"
            << (shown < order.size() ? "; --all for every one" : "") << "):\n";
  std::cout << std::left << std::setw(24) << "surface" << std::right << std::setw(10) << "triangles" << std::setw(9)
            << "patches" << std::setw(11) << "area m²" << std::setw(6) << "up%" << std::setw(6) << "down%"
            << std::setw(6) << "vert%" << std::setw(18) << "height m" << std::setw(28) << "x, y range m" << std::setw(7)
            << "open" << std::setw(8) << "flipped" << std::setw(8) << "escape%" << std::setw(7) << "back%" << "\n";
  for (std::size_t r = 0; r < shown; ++r) {
    const SurfaceInspection& s = in.surfaces[order[r]];
    const auto& b = s.bounds_m;
    const bool empty = b.isEmpty();
    std::string name = s.name + (s.is_luminaire ? " (luminaire)" : s.two_sided ? " (2-sided)" : "");
    if (name.size() > 23) name = name.substr(0, 22) + "~";
    std::cout << std::left << std::setw(24) << name << std::right << std::setw(10) << s.triangles << std::setw(9)
              << s.patches << std::setw(11) << fixed(s.area_m2, 2) << std::setw(6) << fixed(100 * s.up_share, 0)
              << std::setw(6) << fixed(100 * s.down_share, 0) << std::setw(6) << fixed(100 * s.vertical_share, 0)
              << std::setw(18)
              << (empty ? std::string("-") : fixed(b.min().z(), 2) + " .. " + fixed(b.max().z(), 2)) << std::setw(28)
              << (empty ? std::string("-")
                        : fixed(b.min().x(), 1) + ".." + fixed(b.max().x(), 1) + ", " + fixed(b.min().y(), 1) + ".." +
                              fixed(b.max().y(), 1))
              << std::setw(7) << s.open_edges << std::setw(8) << s.flipped_edges << std::setw(8)
              << fixed(100 * s.escape_share, 0) << std::setw(7) << fixed(100 * s.back_struck_share, 0) << "\n";
  }
  if (shown < order.size()) {
    double rest = 0.0;
    for (std::size_t r = shown; r < order.size(); ++r) rest += in.surfaces[order[r]].area_m2;
    std::cout << "  ... " << order.size() - shown << " more surfaces, " << fixed(rest, 2) << " m² in all\n";
  }
}

void print_suggestion(const char* what, const SceneInspection& in, int index, bool down) {
  if (index < 0) return;
  const SurfaceInspection& s = in.surfaces[static_cast<std::size_t>(index)];
  std::cout << what << s.name << " (" << fixed((down ? s.down_share : s.up_share) * s.area_m2, 1) << " m² facing "
            << (down ? "down" : "up") << " at z ≈ " << fixed(down ? s.down_mean_z_m : s.up_mean_z_m, 2) << " m)\n";
}

}  // namespace

namespace {

// The estimate `ilp run` prints for each variant of the job (its products' files read),
// the same figures from the same function (costed_geometry); `label` names a group.
std::vector<CostEstimate> print_cost_estimates(const std::vector<VariantPlan>& plans, const RunOptions& run,
                                               const Scene& scene, const std::string& label = {}) {
  const std::optional<MemoryBudget> budget = memory_budget(run.max_memory_bytes);
  const std::optional<double> bytes = budget ? std::optional<double>(budget->bytes) : std::nullopt;
  std::vector<CostEstimate> estimates;
  for (const VariantPlan& plan : plans) {
    const CostedGeometry costed = costed_geometry(plan, scene, budget, job_machine_costs(plan.model.threads, run));
    estimates.push_back(costed.estimate);
    const CostCounts& counts = costed.counts;
    std::cout << "cost estimate of `ilp run`" << label;
    if (plans.size() > 1) std::cout << " for " << printable(plan.product.product) << " at " << plan.product.rotation_deg << " deg";
    std::cout << " (" << counts.goal_patches << " goal patches, " << counts.grid_points << " grid points, "
              << costed.model.grid.size() << " candidates, k = " << counts.sample_size << ", " << counts.channels
              << (counts.channels == 1 ? " channel" : " channels") << ", " << plan.model.operator_options.form_factors.rays_per_patch
              << " rays per row; memory available "
              << (budget ? format_bytes(budget->bytes) + " (" + budget->source + ")" : std::string("unknown")) << "):\n";
    for (const std::string& line : format_estimate(costed.estimate)) std::cout << "  " << line << "\n";
    const VerificationPlan verification = plan_verification(plan.verification.settings, scene.patches.size(), counts.population,
                                                            counts.goal_patches, counts.luminaires, bytes);
    if (!verification.reason.empty()) std::cout << "  verification: " << verification.reason << "\n";
    if (!costed.refusal.empty()) std::cout << "  would be refused: " << costed.refusal << "\n";
  }
  return estimates;
}

// A single room: its variants' estimates and, for several, the whole run's (each variant
// builds its own operator and runs its own verification), the figure `ilp run` prints
// from the same function. A job of luminaire groups: each group's, then the whole run's
// as groups_run_seconds counts it. Returns the whole run's seconds.
double print_room_estimates(const JobPlan& job, const RunOptions& run, const Scene& scene) {
  if (!job.groups.empty()) {
    std::vector<std::vector<CostEstimate>> groups;
    for (const GroupPlan& group : job.groups)
      groups.push_back(print_cost_estimates(group.variants, run, scene, " for group '" + group.name + "'"));
    const double whole_s = groups_run_seconds(groups);
    std::cout << "cost estimate of the whole run: about " << fixed(whole_s, 1) << " s for its " << groups.size()
              << " groups (every group's operators, searched together, verified once)\n";
    return whole_s;
  }
  const std::vector<CostEstimate> estimates = print_cost_estimates(job.variants, run, scene);
  const double whole_run_s = whole_run_seconds(job.goals.objective, estimates);
  if (estimates.size() > 1)
    std::cout << "cost estimate of the whole run: about " << fixed(whole_run_s, 1) << " s for its " << estimates.size()
              << " variants, one after another\n";
  return whole_run_s;
}

// A building job: each room's estimate on its own scene (its part of the model), then the sum.
void print_building_estimates(const JobConfig& job, const RunOptions& run) {
  double total_s = 0.0;
  for (std::size_t r = 0; r < job.rooms.size(); ++r) {
    const JobConfig& room = room_job(job, r);
    const JobPlan plan = plan_job(room, run);
    const JobScene loaded = load_job_scene(plan.scene);
    std::cout << "room " << job.rooms[r].name << " (" << loaded.scene.patches.size() << " patches):\n";
    total_s += print_room_estimates(plan, run, loaded.scene);
  }
  std::cout << "cost estimate of the building: about " << fixed(total_s, 1) << " s for its " << job.rooms.size()
            << " rooms, one after another\n";
}

}  // namespace

int run_inspect(const InspectArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  JobConfig job = job_for(args);
  const RunOptions run = run_options(args.threads, args.max_memory);
  job.mesh_read.import_limits.max_memory_bytes = memory_budget_bytes(run.max_memory_bytes);
  TriangleMesh mesh;
  const JobScene loaded = load_job_scene(scene_spec(job), &mesh);
  const Scene& scene = loaded.scene;
  const RayCaster caster(scene, worker_threads(job, run));
  InspectOptions options;
  options.weld_tolerance_m = job.surface_split.weld_tolerance_m;
  options.threads = worker_threads(job, run);
  options.two_sided.assign(scene.surfaces.size(), job.two_sided_all);
  for (const std::string& name : job.two_sided_surfaces)
    if (const int s = scene.find_surface(name); s >= 0) options.two_sided[static_cast<std::size_t>(s)] = true;
  const SceneInspection in = inspect_scene(scene, mesh, loaded.frame, caster, options);

  std::cout << "scene: " << job.mesh_path << " as ilp sees it (metres, z up; scale_to_m " << loaded.frame.scale_to_m
            << ", up_axis " << (loaded.frame.up_axis == UpAxis::y ? "y" : "z") << ")\n";
  for (const std::string& line : loaded.log)
    if (line.rfind("warning: nothing emits", 0) != 0) std::cout << "  " << line << "\n";  // inspect places none
  std::cout << "  " << in.triangles << " triangles, " << in.welded_vertices << " vertices welded at "
            << options.weld_tolerance_m << " m; " << in.patches << " patches"
            << (job.scene.max_patch_edge_m > 0.0 ? " (max_patch_edge_m " + fixed(job.scene.max_patch_edge_m, 3) + ")"
                                                 : std::string(" (no subdivision)"))
            << ", " << fixed(in.area_m2, 2) << " m²\n";
  std::cout << "  probe rays: " << in.probe_rays << "; " << fixed(100 * in.escape_share, 1)
            << " % leave the model, " << fixed(100 * in.back_hit_share, 1) << " % strike a back face\n";
  print_surfaces(in, args.all ? in.surfaces.size() : 40);
  print_suggestion("suggested mounting surface: ", in, in.mounting, true);
  print_suggestion("suggested floor: ", in, in.floor, false);
  if (!in.warnings.empty()) {
    std::cout << "warnings:\n";
    for (const std::string& w : in.warnings) std::cout << "  - " << w << "\n";
  }

  // The cost of running the job, for an inverse job.
  if ((job.search && !job.goals.empty()) || !job.groups.empty() || !job.rooms.empty()) {
    try {
      RunOptions calibrated = run;  // the machine's speed, as `ilp run` reads it
      calibrated.machine = machine_calibration();
      std::cout << describe(calibrated.machine) << "\n";
      if (job.rooms.empty()) print_room_estimates(plan_job(job, calibrated), calibrated, scene);
      else print_building_estimates(job, calibrated);
    } catch (const IlpError& e) {
      std::cout << "cost estimate: not available: " << e.what() << "\n";
    } catch (const std::invalid_argument& e) {
      std::cout << "cost estimate: not available: " << e.what() << "\n";
    }
  } else {
    std::cout << "cost estimate: not an inverse job (no luminaires.mounting_surface or goals)\n";
  }
  std::cout << "inspect took " << fixed(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2)
            << " s\n";
  return 0;
}

}  // namespace ilp::cli
