#include "core/operator/sample_operator.h"

#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/operator/contraction_solve.h"
#include "core/base/error.h"
#include "core/rays/point_gather.h"
#include "core/exact/radiosity.h"
#include "core/base/key_hash.h"

namespace ilp {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool is_reflecting(const Scene& scene, const Patch& p) {
  return !scene.surfaces[p.surface].is_luminaire() && p.reflectance.maxCoeff() > 0.0;
}

// Luminaires get closed-form direct light; any other source is gathered by the rows' rays.
struct SourceTable {
  std::vector<double> area_m2;          // per source
  std::vector<int> emitting_index;      // per source: index among gathered sources, -1 for luminaires
  std::vector<int> gathered;            // source index of each gathered source
  std::vector<int> luminaire_patches;   // the luminaires' openings (rays that strike them are dropped)
  std::vector<int> luminaire_surfaces;  // for compute_luminaire_light
  std::vector<int> luminaire_source;    // source index of each luminaire surface
  std::vector<int> gathered_of_patch;   // per scene patch: gathered source index or -1
  std::vector<bool> absorbs;            // per source: a luminaire in the geometry (not a virtual candidate)
};

SourceTable make_source_table(const Scene& scene, std::span<const LightSource> sources) {
  SourceTable t;
  std::vector<int> source_of_surface(scene.surfaces.size(), -1);
  for (std::size_t l = 0; l < sources.size(); ++l) {
    const int s = sources[l].surface;
    if (s < 0 || s >= static_cast<int>(scene.surfaces.size()))
      throw std::invalid_argument("light source '" + sources[l].name + "': surface " + std::to_string(s) +
                                  " is not in the scene");
    if (source_of_surface[s] >= 0)
      throw std::invalid_argument("light source '" + sources[l].name + "': surface listed twice");
    source_of_surface[s] = static_cast<int>(l);
    const bool luminaire = scene.surfaces[s].is_luminaire();
    t.emitting_index.push_back(luminaire ? -1 : static_cast<int>(t.gathered.size()));
    t.absorbs.push_back(luminaire && !scene.surfaces[s].is_virtual);
    if (!luminaire) t.gathered.push_back(static_cast<int>(l));
    if (luminaire) {
      t.luminaire_surfaces.push_back(s);
      t.luminaire_source.push_back(static_cast<int>(l));
    }
  }
  t.area_m2.assign(sources.size(), 0.0);
  t.gathered_of_patch.assign(scene.patches.size(), -1);
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const int l = source_of_surface[scene.patches[i].surface];
    if (l < 0) continue;
    t.area_m2[l] += scene.patches[i].area_m2;
    if (t.emitting_index[l] < 0) {
      t.luminaire_patches.push_back(static_cast<int>(i));
    } else {
      t.gathered_of_patch[i] = t.emitting_index[l];
    }
  }
  return t;
}

// Row sums of one row split the way the gather needs them: s_i over the reflecting
// patches, per gathered source the fraction of rays reaching it, and the split of
// front hits between luminaires (of the sources) and everything else.
struct RowSums {
  Eigen::VectorXd reflecting;   // per row
  Eigen::MatrixXd gathered;     // rows by #gathered sources
  Eigen::VectorXd luminaire;    // rays that struck a luminaire
  Eigen::VectorXd kept;         // rays that struck the front of any other patch
};

std::vector<bool> source_luminaire_mask(const Scene& scene, const SourceTable& sources) {
  std::vector<bool> mask(scene.patches.size(), false);
  for (int p : sources.luminaire_patches) mask[static_cast<std::size_t>(p)] = true;
  return mask;
}

RowSums row_sums_from_rows(const Scene& scene, const SparseRows& F, const SourceTable& sources) {
  const Eigen::Index rows = F.rows();
  RowSums out{Eigen::VectorXd::Zero(rows), Eigen::MatrixXd::Zero(rows, static_cast<Eigen::Index>(sources.gathered.size())),
              Eigen::VectorXd::Zero(rows), Eigen::VectorXd::Zero(rows)};
  const std::vector<bool> luminaire = source_luminaire_mask(scene, sources);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (SparseRows::InnerIterator it(F, r); it; ++it) {
      if (luminaire[static_cast<std::size_t>(it.col())]) {
        out.luminaire[r] += it.value();
        continue;
      }
      out.kept[r] += it.value();
      if (is_reflecting(scene, scene.patches[it.col()])) out.reflecting[r] += it.value();
      if (const int e = sources.gathered_of_patch[it.col()]; e >= 0) out.gathered(r, e) += it.value();
    }
  return out;
}

// The same sums by counting rays only: bin 0 reflecting, 1 + e gathered source e,
// 1 + m + e both (a reflecting emitter), 1 + 2m luminaires.
RowSums row_sums_by_counting(const Scene& scene, const RayCaster& caster, std::span<const int> patches,
                             const SourceTable& sources, const FormFactorOptions& options,
                             const ProgressCallback& progress) {
  const int m = static_cast<int>(sources.gathered.size());
  const std::vector<bool> luminaire = source_luminaire_mask(scene, sources);
  std::vector<int> bin(scene.patches.size(), -1);
  for (std::size_t j = 0; j < scene.patches.size(); ++j) {
    const bool reflecting = is_reflecting(scene, scene.patches[j]);
    const int e = sources.gathered_of_patch[j];
    bin[j] = luminaire[j] ? 1 + 2 * m : e >= 0 ? (reflecting ? 1 + m + e : 1 + e) : (reflecting ? 0 : -1);
  }
  const int bins = 2 + 2 * m;
  const Eigen::MatrixXd f = compute_row_bin_fractions(scene, caster, patches, bin, bins, options, progress);
  RowSums out{f.col(0), Eigen::MatrixXd::Zero(f.rows(), m), f.col(1 + 2 * m), Eigen::VectorXd()};
  for (int e = 0; e < m; ++e) {
    out.reflecting += f.col(1 + m + e);
    out.gathered.col(e) = f.col(1 + e) + f.col(1 + m + e);
  }
  // Columns bins and bins + 1 are the escaped and back-hit fractions.
  out.kept = Eigen::VectorXd::Ones(f.rows()) - f.col(bins) - f.col(bins + 1) - out.luminaire;
  return out;
}

