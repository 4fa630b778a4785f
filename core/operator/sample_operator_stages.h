// The stages of build_sample_operator (core/operator/sample_operator.h), shared by its
// source files; not part of core's interface. In data-path order: the sources' table
// and row sums (sample_rows.cpp: goal rows, the sample's rows, direct light at the
// sample and at the patches the rows hit), the gather weights W (gather_weights.cpp),
// the per-channel solve of (I - K) and the assembly of T (sample_solve.cpp); the
// top-level steps, the checks and the run log are in sample_operator.cpp.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <chrono>
#include <span>
#include <vector>

#include "core/base/progress.h"
#include "core/operator/contraction_solve.h"
#include "core/operator/sample_operator.h"
#include "core/transport/form_factors.h"
#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp::detail {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

inline bool is_reflecting(const Scene& scene, const Patch& p) {
  return !scene.surfaces[p.surface].is_luminaire() && p.reflectance.maxCoeff() > 0.0;
}

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// ---- Checks (sample_operator.cpp).

// Row labels for messages: goal patches, then points as -1 - index.
std::vector<int> goal_row_labels(std::span<const int> patches, std::size_t points);
// "patch 12 (floor)", or "grid point 3" for a label -1 - 3.
std::string patch_name(const Scene& scene, int patch);
// Throws NumericalError naming the stage, row and source of the first NaN or Inf in m
// (rows labelled by row_patches, columns by sources).
void require_finite(const Eigen::MatrixXd& m, const char* stage, const Scene& scene, std::span<const int> row_patches,
                    std::span<const LightSource> sources);
// Throws NumericalError for a reflectance outside [0, 1) or an exitance not finite and >= 0.
void require_valid_materials(const Scene& scene);

// ---- Sources, row sums and direct light (sample_rows.cpp).

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

// Throws std::invalid_argument for a source whose surface is not in the scene or is listed twice.
SourceTable make_source_table(const Scene& scene, std::span<const LightSource> sources);

// Row sums of one row split the way the gather needs them: s_i over the reflecting
// patches, per gathered source the fraction of rays reaching it, and the split of
// front hits between luminaires (of the sources) and everything else.
struct RowSums {
  Eigen::VectorXd reflecting;   // per row
  Eigen::MatrixXd gathered;     // rows by #gathered sources
  Eigen::VectorXd luminaire;    // rays that struck a luminaire
  Eigen::VectorXd kept;         // rays that struck the front of any other patch
};

// The sample P and its rows: the first stage of the build.
struct SampleRows {
  FormFactorRows rows;              // F(P,:), k rows
  RowSums sums;                     // of those rows, scaled by direct_light_at_sample
  std::vector<int> sample_slot;     // per scene patch: its index in P, or -1
  std::vector<int> goal_slot;       // per scene patch: its goal row, or -1
};

// Casts the rows of the sample patches; fills stats.sample_row_seconds and adds to stats.rays_cast.
SampleRows cast_sample_rows(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                            const PatchSample& sample, const SourceTable& table, const SampleOperatorOptions& options,
                            const ProgressCallback& progress, SampleOperatorStats& stats);

// Direct light at the sample patches, D(P,:), with the closed-form luminaire loss
// applied to the rows (rows.sums is scaled in place).
struct SampleDirect {
  Eigen::MatrixXd D_P;             // k by #sources (a split build: its share's columns, options.share)
  Eigen::VectorXd kept_scale;      // k: the rows' factor on their non-luminaire entries
};

// Copies the rows of sample patches that are goals; computes the others. Adds to stats.direct_rows.
SampleDirect direct_light_at_sample(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                    const PatchSample& sample, SampleRows& rows, const SourceTable& table,
                                    const SampleOperatorOptions& options, const ProgressCallback& progress,
                                    SampleOperatorStats& stats);

