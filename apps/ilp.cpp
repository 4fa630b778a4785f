// ilp: the command-line program. Arguments -> options -> library calls -> report.
// No numerics here; every step is a library function the tests also call.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>
#include <streambuf>
#include <string>

#include "apps/commands.h"
#include "core/base/error.h"
#include "dist/communicator.h"
#include "job/setting_keys.h"

namespace {
constexpr int kMaxThreads = 1024;  // as solver.threads of a job
constexpr const char* kMaxMemoryHelp =
    "memory budget, e.g. 4G or 512M (default: the machine's available memory); a job whose estimate exceeds it is "
    "refused before any work";
// A path option given as '' is refused, never taken as "not given" (--out '' once fell
// back to output.directory without a word).
const CLI::Validator kNonEmpty(
    [](std::string& value) { return value.empty() ? std::string("must not be empty") : std::string(); }, "PATH");

// Every byte the program writes to stdout and stderr passes here: control characters
// (but newline, carriage return and tab) from a file, such as a vendor's terminal escape
// codes, are shown as \xNN, never obeyed by the terminal.
class PrintableBuf : public std::streambuf {
 public:
  explicit PrintableBuf(std::streambuf* to) : to_(to) {}

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    const auto u = static_cast<unsigned char>(traits_type::to_char_type(c));
    if ((u >= 0x20 && u != 0x7f) || u == '\n' || u == '\r' || u == '\t') return to_->sputc(static_cast<char>(u));
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02x", u);
    return to_->sputn(hex, 4) == 4 ? c : traits_type::eof();
  }
  std::streamsize xsputn(const char* s, std::streamsize n) override {
    for (std::streamsize i = 0; i < n; ++i)
      if (traits_type::eq_int_type(overflow(traits_type::to_int_type(s[i])), traits_type::eof())) return i;
    return n;
  }
  int sync() override { return to_->pubsync(); }

 private:
  std::streambuf* to_;
};

// Under mpirun, a rank's stderr goes out a line at a time (one write each), so the
// ranks' lines are not cut into one another by the launcher's forwarding.
class LineBuf : public std::streambuf {
 public:
  explicit LineBuf(std::streambuf* to) : to_(to) {}
  ~LineBuf() override { write(line_.size()); }

 protected:
  int_type overflow(int_type c) override {
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    line_.push_back(traits_type::to_char_type(c));
    if (line_.back() == '\n' && write(line_.size()) != 0) return traits_type::eof();
    return c;
  }
  // std::cerr flushes after every <<: only whole lines go out then.
  int sync() override { return 0; }

 private:
  int write(std::size_t count) {
    if (count == 0) return 0;
    const auto n = static_cast<std::streamsize>(count);
    const bool ok = to_->sputn(line_.data(), n) == n;
    line_.erase(0, count);
    return ok && to_->pubsync() == 0 ? 0 : -1;
  }

  std::streambuf* to_;
  std::string line_;
};

// Puts a stream's own buffer back (flushed) before the PrintableBuf goes away.
struct StreamRestore {
  std::ostream& stream;
  std::streambuf* original;
  ~StreamRestore() {
    stream.flush();
    stream.rdbuf(original);
  }
};