// Rays that strike a luminaire only sample its solid angle, which the closed form
// knows exactly. Each row's other entries are scaled by (kept + hits - closed) / kept
// so that the row loses exactly the closed-form share to luminaires and keeps its
// escaped and back-hit shares. Without this, a room of rho 0.999 whose only loss is
// its luminaires gets that loss from 0 to 3 ray hits per row, and interreflection
// multiplies the noise by 1 / (1 - rho s). `absorbed`: the rows' form factors to the
// luminaires that absorb (DirectRows). Applies the scale to the sums and to D's
// gathered columns.
Eigen::VectorXd apply_closed_form_loss(RowSums& sums, Eigen::MatrixXd& D, const Eigen::MatrixXd& absorbed,
                                       const SourceTable& sources) {
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(sums.kept.size());
  for (Eigen::Index r = 0; r < scale.size(); ++r) {
    const double closed = absorbed.row(r).sum();
    if (sums.kept[r] > 0.0) scale[r] = std::max(0.0, sums.kept[r] + sums.luminaire[r] - closed) / sums.kept[r];
  }
  sums.reflecting.array() *= scale.array();
  for (Eigen::Index e = 0; e < sums.gathered.cols(); ++e) sums.gathered.col(e).array() *= scale.array();
  for (int l : sources.gathered) D.col(l).array() *= scale.array();
  return scale;
}

// D(R,:): illuminance at each receiver per lumen of each source, and the receivers'
// form factors to the luminaires that absorb (columns of the other sources are 0).
struct DirectRows {
  Eigen::MatrixXd D;
  Eigen::MatrixXd absorbed;
};

DirectRows direct_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                        std::size_t source_count, const SourceTable& sources, const Eigen::MatrixXd& gathered,
                        const DirectLightOptions& options) {
  const auto R = static_cast<Eigen::Index>(receivers.size()), L = static_cast<Eigen::Index>(source_count);
  DirectRows out{Eigen::MatrixXd::Zero(R, L), Eigen::MatrixXd::Zero(R, L)};
  if (!sources.luminaire_surfaces.empty() && R > 0) {
    const LuminaireLight light = compute_luminaire_light(scene, caster, receivers, sources.luminaire_surfaces, options);
    for (std::size_t e = 0; e < sources.luminaire_surfaces.size(); ++e) {
      const int l = sources.luminaire_source[e];
      out.D.col(l) = light.lux_per_lm.col(static_cast<Eigen::Index>(e));
      if (sources.absorbs[static_cast<std::size_t>(l)]) out.absorbed.col(l) = light.form_factor.col(static_cast<Eigen::Index>(e));
    }
  }
  for (std::size_t e = 0; e < sources.gathered.size(); ++e) {
    const int l = sources.gathered[e];
    if (sources.area_m2[l] > 0.0) out.D.col(l) = gathered.col(static_cast<Eigen::Index>(e)) / sources.area_m2[l];
  }
  return out;
}

// D(Q,:) at goal points and their form factors to the absorbing luminaires, as
// direct_light gives them for patches: luminaires through compute_luminaire_light_at_points,
// gathered sources from the points' own rows (fraction of rays reaching the source / its area).
DirectRows point_direct_light(const Scene& scene, const RayCaster& caster, std::span<const ReceiverPoint> points,
                              std::size_t source_count, const SourceTable& table, const Eigen::MatrixXd& gathered,
                              const DirectLightOptions& options) {
  const auto Q = static_cast<Eigen::Index>(points.size()), L = static_cast<Eigen::Index>(source_count);
  DirectRows out{Eigen::MatrixXd::Zero(Q, L), Eigen::MatrixXd::Zero(Q, L)};
  if (!table.luminaire_surfaces.empty() && Q > 0) {
    const LuminaireLight light =
        compute_luminaire_light_at_points(scene, caster, points, table.luminaire_surfaces, options);
    for (std::size_t e = 0; e < table.luminaire_surfaces.size(); ++e) {
      const int l = table.luminaire_source[e];
      out.D.col(l) = light.lux_per_lm.col(static_cast<Eigen::Index>(e));
      if (table.absorbs[static_cast<std::size_t>(l)]) out.absorbed.col(l) = light.form_factor.col(static_cast<Eigen::Index>(e));
    }
  }
  for (std::size_t e = 0; e < table.gathered.size(); ++e) {
    const int l = table.gathered[e];
    if (table.area_m2[l] > 0.0 && gathered.rows() > 0) out.D.col(l) = gathered.col(static_cast<Eigen::Index>(e)) / table.area_m2[l];
  }
  return out;
}

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

