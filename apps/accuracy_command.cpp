// ilp accuracy: what the sample-based operator's accuracy costs in time, against
// the exact reference. Writes accuracy.csv and accuracy.svg into the output folder.
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "apps/cli_support.h"
#include "apps/commands.h"
#include "core/study/accuracy_study.h"
#include "core/grid/calc_grid.h"
#include "core/transport/ray_caster.h"
#include "job/config.h"
#include "job/plan.h"
#include "core/base/error.h"
#include "job/job_scene.h"
#include "output/atomic_file.h"
#include "output/svg_plot.h"

namespace ilp::cli {
namespace {

std::string series_name(const AccuracyRow& row, bool with_strategy) {
  std::ostringstream s;
  if (with_strategy) s << to_string(row.strategy) << ", ";
  s << row.rays_per_row << " rays, " << (row.method == IndirectMethod::sample_gather ? "all via sample" : "exact 2nd");
  return s.str();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

void write_csv(const std::string& path, const AccuracyStudy& study) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << std::setprecision(6);
    out << "strategy,indirect,sample_fraction,k,sample_patches,rays_per_row,sample_seed,build_seconds,"
           "evaluation_microseconds,rms_rel_error_total,max_rel_error_total,rms_rel_error_indirect,"
           "max_rel_error_indirect,predicted_rms_rel_error_total,goal_fallback_patches,condition_estimate";
    for (const std::string& g : study.grids)
      out << ',' << csv_field("grid." + g + ".rms_rel_error_total") << ',' << csv_field("grid." + g + ".max_rel_error_total");
    out << '\n';
    for (const AccuracyRow& r : study.rows) {
      out << to_string(r.strategy) << ',' << to_string(r.method) << ',' << r.sample_fraction << ',' << r.sample_size
          << ',' << r.sample_patches << ',' << r.rays_per_row << ',' << r.sample_seed << ',' << r.build_seconds << ','
          << r.evaluation_microseconds << ',' << r.error.rms_relative_total << ',' << r.error.max_relative_total
          << ',' << r.error.rms_relative_indirect << ',' << r.error.max_relative_indirect << ','
          << r.predicted_rms_error_total << ',' << r.goal_fallback_rows << ',' << r.condition_estimate;
      for (const PointError& e : r.grids) out << ',' << e.rms_relative_total << ',' << e.max_relative_total;
      out << '\n';
    }
  });
}

// Medians over seeds, per series and sample size.
struct Point {
  double fraction = 0.0, build_seconds = 0.0, eval_us = 0.0, rms_total = 0.0, max_total = 0.0, rms_indirect = 0.0,
         predicted = 0.0;
  std::vector<PointError> grids;  // per grid: medians of RMS and max
  int k = 0;
  std::size_t runs = 0;
};

std::map<std::string, std::vector<Point>> summarise(const AccuracyStudy& study) {
  bool several_strategies = false;
  for (const AccuracyRow& r : study.rows) several_strategies |= r.strategy != study.rows.front().strategy;
  std::map<std::string, std::map<int, std::vector<const AccuracyRow*>>> grouped;
  for (const AccuracyRow& r : study.rows) grouped[series_name(r, several_strategies)][r.sample_size].push_back(&r);
  std::map<std::string, std::vector<Point>> out;
  for (const auto& [name, by_k] : grouped)
    for (const auto& [k, rows] : by_k) {
      Point p;
      p.k = k;
      p.fraction = rows.front()->sample_fraction;
      p.predicted = rows.front()->predicted_rms_error_total;
      p.runs = rows.size();
      // A named reference, not the binding: clang before 16 cannot capture a structured
      // binding in a lambda (the sanitizer build failed here).
      const std::vector<const AccuracyRow*>& group = rows;
      auto med = [&](auto field) {
        std::vector<double> v;
        for (const AccuracyRow* r : group) v.push_back(field(*r));
        return median(v);
      };
      p.build_seconds = med([](const AccuracyRow& r) { return r.build_seconds; });
      p.eval_us = med([](const AccuracyRow& r) { return r.evaluation_microseconds; });
      p.rms_total = med([](const AccuracyRow& r) { return r.error.rms_relative_total; });
      p.max_total = med([](const AccuracyRow& r) { return r.error.max_relative_total; });
      p.rms_indirect = med([](const AccuracyRow& r) { return r.error.rms_relative_indirect; });
      for (std::size_t g = 0; g < rows.front()->grids.size(); ++g)
        p.grids.push_back({med([&](const AccuracyRow& r) { return r.grids[g].rms_relative_total; }),
                           med([&](const AccuracyRow& r) { return r.grids[g].max_relative_total; })});
      out[name].push_back(p);
    }
  return out;
}

