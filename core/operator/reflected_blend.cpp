// The blended operator (core/operator/reflected_blend.h): the plain operator over the
// computed sources, then each source's reflected light as a blend of theirs.
#include "core/operator/reflected_blend.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace ilp {
namespace {

Eigen::MatrixXd select_columns(const Eigen::MatrixXd& m, const std::vector<int>& columns) {
  if (m.cols() == 0) return m;
  Eigen::MatrixXd out(m.rows(), static_cast<Eigen::Index>(columns.size()));
  for (std::size_t c = 0; c < columns.size(); ++c) out.col(static_cast<Eigen::Index>(c)) = m.col(columns[c]);
  return out;
}

// Sum over channels of the luminance weight times the goal patch's reflectance: the
// factor on D in the reflected radiosity rho (D + indirect), photometric.
Eigen::VectorXd luminance_reflectance(const Scene& scene, const std::vector<int>& patches) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(patches.size()));
  for (std::size_t g = 0; g < patches.size(); ++g)
    for (int c = 0; c < scene.channels; ++c)
      out[static_cast<Eigen::Index>(g)] +=
          (scene.channels == 1 ? 1.0 : kLuminanceWeights[c]) * scene.reflectance(patches[g], c);
  return out;
}

}  // namespace

ReflectedBlend identity_blend(std::size_t sources) {
  ReflectedBlend blend;
  const auto L = static_cast<Eigen::Index>(sources);
  blend.weights.resize(L, L);
  blend.weights.setIdentity();
  for (std::size_t s = 0; s < sources; ++s) blend.computed.push_back(static_cast<int>(s));
  return blend;
}

void check_blend(const ReflectedBlend& blend, std::size_t sources) {
  const auto fail = [](const std::string& what) { throw std::invalid_argument("reflected blend: " + what); };
  const auto L = static_cast<Eigen::Index>(sources);
  if (blend.weights.rows() != static_cast<Eigen::Index>(blend.computed.size()) || blend.weights.cols() != L)
    fail("weights are " + std::to_string(blend.weights.rows()) + " x " + std::to_string(blend.weights.cols()) +
         ", not #computed x #sources");
  for (std::size_t c = 0; c < blend.computed.size(); ++c) {
    const int s = blend.computed[c];
    if (s < 0 || s >= L) fail("computed source " + std::to_string(s) + " is not a source");
    if (c > 0 && s <= blend.computed[c - 1]) fail("computed sources are not ascending and distinct");
  }
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(L);
  for (Eigen::Index s = 0; s < blend.weights.outerSize(); ++s)
    for (Eigen::SparseMatrix<double>::InnerIterator it(blend.weights, s); it; ++it) {
      if (!(it.value() >= 0.0)) fail("a negative weight for source " + std::to_string(s));
      sum[it.col()] += it.value();
    }
  for (Eigen::Index s = 0; s < L; ++s)
    if (std::abs(sum[s] - 1.0) > 1e-12) fail("the weights of source " + std::to_string(s) + " sum to " + std::to_string(sum[s]));
  for (std::size_t c = 0; c < blend.computed.size(); ++c)
    if (blend.weights.coeff(static_cast<Eigen::Index>(c), blend.computed[c]) != 1.0)
      fail("computed source " + std::to_string(blend.computed[c]) + " is not its own blend");
}

GoalRows select_sources(GoalRows&& goals, const std::vector<int>& computed) {
  GoalRows out = std::move(goals);
  std::vector<LightSource> sources;
  for (int s : computed) sources.push_back(out.sources[static_cast<std::size_t>(s)]);
  out.sources = std::move(sources);
  out.direct_lux_per_lm = select_columns(out.direct_lux_per_lm, computed);
  out.luminaire_form_factor = select_columns(out.luminaire_form_factor, computed);
  out.point_direct_lux_per_lm = select_columns(out.point_direct_lux_per_lm, computed);
  return out;
}

SampleOperator build_blended_sample_operator(const Scene& scene, const RayCaster& caster, GoalRows goals,
                                             const SampleOperatorOptions& options, const ReflectedBlend& blend,
                                             const ProgressCallback& progress) {
  const std::size_t L = goals.sources.size();
  check_blend(blend, L);
  if (blend.computed.size() == L) return build_sample_operator(scene, caster, goals, options, progress);

  // Every source's own direct light (goal patches, then points), kept before the rows
  // move into the computed sources' GoalRows.
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());
  const Eigen::Index Q = static_cast<Eigen::Index>(goals.points.size());
  Eigen::MatrixXd direct(G + Q, static_cast<Eigen::Index>(L));
  direct << goals.direct_lux_per_lm, goals.point_direct_lux_per_lm;
  std::vector<LightSource> sources = goals.sources;

  SampleOperator op = build_sample_operator(scene, caster, select_sources(std::move(goals), blend.computed), options, progress);
  const Eigen::MatrixXd reflected_light = op.total_lux_per_lm - op.direct_lux_per_lm;  // R, #rows x #computed
  const Eigen::VectorXd rho = luminance_reflectance(scene, op.goal_patches);
  Eigen::MatrixXd radiosity_after_direct = op.reflected_lm_per_m2_per_lm;  // rho x indirect (rho D removed)
  radiosity_after_direct.topRows(G) -= rho.asDiagonal() * op.direct_lux_per_lm.topRows(G);

  op.sources = std::move(sources);
  op.total_lux_per_lm = direct + reflected_light * blend.weights;
  op.reflected_lm_per_m2_per_lm = radiosity_after_direct * blend.weights;
  op.reflected_lm_per_m2_per_lm.topRows(G) += rho.asDiagonal() * direct.topRows(G);
  op.direct_lux_per_lm = std::move(direct);
  // Round-off: T - D a few ulps below 0 in a computed column must not make T negative.
  op.total_lux_per_lm = op.total_lux_per_lm.cwiseMax(0.0);
  std::ostringstream line;
  line << "reflected light computed for " << blend.computed.size() << " of " << L
       << " light sources and blended between them for the others (their direct light is their own)";
  op.log.push_back(line.str());
  return op;
}

}  // namespace ilp