// I - K is an M-matrix, so exact arithmetic gives T >= 0; LU round-off may leave
// values a few ulps below 0, which are set to 0. Anything clearly negative is a bug.
void clamp_round_off(Eigen::MatrixXd& T, const Scene& scene, std::span<const int> row_patches,
                     std::span<const LightSource> sources) {
  if (T.size() == 0) return;  // no rows (a job whose goals are all grid points)
  const double tolerance = 1e-9 * std::max(T.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index c = 0; c < T.cols(); ++c)
    for (Eigen::Index r = 0; r < T.rows(); ++r)
      if (T(r, c) < 0.0) {
        if (T(r, c) < -tolerance)
          throw NumericalError("sample operator: negative illuminance " + std::to_string(T(r, c)) + " lux/lm at " +
                               patch_name(scene, row_patches[static_cast<std::size_t>(r)]) + " for light source '" +
                               sources[static_cast<std::size_t>(c)].name + "'");
        T(r, c) = 0.0;
      }
}

// F(rows,:) B1 where B1_j = rho_j(channel) D(j,:) is known at the patches in `at`
// (dense index `slot`): the first reflection gathered through full rows.
using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Row-major: each hit adds a whole row of D, and rows are split among threads (each
// row's sum is its own, so the result does not depend on the split).
Eigen::MatrixXd gather_first_reflection(const Scene& scene, const SparseRows& F, const std::vector<int>& slot,
                                        const RowMajorMatrix& D, int channel) {
  RowMajorMatrix out = RowMajorMatrix::Zero(F.rows(), D.cols());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, F.rows(), 64), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index row = r.begin(); row < r.end(); ++row)
      for (SparseRows::InnerIterator it(F, row); it; ++it)
        if (const int s = slot[it.col()]; s >= 0)
          out.row(row) += it.value() * scene.reflectance(static_cast<int>(it.col()), channel) * D.row(s);
  });
  return out;
}

// (I - K) X = rhs. By iteration (core/operator/contraction_solve.h) when K's contraction
// factor lets it converge in kMaxSweeps or k is too large for a dense k x k matrix
// (memory grows as k, not k^2), else by a dense LU. The condition figure in the stats
// is the LU's 1-norm estimate, or for the iteration the infinity-norm bound
// (1 + q) / (1 - q); either way the largest over channels.
constexpr double kSolveTolerance = 1e-10;
constexpr int kMaxSweeps = 3000;
constexpr Eigen::Index kLargestDenseSolve = 4000;  // 128 MB a copy

Eigen::MatrixXd solve_interreflection(const ContractionSystem& system, const Eigen::MatrixXd& rhs,
                                      SampleOperatorStats& st, int& sweeps) {
  // No source (a scene without light) gives no column: nothing to solve, and Eigen's
  // triangular solve of an empty right-hand side binds a reference to null (UBSan).
  if (rhs.cols() == 0) return rhs;
  const double q = contraction_factor(system);
  const Eigen::Index k = system.W.rows();
  const double needed = sweeps_needed(q, kSolveTolerance);
  if (needed <= kMaxSweeps || k > kLargestDenseSolve) {
    const int most = static_cast<int>(std::min(1e6, std::max<double>(kMaxSweeps, needed)));
    if (std::optional<ContractionSolution> x = solve_contraction(system, rhs, kSolveTolerance, most)) {
      st.condition_estimate = std::max(st.condition_estimate, (1.0 + q) / (1.0 - q));
      sweeps = std::max(sweeps, x->sweeps);
      return std::move(x->X);
    }
    if (k > kLargestDenseSolve)
      throw NumericalError("interreflection solve: no convergence in " + std::to_string(most) +
                           " sweeps (largest row sum of K " + std::to_string(q) + ")");
  }
  Eigen::MatrixXd dense = Eigen::MatrixXd(system.W);
  for (Eigen::Index a = 0; a < k; ++a)
    if (system.fallback_scale[a] > 0.0) dense.row(a) += system.fallback_scale[a] * system.ambient.transpose();
  // I - K factorised in place: at k = n (10K patches) each k x k copy is 800 MB.
  dense = -(system.rho.asDiagonal() * dense);
  dense.diagonal().array() += 1.0;
  const Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(dense);
  const double rcond = lu.rcond();
  st.condition_estimate = std::max(st.condition_estimate, rcond > 0.0 ? 1.0 / rcond : INFINITY);
  return lu.solve(rhs);
}

}  // namespace

std::vector<LightSource> scene_light_sources(const Scene& scene) {
  std::vector<LightSource> out;
  std::vector<bool> emits(scene.surfaces.size(), false);
  for (const Patch& p : scene.patches)
    if (p.exitance_lm_per_m2 > 0.0) emits[p.surface] = true;
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s)
    if (scene.surfaces[s].is_luminaire() || emits[s]) out.push_back({scene.surfaces[s].name, static_cast<int>(s)});
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

GoalRows compute_goal_rows(const Scene& scene, const RayCaster& caster, std::span<const int> goal_patches,
                           std::span<const LightSource> sources, const SampleOperatorOptions& options,
                           const ProgressCallback& progress) {
  return compute_goal_rows(scene, caster, goal_patches, {}, sources, options, progress);
}

