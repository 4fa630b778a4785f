// The sample-based radiosity operator (METHOD sections 3 and 4). From the rows of a
// random sample P of k patches it builds T, the illuminance at chosen goal patches
// G per lumen of each light source, so that a configuration of source fluxes phi
// costs one product: H_G = T phi. Light straight from a source is exact; light
// reflected once or more goes through the sample:
//
//   gather weights  W_ip = s_i w_p a_ip / sum_q w_q a_iq       (ratio estimator)
//   K = R_P W(P,P),  Bʳ_P = (I - K)^-1 R_P D(P,:)   per colour channel, LU in double
//   T = D(G,:) + W(G,P) Bʳ_P
//
// With the first reflection gathered exactly (IndirectMethod::exact_second_bounce,
// the default), B1 = R D at the patches the full rows hit and
//   T = D(G,:) + F(G,:) B1 + W(G,P) (I - K)^-1 R_P F(P,:) B1
//
// s_i is the fraction of patch i's rays that reach a reflecting patch (the row sum
// over the population), w_p the sample weight (1 / inclusion probability) and
// a_ip an estimate of A_i F_ip: from i's own row when i was sampled (so k = n
// reproduces the exact solve), else A_p F_pi by reciprocity from p's row, plus
// A_i F_ip from i's own row where goal rows are kept (exact_second_bounce). Where no
// sample patch is seen from i (every a_ip = 0) the fallback is the ambient term:
// W_ip = s_i A_p w_p / sum_q A_q w_q, i.e. i sees the area-weighted mean of the
// sample's reflected radiosity. Row sums of K are rho_i s_i < 1, so I - K is
// strictly diagonally dominant and its inverse is non-negative.
//
// Only the rows needed are computed: k sample rows, the goal patches' row sums,
// and direct light at goal and sample patches (all patches only when the goals
// are all patches). With every reflectance 0 there is no sample at all.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/base/progress.h"
#include "core/transport/direct_light.h"
#include "core/operator/patch_sample.h"
#include "core/operator/work_share.h"
#include "core/transport/form_factors.h"
#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

// A column of T: a luminaire surface (direct light in closed form with shadow rays)
// or a surface given an exitance (direct light gathered by the rows' rays).
// What a source of light is: a luminaire (its photometry gives its direct light), an
// emitting surface (Lambertian exitance), and room for what a daylight job adds: a patch of
// sky or the sun, whose light enters through the rays that leave the scene
// (core/transport/form_factors.h, EscapeBins), not through a surface of the scene.
enum class SourceKind { luminaire, emitting_surface, sky_patch, sun };

struct LightSource {
  std::string name;
  int surface = -1;  // its surface (-1 for a sky patch or the sun)
  SourceKind kind = SourceKind::luminaire;
};

// Every luminaire and every emitting surface of the scene, in surface order.
std::vector<LightSource> scene_light_sources(const Scene& scene);
// The flux each source emits as the scene stands (exitance x area), lm.
Eigen::VectorXd source_flux_lm(const Scene& scene, std::span<const LightSource> sources);

// How light reflected at least once reaches the sample and goal patches.
enum class IndirectMethod {
  sample_gather,        // every bounce through the sample (METHOD section 4, the plain form)
  exact_second_bounce,  // the first reflection gathered through full rows (needs direct light at
                        // every patch those rows hit); the sample carries the rest
};
std::string_view to_string(IndirectMethod method);
std::optional<IndirectMethod> parse_indirect_method(std::string_view text);

struct SampleOperatorOptions {
  int sample_size = 1;  // k: patches drawn from the reflecting ones; >= their number means all of them
  SampleStrategy strategy = SampleStrategy::stratified;
  std::uint64_t sample_seed = 1;  // which patches are drawn (the rays follow form_factors.seed)
  IndirectMethod indirect = IndirectMethod::exact_second_bounce;
  FormFactorOptions form_factors;  // rays per row for sample and goal rows
  DirectLightOptions direct_light;
  // exact_second_bounce only: direct light at the patches the rows hit that are
  // neither goal nor sample patches, seen only through a row's average over its hits.
  DirectLightOptions hit_direct_light = cheap_direct_light_options();
  // Direct light at the sample patches that are not goal patches: like the hits, it is
  // read only through reflections (the k x k system's emission), and each sample patch
  // stands for a stratum of about n / k patches, so one patch's estimate needs no more
  // precision than the stratum's spread. Receiver points are random on the patch and
  // shadow rays stratified over the opening: the cheap estimate is unbiased.
  DirectLightOptions sample_direct_light = cheap_direct_light_options();
  // exact_second_bounce: the patches the rows hit are taken in fixed blocks of this many
  // (the first reflection's partial sums are added in block order): a block's direct
  // light is held at a time. Also the blocks of goal patches whose precise direct light
  // a split build spreads. Changes the last bits of T (the order of the sums), never
  // with share or threads.
  int hit_block_patches = 1 << 14;
  // How a split build shares the work (one process by default; docs/cluster.md): the
  // goal patches' direct light by blocks; the sources (T's columns) by contiguous ranges
  // (WorkShare::column_range), each process holding only its columns of the direct
  // light at the sample and hit patches, the first reflection and the k x k solve, the
  // goals' and points' light gathered at the end. Not in the cache key: the bits do not
  // depend on it.
  WorkShare share;
};

// The operator cache's key (core/base/key_hash.h): every field (the nested options
// leave out their threads and progress).
void hash_fields(KeyWriter& k, const SampleOperatorOptions& o);

// Goal points' gather rows cast this many times form_factors.rays_per_patch rays.
inline constexpr int kPointRayFactor = 4;

