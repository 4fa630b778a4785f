// ilp: the command-line program. Arguments -> options -> library calls -> report.
// No numerics here; every step is a library function the tests also call.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <string>

#include <unistd.h>

#include "core/config.h"
#include "core/exact_solver.h"
#include "core/job.h"
#include "optimizer/illuminance_metrics.h"

namespace {

// On a terminal: one line per phase, rewritten in place. Elsewhere (logs, CI): a
// line at every quarter, so long runs still show they are moving.
ilp::ProgressCallback make_progress(bool quiet) {
  if (quiet) return {};
  struct State {
    std::mutex mutex;
    std::string phase;
    int shown = -1;
  };
  auto state = std::make_shared<State>();
  const bool tty = isatty(STDERR_FILENO);
  return [state, tty](std::string_view phase, std::size_t done, std::size_t total) {
    const int percent = total ? static_cast<int>(100 * done / total) : 100;
    std::lock_guard lock(state->mutex);
    if (phase != state->phase) {
      state->phase = phase;
      state->shown = -1;
    }
    const int step = tty ? 1 : 25;
    if (percent / step == state->shown / step && percent != 100) return;
    if (percent == state->shown) return;
    state->shown = percent;
    if (tty) std::cerr << "\r  " << phase << ": " << percent << " %" << (percent == 100 ? "\n" : "") << std::flush;
    else std::cerr << "  " << phase << ": " << percent << " %\n";
  };
}

// A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

// Writes the per-patch results to `path` through a temporary file, so that a
// failure never leaves a half-written file behind.
void write_patch_csv(const std::string& path, const ilp::Scene& scene, const ilp::RadiositySolution& solution) {
  const std::string tmp = path + ".tmp";
  try {
    std::ofstream out(tmp);
    if (!out) throw ilp::IlpError(path + ": cannot write");
    out << std::setprecision(9);
    out << "patch,surface,centroid_x_m,centroid_y_m,centroid_z_m,normal_x,normal_y,normal_z,area_m2,"
           "direct_lux,total_lux,radiosity_lm_per_m2\n";
    for (std::size_t i = 0; i < scene.patches.size(); ++i) {
      const ilp::Patch& p = scene.patches[i];
      const auto row = static_cast<Eigen::Index>(i);
      out << i << ',' << csv_field(scene.surfaces[p.surface].name) << ',' << p.centroid_m.x() << ','
          << p.centroid_m.y() << ',' << p.centroid_m.z() << ',' << p.normal.x() << ',' << p.normal.y() << ','
          << p.normal.z() << ',' << p.area_m2 << ',' << solution.direct_lux[row] << ',' << solution.total_lux[row]
          << ',' << ilp::photometric(solution.radiosity_lm_per_m2.row(row)) << '\n';
    }
    if (!out.flush()) throw ilp::IlpError(path + ": write failed");
    out.close();
    std::filesystem::rename(tmp, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

int run_solve(const std::string& config_path, const std::string& csv_path, int threads, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  ilp::JobConfig job = ilp::load_job_config(config_path);
  if (threads >= 0) job.form_factors.threads = job.direct_light.threads = threads;
  ilp::JobScene loaded = ilp::load_job_scene(job);
  for (const std::string& line : loaded.log) std::cerr << line << "\n";

  ilp::ExactSolveOptions options{job.form_factors, job.direct_light, job.radiosity};
  const ilp::ExactSolution solution = ilp::solve_exact(loaded.scene, options, make_progress(quiet));
  std::cerr << solution.summary << "\n";
  // A closed model with consistent winding absorbs little on back faces; more hints at flipped faces.
  constexpr double kBackFaceWarning = 0.05;
  if (solution.summary.mean_back_hit_fraction > kBackFaceWarning)
    std::cerr << "warning: " << std::fixed << std::setprecision(1) << 100.0 * solution.summary.mean_back_hit_fraction
              << " % of the light strikes the back of one-sided patches and is absorbed: check the winding of the "
                 "model's faces\n";

  if (!csv_path.empty()) write_patch_csv(csv_path, loaded.scene, solution.radiosity);

  std::cout << "Illuminance per surface (exact radiosity, " << job.form_factors.rays_per_patch
            << " rays per patch, seed " << job.form_factors.seed << ")\n";
  ilp::print_illuminance_table(std::cout, ilp::surface_illuminance_table(loaded.scene, solution.radiosity.total_lux,
                                                                         job.report_surfaces));
  std::cout << "total time " << std::fixed << std::setprecision(2)
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  if (!csv_path.empty()) std::cout << "per-patch results: " << csv_path << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ilp: inverse lighting through a sample-based radiosity inverse"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "ilp 0.1.0");

  std::string config, csv;
  int threads = -1;
  bool quiet = false;
  CLI::App* solve = app.add_subcommand("solve", "Solve a job's scene exactly (full form factors, Gauss-Seidel) "
                                                "and print illuminance per surface in lux");
  solve->add_option("config", config, "job file (YAML)")->required();
  solve->add_option("--csv", csv, "also write per-patch results (centroid, area, direct and total lux) to this CSV");
  solve->add_option("--threads", threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::NonNegativeNumber);
  solve->add_flag("-q,--quiet", quiet, "no progress lines");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*solve) return run_solve(config, csv, threads, quiet);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