GoalRows compute_goal_rows(const Scene& scene, const RayCaster& caster, std::span<const int> goal_patches,
                           std::span<const ReceiverPoint> goal_points, std::span<const LightSource> sources,
                           const SampleOperatorOptions& options, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  require_valid_materials(scene);
  for (int p : goal_patches)
    if (p < 0 || p >= static_cast<int>(scene.patches.size()))
      throw std::invalid_argument("compute_goal_rows: patch " + std::to_string(p) + " is not in the scene");
  const SourceTable table = make_source_table(scene, sources);
  GoalRows goals;
  goals.patches.assign(goal_patches.begin(), goal_patches.end());
  goals.sources.assign(sources.begin(), sources.end());
  const bool any_reflecting = !reflecting_patches(scene).empty();
  const Eigen::Index G = static_cast<Eigen::Index>(goal_patches.size());
  RowSums sums{Eigen::VectorXd::Zero(G), Eigen::MatrixXd::Zero(G, static_cast<Eigen::Index>(table.gathered.size())),
               Eigen::VectorXd::Zero(G), Eigen::VectorXd::Zero(G)};
  if (options.indirect == IndirectMethod::exact_second_bounce && any_reflecting) {
    goals.rows = compute_form_factor_rows(scene, caster, goal_patches, options.form_factors, progress);
    sums = row_sums_from_rows(scene, goals.rows->F, table);
    goals.rays_cast = goals.rows->rays_cast;
  } else if (any_reflecting || !table.gathered.empty()) {
    sums = row_sums_by_counting(scene, caster, goal_patches, table, options.form_factors, progress);
    goals.rays_cast = static_cast<std::uint64_t>(goal_patches.size()) * options.form_factors.rays_per_patch;
  }
  DirectLightOptions goal_light = options.direct_light;
  goal_light.progress = progress;
  goal_light.progress_label = "direct light (goals)";
  DirectRows direct = direct_light(scene, caster, goal_patches, sources.size(), table, sums.gathered, goal_light);
  goals.direct_lux_per_lm = std::move(direct.D);
  goals.luminaire_form_factor = std::move(direct.absorbed);
  goals.kept_scale = apply_closed_form_loss(sums, goals.direct_lux_per_lm, goals.luminaire_form_factor, table);
  goals.reflecting_fraction = sums.reflecting;
  require_finite(goals.direct_lux_per_lm, "direct light", scene, goal_patches, sources);

  // Goal points: their own full rows, then exact direct light at the point.
  goals.points.assign(goal_points.begin(), goal_points.end());
  const Eigen::Index Q = static_cast<Eigen::Index>(goal_points.size());
  RowSums point_sums{Eigen::VectorXd::Zero(Q), Eigen::MatrixXd::Zero(Q, static_cast<Eigen::Index>(table.gathered.size())),
                     Eigen::VectorXd::Zero(Q), Eigen::VectorXd::Zero(Q)};
  if (Q > 0 && (any_reflecting || !table.gathered.empty())) {
    // Points are few (a grid has hundreds, a mesh tens of thousands of patches) and each
    // stands alone (no area to average over): their rows get kPointRayFactor x the rays.
    FormFactorOptions point_options = options.form_factors;
    point_options.rays_per_patch = options.form_factors.rays_per_patch * kPointRayFactor;
    goals.point_rows = compute_point_rows(scene, caster, goal_points, point_options, progress);
    point_sums = row_sums_from_rows(scene, goals.point_rows->F, table);
    goals.rays_cast += goals.point_rows->rays_cast;
  }
  DirectRows point_direct = point_direct_light(scene, caster, goal_points, sources.size(), table, point_sums.gathered,
                                               options.direct_light);
  goals.point_direct_lux_per_lm = std::move(point_direct.D);
  goals.point_kept_scale = apply_closed_form_loss(point_sums, goals.point_direct_lux_per_lm, point_direct.absorbed, table);
  goals.point_reflecting_fraction = point_sums.reflecting;
  if (Q > 0) {
    const std::vector<int> labels = goal_row_labels({}, goal_points.size());
    require_finite(goals.point_direct_lux_per_lm, "direct light", scene, labels, sources);
  }
  goals.seconds = seconds_since(start);
  return goals;
}

namespace {
SampleOperator build_in_arena(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                              const SampleOperatorOptions& options, const ProgressCallback& progress);
}  // namespace

// The phases that do not open their own arena (the first-reflection gathers, the
// interreflection solve) run in an arena of options.form_factors.threads threads, as the
// ray casting does.
SampleOperator build_sample_operator(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                     const SampleOperatorOptions& options, const ProgressCallback& progress) {
  const int threads = options.form_factors.threads;
  tbb::task_arena arena(threads > 0 ? threads : static_cast<int>(tbb::task_arena::automatic));
  return arena.execute([&] { return build_in_arena(scene, caster, goals, options, progress); });
}

namespace {

SampleOperator build_in_arena(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                              const SampleOperatorOptions& options, const ProgressCallback& progress) {
  if (options.sample_size < 1)
    throw std::invalid_argument("sample_size = " + std::to_string(options.sample_size) + ": must be >= 1");
  require_valid_materials(scene);
  const std::span<const LightSource> sources = goals.sources;
  const SourceTable table = make_source_table(scene, sources);
  const Eigen::Index L = static_cast<Eigen::Index>(sources.size());
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());

