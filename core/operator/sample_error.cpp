#include "core/operator/sample_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace ilp {
namespace {

// Area-weighted RMS and maximum of |a - b| / b where b is meaningful.
std::pair<double, double> relative_error(const Scene& scene, std::span<const int> goals, const Eigen::VectorXd& a,
                                         const Eigen::VectorXd& b) {
  const double floor = 1e-9 * std::max(b.cwiseAbs().maxCoeff(), 0.0);
  double sum = 0.0, area = 0.0, worst = 0.0;
  for (std::size_t g = 0; g < goals.size(); ++g) {
    const Eigen::Index r = static_cast<Eigen::Index>(g);
    if (!(b[r] > floor)) continue;
    const double e = std::abs(a[r] - b[r]) / b[r];
    const double w = scene.patches[goals[g]].area_m2;
    sum += w * e * e;
    area += w;
    worst = std::max(worst, e);
  }
  return {area > 0.0 ? std::sqrt(sum / area) : 0.0, worst};
}

}  // namespace

IlluminanceError compare_illuminance(const Scene& scene, std::span<const int> goal_patches,
                                     const Eigen::VectorXd& total_lux, const Eigen::VectorXd& direct_lux,
                                     const Eigen::VectorXd& reference_total_lux,
                                     const Eigen::VectorXd& reference_direct_lux) {
  const Eigen::Index n = static_cast<Eigen::Index>(goal_patches.size());
  if (total_lux.size() != n || direct_lux.size() != n || reference_total_lux.size() != n ||
      reference_direct_lux.size() != n)
    throw std::invalid_argument("compare_illuminance: need one value per goal patch");
  IlluminanceError e;
  std::tie(e.rms_relative_total, e.max_relative_total) =
      relative_error(scene, goal_patches, total_lux, reference_total_lux);
  std::tie(e.rms_relative_indirect, e.max_relative_indirect) = relative_error(
      scene, goal_patches, total_lux - direct_lux, reference_total_lux - reference_direct_lux);
  return e;
}

double ErrorPrediction::predicted_rms_error(int k) const {
  const double n = static_cast<double>(population);
  if (k >= static_cast<int>(population) || pilot_size >= static_cast<int>(population)) return 0.0;
  const double scale = (1.0 / k - 1.0 / n) / (1.0 / pilot_size - 1.0 / n);
  return rms_relative_spread_total * std::sqrt(scale);
}

int ErrorPrediction::recommended_sample_size(double target) const {
  if (!(target > 0.0)) throw std::invalid_argument("target error must be > 0");
  const double n = static_cast<double>(population);
  // eps(k)^2 = c (1/k - 1/n), c = eps0^2 / (1/k0 - 1/n)  =>  k = 1 / (target^2 / c + 1/n).
  const int census = std::max(1, static_cast<int>(population));
  if (pilot_size >= census) return census;
  const double eps0 = rms_relative_spread_total;
  if (eps0 == 0.0) return std::clamp(pilot_size, 1, census);
  const double c = eps0 * eps0 / (1.0 / pilot_size - 1.0 / n);
  const double k = 1.0 / (target * target / c + 1.0 / n);
  const double rounded = std::ceil(k - 1e-9);  // in double: clamp before the cast (k <= n, but NaN-safe)
  if (!(rounded >= 1.0)) return 1;
  return rounded >= census ? census : static_cast<int>(rounded);
}

ErrorPrediction predict_sample_error(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                     const Eigen::VectorXd& flux_lm, const SampleOperatorOptions& base,
                                     int pilot_size, int samples, const ProgressCallback& progress) {
  if (samples < 2) throw std::invalid_argument("predict_sample_error: need at least 2 samples, got " +
                                               std::to_string(samples));
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index G = static_cast<Eigen::Index>(goals.patches.size());
  // Goal rows: patches (weighted by area), then points (each weighted by the mean goal
  // patch area, or 1 without goal patches: a point stands for its cell of a grid).
  const Eigen::Index rows = G + static_cast<Eigen::Index>(goals.points.size());
  double patch_area = 0.0;
  for (int p : goals.patches) patch_area += scene.patches[static_cast<std::size_t>(p)].area_m2;
  const double point_weight = G > 0 ? patch_area / static_cast<double>(G) : 1.0;
  Eigen::VectorXd sum_total = Eigen::VectorXd::Zero(rows), sq_total = sum_total, sum_indirect = sum_total,
                  sq_indirect = sum_total;
  ErrorPrediction out;
  out.population = reflecting_patches(scene).size();
  out.pilot_size = std::clamp(pilot_size, 1, std::max(1, static_cast<int>(out.population)));
  out.samples = samples;
  for (int e = 0; e < samples; ++e) {
    SampleOperatorOptions options = base;
    options.sample_size = out.pilot_size;
    options.sample_seed = base.sample_seed + 1 + static_cast<std::uint64_t>(e);
    const SampleOperator op = build_sample_operator(scene, caster, goals, options);
    const Eigen::VectorXd total = op.illuminance_lux(flux_lm);
    const Eigen::VectorXd indirect = total - op.direct_lux(flux_lm);
    sum_total += total;
    sq_total += total.cwiseAbs2();
    sum_indirect += indirect;
    sq_indirect += indirect.cwiseAbs2();
    if (progress) progress("sample-size estimate", static_cast<std::size_t>(e + 1), static_cast<std::size_t>(samples));
  }
  // Per patch: unbiased variance over the eta samples, relative to the mean.
  auto spread = [&](const Eigen::VectorXd& sum, const Eigen::VectorXd& sq) {
    double acc = 0.0, area = 0.0;
    const double floor = 1e-9 * sum.cwiseAbs().maxCoeff();
    for (Eigen::Index g = 0; g < rows; ++g) {
      const double mean = sum[g] / samples;
      if (!(std::abs(sum[g]) > floor)) continue;
      const double variance = std::max(0.0, (sq[g] - samples * mean * mean) / (samples - 1));
      const double w = g < G ? scene.patches[goals.patches[static_cast<std::size_t>(g)]].area_m2 : point_weight;
      acc += w * variance / (mean * mean);
      area += w;
    }
    return area > 0.0 ? std::sqrt(acc / area) : 0.0;
  };
  out.rms_relative_spread_total = spread(sum_total, sq_total);
  out.rms_relative_spread_indirect = spread(sum_indirect, sq_indirect);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace ilp
