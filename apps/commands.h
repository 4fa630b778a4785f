// The ilp subcommands. Each takes parsed arguments, calls the library and prints;
// errors propagate to main, which prints one line and exits 1.
#pragma once

#include <string>
#include <vector>

namespace ilp::cli {

struct SolveArgs {
  std::string config;
  std::string csv;            // per-patch results; asks for the full-scene solution
  std::string out_dir;        // grid.csv and isolux plans of the job's grids; "": <output directory>/solve
  std::string method;         // "", "sample" or "exact": overrides solver.method
  int threads = -1;           // -1: the job's solver.threads
  std::string max_memory;     // --max-memory: a memory budget (e.g. 4G) below the machine's available memory
  bool quiet = false;
};
int run_solve(const SolveArgs& args);

struct AccuracyArgs {
  std::string config;
  std::string out_dir = "accuracy";
  std::vector<double> fractions{0.01, 0.02, 0.05, 0.10, 0.25, 1.0};
  int seeds = 3;
  std::vector<int> rays{256};
  std::vector<std::string> strategies{"stratified"};
  std::vector<std::string> methods{"exact_second_bounce"};
  std::vector<std::string> goals;  // surfaces; empty: the job's report surfaces
  int reference_rays = 1024;
  int error_samples = 4;
  double pilot_fraction = 0.02;
  int threads = -1;
  bool quiet = false;
};
int run_accuracy(const AccuracyArgs& args);

struct RunArgs {
  std::string config;
  std::string out_dir;        // overrides output.directory
  std::string cache_dir;      // operator cache folder; empty: the default (see default_cache_dir)
  bool no_cache = false;
  int threads = -1;
  std::string max_memory;     // --max-memory: a memory budget (e.g. 4G) below the machine's available memory
  bool quiet = false;
};
// Exit code 0 when every goal is met, 2 when the closest layout found misses one.
int run_job(const RunArgs& args);

struct SweepArgs {
  std::string config;
  std::string set;            // KEY=V1,V2,...: overrides the job's sweep block
  std::string out_dir;
  std::string cache_dir;
  bool no_cache = false;
  int threads = -1;
  std::string max_memory;     // --max-memory: a memory budget (e.g. 4G) below the machine's available memory
  bool quiet = false;
};
int run_sweep(const SweepArgs& args);

struct BenchArgs {
  std::string config;
  int luminaires = 8;           // per evaluated layout
  double patch_edge_m = 0.0;    // > 0: overrides scene.max_patch_edge_m
  double sample_fraction = 0.0; // > 0: overrides the solver's sample size
  bool skip_full_solve = false;
  std::string csv;              // append one row of figures
  int threads = -1;
  std::string max_memory;     // --max-memory: a memory budget (e.g. 4G) below the machine's available memory
  bool quiet = false;
};
int run_bench(const BenchArgs& args);

struct InspectArgs {
  std::string target;         // a job file (.yaml) or a mesh
  double scale = 0.0;         // > 0: overrides scene.scale_to_m
  std::string up;             // "y" or "z": overrides scene.up_axis
  double patch_edge_m = 0.0;  // > 0: overrides scene.max_patch_edge_m
  bool connected = false;     // scene.surfaces_from: connected
  double weld_m = 0.0;        // > 0: overrides scene.weld_tolerance_m
  std::string max_memory;     // the budget the cost estimate is judged against
  bool all = false;           // every surface, not the 40 largest
  int threads = -1;
};
int run_inspect(const InspectArgs& args);

// $XDG_CACHE_HOME/ilp, else $HOME/.cache/ilp, else .ilp-cache in the working directory.
// The operator cache's default folder and, unless $ILP_MACHINE_DIR says otherwise, where
// this machine's calibration is kept.
std::string default_cache_dir();

struct CalibrateArgs {
  bool cached = false;        // print the cached calibration (probe only when there is none)
};
// Exit 1 when the calibration could not be cached.
int run_calibrate(const CalibrateArgs& args);

struct UgrTableArgs {
  std::string file;           // a photometric file (.ies, .ldt)
  bool csv = false;           // 19 rows x 10 columns, two decimals, no header
  bool levin_formula = false; // position index by Levin's formula instead of CIE 117's table
};
int run_ugr_table(const UgrTableArgs& args);

struct PrintArgs {
  std::string result;         // result.json
};
int run_print(const PrintArgs& args);

}  // namespace ilp::cli
