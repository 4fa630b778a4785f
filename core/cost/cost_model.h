// What a job will cost before it is run: memory and time of each phase of the
// operator build (goal rows, direct light, sample rows, the k x k solve, T), the
// search and the verification, from counts alone (patches, goal patches, k,
// sources, rays, channels) and per-unit constants measured on the reference machine
// (docs/benchmarks.md, "Cost model"). Used to print the estimate in the run log, to
// refuse a job that would not fit in memory before any work is done (naming the
// setting to change), and to choose the automatic verification method.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace ilp {

// Per-unit costs on 2 threads of the reference machine: the direct light, the
// verification's solves and rounds fitted on an Intel Xeon 2.8 GHz (2026-12-03,
// docs/benchmarks.md "Cost model"), the rest earlier on an AMD EPYC, where the shipped
// jobs ran 1.4-1.6x faster. Another machine's, and another thread count's, are these
// scaled by its probed speed (machine_costs in core/cost/machine_speed.h).
struct MachineCosts {
  double gather_ray_s = 1.0 / 5.3e6;        // one form-factor ray (closest hit, row assembly)
  double precise_pair_ray_s = 7.8e-8;       // direct light: per shadow ray of a precise receiver-source pair
  double cheap_pair_s = 6.4e-8;             // direct light: one cheap (1 point, 2 rays) receiver-source pair
  double dense_flop_s = 1.0 / 13.3e9;       // LU and triangular solves in double
  // Gathers of rows of D and X (memory-bound): the classroom's interreflection solve,
  // 2.8e9 of them as interreflection_flops counts, in 0.66-0.9 s (2026-12-03).
  double sparse_flop_s = 1.0 / 3.5e9;
  int interreflection_sweeps = 100;         // sweeps of a typical interreflection solve (q ~ 0.9, 1e-10)
  double blend_mac_s = 1.44e-10;            // search: one multiply-add of a candidate column, single precision
  double gauss_seidel_nnz_s = 2.0e-9;       // one non-zero of F per Gauss-Seidel sweep, one channel
  double gauss_seidel_channel_share = 0.5;  // each further colour channel, swept in the same pass
  // Sweeps of the exact verification's solves (the classroom: 16, 8, then 16 to 1e-8 after
  // its decisive pass): its first step to the steps' residual (1e-5), each later step
  // from the last solution, the last solve on to solver.relative_residual.
  int gauss_seidel_sweeps = 16;
  int gauss_seidel_step_sweeps = 8;
  int gauss_seidel_final_sweeps = 16;
  // With the patches' area shares (CostCounts::area_shares): the effective share of rays
  // that strike a reflecting patch, 0.5 from the classroom (46,050 cheap hits).
  double hit_area_factor = 0.5;
  double hit_coverage = 0.13;               // distinct patches hit ~ pop (1 - exp(-coverage rows rays / pop)): the
                                            // classroom's 3,537 rows of 128 rays hit 49,400 of 160,000 (2026-12-03)
  // A photometric product's cheap pair (the opening's point sources and 2 shadow rays, each
  // weighed by its target's intensity), per pair whose light is computed: 0.41, 0.49 and
  // 0.58 us on the classroom, Sibenik and office_wallwash (2026-12-03, Intel Xeon 2.8 GHz),
  // whatever their point sources a pair (4.0, 1.1-1.5, 4.2).
  double photometric_cheap_pair_s = 4.5e-7;
  // A precise photometric point's intensity lookups: at each point source the opening is
  // cut into (CostCounts::point_sources) and at its 4 grid cells' centroids.
  double point_source_s = 6.0e-8;
  // A Lambertian panel's precise pair against its shadow rays alone: the opening's and
  // each grid cell's closed-form form factor (the office's 1,682 goal patches x 96
  // panels in 3.2 s, 4x their rays' cost).
  double lambertian_precise_factor = 4.0;
  // Reading and meshing the model and building its BVH, per patch: the conference's
  // 346,551 patches in 0.71 + 0.28 s, the classroom's 167,659 in 0.15-0.30 + 0.20-0.24 s.
  double scene_patch_s = 2.8e-6;
  // Writing the outputs: a fixed part (result.json, SVG plans: 0.05 s; rendering PNGs and the
  // PDF: 0.3 s more on the office) and, where the formats write every patch (scene.ply, illuminance.csv),
  // a part per patch (the classroom's 167,659 and the conference's 346,461 patches: 0.8
  // and 1.3 s between the timings' total and the process's wall clock, 2026-12-03).
  double output_base_s = 0.05;
  double output_render_s = 0.3;             // when plans, isolux maps are rendered to PNG or the PDF is written
  // A rendered plan (plan.png, the PDF's) fills the room's outline, one triangle a
  // mounting patch (every patch for suspended luminaires): with Sibenik's 222,000 outline
  // triangles its outputs took 3.4-4.1 s (the wall clock of `ilp run --no-cache` less
  // timings.json's total) where 1.0 s was estimated; the classroom's 9,500, 0.85-1.03 s
  // (2026-12-03).
  double output_plan_patch_s = 1.2e-5;
  double output_patch_s = 2.8e-6;
  int grid_rays_per_cell = 8;               // laying a grid: 6 inside-solid rays and 2 floor rays a cell
  double outline_test_s = 1.5e-8;           // one point against one outline triangle, 9 times (the band)
};