  SampleOperator op;
  op.goal_patches = goals.patches;
  op.sources = goals.sources;
  op.direct_lux_per_lm = goals.direct_lux_per_lm;
  SampleOperatorStats& st = op.stats;
  st.patches = scene.patches.size();
  st.channels = scene.channels;
  st.goal_patches = goals.patches.size();
  st.goal_points = goals.points.size();
  op.goal_points = goals.points;
  const Eigen::Index Q = static_cast<Eigen::Index>(goals.points.size());
  // T and D get the points' rows after the patches' (a no-op without points).
  auto append_points = [&](const Eigen::MatrixXd& point_total) {
    if (Q == 0) return;
    Eigen::MatrixXd direct(G + Q, L), total(G + Q, L), reflected = Eigen::MatrixXd::Zero(G + Q, L);
    direct << op.direct_lux_per_lm, goals.point_direct_lux_per_lm;
    total << op.total_lux_per_lm, point_total;
    reflected.topRows(G) = op.reflected_lm_per_m2_per_lm;
    op.direct_lux_per_lm = std::move(direct);
    op.total_lux_per_lm = std::move(total);
    op.reflected_lm_per_m2_per_lm = std::move(reflected);
  };
  if (Q > 0 && goals.point_direct_lux_per_lm.rows() != Q)
    throw std::invalid_argument("build_sample_operator: goal points without their direct light");
  st.rays_cast = goals.rays_cast;
  st.goal_seconds = goals.seconds;  // computed before, once for every build on these rows
  st.direct_rows = goals.patches.size();

  const std::vector<int> population = reflecting_patches(scene);
  st.population = population.size();
  if (population.empty()) {
    st.direct_only = true;
    op.total_lux_per_lm = op.direct_lux_per_lm;
    op.reflected_lm_per_m2_per_lm = Eigen::MatrixXd::Zero(G, L);
    append_points(goals.point_direct_lux_per_lm);
    op.log.push_back("every reflectance is 0: direct light only, no sample, no interreflection");
    return op;
  }
  if (options.indirect == IndirectMethod::exact_second_bounce && !goals.rows)
    throw std::invalid_argument("build_sample_operator: exact_second_bounce needs goal rows computed with it");

  // The sample and its rows.
  op.sample = draw_patch_sample(scene, population, options.sample_size, options.strategy, options.sample_seed);
  const std::vector<int>& P = op.sample.patches;
  const Eigen::Index k = static_cast<Eigen::Index>(P.size());
  st.sample_patches = P.size();
  st.census = op.sample.census;
  FormFactorRows rows = compute_form_factor_rows(scene, caster, P, options.form_factors, progress);
  st.sample_row_seconds = rows.seconds;
  st.rays_cast += rows.rays_cast;
  RowSums sample_sums = row_sums_from_rows(scene, rows.F, table);

  // Direct light at the sample patches (copied where a sample patch is a goal).
  auto start = std::chrono::steady_clock::now();
  std::vector<int> goal_slot(scene.patches.size(), -1), sample_slot(scene.patches.size(), -1);
  for (Eigen::Index g = 0; g < G; ++g) goal_slot[goals.patches[g]] = static_cast<int>(g);
  for (Eigen::Index b = 0; b < k; ++b) sample_slot[P[b]] = static_cast<int>(b);
  std::vector<int> need_direct;
  std::vector<Eigen::Index> need_direct_row;
  for (Eigen::Index b = 0; b < k; ++b)
    if (goal_slot[P[b]] < 0) {
      need_direct.push_back(P[b]);
      need_direct_row.push_back(b);
    }
  Eigen::MatrixXd gathered_needed(static_cast<Eigen::Index>(need_direct.size()), sample_sums.gathered.cols());
  for (std::size_t m = 0; m < need_direct.size(); ++m)
    gathered_needed.row(static_cast<Eigen::Index>(m)) = sample_sums.gathered.row(need_direct_row[m]);
  DirectLightOptions sample_light = options.direct_light;
  sample_light.progress = progress;
  sample_light.progress_label = "direct light (sample)";
  const DirectRows D_new = direct_light(scene, caster, need_direct, sources.size(), table, gathered_needed, sample_light);
  Eigen::MatrixXd D_P(k, L), absorbed_P(k, L);
  for (Eigen::Index b = 0; b < k; ++b)
    if (goal_slot[P[b]] >= 0) {
      D_P.row(b) = goals.direct_lux_per_lm.row(goal_slot[P[b]]);
      absorbed_P.row(b) = goals.luminaire_form_factor.row(goal_slot[P[b]]);
    }
  for (std::size_t m = 0; m < need_direct.size(); ++m) {
    D_P.row(need_direct_row[m]) = D_new.D.row(static_cast<Eigen::Index>(m));
    absorbed_P.row(need_direct_row[m]) = D_new.absorbed.row(static_cast<Eigen::Index>(m));
  }
  st.direct_rows += need_direct.size();
  // Rows copied from the goals are scaled already (same patch, same rays, same scale).
  Eigen::MatrixXd D_scaled = D_P;
  const Eigen::VectorXd kept_scale_P = apply_closed_form_loss(sample_sums, D_scaled, absorbed_P, table);
  for (std::size_t m = 0; m < need_direct.size(); ++m) D_P.row(need_direct_row[m]) = D_scaled.row(need_direct_row[m]);
  require_finite(D_P, "direct light", scene, P, sources);

