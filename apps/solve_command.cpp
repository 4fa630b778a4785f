// ilp solve: illuminance per surface for the job's luminaires as placed, through the
// sample-based operator (default) or the exact reference.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "apps/cli_support.h"
#include "apps/commands.h"
#include "apps/grid_outputs.h"
#include "job/config.h"
#include "core/cost/cost_model.h"
#include "core/exact/exact_solver.h"
#include "job/job_cost.h"
#include "job/job_scene.h"
#include "core/exact/point_illuminance.h"
#include "job/plan.h"
#include "core/operator/sample_operator.h"
#include "optimizer/illuminance_metrics.h"
#include "output/atomic_file.h"
#include "output/result_record.h"

namespace ilp::cli {
namespace {

// Per-patch results for the patches in `patches` (every patch for the full scene).
void write_patch_csv(const std::string& path, const Scene& scene, const std::vector<int>& patches,
                     const Eigen::VectorXd& direct_lux, const Eigen::VectorXd& total_lux,
                     const Eigen::VectorXd& radiosity_lm_per_m2) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(9);
    out << "patch,surface,centroid_x_m,centroid_y_m,centroid_z_m,normal_x,normal_y,normal_z,area_m2,"
           "direct_lux,total_lux,radiosity_lm_per_m2\n";
    for (std::size_t r = 0; r < patches.size(); ++r) {
      const Patch& p = scene.patches[patches[r]];
      const auto row = static_cast<Eigen::Index>(r);
      out << patches[r] << ',' << csv_field(scene.surfaces[p.surface].name) << ',' << p.centroid_m.x() << ','
          << p.centroid_m.y() << ',' << p.centroid_m.z() << ',' << p.normal.x() << ',' << p.normal.y() << ','
          << p.normal.z() << ',' << p.area_m2 << ',' << direct_lux[row] << ',' << total_lux[row] << ','
          << radiosity_lm_per_m2[row] << '\n';
    }
  });
}

void print_table(const Scene& scene, const std::vector<int>& patches, const Eigen::VectorXd& lux,
                 const std::vector<std::string>& surfaces) {
  Eigen::VectorXd all = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(scene.patches.size()));
  for (std::size_t r = 0; r < patches.size(); ++r) all[patches[r]] = lux[static_cast<Eigen::Index>(r)];
  print_illuminance_table(std::cout, surface_illuminance_table(scene, all, surfaces));
}

// The job's calculation grids laid on the scene, and their points in one list (grid after grid).
struct SolveGrids {
  std::vector<CalcGrid> grids;
  std::vector<ReceiverPoint> points;
};

SolveGrids lay_grids(const Scene& scene, const RayCaster& caster, const JobConfig& job) {
  SolveGrids out;
  for (const CalcGridSetting& setting : job.grids) {
    out.grids.push_back(make_calc_grid(scene, caster, setting));
    const CalcGrid& g = out.grids.back();
    out.points.insert(out.points.end(), g.points.begin(), g.points.end());
    std::cerr << "grid '" << g.name << "': " << g.points.size() << " points (" << g.cells_u << " x " << g.cells_v
              << " cells), " << g.inside_solid << " inside solid objects dropped\n";
  }
  return out;
}

// Prints the grids' table and writes their files (grid.csv, isolux plans as
// output.formats says) into the solve folder as one set. `total` and `direct`: lux at
// every grid point, grid after grid.
void report_grids(const JobConfig& job, const std::string& out_dir, const Scene& scene, const SolveGrids& laid,
                  const Eigen::VectorXd& total, const Eigen::VectorXd& direct, const std::string& basis) {
  if (laid.grids.empty()) return;
  std::vector<GridResult> results;
  std::vector<GridRecord> records;
  Eigen::Index first = 0;
  for (const CalcGrid& grid : laid.grids) {
    const auto n = static_cast<Eigen::Index>(grid.points.size());
    GridResult r{&grid, {direct.segment(first, n), total.segment(first, n), job.maintenance_factor,
                         grid_target_lux(job, grid.name), basis}};
    records.push_back(grid_record(r, false));
    results.push_back(std::move(r));
    first += n;
  }
  std::cout << "\nIlluminance per calculation grid (the luminaires of the job, maintenance factor "
            << job.maintenance_factor << ")\n";
  print_grid_table(std::cout, records, basis);
  std::vector<std::string> owned = grid_csv_names(job);
  for (const char* ext : {".svg", ".png"})
    for (const std::string& name : isolux_names(job, ext)) owned.push_back(name);
  OutputSet set(out_dir, owned);
  if (job.output.wants("grid_csv")) stage_grid_csv(set, results);
  if (job.output.wants("isolux_svg")) stage_isolux(set, results, scene_luminaires(scene), ".svg");
  if (job.output.wants("isolux_png")) stage_isolux(set, results, scene_luminaires(scene), ".png");
  for (const std::string& file : set.commit()) std::cout << "wrote " << file << "\n";
}