// The counts a job's cost follows.
struct CostCounts {
  std::size_t patches = 0;           // n, in the job scene
  std::size_t population = 0;        // reflecting patches
  std::vector<std::pair<double, double>> area_shares;  // their area shares, binned (area_share_bins); empty: unknown
  std::size_t goal_patches = 0;      // G
  // Calculation-grid points P: goal rows too (their own gather rows of kPointRayFactor x
  // rays, direct light, rows of D and T), and laid first (the inside-solid and floor
  // rays per cell, the outline test per cell and outline part).
  std::size_t grid_points = 0;       // the grids' cells when not laid yet (the most points)
  std::size_t grid_outline_tests = 0;  // cells x outline parts (triangles or polygon edges)
  std::size_t sources = 0;           // L: fixed sources + candidates
  // Of those, the ones whose reflected light is computed (the rest blended:
  // core/operator/reflected_blend.h); 0: every source. The sample's and the hit
  // patches' direct light and the k x k solve run over these columns only.
  std::size_t reflected_sources = 0;
  std::size_t sample_size = 0;       // k (0: direct light only)
  int channels = 1;
  int rays_per_patch = 128;
  bool exact_second_bounce = true;
  int direct_rays = 64;              // receiver points x shadow rays of precise direct light
  int point_direct_rays = 8;         // a grid point's: one receiver point, its shadow rays
  bool photometric = false;          // the candidates' product has a photometric file (not a Lambertian panel)
  int direct_points = 8;             // receiver points of a precise patch
  // Point sources per receiver point and photometric luminaire (mean_point_sources over
  // the reflecting patches and the job scene's luminaires): more in a small room of long
  // luminaires, whose receivers are near them.
  double point_sources = 1.0;
  // A split build (core/operator/work_share.h): the sources (T's columns) split over
  // the ranks. The estimate is one rank's: the scene and BVH, the rows and the sample's
  // direct light replicated; its columns of the hits' direct light, of the first
  // reflection and of the k x k solve.
  int shares = 1;
  std::size_t hit_block_patches = std::size_t{1} << 14;
  int pilot_builds = 0;              // target_error: pilot operators built before the real one
  std::size_t pilot_size = 0;
  // search
  int luminaires = 1;                // largest count searched
  long long evaluations = 0;         // budget (global + local) per count, times the counts tried
  double search_max_seconds = 0.0;   // optimizer.max_seconds (0: no cap), per search round
  // verification
  enum class Verify { none, exact, sample } verify = Verify::none;
  int verify_rays = 1024;            // goal patches' rows and grid points' gathers
  int verify_indirect_rays = 1 << 30;  // exact: every other patch's row (capped at verify_rays): the most
  int verify_first_indirect_rays = 1 << 30;  // exact: where the progressive refinement starts (one doubling assumed)
  // exact: the points deciding a minimum or maximum gathered again with this many rays
  // and their dominant patches' rows at a sixteenth (0: off; one pass of kCostDecisivePoints assumed)
  int verify_decisive_rays = 0;
  std::size_t verify_sample_size = 0;  // sample verification: k
  int verify_rounds = 1;
  // outputs
  bool writes_outputs = true;        // the run writes its output set (the last phase)
  std::size_t output_patches = 0;    // patches the formats write one by one (scene.ply, illuminance.csv)
  bool output_renders = false;       // PNG plans or isolux maps, or the PDF report
  std::size_t plan_patches = 0;      // the plan's outline triangles when it is rendered (the mounting surface's patches)
};

struct PhaseEstimate {
  std::string name;
  double seconds = 0.0;
  double bytes = 0.0;      // peak memory while the phase runs (on top of the scene)
  std::string setting;     // the setting that governs it, for a refusal message
};