void write_plot(const std::string& path, const std::map<std::string, std::vector<Point>>& summary,
                const std::string& scene_name, double reference_seconds) {
  std::vector<PlotSeries> series;
  for (const auto& [name, points] : summary) {
    PlotSeries measured{name, {}, {}}, predicted{"predicted (" + name + ")", {}, {}};
    for (const Point& p : points) {
      measured.x.push_back(p.build_seconds);
      measured.y.push_back(100.0 * p.rms_total);
      if (p.predicted > 0.0) {
        predicted.x.push_back(p.build_seconds);
        predicted.y.push_back(100.0 * p.predicted);
      }
    }
    series.push_back(std::move(measured));
    series.push_back(std::move(predicted));
  }
  std::ostringstream title;
  title << "Accuracy against build time: " << scene_name << " (exact reference: " << std::fixed << std::setprecision(1)
        << reference_seconds << " s)";
  const PlotAxes axes{title.str(), "operator build time (s)", "RMS relative error of total illuminance (%)", true,
                      true};
  const std::string svg = render_svg_plot(axes, series);
  write_file_atomically(path, [&](std::ostream& out) { out << svg; });
}

// Every grid of the job laid on the scene, its points to measure.
std::vector<AccuracyGrid> lay_grids(const Scene& scene, const JobConfig& job, int threads) {
  if (job.grids.empty()) return {};
  const RayCaster caster(scene, threads);
  std::vector<AccuracyGrid> out;
  for (const CalcGridSetting& setting : job.grids) {
    CalcGrid grid = make_calc_grid(scene, caster, setting);
    std::cerr << "grid '" << grid.name << "': " << grid.points.size() << " points\n";
    out.push_back({grid.name, std::move(grid.points)});
  }
  return out;
}

// Per series, sample size and grid: the medians of the points' RMS and max relative errors.
void print_grid_errors(const std::map<std::string, std::vector<Point>>& summary, const std::vector<std::string>& grids) {
  if (grids.empty()) return;
  std::cout << "at grid points (each point weighted equally; reference: each point's gather over the exact "
               "radiosity)\n"
            << std::left << std::setw(40) << "series" << std::setw(20) << "grid" << std::right << std::setw(8) << "k"
            << std::setw(11) << "RMS tot %" << std::setw(11) << "max tot %" << "\n";
  for (const auto& [name, points] : summary)
    for (const Point& p : points)
      for (std::size_t g = 0; g < grids.size(); ++g)
        std::cout << std::left << std::setw(40) << name << std::setw(20) << grids[g] << std::right << std::setw(8) << p.k
                  << std::fixed << std::setprecision(2) << std::setw(11) << 100.0 * p.grids[g].rms_relative_total
                  << std::setw(11) << 100.0 * p.grids[g].max_relative_total << "\n";
}

}  // namespace

