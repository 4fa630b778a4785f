// The sample operator's top level: the build as a list of named stages (their code is
// in sample_rows.cpp, gather_weights.cpp and sample_solve.cpp, declared in
// sample_operator_stages.h), the checks they share, and the run log written from the
// stats once the numerics are done.
#include "core/operator/sample_operator.h"

#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "core/base/error.h"
#include "core/operator/sample_operator_stages.h"
#include "core/base/key_hash.h"

namespace ilp {
namespace detail {

// Row labels for messages: goal patches, then points as -1 - index.
std::vector<int> goal_row_labels(std::span<const int> patches, std::size_t points) {
  std::vector<int> out(patches.begin(), patches.end());
  for (std::size_t q = 0; q < points; ++q) out.push_back(-1 - static_cast<int>(q));
  return out;
}

std::string patch_name(const Scene& scene, int patch) {
  if (patch < 0) return "grid point " + std::to_string(-1 - patch);
  return "patch " + std::to_string(patch) + " (" + scene.surfaces[scene.patches[patch].surface].name + ")";
}

// A NaN or Inf must never reach the output silently: stop and say where it arose.
void require_finite(const Eigen::MatrixXd& m, const char* stage, const Scene& scene, std::span<const int> row_patches,
                    std::span<const LightSource> sources) {
  for (Eigen::Index c = 0; c < m.cols(); ++c)
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      if (!std::isfinite(m(r, c)))
        throw NumericalError(std::string(stage) + ": non-finite value " + std::to_string(m(r, c)) + " at " +
                             patch_name(scene, row_patches[static_cast<std::size_t>(r)]) + " for light source '" +
                             sources[static_cast<std::size_t>(c)].name + "'");
}

// A reflectance outside [0, 1) or a NaN would otherwise drop the patch from the
// population (NaN > 0 is false) and flow into the output unnoticed.
void require_valid_materials(const Scene& scene) {
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    for (int c = 0; c < 3; ++c)
      if (!(p.reflectance[c] >= 0.0 && p.reflectance[c] < 1.0))
        throw NumericalError("materials: reflectance " + std::to_string(p.reflectance[c]) + " (channel " +
                             std::to_string(c) + ") at " + patch_name(scene, static_cast<int>(i)) +
                             " is not a number in [0, 1)");
    if (!(p.exitance_lm_per_m2 >= 0.0 && std::isfinite(p.exitance_lm_per_m2)))
      throw NumericalError("materials: exitance " + std::to_string(p.exitance_lm_per_m2) + " lm/m2 at " +
                           patch_name(scene, static_cast<int>(i)) + " is not a finite number >= 0");
  }
}

}  // namespace detail

using namespace detail;

