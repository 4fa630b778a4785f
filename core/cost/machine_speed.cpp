#include "core/cost/machine_speed.h"

#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cerrno>
#include <cstdio>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <thread>
#include <vector>

#include <tbb/info.h>

#include "core/transport/form_factors.h"
#include "core/transport/ray_caster.h"
#include "core/transport/sampling.h"
#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

// Bump when a kernel changes: every cached calibration is then probed anew.
constexpr int kProbeVersion = 3;
constexpr int kProbeThreadsMax = 16;
constexpr const char* kFileHeader = "ilp machine calibration 1";

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// One timing of `kernel`, in CPU seconds of this thread.
template <class Kernel>
double cpu_seconds(Kernel&& kernel) {
  const double start = thread_cpu_seconds();
  kernel();
  return thread_cpu_seconds() - start;
}

// Rounds of the three kernels, interleaved: the speed of a shared host drifts from one
// second to the next, and the median of rounds spread over half a second follows a run's
// mix of it better than one longer timing or the fastest.
constexpr int kRounds = 9;

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// A furnished room: 8 x 6 x 3 m, twelve desks, patches of at most 0.25 m (about 18,000).
Scene probe_room() {
  using V = Eigen::Vector3d;
  using reference::QuadSpec;
  const V r = V::Constant(0.5);
  const double X = 8.0, Y = 6.0, Z = 3.0;
  std::vector<QuadSpec> quads = {{"floor", V(0, 0, 0), V(X, 0, 0), V(X, Y, 0), V(0, Y, 0), r},
                                 {"ceiling", V(0, 0, Z), V(0, Y, Z), V(X, Y, Z), V(X, 0, Z), r},
                                 {"wall_x0", V(0, 0, 0), V(0, Y, 0), V(0, Y, Z), V(0, 0, Z), r},
                                 {"wall_x1", V(X, 0, 0), V(X, 0, Z), V(X, Y, Z), V(X, Y, 0), r},
                                 {"wall_y0", V(0, 0, 0), V(0, 0, Z), V(X, 0, Z), V(X, 0, 0), r},
                                 {"wall_y1", V(0, Y, 0), V(X, Y, 0), V(X, Y, Z), V(0, Y, Z), r}};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 3; ++j) {  // a desk: its top and four sides, facing out
      const double x0 = 1.0 + 1.6 * i, y0 = 1.0 + 1.6 * j, x1 = x0 + 1.2, y1 = y0 + 0.8, z1 = 0.75;
      quads.push_back({"desks", V(x0, y0, z1), V(x1, y0, z1), V(x1, y1, z1), V(x0, y1, z1), r});
      quads.push_back({"desks", V(x1, y0, 0), V(x1, y1, 0), V(x1, y1, z1), V(x1, y0, z1), r});
      quads.push_back({"desks", V(x0, y0, 0), V(x0, y0, z1), V(x0, y1, z1), V(x0, y1, 0), r});
      quads.push_back({"desks", V(x0, y1, 0), V(x0, y1, z1), V(x1, y1, z1), V(x1, y1, 0), r});
      quads.push_back({"desks", V(x0, y0, 0), V(x1, y0, 0), V(x1, y0, z1), V(x0, y0, z1), r});
    }
  return reference::make_quad_scene(quads, 0.25);
}

// Form-factor rows of every 40th patch at 128 rays, on this thread: seconds per ray.
double probe_rays(const Scene& scene, const RayCaster& caster) {
  std::vector<int> rows;
  for (std::size_t i = 0; i < scene.patches.size(); i += 40) rows.push_back(static_cast<int>(i));
  FormFactorOptions options;
  options.rays_per_patch = 128;
  options.threads = 1;
  const double s = cpu_seconds([&] { (void)compute_form_factor_rows(scene, caster, rows, options); });
  return s / (static_cast<double>(rows.size()) * options.rays_per_patch);
}