// IndirectMethod::exact_second_bounce: the first reflection B1 = R D gathered through
// the full rows, F(rows,:) B1, for the sample, goal and point rows, B1 known at every
// reflecting patch those rows hit. Per colour channel, #rows by #sources (gathered
// sources' columns 0), before the rows' kept_scale. A split build (options.share) holds
// its share's columns only (WorkShare::column_range).
struct FirstReflection {
  std::vector<Eigen::MatrixXd> at_sample;  // per channel: k by #sources
  std::vector<Eigen::MatrixXd> at_goals;   // per channel: #goal patches by #sources
  std::vector<Eigen::MatrixXd> at_points;  // per channel: #goal points by #sources (empty without point rows)
};

// The hit patches, in the order the rows first hit them, are cut into blocks of
// options.hit_block_patches; each block's direct light (goal and sample patches reuse
// theirs, the others get options.hit_direct_light) is gathered into the rows' partial
// sums and dropped, and the partial sums are added in block order, so no process holds
// the hits' direct light whole. A split build computes every block for its share's
// columns (sources) only: each column's sums are the single process's, no exchange.
// Fills stats.cheap_direct_rows (every block's).
FirstReflection first_reflection_at_rows(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                         const SampleRows& rows, const SampleDirect& direct, const SourceTable& table,
                                         const SampleOperatorOptions& options, const ProgressCallback& progress,
                                         SampleOperatorStats& stats);

// ---- Gather weights (gather_weights.cpp).

// W: the sample's, the goal patches' and the goal points' gathers over the sample,
// each row with its ambient fallback scale (0 where the row gathers from the sample).
struct GatherWeights {
  ContractionSystem sample;                               // W(P,P) and the ambient term; rho set per channel
  Eigen::SparseMatrix<double, Eigen::RowMajor> goals;    // W(G,P)
  Eigen::VectorXd goal_fallback_scale;                    // #goal patches
  Eigen::SparseMatrix<double, Eigen::RowMajor> points;   // W(Q,P)
  Eigen::VectorXd point_fallback_scale;                   // #goal points
};

// Fills stats.sample_fallback_rows, goal_fallback_rows, goal_fallback_area_fraction and point_fallback_rows.
GatherWeights compute_gather_weights(const Scene& scene, const GoalRows& goals, const PatchSample& sample,
                                     const SampleRows& rows, SampleOperatorStats& stats);

// ---- The per-channel solve and T (sample_solve.cpp).

// Relative error bound of the iterative solve of (I - K) X = rhs.
inline constexpr double kSolveTolerance = 1e-10;

// The reflected light summed over the channels (luminance-weighted for RGB).
struct IndirectLight {
  Eigen::MatrixXd at_goals;        // #goal patches by #sources, lux per lm
  Eigen::MatrixXd at_points;       // #goal points by #sources, lux per lm
  Eigen::MatrixXd reflected;       // #goal patches by #sources: rho H, lm/m2 per lm
  int solve_sweeps = 0;            // most sweeps of the iterative solve over channels; 0: every channel by LU
};

// Per colour channel: (I - K) Bʳ_P = right-hand side, then the goal rows gather Bʳ_P.
// A split build solves its share's columns (the iteration stops when the largest change
// over every share is small enough) and gathers every share's light at the goals and
// points, so the result is whole and has the same bits on every share.
// Sets weights.sample.rho per channel. Fills stats.max_row_sum, condition_estimate,
// condition_bound_inf, solve_seconds and response_seconds. Throws NumericalError where
// energy would be created or a value becomes non-finite.
IndirectLight solve_indirect_light(const Scene& scene, const GoalRows& goals, const PatchSample& sample,
                                   const SampleDirect& direct, const FirstReflection& first,
                                   const SourceTable& table, GatherWeights& weights,
                                   const SampleOperatorOptions& options, const ProgressCallback& progress,
                                   SampleOperatorStats& stats);

// T = D + indirect light at the goal patches, then the goal points' rows after them,
// each checked finite and with round-off below 0 clamped. Sets op.total_lux_per_lm and
// op.reflected_lm_per_m2_per_lm, and appends the points' rows to op.direct_lux_per_lm.
void assemble_response(const Scene& scene, const GoalRows& goals, const IndirectLight& indirect, SampleOperator& op);
// Every reflectance 0: T = D, no reflected light.
void assemble_direct_only(const GoalRows& goals, SampleOperator& op);

}  // namespace ilp::detail