int solve_with_sample(const JobConfig& job, const RunOptions& run, const JobScene& loaded, const SolveArgs& args) {
  const bool full_scene = !args.csv.empty(), quiet = args.quiet;
  const std::string& csv = args.csv;
  const Scene& scene = loaded.scene;
  const ProgressCallback progress = make_progress(quiet);
  auto start = std::chrono::steady_clock::now();
  const RayCaster caster(scene, worker_threads(job, run));
  const double bvh_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const std::vector<LightSource> sources = scene_light_sources(scene);
  const Eigen::VectorXd flux = source_flux_lm(scene, sources);
  const std::vector<int> goals = full_scene ? scene.all_patches() : scene.patches_of(job.report_surfaces);
  const SolveGrids laid = lay_grids(scene, caster, job);

  SampleOperatorOptions options = operator_options(job, run);
  const GoalRows goal_rows = compute_goal_rows(scene, caster, goals, laid.points, sources, options, progress);
  const SampleSizeChoice choice = choose_sample_size(job.sample.rule(), scene, caster, goal_rows, flux, options, progress);
  if (!choice.log.empty()) std::cerr << choice.log << "\n";
  options.sample_size = choice.sample_size;
  const SampleOperator op = build_sample_operator(scene, caster, goal_rows, options, progress);
  for (const std::string& line : op.log) std::cerr << line << "\n";
  const SampleOperatorStats& st = op.stats;
  std::cerr << std::fixed << std::setprecision(3) << "build: BVH " << bvh_seconds << " s, goal rows "
            << st.goal_seconds << " s, sample rows " << st.sample_row_seconds << " s, direct light "
            << st.direct_seconds << " s, solve " << st.solve_seconds << " s, T " << st.response_seconds
            << " s; total " << bvh_seconds + st.build_seconds() << " s\n";

  const Eigen::VectorXd all_total = op.illuminance_lux(flux), all_direct = op.direct_lux(flux);
  const auto G = static_cast<Eigen::Index>(goals.size()), Q = static_cast<Eigen::Index>(laid.points.size());
  const Eigen::VectorXd total = all_total.head(G), direct = all_direct.head(G);
  if (!csv.empty()) {
    const Eigen::VectorXd radiosity_all = op.reflected_lm_per_m2_per_lm * flux;
    Eigen::VectorXd radiosity = radiosity_all.head(G);
    for (std::size_t r = 0; r < goals.size(); ++r)
      radiosity[static_cast<Eigen::Index>(r)] += scene.patches[goals[r]].exitance_lm_per_m2;
    write_patch_csv(csv, scene, goals, direct, total, radiosity);
  }
  std::cout << "Illuminance per surface (sample-based operator, ";
  if (st.direct_only) std::cout << "direct light only";
  else std::cout << "k = " << st.sample_patches << " of " << st.population << " reflecting patches";
  std::cout << ", " << job.form_factors.rays_per_patch << " rays per row, seed " << job.form_factors.seed << ")\n";
  print_table(scene, goals, total, job.report_surfaces);
  report_grids(job, args.out_dir, scene, laid, all_total.tail(Q), all_direct.tail(Q), "sample-based operator");
  return 0;
}

