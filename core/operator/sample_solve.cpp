// The per-channel solve of the sample operator (core/operator/sample_operator.h):
// (I - K) Bʳ_P = R_P D(P,:) (or, refined, the bounces after the first reflection) by
// iteration or a dense LU, the goal rows' gather of Bʳ_P, and T assembled from it.
#include <Eigen/LU>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <optional>
#include <string>

#include "core/base/error.h"
#include "core/operator/sample_operator_stages.h"
#include "core/operator/work_share.h"

namespace ilp::detail {
namespace {

// (I - K) X = rhs. By iteration (core/contraction_solve.h) when K's contraction
// factor lets it converge in kMaxSweeps or k is too large for a dense k x k matrix
// (memory grows as k, not k^2), else by a dense LU. The condition figure in the stats
// is the LU's 1-norm estimate, or for the iteration the infinity-norm bound
// (1 + q) / (1 - q); either way the largest over channels.
constexpr int kMaxSweeps = 3000;
constexpr Eigen::Index kLargestDenseSolve = 4000;  // 128 MB a copy

// A split build (share.count > 1) passes its share's columns of the right-hand side and
// gets its columns of X, with the bits the whole right-hand side gives them: the
// iteration's stopping test takes the largest change over every share; the dense LU
// (small k only) solves every column on every share and keeps its own.
Eigen::MatrixXd solve_interreflection(const ContractionSystem& system, const Eigen::MatrixXd& rhs,
                                      std::size_t all_columns, const WorkShare& share, SampleOperatorStats& st,
                                      int& sweeps) {
  // No source (a scene without light) gives no column: nothing to solve, and Eigen's
  // triangular solve of an empty right-hand side binds a reference to null (UBSan).
  if (all_columns == 0) return rhs;
  const bool split = share.count > 1;
  const double q = contraction_factor(system);
  const Eigen::Index k = system.W.rows();
  const double needed = sweeps_needed(q, kSolveTolerance);
  if (needed <= kMaxSweeps || k > kLargestDenseSolve) {
    const int most = static_cast<int>(std::min(1e6, std::max<double>(kMaxSweeps, needed)));
    std::function<std::array<double, 2>(std::array<double, 2>)> largest;
    // One column in all: the shares without it need not iterate, and its share solves it
    // as one process does.
    if (split && all_columns > 1)
      largest = [&share](std::array<double, 2> mine) {
        const std::vector<double> most = max_over_shares(share, {mine[0], mine[1]});
        return std::array<double, 2>{most.at(0), most.at(1)};
      };
    if (std::optional<ContractionSolution> x = solve_contraction(system, rhs, kSolveTolerance, most, largest)) {
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
  if (!split) return lu.solve(rhs);
  // Every share's columns (column-major, in share order: the whole right-hand side).
  const std::vector<double> all =
      gather_shares(share, std::vector<double>(rhs.data(), rhs.data() + rhs.size()));
  const auto cols = static_cast<Eigen::Index>(all_columns);
  const Eigen::MatrixXd X = lu.solve(Eigen::Map<const Eigen::MatrixXd>(all.data(), k, cols));
  const auto [first, last] = share.column_range(all_columns);
  return X.middleCols(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(last - first));
}

// Energy: a sample patch reflects rho_a s_a < 1 of what reaches it (row sums of
// K), so no light is created and K is a contraction. Raises stats.max_row_sum.
void require_energy_conserved(const Scene& scene, const std::vector<int>& P, const ContractionSystem& W_PP, int c,
                              SampleOperatorStats& st) {
  const Eigen::VectorXd& rho = W_PP.rho;
  const double ambient_sum = W_PP.ambient.sum();
  for (Eigen::Index a = 0; a < static_cast<Eigen::Index>(P.size()); ++a) {
    const double row_sum = rho[a] * (W_PP.W.row(a).sum() + W_PP.fallback_scale[a] * ambient_sum);
    st.max_row_sum = std::max(st.max_row_sum, row_sum);
    if (!(row_sum < 1.0))
      throw NumericalError("interreflection operator: " + patch_name(scene, P[a]) + " would reflect " +
                           std::to_string(row_sum) + " of the light reaching it (rho " + std::to_string(rho[a]) +
                           ", channel " + std::to_string(c) + "): energy would be created");
  }
}

// One channel's reflected radiosity at the sample, Bʳ_P per lumen (refined: bounces 2
// and up), and (refined) the first reflection gathered at the goal patches, F(G,:) B1.
struct ChannelSolution {
  Eigen::MatrixXd reflected;
  Eigen::MatrixXd first_at_goals;
};

ChannelSolution solve_channel(const Scene& scene, const GoalRows& goals, const PatchSample& sample,
                              const SampleDirect& direct, const FirstReflection& first,
                              const SourceTable& table, bool refine, int c, ContractionSystem& W_PP,
                              const SampleOperatorOptions& options, SampleOperatorStats& st, int& solve_sweeps) {
  const std::vector<int>& P = sample.patches;
  const Eigen::Index k = static_cast<Eigen::Index>(P.size());
  // This share's columns (every column in one process).
  const auto [c0, c1] = options.share.column_range(goals.sources.size());
  const Eigen::Index L = static_cast<Eigen::Index>(c1 - c0);
  Eigen::VectorXd rho(k);
  for (Eigen::Index b = 0; b < k; ++b) rho[b] = scene.reflectance(P[b], c);
  W_PP.rho = rho;
  require_energy_conserved(scene, P, W_PP, c, st);
  // Plain: (I - K) Bʳ_P = R D_P, every reflection through the sample. Refined
  // (luminaire columns): the first reflection B1 = R D is gathered exactly through
  // full rows, S = F(P,:) B1, and the sample carries bounces 2 and up:
  // Bʳ_P - B1_P = (I - K)^-1 R S, non-negative like every term here.
  Eigen::MatrixXd rhs = rho.asDiagonal() * direct.D_P;
  ChannelSolution out;
  if (refine) {
    const Eigen::MatrixXd S = direct.kept_scale.asDiagonal() * first.at_sample[static_cast<std::size_t>(c)];
    out.first_at_goals = goals.kept_scale.asDiagonal() * first.at_goals[static_cast<std::size_t>(c)];
    for (Eigen::Index l = 0; l < L; ++l)
      if (table.emitting_index[c0 + static_cast<std::size_t>(l)] < 0) rhs.col(l) = rho.asDiagonal() * S.col(l);
  }
  out.reflected = solve_interreflection(W_PP, rhs, goals.sources.size(), options.share, st, solve_sweeps);
  require_finite(out.reflected, "interreflection solve (I - K)", scene, P,
                 std::span<const LightSource>(goals.sources).subspan(c0, c1 - c0));
  return out;
}

// The goal patches' and points' gather of one channel's Bʳ_P (plus, refined, the
// first reflection), added to `sum` with the channel's luminance weight.
void add_channel_response(const Scene& scene, const GoalRows& goals, const FirstReflection& first, const SourceTable& table,
                          const GatherWeights& W, bool refine, int c, const ChannelSolution& solved,
                          const WorkShare& share, IndirectLight& sum) {
  // This share's columns (every column in one process).
  const auto [c0, c1] = share.column_range(goals.sources.size());
  const Eigen::Index L = static_cast<Eigen::Index>(c1 - c0);
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());
  const Eigen::Index Q = static_cast<Eigen::Index>(goals.points.size());
  const Eigen::MatrixXd& reflected = solved.reflected;
  const Eigen::VectorXd& ambient = W.sample.ambient;
  // A split build's shares of several columns: each column's ambient product as the whole's.
  const bool padded = share.count > 1 && goals.sources.size() > 1;
  const Eigen::RowVectorXd ambient_reflected =
      padded ? ambient_product(ambient, reflected) : Eigen::RowVectorXd(ambient.transpose() * reflected);
  Eigen::MatrixXd channel_indirect = W.goals * reflected + W.goal_fallback_scale * ambient_reflected;
  if (refine)
    for (Eigen::Index l = 0; l < L; ++l)
      if (table.emitting_index[c0 + static_cast<std::size_t>(l)] < 0) channel_indirect.col(l) += solved.first_at_goals.col(l);
  const double weight = scene.channels == 1 ? 1.0 : kLuminanceWeights[c];
  sum.at_goals += weight * channel_indirect;
  if (Q > 0) {
    Eigen::MatrixXd at_points = W.points * reflected + W.point_fallback_scale * ambient_reflected;
    if (refine && goals.point_rows) {
      const Eigen::MatrixXd at_first = goals.point_kept_scale.asDiagonal() * first.at_points[static_cast<std::size_t>(c)];
      for (Eigen::Index l = 0; l < L; ++l)
        if (table.emitting_index[c0 + static_cast<std::size_t>(l)] < 0) at_points.col(l) += at_first.col(l);
    }
    sum.at_points += weight * at_points;
  }
  Eigen::VectorXd rho_goal(G);
  for (Eigen::Index g = 0; g < G; ++g) rho_goal[g] = scene.reflectance(goals.patches[g], c);
  sum.reflected += weight * (rho_goal.asDiagonal() *
                             (goals.direct_lux_per_lm.middleCols(static_cast<Eigen::Index>(c0), L) + channel_indirect));
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

// T and D get the points' rows after the patches' (a no-op without points); the
// reflected light is 0 at points.
void append_point_rows(const GoalRows& goals, const Eigen::MatrixXd& point_total, SampleOperator& op) {
  const Eigen::Index L = static_cast<Eigen::Index>(goals.sources.size());
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());
  const Eigen::Index Q = static_cast<Eigen::Index>(goals.points.size());
  if (Q == 0) return;
  Eigen::MatrixXd direct(G + Q, L), total(G + Q, L), reflected = Eigen::MatrixXd::Zero(G + Q, L);
  direct << op.direct_lux_per_lm, goals.point_direct_lux_per_lm;
  total << op.total_lux_per_lm, point_total;
  reflected.topRows(G) = op.reflected_lm_per_m2_per_lm;
  op.direct_lux_per_lm = std::move(direct);
  op.total_lux_per_lm = std::move(total);
  op.reflected_lm_per_m2_per_lm = std::move(reflected);
}

}  // namespace

IndirectLight solve_indirect_light(const Scene& scene, const GoalRows& goals, const PatchSample& sample,
                                   const SampleDirect& direct, const FirstReflection& first,
                                   const SourceTable& table, GatherWeights& weights,
                                   const SampleOperatorOptions& options, const ProgressCallback& progress,
                                   SampleOperatorStats& st) {
  const auto [c0, c1] = options.share.column_range(goals.sources.size());
  const Eigen::Index L = static_cast<Eigen::Index>(c1 - c0);  // this share's columns
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());
  const Eigen::Index Q = static_cast<Eigen::Index>(goals.points.size());
  const bool refine = options.indirect == IndirectMethod::exact_second_bounce;
  const auto channels = static_cast<std::size_t>(scene.channels);
  IndirectLight sum{Eigen::MatrixXd::Zero(G, L), Eigen::MatrixXd::Zero(Q, L), Eigen::MatrixXd::Zero(G, L), 0};
  for (int c = 0; c < scene.channels; ++c) {
    if (progress) progress("k x k solve", static_cast<std::size_t>(c), channels);
    const auto solve_start = std::chrono::steady_clock::now();
    const ChannelSolution solved =
        solve_channel(scene, goals, sample, direct, first, table, refine, c, weights.sample, options, st, sum.solve_sweeps);
    st.solve_seconds += seconds_since(solve_start);
    const auto response_start = std::chrono::steady_clock::now();
    add_channel_response(scene, goals, first, table, weights, refine, c, solved, options.share, sum);
    st.response_seconds += seconds_since(response_start);
  }
  if (progress) progress("k x k solve", channels, channels);
  if (options.share.count > 1) {
    // Every share's columns of the goals' and points' light (small: rows x sources),
    // concatenated in share order (= column order) on every share.
    const auto whole = [&](const Eigen::MatrixXd& mine) {
      const std::vector<double> all =
          gather_shares(options.share, std::vector<double>(mine.data(), mine.data() + mine.size()));
      const Eigen::Index cols = mine.rows() > 0 ? static_cast<Eigen::Index>(all.size()) / mine.rows()
                                                : static_cast<Eigen::Index>(goals.sources.size());
      if (cols != static_cast<Eigen::Index>(goals.sources.size()))
        throw std::logic_error("solve_indirect_light: " + std::to_string(all.size()) + " values gathered for " +
                               std::to_string(mine.rows()) + " rows of " + std::to_string(goals.sources.size()) + " sources");
      return Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(all.data(), mine.rows(), cols));
    };
    sum.at_goals = whole(sum.at_goals);
    sum.at_points = whole(sum.at_points);
    sum.reflected = whole(sum.reflected);
  }
  st.condition_bound_inf = (1.0 + st.max_row_sum) / (1.0 - st.max_row_sum);
  return sum;
}