int run_accuracy(const AccuracyArgs& args) {
  JobConfig job = load_job_config(args.config);
  const RunOptions run = run_options(args.threads, "");
  const JobScene loaded = load_job_scene(scene_spec(job));
  const Scene& scene = loaded.scene;
  for (const std::string& line : loaded.log) std::cerr << line << "\n";
  double emitted_lm = 0.0;
  for (const Patch& p : scene.patches) emitted_lm += p.area_m2 * p.exitance_lm_per_m2;
  if (!(emitted_lm > 0.0))
    throw ConfigError(args.config + ": nothing emits light, so there is no error to measure (every value is 0 lx); "
                                    "add luminaires.placed or scene.emitting_surfaces");

  AccuracyStudyOptions options;
  options.sample_fractions = args.fractions;
  options.seeds = args.seeds;
  options.rays_per_row = args.rays;
  options.strategies.clear();
  for (const std::string& s : args.strategies) {
    const auto strategy = parse_sample_strategy(s);
    if (!strategy) throw ConfigError("--strategies: '" + s + "' is not uniform, area or stratified");
    options.strategies.push_back(*strategy);
  }
  options.methods.clear();
  for (const std::string& m : args.methods) {
    const auto method = parse_indirect_method(m);
    if (!method) throw ConfigError("--methods: '" + m + "' is not sample_gather or exact_second_bounce");
    options.methods.push_back(*method);
  }
  options.reference_rays = args.reference_rays;
  options.error_samples = args.error_samples;
  options.pilot_fraction = args.pilot_fraction;
  const SampleOperatorOptions solver = operator_options(job, run);
  options.base.form_factors = solver.form_factors;
  options.base.direct_light = solver.direct_light;
  options.base.sample_seed = job.sample.seed;
  const std::vector<std::string>& goal_surfaces = args.goals.empty() ? job.report_surfaces : args.goals;
  if (goal_surfaces.empty() && job.grids.empty())
    throw ConfigError(args.config + ": no goal surfaces (give --goals or report.surfaces) and no grids");
  std::vector<int> goals;
  try {
    if (!goal_surfaces.empty()) goals = scene.patches_of(goal_surfaces);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(args.config + ": goal " + e.what());
  }
  const std::vector<AccuracyGrid> grids = lay_grids(scene, job, worker_threads(job, run));

  OutputSet set(args.out_dir, {"accuracy.csv", "accuracy.svg"});  // one set: the folder never mixes two studies
  const AccuracyStudy study = run_accuracy_study(scene, goals, grids, options, make_progress(args.quiet));
  write_csv(set.staging_path("accuracy.csv"), study);
  set.staged("accuracy.csv");
  const auto summary = summarise(study);
  const double reference_seconds = study.reference.bvh_seconds + study.reference.form_factor_seconds +
                                   study.reference.direct_light_seconds + study.reference.solve_seconds;
  write_plot(set.staging_path("accuracy.svg"), summary, std::filesystem::path(args.config).filename().string(),
             reference_seconds);
  set.staged("accuracy.svg");
  const std::vector<std::string> written = set.commit();
  const std::string csv = written[0], svg = written[1];

  std::cout << "Accuracy of the sample-based operator: " << study.patches << " patches, " << study.population
            << " reflecting, " << study.goal_patches << " goal patches, " << study.goal_points << " grid points\n"
            << "reference: exact solve with " << options.reference_rays << " rays per patch (seed "
            << options.reference_seed << ") in " << std::fixed << std::setprecision(2) << reference_seconds << " s\n";
  for (const StudyPrediction& sp : study.predictions) {
    const ErrorPrediction& p = sp.prediction;
    std::cout << "pilot (" << to_string(sp.strategy) << ", " << sp.rays_per_row << " rays, " << to_string(sp.method)
              << "): " << p.samples << " samples of k0 = " << p.pilot_size << " spread by "
              << std::setprecision(2) << 100.0 * p.rms_relative_spread_total << " % RMS (total), "
              << 100.0 * p.rms_relative_spread_indirect << " % (indirect) in " << p.seconds << " s\n";
  }
  std::cout << "medians over seeds; errors are area-weighted RMS and maximum over goal patches, relative"
            << (goals.empty() ? " (no goal patches: -nan)" : "") << "\n";
  std::cout << std::left << std::setw(40) << "series" << std::right << std::setw(8) << "k %" << std::setw(8) << "k"
            << std::setw(10) << "build s" << std::setw(10) << "eval us" << std::setw(11) << "RMS tot %"
            << std::setw(11) << "max tot %" << std::setw(11) << "RMS ind %" << std::setw(11) << "predict %" << "\n";
  for (const auto& [name, points] : summary)
    for (const Point& p : points)
      std::cout << std::left << std::setw(40) << name << std::right << std::fixed << std::setprecision(1)
                << std::setw(8) << 100.0 * p.fraction << std::setw(8) << p.k << std::setprecision(3) << std::setw(10)
                << p.build_seconds << std::setprecision(2) << std::setw(10) << p.eval_us << std::setw(11)
                << 100.0 * p.rms_total << std::setw(11) << 100.0 * p.max_total << std::setw(11)
                << 100.0 * p.rms_indirect << std::setw(11) << 100.0 * p.predicted << "\n";
  print_grid_errors(summary, study.grids);
  std::cout << "wrote " << csv << " and " << svg << "\n";
  return 0;
}

}  // namespace ilp::cli