int solve_exactly(const JobConfig& job, const RunOptions& run, const JobScene& loaded, const SolveArgs& args) {
  const Scene& scene = loaded.scene;
  const std::string& csv = args.csv;
  const ExactSolveOptions options = exact_options(job, run);
  const ExactSolution solution = solve_exact(scene, options, make_progress(args.quiet));
  std::cerr << solution.summary << "\n";
  // A closed model with consistent winding absorbs little on back faces; more hints at flipped faces.
  constexpr double kBackFaceWarning = 0.05;
  if (solution.summary.mean_back_hit_fraction > kBackFaceWarning)
    std::cerr << "warning: " << std::fixed << std::setprecision(1) << 100.0 * solution.summary.mean_back_hit_fraction
              << " % of the light strikes the back of one-sided patches and is absorbed: check the winding of the "
                 "model's faces\n";
  if (!csv.empty()) {
    Eigen::VectorXd radiosity(static_cast<Eigen::Index>(scene.patches.size()));
    for (Eigen::Index i = 0; i < radiosity.size(); ++i)
      radiosity[i] = photometric(solution.radiosity.radiosity_lm_per_m2.row(i));
    write_patch_csv(csv, scene, scene.all_patches(), solution.radiosity.direct_lux, solution.radiosity.total_lux,
                    radiosity);
  }
  std::cout << "Illuminance per surface (exact radiosity, " << job.form_factors.rays_per_patch
            << " rays per patch, seed " << job.form_factors.seed << ")\n";
  print_table(scene, scene.all_patches(), solution.radiosity.total_lux, job.report_surfaces);
  if (!job.grids.empty()) {
    // The points as the verification of `ilp run` computes them: each point's gather over the exact radiosity.
    const RayCaster caster(scene, worker_threads(job, run));
    const SolveGrids laid = lay_grids(scene, caster, job);
    const PointIlluminance at = exact_point_illuminance(scene, caster, solution.radiosity, laid.points,
                                                        options.form_factors, options.direct_light, make_progress(args.quiet));
    report_grids(job, args.out_dir, scene, laid, at.total_lux, at.direct_lux, "exact");
  }
  return 0;
}

// The grids' points in the cost: their cells (the most points they can have), counted
// before any point is laid, so a grid the memory cannot hold is refused first.
void add_grid_points(CostCounts& c, const Scene& scene, const JobConfig& job) {
  for (const CalcGridSetting& setting : job.grids) {
    const CalcGridSize size = calc_grid_size(scene, setting);
    c.grid_points += size.cells;
    c.grid_outline_tests += size.cells * size.outline_parts;
  }
}

}  // namespace

int run_solve(const SolveArgs& args) {
  const auto start = std::chrono::steady_clock::now();
  JobConfig job = load_job_config(args.config);
  const RunOptions run = run_options(args.threads, args.max_memory, true);
  if (args.method == "exact") job.method = SolveMethod::exact;
  if (args.method == "sample") job.method = SolveMethod::sample;
  job.mesh_read.import_limits.max_memory_bytes = memory_budget_bytes(run.max_memory_bytes);
  const JobScene loaded = load_job_scene(scene_spec(job));
  for (const std::string& line : loaded.log) std::cerr << line << "\n";
  std::cerr << describe(run.machine) << "\n";
  {
    // The cost model: the exact solve as a verification of every patch, or one operator build.
    const Scene& scene = loaded.scene;
    CostCounts c;
    c.patches = scene.patches.size();
    c.population = reflecting_patches(scene).size();
    c.channels = scene.channels;
    c.sources = scene_light_sources(scene).size();
    c.luminaires = static_cast<int>(c.sources);
    c.rays_per_patch = job.form_factors.rays_per_patch;
    c.direct_rays = job.direct_light.receiver_points * job.direct_light.shadow_rays;
    c.exact_second_bounce = job.sample.indirect == IndirectMethod::exact_second_bounce;
    if (job.method == SolveMethod::exact) {
      c.verify = CostCounts::Verify::exact;
      c.verify_rays = job.form_factors.rays_per_patch;
      c.goal_patches = c.patches;
    } else {
      c.goal_patches = !args.csv.empty() ? c.patches : scene.patches_of(job.report_surfaces).size();
      c.sample_size = c.population ? static_cast<std::size_t>(std::min<double>(
                                         static_cast<double>(c.population), job.sample.size_for(c.population)))
                                   : 0;
    }
    add_grid_points(c, scene, job);
    const std::optional<MemoryBudget> budget = memory_budget(run.max_memory_bytes);
    const CostEstimate estimate = estimate_job_cost(c, job_machine_costs(worker_threads(job, run), run));
    for (const std::string& line : format_estimate(estimate)) std::cerr << line << "\n";
    require_fits(estimate, budget, job.path);
  }
  SolveArgs resolved = args;
  resolved.out_dir = args.out_dir.empty() ? (std::filesystem::path(output_directory(job, "")) / "solve").string() : args.out_dir;
  if (job.method == SolveMethod::exact) solve_exactly(job, run, loaded, resolved);
  else solve_with_sample(job, run, loaded, resolved);
  std::cout << "total time " << std::fixed << std::setprecision(2)
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  if (!args.csv.empty()) std::cout << "per-patch results: " << args.csv << "\n";
  return 0;
}

}  // namespace ilp::cli
