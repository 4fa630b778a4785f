#include "core/cost/cost_model.h"

#include "core/base/setting.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

#include "core/base/error.h"
#include "core/operator/sample_operator.h"

namespace ilp {
namespace {

// Bytes per patch of the scene (Patch is 168 bytes) held twice (the job scene and
// the model's copy with the candidates), its BVH (float vertices and nodes, about
// 100 bytes a triangle) and the per-patch index tables of a build.
constexpr double kPatchBytes = 168.0;
constexpr double kBvhBytesPerPatch = 100.0;
constexpr double kIndexBytesPerPatch = 40.0;
constexpr double kProcessBytes = 50e6;  // the program, its libraries and thread pools
// A non-zero of a form-factor row while rows are assembled: the (patch, count) pair
// of the row result and the sparse matrix entry (double + int).
constexpr double kRowNnzPeakBytes = 20.0;
constexpr double kRowNnzBytes = 12.0;
// A grid point while grids are laid and kept: its position and normal, its cell.
constexpr double kGridPointBytes = 64.0;

double d(std::size_t v) { return static_cast<double>(v); }

// Non-zeros of `rows` rows of `rays` rays in a scene of n patches (at most one per ray).
double row_nnz(double rows, int rays, std::size_t n) { return rows * std::min<double>(rays, d(n)); }

// One pass of the exact verification's decisive points (job_runner.cpp): a handful of
// points gathered again, about kDominantPerPoint patches each made precise (rows and
// direct light), one more solve and one more gather of every point.
// Its solve is the verification's last (counted there).
double decisive_pass_seconds(const CostCounts& c, const MachineCosts& m, double precise_pair_s, double Lv) {
  if (c.verify_decisive_rays <= 0 || c.grid_points == 0) return 0.0;
  constexpr double kDecisivePoints = 8.0, kDominantPerPoint = 20.0;
  const double P = static_cast<double>(c.grid_points), points = std::min(P, kDecisivePoints);
  const double rays = std::max(c.verify_rays, c.verify_decisive_rays);
  const double dominant = points * kDominantPerPoint;
  return (points * rays + dominant * std::max<double>(c.verify_rays, rays / 16.0) + P * c.verify_rays) * m.gather_ray_s +
         dominant * precise_pair_s * Lv;
}

// Direct light of one receiver-source pair: the cheap estimate (1 point, 2 rays), a
// precise patch (direct_points points, their grid rays) and a grid point (one point).
struct PairCosts {
  double cheap = 0.0, precise = 0.0, point = 0.0;
};

PairCosts pair_costs(const CostCounts& c, const MachineCosts& m) {
  PairCosts out;
  const double lookups = c.photometric ? c.point_sources * m.point_source_s : 0.0;  // per point
  const double rays = c.photometric ? m.precise_pair_ray_s : m.lambertian_precise_factor * m.precise_pair_ray_s;
  constexpr double kGridCells = 4.0;
  out.cheap = c.photometric ? m.photometric_cheap_pair_s : m.cheap_pair_s;
  const double cells = c.photometric ? kGridCells * m.point_source_s : 0.0;
  out.precise = c.direct_rays * rays + c.direct_points * (lookups + cells);
  out.point = c.point_direct_rays * rays + lookups + cells;
  return out;
}

// Gauss-Seidel sweeps of the exact verification: its first step from nothing, each
// later step from the last solution (both to the steps' loose residual), and the last
// solve on to the full tolerance; per sweep every non-zero of F, the colour channels
// swept together.
double verification_solve_seconds(const CostCounts& c, const MachineCosts& m, int steps, double nnz) {
  const double sweeps = m.gauss_seidel_sweeps + (steps - 1) * m.gauss_seidel_step_sweeps + m.gauss_seidel_final_sweeps;
  return sweeps * nnz * m.gauss_seidel_nnz_s * (1.0 + m.gauss_seidel_channel_share * (c.channels - 1));
}

// The interreflection solve (core/operator/contraction_solve.h): per channel, the first
// reflection gathered through the sample rows (rays x sources each), then sweeps
// over k rows of about 2 gathers (one sampled hit, the ambient term) x sources.
double interreflection_flops(double k, double sources, int channels, int rays_per_patch, const MachineCosts& m) {
  return channels * (2.0 * k * rays_per_patch * sources + m.interreflection_sweeps * 2.0 * 3.0 * k * sources);
}

}  // namespace

double expected_hit_patches(double rows, double rays, double population, const MachineCosts& costs) {
  if (!(population > 0.0)) return 0.0;
  return population * (1.0 - std::exp(-costs.hit_coverage * rows * rays / population));
}

AreaShareBins area_share_bins(const std::vector<double>& areas_m2) {
  double total = 0.0;
  for (double a : areas_m2) total += a;
  if (!(total > 0.0)) return {};
  // Bins of a quarter of a binary order of magnitude of the share.
  constexpr double kBinsPerOctave = 4.0;
  std::map<int, std::pair<double, double>> bins;  // bin -> (count, sum of shares)
  for (double a : areas_m2) {
    if (!(a > 0.0)) continue;
    const double share = a / total;
    auto& b = bins[static_cast<int>(std::floor(std::log2(share) * kBinsPerOctave))];
    b.first += 1.0;
    b.second += share;
  }
  AreaShareBins out;
  for (const auto& [bin, b] : bins) out.emplace_back(b.first, b.second / b.first);
  return out;
}

double expected_hit_patches(double rows, double rays, const AreaShareBins& bins, const MachineCosts& costs) {
  double hit = 0.0;
  for (const auto& [count, share] : bins) hit += count * (1.0 - std::exp(-costs.hit_area_factor * rows * rays * share));
  return hit;
}

double exact_verification_bytes(std::size_t patches, int rays_per_patch) {
  const double n = d(patches);
  // The scene's copy with the layout; no BVH: the job scene's is reused (RayCaster).
  return n * (kPatchBytes + kIndexBytesPerPatch) + row_nnz(n, rays_per_patch, patches) * kRowNnzPeakBytes;
}

double sample_verification_bytes(std::size_t k, std::size_t goal_patches, std::size_t sources, int rays_per_patch) {
  const double kk = d(k);
  return row_nnz(kk + d(goal_patches), rays_per_patch, k + goal_patches) * kRowNnzPeakBytes +
         8.0 * 4.0 * (kk + d(goal_patches)) * d(sources);
}

double CostEstimate::peak_bytes() const {
  const PhaseEstimate* p = largest_phase();
  return scene_bytes + (p ? p->bytes : 0.0);
}

double CostEstimate::total_seconds() const {
  double s = 0.0;
  for (const PhaseEstimate& p : phases) s += p.seconds;
  return s;
}

const PhaseEstimate* CostEstimate::largest_phase() const {
  const PhaseEstimate* best = nullptr;
  for (const PhaseEstimate& p : phases)
    if (!best || p.bytes > best->bytes) best = &p;
  return best;
}

namespace {

// Verification rounds (a search again when a goal is missed on verification): every
// shipped job verifies once (the flux correction meets what the verification finds), so
// the search and verification are counted once, whatever verification.rounds allows.
std::string rounds_text(int rounds) {
  return rounds > 1 ? "1 round expected, up to " + std::to_string(rounds) : std::string("1 round");
}

}  // namespace

CostEstimate estimate_job_cost(const CostCounts& c, const MachineCosts& m) {
  CostEstimate out;
  const double n = d(c.patches), L = d(c.sources), k = d(c.sample_size);
  const double Lr = c.reflected_sources > 0 ? std::min(L, d(c.reflected_sources)) : L;  // columns reflected
  const double pop = d(c.population);
  out.scene_bytes = kProcessBytes + n * (2.0 * kPatchBytes + kBvhBytesPerPatch + kIndexBytesPerPatch);
  const bool reflecting = c.population > 0 && c.sample_size > 0;
  const double P = d(c.grid_points), G = d(c.goal_patches) + P;  // every goal row: patches, then points
  const int point_rays = kPointRayFactor * c.rays_per_patch;
  const double goal_nnz = reflecting && c.exact_second_bounce
                              ? row_nnz(G - P, c.rays_per_patch, c.patches) + row_nnz(P, point_rays, c.patches)
                              : 0.0;
  const double D_goal = 8.0 * G * L;
  const PairCosts pair = pair_costs(c, m);
  const std::string grid_setting =
      setting_name(Setting::grid_spacing) + " (fewer points) or " + setting_name(Setting::grid_max_points);
  out.phases.push_back({kScenePhase, n * m.scene_patch_s, 0.0,
                        setting_name(Setting::patch_edge) + " (fewer patches)"});
  if (c.grid_points > 0)
    out.phases.push_back({"laying grids (" + std::to_string(c.grid_points) + " points at most)",
                          P * m.grid_rays_per_cell * m.gather_ray_s + d(c.grid_outline_tests) * m.outline_test_s,
                          P * kGridPointBytes, grid_setting});
  out.phases.push_back({"goal rows and direct light at goal patches" + std::string(P > 0 ? " and grid points" : ""),
                        ((G - P) * c.rays_per_patch + P * point_rays) * m.gather_ray_s +
                            ((G - P) * pair.precise + P * pair.point) * L,
                        goal_nnz * kRowNnzPeakBytes + 2.0 * D_goal,
                        P > 0 ? grid_setting + ", or " + setting_name(Setting::candidate_spacing) + " (fewer candidates)"
                              : setting_name(Setting::patch_edge) + " (fewer goal patches) or " +
                                    setting_name(Setting::candidate_spacing) + " (fewer candidates)"});
  auto hit_patches = [&](double rows, double rays) {
    return c.area_shares.empty() ? expected_hit_patches(rows, rays, pop, m) : expected_hit_patches(rows, rays, c.area_shares, m);
  };
  // One sample-based build of size kk on top of the goal rows.
  auto build = [&](double kk, const std::string& label, const std::string& setting) {
    const double hits = c.exact_second_bounce ? std::max(0.0, hit_patches(kk + G, c.rays_per_patch) - kk - G) : 0.0;
    const double sample_nnz = row_nnz(kk, c.rays_per_patch, c.patches);
    const double held = goal_nnz * kRowNnzBytes + D_goal;
    std::vector<PhaseEstimate> phases;
    phases.push_back({label + "sample rows (k = " + std::to_string(static_cast<long long>(kk)) + ")",
                      kk * c.rays_per_patch * m.gather_ray_s, held + sample_nnz * kRowNnzPeakBytes, setting});
    // The sample's direct light is the cheap estimate too, but a census's is precise.
    const double sample_pair_s = kk >= pop ? pair.precise : pair.cheap;
    // The hits in blocks: one block's direct light held at a time. A split build gives
    // each rank its share of the sources (T's columns, about Lr / shares): its columns of
    // every block's direct light, of the partial sums of F(rows,:) B1 (k + G rows per
    // channel) and their total, and of the sample's direct light (computed whole, then
    // cut to the rank's columns).
    const double shares = std::max(1, c.shares);
    const double Ls = std::ceil(Lr / shares);
    const double block = std::min(hits, d(std::max<std::size_t>(1, c.hit_block_patches)));
    const double first_bytes = c.exact_second_bounce ? 8.0 * c.channels * (kk + G) * Ls : 0.0;
    phases.push_back({label + "direct light at sample and hit patches (" + std::to_string(static_cast<long long>(hits)) +
                          " cheap" +
                          (shares > 1 ? ", " + std::to_string(static_cast<long long>(Ls)) + " of " +
                                            std::to_string(static_cast<long long>(Lr)) + " sources on this rank"
                                      : "") +
                          ")",
                      kk * sample_pair_s * Lr + hits * pair.cheap * Ls,
                      held + 2.0 * sample_nnz * kRowNnzBytes +
                          (shares > 1 ? std::max(3.0 * 8.0 * kk * Lr, 8.0 * kk * Ls + 2.0 * 8.0 * block * Ls + 2.0 * first_bytes)
                                      : 3.0 * 8.0 * kk * Lr + 2.0 * 8.0 * block * Lr + 2.0 * first_bytes),
                      setting_name(Setting::candidate_spacing) + " (fewer candidates) or " + setting});
    phases.push_back({label + "k x k solve (" + std::to_string(c.channels) + (c.channels == 1 ? " channel)" : " channels)"),
                      interreflection_flops(kk, Ls, c.channels, c.rays_per_patch, m) * m.sparse_flop_s,
                      held + 2.0 * sample_nnz * kRowNnzBytes + 6.0 * 8.0 * kk * Ls + first_bytes + 4.0 * D_goal,
                      // The first reflection's total has a row per goal row: grid points count.
                      P > 0 && first_bytes > 0.0 ? setting + ", or " + grid_setting : setting});
    return phases;
  };
  const std::string k_setting = setting_name(Setting::sample_fraction) + ", " + setting_name(Setting::sample_size) + " or " +
                                setting_name(Setting::target_error) + " (k)";
  if (reflecting && c.pilot_builds > 0 && c.pilot_size > 0) {
    PhaseEstimate pilot{"pilot samples (" + std::to_string(c.pilot_builds) + " x k = " + std::to_string(c.pilot_size) + ")",
                        0.0, 0.0, setting_name(Setting::pilot_fraction) + " or " + setting_name(Setting::error_samples)};
    for (const PhaseEstimate& p : build(d(c.pilot_size), "", pilot.setting)) {
      pilot.seconds += c.pilot_builds * p.seconds;
      pilot.bytes = std::max(pilot.bytes, p.bytes);
    }
    out.phases.push_back(pilot);
  }
  if (reflecting)
    for (PhaseEstimate& p : build(k, "", k_setting)) out.phases.push_back(std::move(p));
  out.phases.push_back({"T (goal patches x sources)",
                        c.channels * G * std::min<double>(k, c.rays_per_patch) * L * 2.0 * m.dense_flop_s,
                        5.0 * D_goal, setting_name(Setting::candidate_spacing) + " (fewer candidates)"});
  const double model_bytes = 2.0 * D_goal;  // the candidate columns, total and direct
  if (c.evaluations > 0)
    out.phases.push_back({"search (" + std::to_string(c.evaluations) + " evaluations)",
                          [&] {
                            const double s = d(static_cast<std::size_t>(c.evaluations)) * c.luminaires * 16.0 * G *
                                             m.blend_mac_s;
                            return c.search_max_seconds > 0.0 ? std::min(s, c.search_max_seconds) : s;
                          }(),
                          model_bytes + 4.0 * G * L, setting_name(Setting::max_evaluations)});
  const double Lv = c.luminaires + 1.0;
  if (c.verify == CostCounts::Verify::exact) {
    // Goal patches' rows and the points' gathers at verify_rays, every other row at
    // verify_indirect_rays (at most verify_rays): per row, the mean.
    const double Gp = d(c.goal_patches), indirect = std::min(c.verify_indirect_rays, c.verify_rays);
    // Progressive: the other rows at the first count, then doubled once (what the shipped
    // jobs mostly need), a Gauss-Seidel solve at each step.
    const int first = std::min(c.verify_first_indirect_rays, static_cast<int>(indirect));
    const int steps = first < indirect ? 2 : 1;
    const double other_rays = std::min<double>(indirect, first < indirect ? 2.0 * first : first);
    const int row_rays = n > 0.0 ? static_cast<int>(std::ceil((Gp * c.verify_rays + (n - Gp) * other_rays) / n)) : 1;
    // No BVH of its own: the job scene's is reused (RayCaster), the luminaires' alone built.
    const double per = (n * row_rays + P * c.verify_rays) * m.gather_ray_s +
                       ((G - P) * pair.precise + P * pair.point + n * pair.cheap) * Lv +
                       verification_solve_seconds(c, m, steps, row_nnz(n, row_rays, c.patches)) +
                       decisive_pass_seconds(c, m, pair.precise, Lv);
    out.phases.push_back({"verification (exact, " + std::to_string(c.verify_rays) + " rays per goal row, " +
                              std::to_string(static_cast<int>(other_rays)) + " elsewhere (up to " +
                              std::to_string(static_cast<int>(indirect)) + "), " + rounds_text(c.verify_rounds) + ")",
                          per, model_bytes + exact_verification_bytes(c.patches, row_rays),
                          setting_name(Setting::verification_rays) + " or " + setting_name(Setting::verification_method)});
  } else if (c.verify == CostCounts::Verify::sample) {
    const double kv = d(c.verify_sample_size);
    const double hits = std::max(0.0, hit_patches(kv + G, c.verify_rays) - kv - G);
    // Precise direct light at the goal patches and points; the sample's and its hits' cheap.
    const double per = (kv + G) * c.verify_rays * m.gather_ray_s +
                       ((G - P) * pair.precise + P * pair.point + (kv + hits) * pair.cheap) * Lv +
                       interreflection_flops(kv, Lv, c.channels, c.verify_rays, m) * m.sparse_flop_s;
    out.phases.push_back({"verification (sample, k = " + std::to_string(c.verify_sample_size) + ", " +
                              rounds_text(c.verify_rounds) + ")",
                          per,
                          model_bytes + n * kPatchBytes +
                              sample_verification_bytes(c.verify_sample_size, c.goal_patches + c.grid_points, c.luminaires + 1,
                                                       c.verify_rays),
                          setting_name(Setting::verification_sample_fraction) + " or " +
                              setting_name(Setting::verification_method)});
  }
  if (c.writes_outputs)
    out.phases.push_back({kOutputPhase,
                          m.output_base_s + (c.output_renders ? m.output_render_s : 0.0) +
                              d(c.plan_patches) * m.output_plan_patch_s + d(c.output_patches) * m.output_patch_s,
                          0.0,
                          setting_name(Setting::output_formats) + " (ply, csv write every patch)"});
  return out;
}

std::string format_bytes(double bytes) {
  std::ostringstream os;
  os << std::fixed;
  if (bytes >= 1e9) os << std::setprecision(2) << bytes / 1e9 << " GB";
  else os << std::setprecision(0) << bytes / 1e6 << " MB";
  return os.str();
}

std::vector<std::string> format_estimate(const CostEstimate& e) {
  std::vector<std::string> lines;
  for (const PhaseEstimate& p : e.phases) {
    std::ostringstream os;
    os << std::fixed << std::setprecision(1) << "estimate: " << p.name << ": " << p.seconds << " s, "
       << format_bytes(e.scene_bytes + p.bytes);
    lines.push_back(os.str());
  }
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << "estimate: in all about " << e.total_seconds() << " s, peak "
     << format_bytes(e.peak_bytes()) << " (scene and BVH " << format_bytes(e.scene_bytes) << ")";
  lines.push_back(os.str());
  return lines;
}

std::optional<double> available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double value = 0.0;
  std::string unit;
  while (in >> key >> value) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return value * 1024.0;  // kB
  }
  return std::nullopt;
}