namespace {

// What the run log reports of the interreflection solve beyond SampleOperatorStats,
// whose fields are the model cache's format (job/model_cache.cpp).
struct SolveCounts {
  Eigen::Index gathers = 0;  // non-zeros of W(P,P)
  int sweeps = 0;            // most sweeps of the iterative solve; 0: solved by LU
};

// The run log: what was simulated and why, from the stats of a finished build.
std::vector<std::string> sample_operator_log(const SampleOperatorStats& st, const SampleOperatorOptions& options,
                                             const SolveCounts& solve) {
  if (st.direct_only) return {"every reflectance is 0: direct light only, no sample, no interreflection"};
  const bool refine = options.indirect == IndirectMethod::exact_second_bounce;
  const std::size_t k = st.sample_patches;
  std::vector<std::string> log;
  std::ostringstream line;
  line << (st.channels == 1 ? "gray materials: 1 colour channel" : "coloured materials: 3 colour channels (RGB)");
  log.push_back(line.str());
  line.str("");
  if (st.census)
    line << "sample: every one of the " << st.population << " reflecting patches (k = n, no sampling error)";
  else
    line << "sample: " << k << " distinct patches of " << st.population << " reflecting ("
         << to_string(options.strategy) << ", k = " << options.sample_size << ", seed " << options.sample_seed << ")";
  log.push_back(line.str());
  line.str("");
  line << "rows cast: " << k << " sample + " << st.goal_patches << " goal of " << st.patches << " patches";
  line << ", " << options.form_factors.rays_per_patch << " rays each";
  if (st.goal_points > 0)
    line << " + " << st.goal_points << " goal points, " << options.form_factors.rays_per_patch * kPointRayFactor
         << " rays each";
  line << "; direct light at " << st.direct_rows << " goal and sample patches";
  if (refine) line << " (+ " << st.cheap_direct_rows << " cheap estimates at patches the rows hit)";
  line << "; indirect: " << to_string(options.indirect);
  log.push_back(line.str());
  line.str("");
  line << std::setprecision(3) << "I - K: " << k << " x " << k << " (" << solve.gathers << " gathers, "
       << st.sample_fallback_rows << " ambient rows), ";
  if (solve.sweeps > 0)
    line << "solved by iteration (" << solve.sweeps << " sweeps to a relative error bound of " << kSolveTolerance
         << "), condition estimate " << st.condition_estimate << " (infinity-norm bound)";
  else
    line << "solved by LU, condition estimate " << st.condition_estimate << " (1-norm)";
  line << "; largest row sum of K " << st.max_row_sum << ", so the infinity-norm condition is at most "
       << st.condition_bound_inf;
  log.push_back(line.str());
  if (st.point_fallback_rows > 0)
    log.push_back("ambient fallback: " + std::to_string(st.point_fallback_rows) + " goal points see no sample patch");
  if (st.goal_fallback_rows > 0 || st.sample_fallback_rows > 0) {
    line.str("");
    line << "ambient fallback: " << st.goal_fallback_rows << " goal patches (" << std::setprecision(2)
         << 100.0 * st.goal_fallback_area_fraction << " % of goal area) and " << st.sample_fallback_rows
         << " sample patches see no sample patch";
    log.push_back(line.str());
  }
  return log;
}

// The operator with the goal rows' share filled in: D(G,:), the counts and their rays.
SampleOperator start_from_goal_rows(const Scene& scene, const GoalRows& goals) {
  SampleOperator op;
  op.goal_patches = goals.patches;
  op.sources = goals.sources;
  op.direct_lux_per_lm = goals.direct_lux_per_lm;
  op.goal_points = goals.points;
  SampleOperatorStats& st = op.stats;
  st.patches = scene.patches.size();
  st.channels = scene.channels;
  st.goal_patches = goals.patches.size();
  st.goal_points = goals.points.size();
  if (!goals.points.empty() && goals.point_direct_lux_per_lm.rows() != static_cast<Eigen::Index>(goals.points.size()))
    throw std::invalid_argument("build_sample_operator: goal points without their direct light");
  st.rays_cast = goals.rays_cast;
  st.goal_seconds = goals.seconds;  // computed before, once for every build on these rows
  st.direct_rows = goals.patches.size();
  return op;
}

PatchSample draw_sample(const Scene& scene, std::span<const int> population, const SampleOperatorOptions& options,
                        SampleOperatorStats& st) {
  PatchSample sample = draw_patch_sample(scene, population, options.sample_size, options.strategy, options.sample_seed);
  st.sample_patches = sample.patches.size();
  st.census = sample.census;
  return sample;
}

SampleOperator build_in_arena(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                              const SampleOperatorOptions& options, const ProgressCallback& progress) {
  if (options.sample_size < 1)
    throw std::invalid_argument("sample_size = " + std::to_string(options.sample_size) + ": must be >= 1");
  require_valid_materials(scene);
  const SourceTable table = make_source_table(scene, goals.sources);
  SampleOperator op = start_from_goal_rows(scene, goals);
  SampleOperatorStats& st = op.stats;

  const std::vector<int> population = reflecting_patches(scene);
  st.population = population.size();
  if (population.empty()) {
    st.direct_only = true;
    assemble_direct_only(goals, op);
    op.log = sample_operator_log(st, options, {});
    return op;
  }
  const bool refine = options.indirect == IndirectMethod::exact_second_bounce;
  if (refine && !goals.rows)
    throw std::invalid_argument("build_sample_operator: exact_second_bounce needs goal rows computed with it");

  op.sample = draw_sample(scene, population, options, st);
  SampleRows rows = cast_sample_rows(scene, caster, goals, op.sample, table, options, progress, st);
  const auto direct_start = std::chrono::steady_clock::now();
  const SampleDirect direct = direct_light_at_sample(scene, caster, goals, op.sample, rows, table, options, progress, st);
  const FirstReflection first =
      refine ? first_reflection_at_rows(scene, caster, goals, rows, direct, table, options, progress, st) : FirstReflection{};
  st.direct_seconds = seconds_since(direct_start);
  GatherWeights weights = compute_gather_weights(scene, goals, op.sample, rows, st);
  const IndirectLight indirect =
      solve_indirect_light(scene, goals, op.sample, direct, first, table, weights, options, progress, st);
  assemble_response(scene, goals, indirect, op);

  op.log = sample_operator_log(st, options, {weights.sample.W.nonZeros(), indirect.solve_sweeps});
  return op;
}

}  // namespace

