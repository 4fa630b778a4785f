// This machine's speed against the reference machine the cost model's constants were
// measured on (MachineCosts in cost_model.h), so that the estimate a run prints holds
// on any machine. A probe of a fraction of a second times the kernels the run's phases
// are made of (form-factor rays, a memory-bound sparse sweep, a dense product) on every
// core at once, each thread in its own CPU seconds, so that another process's load counts
// less than in wall-clock time (a heavy one still reads high: docs/benchmarks.md), and the
// result is cached per machine and build so that `ilp inspect` and `ilp run` print the
// same estimate.
#pragma once

#include <string>

#include "core/cost/cost_model.h"

namespace ilp {

// Seconds per unit of each kernel, in a thread's own CPU time (the mean of the cores').
struct ProbeTimes {
  double ray_s = 0.0;         // one form-factor ray: closest hit and the row's assembly
  double sparse_nnz_s = 0.0;  // one non-zero of a Gauss-Seidel sweep over rows much larger than the caches
  double dense_flop_s = 0.0;  // one flop of a dense double product
};

// The probe on the reference machine, where MachineCosts' constants were measured (Intel
// Xeon 2.8 GHz, the Release build, 2026-12-03): with it, the shipped jobs and three real
// models, each run just after a probe of its own, read 0.80-1.25 of their estimate, median
// 1.05 (docs/benchmarks.md, "The cost model per machine").
inline constexpr ProbeTimes kReferenceProbe{2.54e-7, 2.84e-9, 0.98e-10};

// Time here over time on the reference, per kind of work (2: twice as slow).
struct MachineSpeed {
  double rays = 1.0;    // ray casting and the scalar code around it: direct light, meshing, outputs
  double memory = 1.0;  // sparse gathers and sweeps, the search's blends
  double dense = 1.0;   // dense LU and products
};

MachineSpeed speed_against_reference(const ProbeTimes& here);

// Times the three kernels on one thread per core (up to 16) at once, each thread in its
// own CPU seconds, the median of nine interleaved rounds; gives the mean of the threads
// (0.4-0.6 s of wall clock on the reference).
ProbeTimes probe_machine();

// The share of a 2-thread run on the reference machine that did not speed up with the
// second thread (Amdahl's serial share): the classroom ran 1.63x faster on 2 threads
// than on 1 (2026-12-03).
inline constexpr double kSerialShare = 0.23;

// The worker threads that run at once: `threads` (0: every core) but at most the cores
// this process may use (more run no faster).
int usable_threads(int threads);

// MachineCosts for `threads` (>= 1) worker threads at `speed`: the reference constants
// (measured on 2 threads) times the speed of their kind of work and, but for reading the
// model and writing the outputs, Amdahl's factor from 2 threads to `threads`.
MachineCosts machine_costs(const MachineSpeed& speed, int threads, const MachineCosts& reference = {});

// The probe cached for this machine and build.
struct MachineCalibration {
  ProbeTimes probe;
  MachineSpeed speed;
  std::string file;    // where it is cached; empty: not cached
  // What was done, for the log ("probed now (...) and cached in ...", "cached in ...").
  std::string note = "not probed: the reference machine's figures";
};

// What the cache file's name and first lines key on: the CPU's model name, the logical
// CPUs, the compiler and how the program was built (optimised, sanitised), and the
// probe's version. Another build or machine probes anew.
std::string machine_key_text();

// The file of this machine's calibration in `folder`: machine-<digest of the key>.txt.
std::string calibration_path(const std::string& folder);

// The calibration cached in `folder` (calibration_path): read when the
// file is there and whole, else probed and written there. A file another process wrote
// first is kept and read (every command then prints the same estimate); a corrupt or
// stale one is replaced. `probe_again`: probe and replace the file whatever it holds
// (`ilp calibrate`). An empty folder, or one that cannot be written: probed, not cached.
// Never throws for a bad file.
MachineCalibration calibrate_machine(const std::string& folder, bool probe_again = false);

// "this machine against the reference: rays 1.02x, memory 0.97x, dense 1.00x the time (...)".
std::string describe(const MachineCalibration& calibration);

}  // namespace ilp