namespace {

// A limit file's value in bytes; nullopt for "max", a missing file or v1's "no limit" (>= 2^60).
std::optional<double> read_limit(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string text;
  if (!in || !(in >> text) || text == "max") return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !(v > 0.0) || v >= 1152921504606846976.0) return std::nullopt;
  return v;
}

// The least limit in `file_name` of `dir`/`path` and each of its ancestors up to `dir`.
void least_limit(const std::filesystem::path& dir, const std::string& path, const std::string& file_name,
                 std::optional<MemoryBudget>& least) {
  std::filesystem::path p = std::filesystem::path(path).relative_path();
  for (;;) {
    const std::filesystem::path file = dir / p / file_name;
    if (const auto v = read_limit(file); v && (!least || *v < least->bytes))
      least = MemoryBudget{*v, "the cgroup limit in " + file.lexically_normal().string()};
    if (p.empty()) break;
    p = p.parent_path();
  }
}

}  // namespace

std::optional<MemoryBudget> cgroup_memory_limit(const CgroupFiles& files) {
  std::string root = files.root;
  if (root.empty()) {
    const char* env = std::getenv("ILP_CGROUP_ROOT");
    root = env && *env ? env : "/sys/fs/cgroup";
  }
  std::optional<MemoryBudget> least;
  std::ifstream in(files.self_cgroup);
  for (std::string line; std::getline(in, line);) {
    const auto a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    std::string controllers(1, ',');  // (not "," + ...: GCC 12 warns falsely, -Wrestrict)
    controllers.append(line, a + 1, b - a - 1).push_back(',');
    const std::string path = line.substr(b + 1);
    if (controllers == ",,") {  // v2 (or the hybrid layout's unified tree)
      least_limit(root, path, "memory.max", least);
      least_limit(std::filesystem::path(root) / "unified", path, "memory.max", least);
    } else if (controllers.find(",memory,") != std::string::npos) {
      least_limit(std::filesystem::path(root) / "memory", path, "memory.limit_in_bytes", least);
    }
  }
  return least;
}