// The job's luminaires as placed: `ilp solve`.
CLI::App* add_solve_command(CLI::App& app, ilp::cli::SolveArgs& args) {
  CLI::App* command = app.add_subcommand("solve", "Illuminance per surface in lux for the job's luminaires as placed: "
                                                  "through the sample-based operator, or exactly (full form factors, "
                                                  "Gauss-Seidel)");
  command->add_option("config", args.config, "job file (YAML)")->required();
  command->add_option("--csv", args.csv,
                      "also write per-patch results (centroid, area, direct and total lux) for every patch to this CSV")->check(kNonEmpty);
  command->add_option("--out", args.out_dir,
                      "folder for the calculation grids' files: grid.csv, isolux_<grid>.svg and .png (default: the job's "
                      "output folder + /solve)")->check(kNonEmpty);
  command->add_option("--method", args.method, "sample or exact (default: solver.method of the job, else sample)")
      ->check(CLI::IsMember({"sample", "exact"}));
  command->add_option("--threads", args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  command->add_option("--max-memory", args.max_memory, kMaxMemoryHelp);
  command->add_flag("-q,--quiet", args.quiet, "no progress lines");
  return command;
}

// What accuracy costs: `ilp accuracy`.
CLI::App* add_accuracy_command(CLI::App& app, ilp::cli::AccuracyArgs& args) {
  CLI::App* command = app.add_subcommand(
      "accuracy", "What accuracy costs in time: build the sample-based operator for a range of sample sizes and rays "
                  "per row, measure its error against the exact reference, predict it from pilot samples; writes "
                  "accuracy.csv and accuracy.svg");
  command->add_option("config", args.config, "job file (YAML)")->required();
  command->add_option("--out", args.out_dir, "output folder")->capture_default_str()->check(kNonEmpty);
  command->add_option("--fractions", args.fractions, "sample sizes as fractions of the reflecting patches")
      ->delimiter(',')->check(CLI::Range(1e-9, 1.0))->capture_default_str();
  command->add_option("--seeds", args.seeds, "samples drawn per size")->check(CLI::Range(1, 1000))
      ->capture_default_str();
  command->add_option("--rays", args.rays, "rays per form-factor row")->delimiter(',')->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  command->add_option("--strategies", args.strategies, "sampling: uniform, area, stratified")->delimiter(',')
      ->check(CLI::IsMember({"uniform", "area", "stratified"}))->capture_default_str();
  command->add_option("--methods", args.methods, "indirect light: sample_gather, exact_second_bounce")->delimiter(',')
      ->check(CLI::IsMember({"sample_gather", "exact_second_bounce"}))->capture_default_str();
  command->add_option("--goals", args.goals, "goal surfaces (default: the job's report.surfaces)")->delimiter(',');
  command->add_option("--reference-rays", args.reference_rays, "rays per patch of the exact reference")
      ->check(CLI::Range(1, 1 << 20))->capture_default_str();
  command->add_option("--eta", args.error_samples, "pilot samples behind the predicted error")
      ->check(CLI::Range(2, 64))->capture_default_str();
  command->add_option("--pilot-fraction", args.pilot_fraction, "pilot sample size, of the reflecting patches")
      ->check(CLI::Range(1e-9, 1.0))->capture_default_str();
  command->add_option("--threads", args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  command->add_flag("-q,--quiet", args.quiet, "no progress lines");
  return command;
}

// The inverse job: `ilp run`.
CLI::App* add_run_command(CLI::App& app, ilp::cli::RunArgs& args) {
  CLI::App* command = app.add_subcommand(
      "run", "Solve an inverse-lighting job: place luminaires on the mounting surface so the goal surfaces get what "
             "the job asks, verify the layout with an exact solve, print the layout and write result.json, "
             "illuminance.csv, plan.svg and scene.ply. Exit code 2 when a goal is missed");
  command->add_option("config", args.config, "job file (YAML)")->required();
  command->add_option("--out", args.out_dir, "output folder (default: output.directory of the job, else results/<job>)")->check(kNonEmpty);
  command->add_option("--cache", args.cache_dir,
                      "operator cache folder (default: $XDG_CACHE_HOME/ilp or ~/.cache/ilp): a second run of the same "
                      "scene and solver settings skips the build")->check(kNonEmpty);
  command->add_flag("--no-cache", args.no_cache, "build the operator without reading or writing the cache");
  command->add_option("--threads", args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  command->add_option("--max-memory", args.max_memory, kMaxMemoryHelp);
  command->add_flag("-q,--quiet", args.quiet, "no progress lines");
  return command;
}

// One goal parameter over values: `ilp sweep`.
CLI::App* add_sweep_command(CLI::App& app, ilp::cli::SweepArgs& args) {
  CLI::App* command = app.add_subcommand(
      "sweep", "Run a job once per value of one goal parameter, building the operator once; writes sweep.csv (one row "
               "per value) and sweep.svg (power against the parameter)");
  command->add_option("config", args.config, "job file (YAML)")->required();
  command->add_option("--set", args.set,
                      "KEY=V1,V2,...: the parameter and its values, e.g. goals.desks.average_lux=300,500,750 (default: "
                      "the job's sweep block)");
  command->add_option("--out", args.out_dir, "output folder (default: output.directory of the job, else results/<job>)")->check(kNonEmpty);
  command->add_option("--cache", args.cache_dir, "operator cache folder (default: $XDG_CACHE_HOME/ilp or ~/.cache/ilp)")->check(kNonEmpty);
  command->add_flag("--no-cache", args.no_cache, "build the operator without reading or writing the cache");
  command->add_option("--threads", args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  command->add_option("--max-memory", args.max_memory, kMaxMemoryHelp);
  command->add_flag("-q,--quiet", args.quiet, "no progress lines");
  return command;
}

// A saved layout again: `ilp print`.
CLI::App* add_print_command(CLI::App& app, ilp::cli::PrintArgs& args) {
  CLI::App* command = app.add_subcommand("print", "Print a saved layout (result.json of `ilp run`) again");
  command->add_option("result", args.result, "result.json")->required();
  return command;
}

// A job measured on this machine: `ilp bench`.
CLI::App* add_bench_command(CLI::App& app, ilp::cli::BenchArgs& args) {
  CLI::App* command = app.add_subcommand(
      "bench", "Measure a job on this machine: operator build by phase, peak memory, objective evaluations per "
               "second, the search, and one full radiosity solve per configuration for comparison (not a test)");
  command->add_option("config", args.config, "job file (YAML) of an inverse job")->required();
  command->add_option("--luminaires", args.luminaires, "luminaires per evaluated layout")
      ->check(CLI::Range(1, 64))->capture_default_str();
  command->add_option("--patch-edge", args.patch_edge_m, "override scene.max_patch_edge_m (m)")
      ->check(CLI::PositiveNumber);
  command->add_option("--sample-fraction", args.sample_fraction, "override the sample size, of the reflecting patches")
      ->check(CLI::Range(1e-9, 1.0));
  command->add_flag("--skip-full-solve", args.skip_full_solve, "do not run the full radiosity solve");
  command->add_option("--csv", args.csv, "append one row of figures to this CSV")->check(kNonEmpty);
  command->add_option("--threads", args.threads, "worker threads (default: solver.threads of the job, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  command->add_option("--max-memory", args.max_memory, kMaxMemoryHelp);
  command->add_flag("-q,--quiet", args.quiet, "no progress lines");
  return command;
}

// The scene as ilp sees it: `ilp inspect`.
CLI::App* add_inspect_command(CLI::App& app, ilp::cli::InspectArgs& args) {
  CLI::App* command = app.add_subcommand(
      "inspect", "Show the scene as ilp sees it (metres, z up, after exclusions and surface splitting): each surface "
                 "with triangles, patches, area, facing, heights and bounds; a suggested mounting surface and floor; "
                 "warnings (one surface for everything, wrong winding, openings, degenerate triangles); and for an "
                 "inverse job the cost estimate of running it");
  command->add_option("target", args.target, "job file (YAML) or mesh (.obj, .ply, .off)")->required();
  command->add_option("--scale", args.scale, "metres per file unit (overrides scene.scale_to_m)")
      ->check(CLI::PositiveNumber);
  command->add_option("--up", args.up, "the file's up axis (overrides scene.up_axis)")
      ->check(CLI::IsMember({"y", "z"}));
  command->add_option("--patch-edge", args.patch_edge_m, "override scene.max_patch_edge_m (m)")
      ->check(CLI::PositiveNumber);
  command->add_flag("--connected", args.connected,
                    "split surfaces into connected pieces by facing (scene.surfaces_from: connected)");
  command->add_option("--weld", args.weld_m, "weld tolerance for connectivity and edges (m)")
      ->check(CLI::PositiveNumber);
  command->add_option("--max-memory", args.max_memory,
                      "memory budget for the cost estimate, e.g. 4G (default: the machine's available memory)");
  command->add_flag("--all", args.all, "list every surface (default: the 40 largest)");
  command->add_option("--threads", args.threads, "worker threads (default: solver.threads, 0 = all cores)")
      ->check(CLI::Range(0, kMaxThreads));
  return command;
}

// The CIE 190 UGR table of a photometric file: `ilp ugr-table`.
CLI::App* add_ugr_table_command(CLI::App& app, ilp::cli::UgrTableArgs& args) {
  CLI::App* command = app.add_subcommand(
      "ugr-table", "Print the CIE 190 unified glare rating table of a photometric file: rooms 2H x 2H to 12H x 8H, "
                   "reflectances 70/50/20 ... 30/30/20, crosswise and endwise, spacing 0.25H, at the file's flux");
  command->add_option("file", args.file, "photometric file (.ies, .ldt)")->required();
  command->add_flag("--csv", args.csv, "19 rows x 10 columns (crosswise, then endwise), no header");
  command->add_flag("--levin", args.levin_formula, "position index by Levin's formula instead of CIE 117 Table 4.1");
  return command;
}

// This machine's speed for the cost estimate: `ilp calibrate`.
CLI::App* add_calibrate_command(CLI::App& app, ilp::cli::CalibrateArgs& args) {
  CLI::App* command = app.add_subcommand(
      "calibrate", "Probe this machine's speed (form-factor rays, sparse sweeps, dense products; about half a second) "
                   "against the machine the cost model was measured on, and cache it where `ilp run` and `ilp "
                   "inspect` read it for their estimates ($ILP_MACHINE_DIR, else $XDG_CACHE_HOME/ilp or ~/.cache/ilp). They probe once by "
                   "themselves when nothing is cached; run this after a change of hardware or when the estimates "
                   "drift");
  command->add_flag("--cached", args.cached, "print the cached calibration instead (probe only when there is none)");
  return command;
}

}  // namespace

int main(int argc, char** argv) {
  ilp::name_settings_by_key();  // messages name the settings as the job file does
  // Every rank of an mpirun starts MPI here (a plain start makes no MPI call).
  ilp::dist::Communicator& comm = ilp::dist::Communicator::world();
  LineBuf err_lines(std::cerr.rdbuf());
  PrintableBuf out(std::cout.rdbuf()), err(comm.distributed() ? static_cast<std::streambuf*>(&err_lines) : std::cerr.rdbuf());
  const StreamRestore restore_out{std::cout, std::cout.rdbuf(&out)}, restore_err{std::cerr, std::cerr.rdbuf(&err)};
  CLI::App app{"ilp: inverse lighting through a sample-based radiosity inverse"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "ilp 0.1.0");

  ilp::cli::SolveArgs solve_args;
  CLI::App* solve = add_solve_command(app, solve_args);
  ilp::cli::AccuracyArgs acc;
  CLI::App* accuracy = add_accuracy_command(app, acc);
  ilp::cli::RunArgs run_args;
  CLI::App* run = add_run_command(app, run_args);
  ilp::cli::SweepArgs sweep_args;
  CLI::App* sweep = add_sweep_command(app, sweep_args);
  ilp::cli::PrintArgs print_args;
  CLI::App* print = add_print_command(app, print_args);
  ilp::cli::BenchArgs bench_args;
  CLI::App* bench = add_bench_command(app, bench_args);
  ilp::cli::InspectArgs inspect_args;
  CLI::App* inspect = add_inspect_command(app, inspect_args);
  ilp::cli::UgrTableArgs ugr_table_args;
  CLI::App* ugr_table = add_ugr_table_command(app, ugr_table_args);
  ilp::cli::CalibrateArgs calibrate_args;
  CLI::App* calibrate = add_calibrate_command(app, calibrate_args);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every bad argument exits 1, as every other error does
    // (CLI11's own codes, 105 and up, would mean something else to a caller).
    return app.exit(e) == 0 ? 0 : 1;
  }
  struct Finalize {
    ilp::dist::Communicator& comm;
    ~Finalize() { comm.finalize(); }
  } finalize{comm};
  try {
    // A building's rooms are spread over the ranks (run_job); the other commands run
    // on rank 0 alone, the other ranks wait for its exit code.
    if (comm.distributed() && !*run)
      return ilp::dist::on_root_only(comm, [&] {
        if (*solve) return ilp::cli::run_solve(solve_args);
        if (*accuracy) return ilp::cli::run_accuracy(acc);
        if (*sweep) return ilp::cli::run_sweep(sweep_args);
        if (*print) return ilp::cli::run_print(print_args);
        if (*bench) return ilp::cli::run_bench(bench_args);
        if (*inspect) return ilp::cli::run_inspect(inspect_args);
        if (*ugr_table) return ilp::cli::run_ugr_table(ugr_table_args);
        if (*calibrate) return ilp::cli::run_calibrate(calibrate_args);
        return 0;
      });
    if (*solve) return ilp::cli::run_solve(solve_args);
    if (*accuracy) return ilp::cli::run_accuracy(acc);
    if (*run) return ilp::cli::run_job(run_args);
    if (*sweep) return ilp::cli::run_sweep(sweep_args);
    if (*print) return ilp::cli::run_print(print_args);
    if (*bench) return ilp::cli::run_bench(bench_args);
    if (*inspect) return ilp::cli::run_inspect(inspect_args);
    if (*ugr_table) return ilp::cli::run_ugr_table(ugr_table_args);
    if (*calibrate) return ilp::cli::run_calibrate(calibrate_args);
  } catch (const ilp::dist::FailedElsewhere&) {
    return 1;  // rank 0 prints the one message
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory (a smaller job: larger scene.max_patch_edge_m, fewer rays or candidates)\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "error: " << ilp::printable(e.what(), true) << "\n";
    return 1;
  } catch (...) {
    std::cerr << "error: an unexpected failure (please report it with the job file)\n";
    return 1;
  }
  return 0;
}
