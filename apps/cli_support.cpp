#include "apps/cli_support.h"

#include "apps/commands.h"
#include "core/cost/cost_model.h"
#include "core/cost/machine_speed.h"
#include "job/config.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <memory>
#include <mutex>

#include <unistd.h>

namespace ilp::cli {

ProgressCallback make_progress(bool quiet) {
  if (quiet) return {};
  struct State {
    std::mutex mutex;
    std::string phase;
    int shown = -1;
    std::chrono::steady_clock::time_point start;
  };
  auto state = std::make_shared<State>();
  const bool tty = isatty(STDERR_FILENO);
  return [state, tty](std::string_view phase, std::size_t done, std::size_t total) {
    const int percent = total ? static_cast<int>(100 * done / total) : 100;
    std::lock_guard lock(state->mutex);
    const auto now = std::chrono::steady_clock::now();
    if (phase != state->phase) {
      state->phase = phase;
      state->shown = -1;
      state->start = now;
    }
    const int step = tty ? 1 : 25;
    if (percent / step == state->shown / step && percent != 100) return;
    if (percent == state->shown) return;
    state->shown = percent;
    // Elapsed time, and the rest estimated from the rate so far.
    const double elapsed = std::chrono::duration<double>(now - state->start).count();
    std::ostringstream timing;
    timing << std::fixed << std::setprecision(1) << " (" << elapsed << " s";
    if (done > 0 && done < total)
      timing << ", about " << elapsed * static_cast<double>(total - done) / static_cast<double>(done) << " s left";
    timing << ")";
    if (tty)
      std::cerr << "\r  " << phase << ": " << percent << " %" << timing.str() << "   " << (percent == 100 ? "\n" : "")
                << std::flush;
    else std::cerr << "  " << phase << ": " << percent << " %" << timing.str() << "\n";
  };
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string output_directory(const JobConfig& job, const std::string& override_dir) {
  if (!override_dir.empty()) return override_dir;
  if (!job.output.directory.empty()) return job.output.directory;
  return (std::filesystem::path("results") / std::filesystem::path(job.path).stem()).string();
}

double peak_memory_gb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / (1024.0 * 1024.0);  // Linux reports KB
}

RunOptions run_options(int threads, const std::string& max_memory, bool estimates) {
  RunOptions run;
  if (threads >= 0) run.threads = threads;
  if (!max_memory.empty()) run.max_memory_bytes = parse_bytes(max_memory);
  if (estimates) run.machine = machine_calibration();
  return run;
}

std::string machine_folder() {
  if (const char* dir = std::getenv("ILP_MACHINE_DIR"); dir && *dir) return dir;
  return default_cache_dir();
}

MachineCalibration machine_calibration(bool probe_again) { return calibrate_machine(machine_folder(), probe_again); }

}  // namespace ilp::cli