std::vector<LightSource> scene_light_sources(const Scene& scene) {
  std::vector<LightSource> out;
  std::vector<bool> emits(scene.surfaces.size(), false);
  for (const Patch& p : scene.patches)
    if (p.exitance_lm_per_m2 > 0.0) emits[p.surface] = true;
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s)
    if (scene.surfaces[s].is_luminaire() || emits[s])
      out.push_back({scene.surfaces[s].name, static_cast<int>(s),
                     scene.surfaces[s].is_luminaire() ? SourceKind::luminaire : SourceKind::emitting_surface});
  return out;
}

Eigen::VectorXd source_flux_lm(const Scene& scene, std::span<const LightSource> sources) {
  Eigen::VectorXd flux = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sources.size()));
  for (const Patch& p : scene.patches)
    for (std::size_t l = 0; l < sources.size(); ++l)
      if (sources[l].surface == p.surface) flux[static_cast<Eigen::Index>(l)] += p.area_m2 * p.exitance_lm_per_m2;
  return flux;
}

std::string_view to_string(IndirectMethod method) {
  return method == IndirectMethod::sample_gather ? "sample_gather" : "exact_second_bounce";
}

std::optional<IndirectMethod> parse_indirect_method(std::string_view text) {
  for (IndirectMethod m : {IndirectMethod::sample_gather, IndirectMethod::exact_second_bounce})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

std::vector<int> reflecting_patches(const Scene& scene) {
  std::vector<int> out;
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    if (is_reflecting(scene, scene.patches[i])) out.push_back(static_cast<int>(i));
  return out;
}

// The phases that do not open their own arena (the first-reflection gathers, the
// interreflection solve) run in an arena of options.form_factors.threads threads, as the
// ray casting does.
SampleOperator build_sample_operator(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                     const SampleOperatorOptions& options, const ProgressCallback& progress) {
  const int threads = options.form_factors.threads;
  tbb::task_arena arena(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
  return arena.execute([&] { return build_in_arena(scene, caster, goals, options, progress); });
}

// Not hashed: share (which process computes which block never changes the bits).
static_assert(field_count<SampleOperatorOptions>() == 10,
              "SampleOperatorOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const SampleOperatorOptions& o) {
  k.field("sample_size", o.sample_size).field("strategy", o.strategy).field("sample_seed", o.sample_seed);
  k.field("indirect", o.indirect).field("form_factors", o.form_factors).field("direct_light", o.direct_light);
  k.field("hit_direct_light", o.hit_direct_light);
  k.field("sample_direct_light", o.sample_direct_light);
  k.field("hit_block_patches", o.hit_block_patches);
}

}  // namespace ilp