// What the goal patches need whatever the sample: their direct light and row sums.
// Built once, it serves every sample drawn for the same goals (sample-size studies).
struct GoalRows {
  std::vector<int> patches;
  std::vector<LightSource> sources;
  Eigen::MatrixXd direct_lux_per_lm;       // D(G,:), #goals by #sources
  Eigen::MatrixXd luminaire_form_factor;   // #goals by #sources: form factor to each luminaire that absorbs (else 0)
  Eigen::VectorXd reflecting_fraction;     // s_i: rays reaching the front of a reflecting patch
  Eigen::VectorXd kept_scale;              // factor on the non-luminaire entries of each row (see the .cpp)
  std::optional<FormFactorRows> rows;      // full rows, kept for IndirectMethod::exact_second_bounce
  // Goal rows without area (calculation-grid points), after the patches: each has its
  // own full gather row (whatever the indirect method) and exact direct light from
  // compute_luminaire_light_at_points. Like a goal patch outside the sample, but its a_ip
  // come from its own row only (no area, so no reciprocity from the sample's columns).
  std::vector<ReceiverPoint> points;
  Eigen::MatrixXd point_direct_lux_per_lm;  // #points by #sources
  Eigen::VectorXd point_reflecting_fraction;
  Eigen::VectorXd point_kept_scale;
  std::optional<FormFactorRows> point_rows; // present when there are points and something reflects or is gathered
  std::uint64_t rays_cast = 0;
  double seconds = 0.0;
};

GoalRows compute_goal_rows(const Scene& scene, const RayCaster& caster, std::span<const int> goal_patches,
                           std::span<const LightSource> sources, const SampleOperatorOptions& options,
                           const ProgressCallback& progress = {});
// The same with goal points (rows after the patches' in T). Point rows use
// options.form_factors with kPointRayFactor x rays_per_patch rays, and
// options.direct_light.shadow_rays shadow rays per luminaire.
GoalRows compute_goal_rows(const Scene& scene, const RayCaster& caster, std::span<const int> goal_patches,
                           std::span<const ReceiverPoint> goal_points, std::span<const LightSource> sources,
                           const SampleOperatorOptions& options, const ProgressCallback& progress = {});

struct SampleOperatorStats {
  std::size_t patches = 0;                // in the scene
  std::size_t population = 0;             // reflecting patches, the ones a sample is drawn from
  std::size_t sample_patches = 0;         // distinct patches drawn (rows cast)
  bool census = false;                    // every reflecting patch is in the sample
  bool direct_only = false;               // every reflectance is 0: no sample, T = D
  int channels = 1;
  std::size_t goal_patches = 0;
  std::size_t goal_points = 0;            // goal rows without area (grid points), after the patches
  std::size_t point_fallback_rows = 0;    // goal points that see reflecting patches but no sample patch (ambient)
  std::size_t direct_rows = 0;            // goal and sample patches whose direct light was computed
  std::size_t cheap_direct_rows = 0;      // exact_second_bounce: other patches the rows hit (cheap estimate)
  std::size_t goal_fallback_rows = 0;     // goal patches that see reflecting patches but no sample patch (ambient)
  double goal_fallback_area_fraction = 0.0;
  std::size_t sample_fallback_rows = 0;   // likewise for sample patches
  double condition_estimate = 1.0;        // of I - K, 1-norm (LAPACK-style estimate), largest over channels
  // Largest row sum of K (rho_a s_a < 1) and the infinity-norm condition bound it gives by
  // diagonal dominance, (1 + r) / (1 - r): what governs the LU's stability. The 1-norm
  // estimate can be far larger on real meshes, where a few big patches collect large
  // column sums of K, without any loss of accuracy.
  double max_row_sum = 0.0;
  double condition_bound_inf = 1.0;
  std::uint64_t rays_cast = 0;            // gather rays: sample rows + goal rows
  double goal_seconds = 0.0;
  double sample_row_seconds = 0.0;
  double direct_seconds = 0.0;            // direct light at the sample (and, refined, at the rows' hits)
  double solve_seconds = 0.0;             // LU of I - K and the solves
  double response_seconds = 0.0;          // forming T
  double build_seconds() const {
    return goal_seconds + sample_row_seconds + direct_seconds + solve_seconds + response_seconds;
  }
};

struct SampleOperator {
  std::vector<int> goal_patches;
  std::vector<ReceiverPoint> goal_points;  // rows goal_patches.size() and on of T and D
  std::vector<LightSource> sources;
  Eigen::MatrixXd direct_lux_per_lm;  // D(G,:): #goal patches + #goal points by #sources
  Eigen::MatrixXd total_lux_per_lm;   // T: photometric (luminance-weighted for RGB), the same rows
  Eigen::MatrixXd reflected_lm_per_m2_per_lm;  // rho H at the goal rows (0 at points), photometric: radiosity minus emission
  PatchSample sample;
  SampleOperatorStats stats;
  std::vector<std::string> log;       // what was simulated and why, for the run log

  // Total illuminance at the goal patches for the given source fluxes (lm), lux.
  Eigen::VectorXd illuminance_lux(const Eigen::VectorXd& flux_lm) const { return total_lux_per_lm * flux_lm; }
  Eigen::VectorXd direct_lux(const Eigen::VectorXd& flux_lm) const { return direct_lux_per_lm * flux_lm; }
};

// Builds T for the goal rows (from compute_goal_rows with the same options). Throws
// NumericalError naming the stage, patch and source if anything becomes non-finite
// or clearly negative, std::invalid_argument on bad options.
SampleOperator build_sample_operator(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                     const SampleOperatorOptions& options, const ProgressCallback& progress = {});

// Reflecting patches (some channel of rho > 0, not a luminaire): the population.
std::vector<int> reflecting_patches(const Scene& scene);

}  // namespace ilp
