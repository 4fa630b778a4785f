// `ilp calibrate`: probes this machine's speed again and caches it where `ilp run` and
// `ilp inspect` read it (core/cost/machine_speed.h), then prints it.
#include <iomanip>
#include <iostream>

#include "apps/cli_support.h"
#include "apps/commands.h"
#include "core/cost/machine_speed.h"

namespace ilp::cli {

int run_calibrate(const CalibrateArgs& args) {
  const MachineCalibration c = machine_calibration(!args.cached);
  const ProbeTimes& r = kReferenceProbe;
  std::cout << "machine: " << machine_key_text() << "\n";
  std::cout << std::scientific << std::setprecision(3)
            << "  per unit, in each core's CPU seconds (their mean): a form-factor ray " << c.probe.ray_s
            << " s (reference " << r.ray_s << " s), a sparse non-zero " << c.probe.sparse_nnz_s << " s ("
            << r.sparse_nnz_s << " s), a dense flop " << c.probe.dense_flop_s << " s (" << r.dense_flop_s << " s)\n";
  std::cout << describe(c) << "\n";
  if (c.file.empty()) return 1;  // not cached: every run would probe anew
  return 0;
}

}  // namespace ilp::cli