  // Refinement: direct light at every reflecting patch the sample and goal rows hit.
  // Goal and sample patches reuse theirs; the others are only ever read through a
  // row's average over its hits, so a cheaper estimate (hit_direct_light) serves.
  const bool refine = options.indirect == IndirectMethod::exact_second_bounce;
  std::vector<int> hit_slot(scene.patches.size(), -1);
  Eigen::MatrixXd D_hit;
  if (refine) {
    std::vector<int> hit, cheap;
    std::vector<Eigen::Index> cheap_slot;
    auto collect = [&](const SparseRows& F) {
      for (Eigen::Index r = 0; r < F.rows(); ++r)
        for (SparseRows::InnerIterator it(F, r); it; ++it)
          if (hit_slot[it.col()] < 0 && is_reflecting(scene, scene.patches[it.col()])) {
            hit_slot[it.col()] = static_cast<int>(hit.size());
            hit.push_back(static_cast<int>(it.col()));
          }
    };
    collect(rows.F);
    collect(goals.rows->F);
    if (goals.point_rows) collect(goals.point_rows->F);
    D_hit.resize(static_cast<Eigen::Index>(hit.size()), L);
    for (std::size_t h = 0; h < hit.size(); ++h) {
      const auto slot = static_cast<Eigen::Index>(h);
      if (sample_slot[hit[h]] >= 0) D_hit.row(slot) = D_P.row(sample_slot[hit[h]]);
      else if (goal_slot[hit[h]] >= 0) D_hit.row(slot) = goals.direct_lux_per_lm.row(goal_slot[hit[h]]);
      else {
        cheap.push_back(hit[h]);
        cheap_slot.push_back(slot);
      }
    }
    // Gathered sources keep the plain form (their direct light is known only where rows were cast).
    DirectLightOptions cheap_options = options.hit_direct_light;
    cheap_options.seed = options.direct_light.seed;
    cheap_options.threads = options.direct_light.threads;
    cheap_options.progress = progress;
    cheap_options.progress_label = "direct light (patches the rows hit)";
    const Eigen::MatrixXd D_cheap = direct_light(
        scene, caster, cheap, sources.size(), table,
        Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(cheap.size()), static_cast<Eigen::Index>(table.gathered.size())),
        cheap_options).D;
    for (std::size_t m = 0; m < cheap.size(); ++m) D_hit.row(cheap_slot[m]) = D_cheap.row(static_cast<Eigen::Index>(m));
    for (std::size_t e = 0; e < table.gathered.size(); ++e) D_hit.col(table.gathered[e]).setZero();
    st.cheap_direct_rows = cheap.size();
    require_finite(D_hit, "direct light", scene, hit, sources);
  }
  st.direct_seconds = seconds_since(start);

  // Gather weights. Sample rows: from their own rows; ambient where they see no sample patch.
  start = std::chrono::steady_clock::now();
  const Eigen::VectorXd& w = op.sample.weight;
  Eigen::VectorXd ambient(k);
  for (Eigen::Index b = 0; b < k; ++b) ambient[b] = scene.patches[P[b]].area_m2 * w[b];
  ambient /= ambient.sum();
  // W_PP = the sparse gathers + a rank-one ambient term for the rows that saw no
  // sample patch (core/operator/contraction_solve.h).
  ContractionSystem W_PP;
  W_PP.ambient = ambient;
  W_PP.fallback_scale = Eigen::VectorXd::Zero(k);
  std::vector<bool> sample_fallback(static_cast<std::size_t>(k), false);
  {
    std::vector<Eigen::Triplet<double>> gathers;
    for (Eigen::Index a = 0; a < k; ++a) {
      double den = 0.0;
      for (SparseRows::InnerIterator it(rows.F, a); it; ++it)
        if (const int b = sample_slot[it.col()]; b >= 0) den += it.value() * w[b];
      const double s = sample_sums.reflecting[a];
      if (den > 0.0) {
        for (SparseRows::InnerIterator it(rows.F, a); it; ++it)
          if (const int b = sample_slot[it.col()]; b >= 0) gathers.emplace_back(a, b, s * it.value() * w[b] / den);
      } else {
        W_PP.fallback_scale[a] = s;
        sample_fallback[static_cast<std::size_t>(a)] = true;
        if (s > 0.0) ++st.sample_fallback_rows;
      }
    }
    W_PP.W.resize(k, k);
    W_PP.W.setFromTriplets(gathers.begin(), gathers.end());  // a patch hit twice: the entries sum
  }
  // Goal rows: a sampled goal uses its sample row. Others estimate A_i F_ip from
  // the sample's columns (A_p F_pi, reciprocity) and, where the goal's own full row
  // was kept, also from that row (A_i F_ip): two independent estimates of the same
  // quantity, summed, so a goal falls back to ambient only if both saw nothing.
  const Eigen::SparseMatrix<double, Eigen::ColMajor> by_column = rows.F;
  const bool own_goal_rows = goals.rows.has_value();
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd fallback_scale = Eigen::VectorXd::Zero(G);
  std::vector<double> a(static_cast<std::size_t>(k), 0.0);
  std::vector<Eigen::Index> touched;
  double goal_area = 0.0, fallback_area = 0.0;
  for (Eigen::Index g = 0; g < G; ++g) {
    const int i = goals.patches[g];
    goal_area += scene.patches[i].area_m2;
    bool fallback = false;
    if (const int s = sample_slot[i]; s >= 0) {
      if (sample_fallback[static_cast<std::size_t>(s)]) fallback = true;
      else
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(W_PP.W, s); it; ++it)
          if (it.value() != 0.0) entries.emplace_back(g, it.col(), it.value());
    } else {
      auto add = [&](Eigen::Index b, double value) {
        if (a[static_cast<std::size_t>(b)] == 0.0) touched.push_back(b);
        a[static_cast<std::size_t>(b)] += value * w[b];
      };
      for (Eigen::SparseMatrix<double>::InnerIterator it(by_column, i); it; ++it)
        add(it.row(), scene.patches[P[it.row()]].area_m2 * it.value());
      if (own_goal_rows)
        for (SparseRows::InnerIterator it(goals.rows->F, g); it; ++it)
          if (const int b = sample_slot[it.col()]; b >= 0) add(b, scene.patches[i].area_m2 * it.value());
      double den = 0.0;
      for (Eigen::Index b : touched) den += a[static_cast<std::size_t>(b)];
      if (den > 0.0) {
        std::sort(touched.begin(), touched.end());
        for (Eigen::Index b : touched)
          entries.emplace_back(g, b, goals.reflecting_fraction[g] * a[static_cast<std::size_t>(b)] / den);
      } else {
        fallback = true;
      }
      for (Eigen::Index b : touched) a[static_cast<std::size_t>(b)] = 0.0;
      touched.clear();
    }
    // A row that reaches no reflecting patch (s_i = 0: facing the sky, say) needs no
    // fallback: its indirect light is 0 either way.
    if (fallback && goals.reflecting_fraction[g] > 0.0) {
      fallback_scale[g] = goals.reflecting_fraction[g];
      ++st.goal_fallback_rows;
      fallback_area += scene.patches[i].area_m2;
    }
  }
  st.goal_fallback_area_fraction = goal_area > 0.0 ? fallback_area / goal_area : 0.0;
  Eigen::SparseMatrix<double, Eigen::RowMajor> W_GP(G, k);
  W_GP.setFromTriplets(entries.begin(), entries.end());

  // Goal points: a_ip from the point's own row only (it has no area for reciprocity).
  std::vector<Eigen::Triplet<double>> point_entries;
  Eigen::VectorXd point_fallback_scale = Eigen::VectorXd::Zero(Q);
  for (Eigen::Index q = 0; q < Q && goals.point_rows; ++q) {
    double den = 0.0;
    for (SparseRows::InnerIterator it(goals.point_rows->F, q); it; ++it)
      if (const int b = sample_slot[it.col()]; b >= 0) den += it.value() * w[b];
    const double s_q = goals.point_reflecting_fraction[q];
    if (den > 0.0) {
      for (SparseRows::InnerIterator it(goals.point_rows->F, q); it; ++it)
        if (const int b = sample_slot[it.col()]; b >= 0) point_entries.emplace_back(q, b, s_q * it.value() * w[b] / den);
    } else if (s_q > 0.0) {
      point_fallback_scale[q] = s_q;
      ++st.point_fallback_rows;
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> W_QP(Q, k);
  W_QP.setFromTriplets(point_entries.begin(), point_entries.end());  // duplicates (none: columns distinct) would sum
  Eigen::MatrixXd point_indirect = Eigen::MatrixXd::Zero(Q, L);

  // Per channel: (I - K) Bʳ_P = right-hand side, then the goals gather Bʳ_P.
  op.total_lux_per_lm = op.direct_lux_per_lm;
  op.reflected_lm_per_m2_per_lm = Eigen::MatrixXd::Zero(G, L);
  Eigen::MatrixXd indirect = Eigen::MatrixXd::Zero(G, L);
  double solve_seconds = 0.0;
  int solve_sweeps = 0;  // 0: every channel by the dense LU
  const RowMajorMatrix D_hit_rows = refine ? RowMajorMatrix(D_hit) : RowMajorMatrix();
  for (int c = 0; c < scene.channels; ++c) {
    if (progress) progress("k x k solve", static_cast<std::size_t>(c), static_cast<std::size_t>(scene.channels));
    const auto solve_start = std::chrono::steady_clock::now();
    Eigen::VectorXd rho(k);
    for (Eigen::Index b = 0; b < k; ++b) rho[b] = scene.reflectance(P[b], c);
    W_PP.rho = rho;
    // Energy: a sample patch reflects rho_a s_a < 1 of what reaches it (row sums of
    // K), so no light is created and K is a contraction.
    const double ambient_sum = W_PP.ambient.sum();
    for (Eigen::Index a = 0; a < k; ++a) {
      const double row_sum = rho[a] * (W_PP.W.row(a).sum() + W_PP.fallback_scale[a] * ambient_sum);
      st.max_row_sum = std::max(st.max_row_sum, row_sum);
      if (!(row_sum < 1.0))
        throw NumericalError("interreflection operator: " + patch_name(scene, P[a]) + " would reflect " +
                             std::to_string(row_sum) + " of the light reaching it (rho " + std::to_string(rho[a]) +
                             ", channel " + std::to_string(c) + "): energy would be created");
    }
    // Plain: (I - K) Bʳ_P = R D_P, every reflection through the sample. Refined
    // (luminaire columns): the first reflection B1 = R D is gathered exactly through
    // full rows, S = F(P,:) B1, and the sample carries bounces 2 and up:
    // Bʳ_P - B1_P = (I - K)^-1 R S, non-negative like every term here.
    Eigen::MatrixXd rhs = rho.asDiagonal() * D_P;
    Eigen::MatrixXd first_at_goals;  // refined: F(G,:) B1
    if (refine) {
      const Eigen::MatrixXd S = kept_scale_P.asDiagonal() * gather_first_reflection(scene, rows.F, hit_slot, D_hit_rows, c);
      first_at_goals = goals.kept_scale.asDiagonal() * gather_first_reflection(scene, goals.rows->F, hit_slot, D_hit_rows, c);
      for (Eigen::Index l = 0; l < L; ++l)
        if (table.emitting_index[l] < 0) rhs.col(l) = rho.asDiagonal() * S.col(l);
    }
    const Eigen::MatrixXd reflected = solve_interreflection(W_PP, rhs, st, solve_sweeps);  // Bʳ_P per lumen (refined: bounces 2+)
    require_finite(reflected, "interreflection solve (I - K)", scene, P, sources);
    solve_seconds += seconds_since(solve_start);

    const auto response_start = std::chrono::steady_clock::now();
    Eigen::MatrixXd channel_indirect = W_GP * reflected + fallback_scale * (ambient.transpose() * reflected);
    if (refine)
      for (Eigen::Index l = 0; l < L; ++l)
        if (table.emitting_index[l] < 0) channel_indirect.col(l) += first_at_goals.col(l);
    const double weight = scene.channels == 1 ? 1.0 : kLuminanceWeights[c];
    indirect += weight * channel_indirect;
    if (Q > 0) {
      Eigen::MatrixXd at_points = W_QP * reflected + point_fallback_scale * (ambient.transpose() * reflected);
      if (refine && goals.point_rows) {
        const Eigen::MatrixXd first =
            goals.point_kept_scale.asDiagonal() * gather_first_reflection(scene, goals.point_rows->F, hit_slot, D_hit_rows, c);
        for (Eigen::Index l = 0; l < L; ++l)
          if (table.emitting_index[l] < 0) at_points.col(l) += first.col(l);
      }
      point_indirect += weight * at_points;
    }
    Eigen::VectorXd rho_goal(G);
    for (Eigen::Index g = 0; g < G; ++g) rho_goal[g] = scene.reflectance(goals.patches[g], c);
    op.reflected_lm_per_m2_per_lm += weight * (rho_goal.asDiagonal() * (op.direct_lux_per_lm + channel_indirect));
    st.response_seconds += seconds_since(response_start);
  }
  if (progress) progress("k x k solve", static_cast<std::size_t>(scene.channels), static_cast<std::size_t>(scene.channels));
  st.solve_seconds = solve_seconds;
  st.condition_bound_inf = (1.0 + st.max_row_sum) / (1.0 - st.max_row_sum);
  op.total_lux_per_lm += indirect;
  require_finite(op.total_lux_per_lm, "illuminance at goal patches", scene, goals.patches, sources);
  clamp_round_off(op.total_lux_per_lm, scene, goals.patches, sources);
  if (Q > 0) {
    Eigen::MatrixXd point_total = goals.point_direct_lux_per_lm + point_indirect;
    const std::vector<int> labels = goal_row_labels({}, goals.points.size());
    require_finite(point_total, "illuminance at goal points", scene, labels, sources);
    clamp_round_off(point_total, scene, labels, sources);
    append_points(point_total);
  }

  std::ostringstream line;
  line << (scene.channels == 1 ? "gray materials: 1 colour channel" : "coloured materials: 3 colour channels (RGB)");
  op.log.push_back(line.str());
  line.str("");
  if (op.sample.census)
    line << "sample: every one of the " << population.size() << " reflecting patches (k = n, no sampling error)";
  else
    line << "sample: " << P.size() << " distinct patches of " << population.size() << " reflecting ("
         << to_string(options.strategy) << ", k = " << options.sample_size << ", seed " << options.sample_seed << ")";
  op.log.push_back(line.str());
  line.str("");
  line << "rows cast: " << P.size() << " sample + " << goals.patches.size() << " goal of " << scene.patches.size()
       << " patches";
  line << ", " << options.form_factors.rays_per_patch << " rays each";
  if (Q > 0) line << " + " << Q << " goal points, " << options.form_factors.rays_per_patch * kPointRayFactor << " rays each";
  line << "; direct light at " << st.direct_rows
       << " goal and sample patches";
  if (refine) line << " (+ " << st.cheap_direct_rows << " cheap estimates at patches the rows hit)";
  line << "; indirect: " << to_string(options.indirect);
  op.log.push_back(line.str());
  line.str("");
  line << std::setprecision(3) << "I - K: " << k << " x " << k << " (" << W_PP.W.nonZeros() << " gathers, "
       << st.sample_fallback_rows << " ambient rows), ";
  if (solve_sweeps > 0)
    line << "solved by iteration (" << solve_sweeps << " sweeps to a relative error bound of " << kSolveTolerance
         << "), condition estimate " << st.condition_estimate << " (infinity-norm bound)";
  else
    line << "solved by LU, condition estimate " << st.condition_estimate << " (1-norm)";
  line << "; largest row sum of K " << st.max_row_sum << ", so the infinity-norm condition is at most "
       << st.condition_bound_inf;
  op.log.push_back(line.str());
  if (st.point_fallback_rows > 0)
    op.log.push_back("ambient fallback: " + std::to_string(st.point_fallback_rows) + " goal points see no sample patch");
  if (st.goal_fallback_rows > 0 || st.sample_fallback_rows > 0) {
    line.str("");
    line << "ambient fallback: " << st.goal_fallback_rows << " goal patches (" << std::setprecision(2)
         << 100.0 * st.goal_fallback_area_fraction << " % of goal area) and " << st.sample_fallback_rows
         << " sample patches see no sample patch";
    op.log.push_back(line.str());
  }
  return op;
}

}  // namespace

static_assert(field_count<SampleOperatorOptions>() == 7,
              "SampleOperatorOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const SampleOperatorOptions& o) {
  k.field("sample_size", o.sample_size).field("strategy", o.strategy).field("sample_seed", o.sample_seed);
  k.field("indirect", o.indirect).field("form_factors", o.form_factors).field("direct_light", o.direct_light);
  k.field("hit_direct_light", o.hit_direct_light);
}

}  // namespace ilp