struct CostEstimate {
  double scene_bytes = 0.0;            // scene copies and BVH, held throughout
  std::vector<PhaseEstimate> phases;   // in run order
  double peak_bytes() const;           // scene + the largest phase
  double total_seconds() const;
  const PhaseEstimate* largest_phase() const;  // by memory
};

CostEstimate estimate_job_cost(const CostCounts& counts, const MachineCosts& costs = {});
// The name of the last phase, writing the output set, and of the first, the scene and its
// BVH (each once a run, whatever its variants).
inline constexpr const char* kOutputPhase = "writing the outputs";
inline constexpr const char* kScenePhase = "reading the model, meshing and the BVH";

// Memory of the verification alone (peak), for choosing its method.
double exact_verification_bytes(std::size_t patches, int rays_per_patch);
double sample_verification_bytes(std::size_t k, std::size_t goal_patches, std::size_t sources, int rays_per_patch);
// Distinct patches hit by `rows` rows of `rays` rays each, of `population` (a fit).
double expected_hit_patches(double rows, double rays, double population, const MachineCosts& costs = {});
// The reflecting patches' areas as shares of their total area, binned: (patches, mean
// share) per bin. A ray strikes a patch about in proportion to its area, so a model of
// many small patches (a chair's) and a few large ones (walls) is struck on fewer
// distinct patches than one of even patches (a nave): the classroom's 523,000 rows'
// rays strike 49,600 of its 167,659 patches, Sibenik's 282,000 strike 76,500 of 204,572.
using AreaShareBins = std::vector<std::pair<double, double>>;
AreaShareBins area_share_bins(const std::vector<double>& areas_m2);
// Distinct patches hit, from the area shares: sum over patches of 1 - exp(-c R share),
// R = rows x rays, c = costs.hit_area_factor.
double expected_hit_patches(double rows, double rays, const AreaShareBins& bins, const MachineCosts& costs = {});

// Lines for the run log: one per phase (s, GB) and a total.
std::vector<std::string> format_estimate(const CostEstimate& estimate);

// MemAvailable of /proc/meminfo in bytes; nullopt where it cannot be read.
std::optional<double> available_memory_bytes();

// A memory limit and where it comes from, for messages: "the machine's available
// memory (MemAvailable)", "the cgroup limit (/sys/fs/cgroup/.../memory.max)", "--max-memory".
struct MemoryBudget {
  double bytes = 0.0;
  std::string source;
};

// Where the cgroup files are: /proc/self/cgroup names this process's cgroup per
// hierarchy ("0::/PATH" for v2, "N:memory:/PATH" for v1); `root` is where the
// hierarchies are mounted (empty: $ILP_CGROUP_ROOT if set, else /sys/fs/cgroup; v1's
// memory controller in ROOT/memory, v2 in ROOT or ROOT/unified).
struct CgroupFiles {
  std::string self_cgroup = "/proc/self/cgroup";
  std::string root;
};

// The least memory limit of this process's cgroup and its ancestors (v2 memory.max,
// v1 memory.limit_in_bytes; "max" and v1's near-2^63 mean none); nullopt when none.
// A container sees its own cgroup as the root, so the walk goes up to ROOT itself.
std::optional<MemoryBudget> cgroup_memory_limit(const CgroupFiles& files = {});

// The memory a job may use: the least of MemAvailable, the cgroup limit and
// `max_memory_bytes`, with the name of the one that applied.
std::optional<MemoryBudget> memory_budget(std::optional<double> max_memory_bytes, const CgroupFiles& files = {});
std::optional<double> memory_budget_bytes(std::optional<double> max_memory_bytes);

// Throws ConfigError when the estimate's peak exceeds the budget, naming the phase,
// both figures, the budget's source and the setting to change; `where` prefixes the
// message (the config file).
void require_fits(const CostEstimate& estimate, std::optional<double> budget_bytes, const std::string& where,
                  const std::string& budget_source = "the machine's available memory or --max-memory");
void require_fits(const CostEstimate& estimate, const std::optional<MemoryBudget>& budget, const std::string& where);

// "2.5 GB" / "512 MB", for messages.
std::string format_bytes(double bytes);
// "4 GB", "512M", "1.5G", "800 MB": a size with an optional unit (K, M, G, T; B and i
// ignored; none means bytes). Throws ConfigError on anything else.
double parse_bytes(const std::string& text);

}  // namespace ilp