std::optional<MemoryBudget> memory_budget(std::optional<double> max_memory_bytes, const CgroupFiles& files) {
  std::optional<MemoryBudget> least;
  auto consider = [&](std::optional<double> bytes, const std::string& source) {
    if (bytes && (!least || *bytes < least->bytes)) least = MemoryBudget{*bytes, source};
  };
  consider(available_memory_bytes(), "the machine's available memory (MemAvailable)");
  if (const auto cgroup = cgroup_memory_limit(files)) consider(cgroup->bytes, cgroup->source);
  consider(max_memory_bytes, "--max-memory");
  return least;
}

std::optional<double> memory_budget_bytes(std::optional<double> max_memory_bytes) {
  const std::optional<MemoryBudget> budget = memory_budget(max_memory_bytes);
  return budget ? std::optional<double>(budget->bytes) : std::nullopt;
}

void require_fits(const CostEstimate& e, const std::optional<MemoryBudget>& budget, const std::string& where) {
  if (budget) require_fits(e, budget->bytes, where, budget->source);
}

void require_fits(const CostEstimate& e, std::optional<double> budget, const std::string& where,
                  const std::string& budget_source) {
  if (!budget || e.peak_bytes() <= *budget) return;
  const PhaseEstimate* p = e.largest_phase();
  std::ostringstream os;
  os << where << ": the job would need about " << format_bytes(e.peak_bytes()) << " of memory";
  if (p) os << " (" << p->name << ": " << format_bytes(e.scene_bytes + p->bytes) << ")";
  os << ", more than the " << format_bytes(*budget)
     << " it may use (" << budget_source << "); refused before any work";
  if (p) os << ": change " << p->setting;
  throw ConfigError(os.str());
}

double parse_bytes(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size() && (std::isdigit(static_cast<unsigned char>(text[i])) || text[i] == '.')) ++i;
  const std::string number = text.substr(0, i);
  std::string unit;
  for (std::size_t j = i; j < text.size(); ++j)
    if (!std::isspace(static_cast<unsigned char>(text[j]))) unit += static_cast<char>(std::toupper(static_cast<unsigned char>(text[j])));
  char* end = nullptr;
  const double v = number.empty() ? -1.0 : std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !(v > 0.0))
    throw ConfigError("--max-memory " + text + ": must be a positive size such as 4G, 512M or 2000000000");
  if (!unit.empty() && unit.back() == 'B') unit.pop_back();
  if (!unit.empty() && unit.back() == 'I') unit.pop_back();
  double scale = 1.0;
  if (unit == "K") scale = 1024.0;
  else if (unit == "M") scale = 1024.0 * 1024.0;
  else if (unit == "G") scale = 1024.0 * 1024.0 * 1024.0;
  else if (unit == "T") scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else if (!unit.empty())
    throw ConfigError("--max-memory " + text + ": unknown unit (use K, M, G or T)");
  return v * scale;
}

}  // namespace ilp
