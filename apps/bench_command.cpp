// ilp bench: what a job costs on this machine, phase by phase, against what a full
// radiosity solve per configuration would cost. Not part of the test suite.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <random>
#include <sstream>
#include <vector>

#include "apps/cli_support.h"
#include "apps/commands.h"
#include "job/config.h"
#include "job/plan.h"
#include "core/cost/cost_model.h"
#include "core/exact/exact_solver.h"
#include "job/job_runner.h"

namespace ilp::cli {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }


double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// `count` luminaires at random positions over the candidates' extent, relative
// fluxes in (0.5, 1], from a fixed seed.
void random_layout(const LightingModel& model, int count, std::mt19937_64& rng, std::vector<Eigen::Vector2d>& xy,
                   std::vector<double>& w) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector2d lo = model.grid.lower_m(), hi = model.grid.upper_m();
  xy.clear();
  w.clear();
  for (int j = 0; j < count; ++j) {
    xy.emplace_back(lo.x() + unit(rng) * (hi.x() - lo.x()), lo.y() + unit(rng) * (hi.y() - lo.y()));
    w.push_back(0.5 + 0.5 * unit(rng));
  }
}

}  // namespace

int run_bench(const BenchArgs& args) {
  const auto start = Clock::now();
  const JobConfig job = load_job_config(args.config);
  const RunOptions run = run_options(args.threads, args.max_memory, true);  // its estimate of this machine
  if (!job.search) throw ConfigError(job.path + ": ilp bench needs an inverse job (luminaires.mounting_surface, goals)");
  // The bench's own settings edit the plan, never the job: the patch size, the sample,
  // a free layout of exactly --luminaires.
  JobPlan job_plan = plan_job(job, run);
  if (args.patch_edge_m > 0.0) job_plan.scene.scene.max_patch_edge_m = args.patch_edge_m;
  VariantPlan& plan = job_plan.variants.front();  // products: the first product at its first rotation
  if (args.sample_fraction > 0.0) {
    plan.model.sample_size.size.reset();
    plan.model.sample_size.target_error.reset();
    plan.model.sample_size.fraction = args.sample_fraction;
  }
  plan.search.layout.family = LayoutFamily::free;
  plan.search.layout.count_min = plan.search.layout.count_max = args.luminaires;
  const ProgressCallback progress = make_progress(args.quiet);

  // Build (no cache: the build is what is measured).
  const PreparedJob prepared =
      prepare_job(job_plan.scene, plan, run, progress, "", [](const std::string& line) { std::cerr << line << "\n"; });
  const LightingModel& model = prepared.model;
  const SampleOperatorStats& st = model.stats;
  const double build_memory_gb = peak_memory_gb();

  // Evaluations: batches of random layouts, median rate.
  std::mt19937_64 rng(20261126);
  std::vector<Eigen::Vector2d> xy;
  std::vector<double> w;
  std::vector<double> rates;
  const LayoutEvaluator evaluate(model, plan.search);
  volatile double sink = 0.0;  // keeps the evaluations from being optimised away
  for (int batch = 0; batch < 7; ++batch) {
    const auto t0 = Clock::now();
    int n = 0;
    while (seconds_since(t0) < 0.3) {
      random_layout(model, args.luminaires, rng, xy, w);
      sink = sink + evaluate(xy, w).objective;
      ++n;
    }
    rates.push_back(n / seconds_since(t0));
  }
  const double evaluations_per_second = median(rates);

  // The search as configured, without verification.
  const SearchResult search = search_layout(model, plan.search, progress);

  // What one configuration costs without the operator: the luminaires of a layout
  // placed in the scene and the whole radiosity system solved (every form-factor row,
  // direct light, Gauss-Seidel).
  double full_solve_seconds = std::nan(""), full_rays_per_second = std::nan("");
  std::size_t full_patches = 0;
  if (!args.skip_full_solve) {
    random_layout(model, args.luminaires, rng, xy, w);
    const LayoutEvaluation layout = evaluate_layout(model, plan.search, xy, w);
    Scene scene = prepared.loaded.scene;
    add_layout(scene, plan.search.luminaire, layout.luminaires);
    const auto t0 = Clock::now();
    const ExactSolution exact = solve_exact(scene, exact_options(job, run), progress);
    full_solve_seconds = seconds_since(t0);
    full_rays_per_second = exact.summary.rays_per_second;
    full_patches = exact.summary.patches;
  }
  const double total_memory_gb = peak_memory_gb();

  std::ostringstream table;
  table << std::fixed << std::setprecision(3);
  table << "# ilp bench " << job.path << "\n";
  table << "patches " << prepared.loaded.scene.patches.size() << ", goal patches " << model.goal_patches.size()
        << ", goal points " << model.goal_points.size() << ", candidates " << model.grid.size() << ", k = " << model.sample_size << " of " << st.population
        << ", channels " << st.channels << ", rays per row " << job.form_factors.rays_per_patch << ", threads "
        << (worker_threads(job, run) == 0 ? std::string("all") : std::to_string(worker_threads(job, run))) << "\n";
  table << "| phase | s |\n|---|---|\n";
  table << "| scene (load, mesh) | " << prepared.scene_seconds << " |\n";
  table << "| BVH | " << prepared.bvh_seconds << " |\n";
  table << "| goal rows (rays, row sums, direct light at goals) | " << st.goal_seconds << " |\n";
  table << "| sample rows | " << st.sample_row_seconds << " |\n";
  table << "| direct light at sample and hit patches | " << st.direct_seconds << " |\n";
  table << "| k x k solve (per channel) | " << st.solve_seconds << " |\n";
  table << "| T | " << st.response_seconds << " |\n";
  table << "| operator build (total) | " << model.build_seconds << " |\n";
  table << "| search (" << search.evaluations << " evaluations, " << args.luminaires << " luminaires) | "
        << search.seconds << " |\n";
  table << "| full radiosity solve of one configuration | " << full_solve_seconds << " |\n";
  table << std::setprecision(0) << "\nevaluations per second (" << args.luminaires << " luminaires, "
        << model.goal_patches.size() << " goal patches, " << model.goal_points.size()
        << " goal points): " << evaluations_per_second << "\n";
  table << std::setprecision(2) << "peak memory: " << build_memory_gb << " GB after the build, " << total_memory_gb
        << " GB in all (with the full solve)\n";
  if (!args.skip_full_solve)
    table << std::setprecision(0) << "one evaluation against one full solve: " << full_solve_seconds * evaluations_per_second
          << " times cheaper (" << full_patches << " patches, " << full_rays_per_second / 1e6 << std::setprecision(2)
          << " M form-factor rays/s)\n";
  table << std::setprecision(2) << "total bench time " << seconds_since(start) << " s\n";
  std::cout << table.str();
  if (!args.csv.empty()) {
    const bool fresh = !std::ifstream(args.csv).good();
    std::ofstream csv(args.csv, std::ios::app);
    if (!csv) throw IlpError(args.csv + ": cannot append the bench row");
    if (fresh)
      csv << "config,patches,goal_patches,candidates,k,channels,rays,luminaires,scene_s,bvh_s,goal_rows_s,sample_rows_s,"
             "direct_s,solve_s,t_s,build_s,build_peak_gb,evaluations_per_s,search_evaluations,search_s,full_solve_s,"
             "peak_gb\n";
    csv << std::setprecision(6) << csv_field(job.path) << ',' << prepared.loaded.scene.patches.size() << ','
        << model.goal_patches.size() << ',' << model.grid.size() << ',' << model.sample_size << ',' << st.channels << ','
        << job.form_factors.rays_per_patch << ',' << args.luminaires << ',' << prepared.scene_seconds << ','
        << prepared.bvh_seconds << ',' << st.goal_seconds << ',' << st.sample_row_seconds << ',' << st.direct_seconds
        << ',' << st.solve_seconds << ',' << st.response_seconds << ',' << model.build_seconds << ',' << build_memory_gb
        << ',' << evaluations_per_second << ',' << search.evaluations << ',' << search.seconds << ','
        << full_solve_seconds << ',' << total_memory_gb << "\n";
  }
  return 0;
}

}  // namespace ilp::cli
