// ilp: the command-line program. Arguments -> options -> library calls -> report.
// No numerics here; every step is a library function the tests also call.
#include <CLI/CLI.hpp>

#include <iostream>

#include "apps/commands.h"

namespace {
constexpr int kMaxThreads = 1024;  // as solver.threads of a job
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ilp: inverse lighting through a sample-based radiosity inverse"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "ilp 0.1.0");

  ilp::cli::SolveArgs solve_args;
  CLI::App* solve = app.add_subcommand("solve", "Illuminance per surface in lux for the job's luminaires as placed: "
                                                "through the sample-based operator, or exactly (full form factors, "
                                                "Gauss-Seidel)");
  solve->add_option("config", solve_args.config, "job file (YAML)")->required();
  solve->add_option("--csv", solve_args.csv,
                    "also write per-patch results (centroid, area, direct and total lux) for every patch to this CSV");
  solve->add_option("--out", solve_args.out_dir,
                    "folder for the calculation grids' files: grid.csv, isolux_<grid>.svg and .png (default: the job's "
                    "output folder + /solve)");
  solve->add_option("--method", solve_args.method, "sample or exact (default: solver.method of the job, else sample)")
      ->check(CLI::IsMember({"sample", "exact"}));
  solve->add_option("--threads", solve_args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  solve->add_option("--max-memory", solve_args.max_memory,
                  "memory budget, e.g. 4G or 512M (default: the machine's available memory); a job whose "
                  "estimate exceeds it is refused before any work");
  solve->add_flag("-q,--quiet", solve_args.quiet, "no progress lines");

  ilp::cli::AccuracyArgs acc;
  CLI::App* accuracy = app.add_subcommand(
      "accuracy", "What accuracy costs in time: build the sample-based operator for a range of sample sizes and rays "
                  "per row, measure its error against the exact reference, predict it from pilot samples; writes "
                  "accuracy.csv and accuracy.svg");
  accuracy->add_option("config", acc.config, "job file (YAML)")->required();
  accuracy->add_option("--out", acc.out_dir, "output folder")->capture_default_str();
  accuracy->add_option("--fractions", acc.fractions, "sample sizes as fractions of the reflecting patches")
      ->delimiter(',')->check(CLI::Range(1e-9, 1.0))->capture_default_str();
  accuracy->add_option("--seeds", acc.seeds, "samples drawn per size")->check(CLI::Range(1, 1000))
      ->capture_default_str();
  accuracy->add_option("--rays", acc.rays, "rays per form-factor row")->delimiter(',')->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  accuracy->add_option("--strategies", acc.strategies, "sampling: uniform, area, stratified")->delimiter(',')
      ->check(CLI::IsMember({"uniform", "area", "stratified"}))->capture_default_str();
  accuracy->add_option("--methods", acc.methods, "indirect light: sample_gather, exact_second_bounce")->delimiter(',')
      ->check(CLI::IsMember({"sample_gather", "exact_second_bounce"}))->capture_default_str();
  accuracy->add_option("--goals", acc.goals, "goal surfaces (default: the job's report.surfaces)")->delimiter(',');
  accuracy->add_option("--reference-rays", acc.reference_rays, "rays per patch of the exact reference")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  accuracy->add_option("--eta", acc.error_samples, "pilot samples behind the predicted error")
      ->check(CLI::Range(2, 64))->capture_default_str();
  accuracy->add_option("--pilot-fraction", acc.pilot_fraction, "pilot sample size, of the reflecting patches")
      ->check(CLI::Range(1e-9, 1.0))->capture_default_str();
  accuracy->add_option("--threads", acc.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  accuracy->add_flag("-q,--quiet", acc.quiet, "no progress lines");

  ilp::cli::RunArgs run_args;
  CLI::App* run = app.add_subcommand(
      "run", "Solve an inverse-lighting job: place luminaires on the mounting surface so the goal surfaces get what "
             "the job asks, verify the layout with an exact solve, print the layout and write result.json, "
             "illuminance.csv, plan.svg and scene.ply. Exit code 2 when a goal is missed");
  run->add_option("config", run_args.config, "job file (YAML)")->required();
  run->add_option("--out", run_args.out_dir, "output folder (default: output.directory of the job, else results/<job>)");
  run->add_option("--cache", run_args.cache_dir,
                  "operator cache folder (default: $XDG_CACHE_HOME/ilp or ~/.cache/ilp): a second run of the same "
                  "scene and solver settings skips the build");
  run->add_flag("--no-cache", run_args.no_cache, "build the operator without reading or writing the cache");
  run->add_option("--threads", run_args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  run->add_option("--max-memory", run_args.max_memory,
                  "memory budget, e.g. 4G or 512M (default: the machine's available memory); a job whose "
                  "estimate exceeds it is refused before any work");
  run->add_flag("-q,--quiet", run_args.quiet, "no progress lines");

  ilp::cli::SweepArgs sweep_args;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "Run a job once per value of one goal parameter, building the operator once; writes sweep.csv (one row "
               "per value) and sweep.svg (power against the parameter)");
  sweep->add_option("config", sweep_args.config, "job file (YAML)")->required();
  sweep->add_option("--set", sweep_args.set,
                    "KEY=V1,V2,...: the parameter and its values, e.g. goals.desks.average_lux=300,500,750 (default: "
                    "the job's sweep block)");
  sweep->add_option("--out", sweep_args.out_dir, "output folder (default: output.directory of the job, else results/<job>)");
  sweep->add_option("--cache", sweep_args.cache_dir, "operator cache folder (default: $XDG_CACHE_HOME/ilp or ~/.cache/ilp)");
  sweep->add_flag("--no-cache", sweep_args.no_cache, "build the operator without reading or writing the cache");
  sweep->add_option("--threads", sweep_args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  sweep->add_option("--max-memory", sweep_args.max_memory,
                  "memory budget, e.g. 4G or 512M (default: the machine's available memory); a job whose "
                  "estimate exceeds it is refused before any work");
  sweep->add_flag("-q,--quiet", sweep_args.quiet, "no progress lines");

  ilp::cli::PrintArgs print_args;
  CLI::App* print = app.add_subcommand("print", "Print a saved layout (result.json of `ilp run`) again");
  print->add_option("result", print_args.result, "result.json")->required();

  ilp::cli::BenchArgs bench_args;
  CLI::App* bench = app.add_subcommand(
      "bench", "Measure a job on this machine: operator build by phase, peak memory, objective evaluations per "
               "second, the search, and one full radiosity solve per configuration for comparison (not a test)");
  bench->add_option("config", bench_args.config, "job file (YAML) of an inverse job")->required();
  bench->add_option("--luminaires", bench_args.luminaires, "luminaires per evaluated layout")
      ->check(CLI::Range(1, 64))->capture_default_str();
  bench->add_option("--patch-edge", bench_args.patch_edge_m, "override scene.max_patch_edge_m (m)")
      ->check(CLI::PositiveNumber);
  bench->add_option("--sample-fraction", bench_args.sample_fraction, "override the sample size, of the reflecting patches")
      ->check(CLI::Range(1e-9, 1.0));
  bench->add_flag("--skip-full-solve", bench_args.skip_full_solve, "do not run the full radiosity solve");
  bench->add_option("--csv", bench_args.csv, "append one row of figures to this CSV");
  bench->add_option("--threads", bench_args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  bench->add_option("--max-memory", bench_args.max_memory,
                  "memory budget, e.g. 4G or 512M (default: the machine's available memory); a job whose "
                  "estimate exceeds it is refused before any work");
  bench->add_flag("-q,--quiet", bench_args.quiet, "no progress lines");

  ilp::cli::InspectArgs inspect_args;
  CLI::App* inspect = app.add_subcommand(
      "inspect", "Show the scene as ilp sees it (metres, z up, after exclusions and surface splitting): each surface "
                 "with triangles, patches, area, facing, heights and bounds; a suggested mounting surface and floor; "
                 "warnings (one surface for everything, wrong winding, openings, degenerate triangles); and for an "
                 "inverse job the cost estimate of running it");
  inspect->add_option("target", inspect_args.target, "job file (YAML) or mesh (.obj, .ply, .off)")->required();
  inspect->add_option("--scale", inspect_args.scale, "metres per file unit (overrides scene.scale_to_m)")
      ->check(CLI::PositiveNumber);
  inspect->add_option("--up", inspect_args.up, "the file's up axis (overrides scene.up_axis)")
      ->check(CLI::IsMember({"y", "z"}));
  inspect->add_option("--patch-edge", inspect_args.patch_edge_m, "override scene.max_patch_edge_m (m)")
      ->check(CLI::PositiveNumber);
  inspect->add_flag("--connected", inspect_args.connected,
                    "split surfaces into connected pieces by facing (scene.surfaces_from: connected)");
  inspect->add_option("--weld", inspect_args.weld_m, "weld tolerance for connectivity and edges (m)")
      ->check(CLI::PositiveNumber);
  inspect->add_option("--max-memory", inspect_args.max_memory,
                      "memory budget for the cost estimate, e.g. 4G (default: the machine's available memory)");
  inspect->add_flag("--all", inspect_args.all, "list every surface (default: the 40 largest)");
  inspect->add_option("--threads", inspect_args.threads, "worker threads (default: solver.threads, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every bad argument exits 1, as every other error does
    // (CLI11's own codes, 105 and up, would mean something else to a caller).
    return app.exit(e) == 0 ? 0 : 1;
  }
  try {
    if (*solve) return ilp::cli::run_solve(solve_args);
    if (*accuracy) return ilp::cli::run_accuracy(acc);
    if (*run) return ilp::cli::run_job(run_args);
    if (*sweep) return ilp::cli::run_sweep(sweep_args);
    if (*print) return ilp::cli::run_print(print_args);
    if (*bench) return ilp::cli::run_bench(bench_args);
    if (*inspect) return ilp::cli::run_inspect(inspect_args);
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory (a smaller job: larger scene.max_patch_edge_m, fewer rays or candidates)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  } catch (...) {
    std::cerr << "error: an unexpected failure (please report it with the job file)\n";
    return 1;
  }
  return 0;
}