void assemble_response(const Scene& scene, const GoalRows& goals, const IndirectLight& indirect, SampleOperator& op) {
  op.total_lux_per_lm = op.direct_lux_per_lm;
  op.total_lux_per_lm += indirect.at_goals;
  op.reflected_lm_per_m2_per_lm = indirect.reflected;
  require_finite(op.total_lux_per_lm, "illuminance at goal patches", scene, goals.patches, goals.sources);
  clamp_round_off(op.total_lux_per_lm, scene, goals.patches, goals.sources);
  if (!goals.points.empty()) {
    Eigen::MatrixXd point_total = goals.point_direct_lux_per_lm + indirect.at_points;
    const std::vector<int> labels = goal_row_labels({}, goals.points.size());
    require_finite(point_total, "illuminance at goal points", scene, labels, goals.sources);
    clamp_round_off(point_total, scene, labels, goals.sources);
    append_point_rows(goals, point_total, op);
  }
}

void assemble_direct_only(const GoalRows& goals, SampleOperator& op) {
  const Eigen::Index L = static_cast<Eigen::Index>(goals.sources.size());
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());
  op.total_lux_per_lm = op.direct_lux_per_lm;
  op.reflected_lm_per_m2_per_lm = Eigen::MatrixXd::Zero(G, L);
  append_point_rows(goals, goals.point_direct_lux_per_lm, op);
}

}  // namespace ilp::detail