// 2^18 rows of 16 random columns: 50 MB of values and indices, as a form-factor matrix
// is held, much larger than the caches.
struct SparseRowsProbe {
  static constexpr std::size_t kRows = std::size_t{1} << 18, kPerRow = 16;
  std::vector<int> columns;
  std::vector<double> values;
  SparseRowsProbe() : columns(kRows * kPerRow), values(kRows * kPerRow) {
    std::uint64_t state = 1;
    for (std::size_t e = 0; e < columns.size(); ++e) {
      state = splitmix64(state);
      columns[e] = static_cast<int>(state % kRows);
      values[e] = 0.9 / kPerRow * to_unit(splitmix64(state));
    }
  }
};

// A Gauss-Seidel sweep over the rows into x, on this thread: seconds per non-zero.
double probe_sparse(const SparseRowsProbe& m, std::vector<double>& x) {
  constexpr std::size_t kRows = SparseRowsProbe::kRows, kPerRow = SparseRowsProbe::kPerRow;
  x.resize(kRows, 0.0);
  const double s = cpu_seconds([&] {
    for (std::size_t i = 0; i < kRows; ++i) {
      double sum = 1.0;
      for (std::size_t e = i * kPerRow; e < (i + 1) * kPerRow; ++e)
        sum += m.values[e] * x[static_cast<std::size_t>(m.columns[e])];
      x[i] = sum;
    }
  });
  volatile double keep = x[kRows / 2];  // the sweeps are not optimised away
  (void)keep;
  return s / static_cast<double>(m.columns.size());
}

// A product of two 384 x 384 matrices: seconds per flop.
double probe_dense() {
  constexpr int kSize = 384;
  Eigen::MatrixXd a(kSize, kSize), b(kSize, kSize), c(kSize, kSize);
  std::uint64_t state = 7;
  for (Eigen::Index e = 0; e < a.size(); ++e) {
    a.data()[e] = to_unit(state = splitmix64(state));
    b.data()[e] = to_unit(state = splitmix64(state));
  }
  const double s = cpu_seconds([&] { c.noalias() = a * b; });
  volatile double keep = c(kSize / 2, kSize / 2);
  (void)keep;
  return s / (2.0 * kSize * kSize * kSize);
}

std::string cpu_model_name() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.starts_with("model name")) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) {
        std::string name = line.substr(colon + 1);
        name.erase(0, name.find_first_not_of(' '));
        return name;
      }
    }
  return "unknown";
}

#if defined(__has_feature)
#define ILP_HAS_FEATURE(x) __has_feature(x)
#else
#define ILP_HAS_FEATURE(x) 0
#endif

std::string build_kind() {
  std::string out;
#if defined(__OPTIMIZE__)
  out = "optimised";
#else
  out = "unoptimised";
#endif
#if defined(__SANITIZE_ADDRESS__) || ILP_HAS_FEATURE(address_sanitizer)
  out += ", address sanitizer";
#endif
#if defined(__SANITIZE_THREAD__) || ILP_HAS_FEATURE(thread_sanitizer)
  out += ", thread sanitizer";
#endif
  return out;
}

// FNV-1a, 64 bits, as 16 hex digits: the cache file's name.
std::string digest(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char ch : text) h = (h ^ ch) * 0x100000001b3ull;
  std::ostringstream os;
  os << std::hex << std::setw(16) << std::setfill('0') << h;
  return os.str();
}

// The calibration file of `key` in `folder`.
std::string path_of(const std::string& folder, const std::string& key) {
  return (std::filesystem::path(folder) / ("machine-" + digest(key) + ".txt")).string();
}

bool plausible(double per_unit_s) { return std::isfinite(per_unit_s) && per_unit_s > 1e-14 && per_unit_s < 1e-3; }

