// Small pieces every ilp command shares: progress lines and CSV fields.
#pragma once

#include <string>

#include "job/config.h"
#include "job/plan.h"
#include "core/base/progress.h"

namespace ilp::cli {

// On a terminal: one line per phase, rewritten in place. Elsewhere (logs, CI): a
// line at every quarter, so long runs still show they are moving. Empty when quiet.
ProgressCallback make_progress(bool quiet);

// A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break.
std::string csv_field(const std::string& text);

// The folder a job's files go to: `override_dir` if given, else output.directory, else
// results/<config stem>.
std::string output_directory(const JobConfig& job, const std::string& override_dir);

// --threads (negative: not given) and --max-memory ("" : not given) as run options.
// `estimates`: with this machine's calibration for the cost estimates (cached in
// machine_folder(); probed, about half a second, when none is).
RunOptions run_options(int threads, const std::string& max_memory, bool estimates = false);

// Where this machine's calibration is kept: $ILP_MACHINE_DIR, else default_cache_dir().
std::string machine_folder();
// This machine's calibration (core/cost/machine_speed.h), cached in machine_folder();
// `probe_again`: probed and the file replaced (`ilp calibrate`).
MachineCalibration machine_calibration(bool probe_again = false);

// Peak resident memory of this process so far, GB.
double peak_memory_gb();

}  // namespace ilp::cli
