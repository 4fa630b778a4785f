// The gather weights W_ip = s_i w_p a_ip / sum_q w_q a_iq of the sample operator
// (core/operator/sample_operator.h), for the sample's rows, the goal patches and the
// goal points, each with the ambient fallback where a row sees no sample patch.
#include <Eigen/SparseCore>

#include <algorithm>
#include <vector>

#include "core/operator/sample_operator_stages.h"

namespace ilp::detail {
namespace {

// Sample rows: from their own rows; ambient where they see no sample patch. W_PP = the
// sparse gathers + a rank-one ambient term for the rows that saw no sample patch
// (core/operator/contraction_solve.h). `sample_fallback`: per sample row, whether it fell back.
ContractionSystem sample_gather_weights(const Scene& scene, const PatchSample& sample, const SampleRows& rows,
                                        std::vector<bool>& sample_fallback, SampleOperatorStats& st) {
  const std::vector<int>& P = sample.patches;
  const Eigen::Index k = static_cast<Eigen::Index>(P.size());
  const Eigen::VectorXd& w = sample.weight;
  const std::vector<int>& sample_slot = rows.sample_slot;
  Eigen::VectorXd ambient(k);
  for (Eigen::Index b = 0; b < k; ++b) ambient[b] = scene.patches[P[b]].area_m2 * w[b];
  ambient /= ambient.sum();
  ContractionSystem W_PP;
  W_PP.ambient = ambient;
  W_PP.fallback_scale = Eigen::VectorXd::Zero(k);
  sample_fallback.assign(static_cast<std::size_t>(k), false);
  std::vector<Eigen::Triplet<double>> gathers;
  for (Eigen::Index a = 0; a < k; ++a) {
    double den = 0.0;
    for (SparseRows::InnerIterator it(rows.rows.F, a); it; ++it)
      if (const int b = sample_slot[it.col()]; b >= 0) den += it.value() * w[b];
    const double s = rows.sums.reflecting[a];
    if (den > 0.0) {
      for (SparseRows::InnerIterator it(rows.rows.F, a); it; ++it)
        if (const int b = sample_slot[it.col()]; b >= 0) gathers.emplace_back(a, b, s * it.value() * w[b] / den);
    } else {
      W_PP.fallback_scale[a] = s;
      sample_fallback[static_cast<std::size_t>(a)] = true;
      if (s > 0.0) ++st.sample_fallback_rows;
    }
  }
  W_PP.W.resize(k, k);
  W_PP.W.setFromTriplets(gathers.begin(), gathers.end());  // a patch hit twice: the entries sum
  return W_PP;
}

// Goal rows: a sampled goal uses its sample row. Others estimate A_i F_ip from
// the sample's columns (A_p F_pi, reciprocity) and, where the goal's own full row
// was kept, also from that row (A_i F_ip): two independent estimates of the same
// quantity, summed, so a goal falls back to ambient only if both saw nothing.
void goal_gather_weights(const Scene& scene, const GoalRows& goals, const PatchSample& sample, const SampleRows& rows,
                         const ContractionSystem& W_PP, const std::vector<bool>& sample_fallback,
                         GatherWeights& out, SampleOperatorStats& st) {
  const std::vector<int>& P = sample.patches;
  const Eigen::Index k = static_cast<Eigen::Index>(P.size());
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());
  const Eigen::VectorXd& w = sample.weight;
  const std::vector<int>& sample_slot = rows.sample_slot;
  const Eigen::SparseMatrix<double, Eigen::ColMajor> by_column = rows.rows.F;
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
  out.goals.resize(G, k);
  out.goals.setFromTriplets(entries.begin(), entries.end());
  out.goal_fallback_scale = std::move(fallback_scale);
}

// Goal points: a_ip from the point's own row only (it has no area for reciprocity).
void point_gather_weights(const GoalRows& goals, const PatchSample& sample, const SampleRows& rows,
                          GatherWeights& out, SampleOperatorStats& st) {
  const Eigen::Index k = static_cast<Eigen::Index>(sample.patches.size());
  const Eigen::Index Q = static_cast<Eigen::Index>(goals.points.size());
  const Eigen::VectorXd& w = sample.weight;
  const std::vector<int>& sample_slot = rows.sample_slot;
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
  out.points.resize(Q, k);
  out.points.setFromTriplets(point_entries.begin(), point_entries.end());  // duplicates (none: columns distinct) would sum
  out.point_fallback_scale = std::move(point_fallback_scale);
}

}  // namespace

GatherWeights compute_gather_weights(const Scene& scene, const GoalRows& goals, const PatchSample& sample,
                                     const SampleRows& rows, SampleOperatorStats& st) {
  GatherWeights out;
  std::vector<bool> sample_fallback;
  out.sample = sample_gather_weights(scene, sample, rows, sample_fallback, st);
  goal_gather_weights(scene, goals, sample, rows, out.sample, sample_fallback, out, st);
  point_gather_weights(goals, sample, rows, out, st);
  return out;
}

}  // namespace ilp::detail