std::string file_text(const ProbeTimes& p, const std::string& key) {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::ostringstream os;
  os << kFileHeader << "\nkey: " << key << "\nprobed: " << std::put_time(&utc, "%Y-%m-%dT%H:%M:%SZ")
     << std::scientific << std::setprecision(6) << "\nray_s: " << p.ray_s << "\nsparse_nnz_s: " << p.sparse_nnz_s
     << "\ndense_flop_s: " << p.dense_flop_s << "\n";
  return os.str();
}

// The probe times a file of `key` holds, or why it cannot be used.
std::optional<ProbeTimes> read_file(const std::string& path, const std::string& key, std::string& why) {
  std::ifstream in(path);
  if (!in) {
    why = "none cached";
    return std::nullopt;
  }
  std::string line;
  if (!std::getline(in, line) || line != kFileHeader) {
    why = path + " is not a calibration of this version";
    return std::nullopt;
  }
  if (!std::getline(in, line) || line != "key: " + key) {
    why = path + " is another machine's or build's";
    return std::nullopt;
  }
  ProbeTimes p;
  bool ray = false, sparse = false, dense = false;
  while (std::getline(in, line)) {
    const std::size_t colon = line.find(": ");
    if (colon == std::string::npos) continue;
    const std::string name = line.substr(0, colon);
    double v = 0.0;
    std::istringstream value(line.substr(colon + 2));
    if (!(value >> v)) continue;
    if (name == "ray_s") p.ray_s = v, ray = true;
    if (name == "sparse_nnz_s") p.sparse_nnz_s = v, sparse = true;
    if (name == "dense_flop_s") p.dense_flop_s = v, dense = true;
  }
  if (!ray || !sparse || !dense || !plausible(p.ray_s) || !plausible(p.sparse_nnz_s) || !plausible(p.dense_flop_s)) {
    why = path + " is incomplete or corrupt";
    return std::nullopt;
  }
  return p;
}

// Writes `text` to `path` through a temporary file: renamed over it when `replace`,
// else linked only where no file is (another process's file is kept). False when the
// file could not be written; `kept` tells that another's was there.
bool write_file(const std::string& path, const std::string& text, bool replace, bool& kept) {
  kept = false;
  const std::string temporary = path + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(temporary, std::ios::trunc);
    if (!(out << text) || !out.flush()) {
      std::error_code ec;
      std::filesystem::remove(temporary, ec);
      return false;
    }
  }
  bool ok = true;
  if (replace) {
    ok = std::rename(temporary.c_str(), path.c_str()) == 0;
  } else if (::link(temporary.c_str(), path.c_str()) != 0) {
    kept = errno == EEXIST;
    ok = kept;
  }
  std::error_code ec;
  std::filesystem::remove(temporary, ec);
  return ok;
}

}  // namespace

MachineSpeed speed_against_reference(const ProbeTimes& here) {
  return {here.ray_s / kReferenceProbe.ray_s, here.sparse_nnz_s / kReferenceProbe.sparse_nnz_s,
          here.dense_flop_s / kReferenceProbe.dense_flop_s};
}

ProbeTimes probe_machine() {
  const Scene scene = probe_room();
  const RayCaster caster(scene, 1);
  const SparseRowsProbe rows;
  // Every core at once, as a run's worker threads (they share the memory bus, and a
  // virtual machine's cores need not be equally fast); the mean of their times.
  const int cores = std::clamp(tbb::info::default_concurrency(), 1, kProbeThreadsMax);
  std::vector<ProbeTimes> each(static_cast<std::size_t>(cores));
  std::vector<std::exception_ptr> failed(each.size());
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < each.size(); ++i)
    threads.emplace_back([&, i] {
      try {
        const RayCaster::ThreadModes modes;
        std::vector<double> ray_s, sparse_s, dense_s, x;
        for (int r = 0; r < kRounds; ++r) {
          ray_s.push_back(probe_rays(scene, caster));
          sparse_s.push_back(probe_sparse(rows, x));
          dense_s.push_back(probe_dense());
        }
        each[i] = {median(ray_s), median(sparse_s), median(dense_s)};
      } catch (...) {
        failed[i] = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  ProbeTimes mean;
  for (const ProbeTimes& p : each) {
    mean.ray_s += p.ray_s / cores;
    mean.sparse_nnz_s += p.sparse_nnz_s / cores;
    mean.dense_flop_s += p.dense_flop_s / cores;
  }
  return mean;
}

int usable_threads(int threads) {
  const int cores = std::max(1, tbb::info::default_concurrency());
  return threads > 0 ? std::min(threads, cores) : cores;
}

MachineCosts machine_costs(const MachineSpeed& speed, int threads, const MachineCosts& reference) {
  const double t = std::max(1, threads);
  const double amdahl = (kSerialShare + (1.0 - kSerialShare) / t) / (kSerialShare + (1.0 - kSerialShare) / 2.0);
  const double rays = speed.rays * amdahl, memory = speed.memory * amdahl, dense = speed.dense * amdahl;
  MachineCosts m = reference;
  for (double* c : {&m.gather_ray_s, &m.precise_pair_ray_s, &m.cheap_pair_s, &m.photometric_cheap_pair_s,
                    &m.point_source_s, &m.outline_test_s})
    *c *= rays;
  for (double* c : {&m.sparse_flop_s, &m.gauss_seidel_nnz_s, &m.blend_mac_s}) *c *= memory;
  m.dense_flop_s *= dense;
  // Reading the model and writing the outputs: mostly one thread.
  for (double* c : {&m.scene_patch_s, &m.output_base_s, &m.output_render_s, &m.output_plan_patch_s, &m.output_patch_s})
    *c *= speed.rays;
  return m;
}

std::string machine_key_text() {
  std::ostringstream os;
  os << "cpu " << cpu_model_name() << "; " << std::thread::hardware_concurrency() << " logical cpus; compiler "
#if defined(__VERSION__)
     << __VERSION__
#else
     << "unknown"
#endif
     << "; " << build_kind() << "; probe " << kProbeVersion;
  return os.str();
}

std::string calibration_path(const std::string& folder) { return path_of(folder, machine_key_text()); }

MachineCalibration calibrate_machine(const std::string& folder, bool probe_again) {
  MachineCalibration out;
  const std::string key = machine_key_text();  // reads /proc/cpuinfo: once
  const std::string path = folder.empty() ? std::string() : path_of(folder, key);
  std::string why = "no cache folder";
  if (!path.empty()) {
    std::optional<ProbeTimes> cached = probe_again ? std::nullopt : read_file(path, key, why);
    if (probe_again) why = "asked to probe again";
    if (cached) {
      out.probe = *cached;
      out.file = path;
      out.note = "cached in " + path;
      out.speed = speed_against_reference(out.probe);
      return out;
    }
  }
  out.probe = probe_machine();
  out.note = "probed now (" + why + "), not cached";
  if (!path.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(folder, ec);
    bool kept = false;
    const bool absent = !std::filesystem::exists(path, ec);
    if (!write_file(path, file_text(out.probe, key), !absent, kept)) {
      out.note += ": cannot write " + path;
    } else if (!kept) {
      out.file = path;
      out.note = "probed now (" + why + ") and cached in " + path;
    } else if (std::optional<ProbeTimes> theirs = read_file(path, key, why)) {
      out.probe = *theirs;  // another process probed first: its figures, as every later command reads them
      out.file = path;
      out.note = "cached in " + path + " by another process while this one probed";
    }
  }
  out.speed = speed_against_reference(out.probe);
  return out;
}

std::string describe(const MachineCalibration& c) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << "machine: time per unit of work against the reference machine's: rays "
     << c.speed.rays << "x, memory " << c.speed.memory << "x, dense " << c.speed.dense << "x (" << c.note << ")";
  return os.str();
}

}  // namespace ilp
