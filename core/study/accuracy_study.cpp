#include "core/study/accuracy_study.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/exact/point_illuminance.h"
#include "core/transport/ray_caster.h"

namespace ilp {

double time_evaluation_microseconds(const SampleOperator& op, const Eigen::VectorXd& flux_lm, int repeats) {
  constexpr int kBatches = 7;
  const int per_batch = std::max(1, repeats / kBatches);
  std::vector<double> batch_us;
  Eigen::VectorXd H(op.total_lux_per_lm.rows());
  volatile double sink = 0.0;  // keeps the products from being optimised away
  for (int b = 0; b < kBatches; ++b) {
    const auto start = std::chrono::steady_clock::now();
    for (int r = 0; r < per_batch; ++r) {
      H.noalias() = op.total_lux_per_lm * flux_lm;
      sink = sink + H[0];
    }
    batch_us.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count() /
                       per_batch);
  }
  std::nth_element(batch_us.begin(), batch_us.begin() + kBatches / 2, batch_us.end());
  return batch_us[kBatches / 2];
}

PointError compare_point_illuminance(const Eigen::VectorXd& total, const Eigen::VectorXd& reference) {
  if (total.size() != reference.size()) throw std::invalid_argument("compare_point_illuminance: sizes differ");
  PointError e;
  double sum = 0.0;
  Eigen::Index n = 0;
  for (Eigen::Index q = 0; q < total.size(); ++q) {
    if (!(reference[q] > 0.0)) continue;
    const double r = std::abs(total[q] - reference[q]) / reference[q];
    sum += r * r;
    e.max_relative_total = std::max(e.max_relative_total, r);
    ++n;
  }
  e.rms_relative_total = n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
  return e;
}

AccuracyStudy run_accuracy_study(const Scene& scene, std::span<const int> goal_patches,
                                 const AccuracyStudyOptions& options, const ProgressCallback& progress) {
  return run_accuracy_study(scene, goal_patches, {}, options, progress);
}

AccuracyStudy run_accuracy_study(const Scene& scene, std::span<const int> goal_patches,
                                 std::span<const AccuracyGrid> grids, const AccuracyStudyOptions& options,
                                 const ProgressCallback& progress) {
  if (options.seeds < 1) throw std::invalid_argument("accuracy study: seeds must be >= 1");
  for (double f : options.sample_fractions)
    if (!(f > 0.0 && f <= 1.0)) throw std::invalid_argument("accuracy study: sample fractions must be in (0, 1]");
  AccuracyStudy study;
  study.patches = scene.patches.size();
  study.population = reflecting_patches(scene).size();
  study.goal_patches = goal_patches.size();
  std::vector<ReceiverPoint> points;
  for (const AccuracyGrid& g : grids) {
    study.grids.push_back(g.name);
    points.insert(points.end(), g.points.begin(), g.points.end());
  }
  study.goal_points = points.size();
  if (study.population == 0) throw std::invalid_argument("accuracy study: every reflectance is 0, nothing to sample");

  // The reference: every row, more rays, independent seed.
  ExactSolveOptions exact;
  exact.form_factors = options.base.form_factors;
  exact.form_factors.rays_per_patch = options.reference_rays;
  exact.form_factors.seed = options.reference_seed;
  exact.direct_light = options.base.direct_light;
  exact.radiosity.relative_residual = 1e-10;
  const ExactSolution reference = solve_exact(scene, exact, progress);
  study.reference = reference.summary;
  Eigen::VectorXd reference_total(static_cast<Eigen::Index>(goal_patches.size())), reference_direct = reference_total;
  for (std::size_t g = 0; g < goal_patches.size(); ++g) {
    reference_total[static_cast<Eigen::Index>(g)] = reference.radiosity.total_lux[goal_patches[g]];
    reference_direct[static_cast<Eigen::Index>(g)] = reference.radiosity.direct_lux[goal_patches[g]];
  }

  const RayCaster caster(scene, options.base.form_factors.threads);
  const Eigen::VectorXd reference_points =
      points.empty() ? Eigen::VectorXd()
                     : exact_point_illuminance(scene, caster, reference.radiosity, points, exact.form_factors,
                                               exact.direct_light, progress)
                           .total_lux;
  // The error of one operator: over the goal patches (NaN without any), per grid over its points.
  const auto G = static_cast<Eigen::Index>(goal_patches.size());
  auto measure = [&](const Eigen::VectorXd& total, const Eigen::VectorXd& direct, AccuracyRow& row) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    row.error = G ? compare_illuminance(scene, goal_patches, total.head(G), direct.head(G), reference_total, reference_direct)
                  : IlluminanceError{nan, nan, nan, nan};
    Eigen::Index first = G;
    for (const AccuracyGrid& g : grids) {
      const auto n = static_cast<Eigen::Index>(g.points.size());
      row.grids.push_back(compare_point_illuminance(total.segment(first, n), reference_points.segment(first - G, n)));
      first += n;
    }
  };
  const std::vector<LightSource> sources = scene_light_sources(scene);
  const Eigen::VectorXd flux = source_flux_lm(scene, sources);
  const int population = static_cast<int>(study.population);
  auto size_of = [&](double fraction) { return std::max(1, static_cast<int>(std::lround(fraction * population))); };
  // The census does not depend on the seed: one build.
  auto seeds_of = [&](int k) { return k >= population ? 1 : options.seeds; };
  // Fractions that round to the same k are built once.
  std::vector<int> sizes;
  for (double fraction : options.sample_fractions)
    if (std::find(sizes.begin(), sizes.end(), size_of(fraction)) == sizes.end()) sizes.push_back(size_of(fraction));
  std::size_t builds = 0;
  for (int k : sizes) builds += static_cast<std::size_t>(seeds_of(k));
  builds *= options.methods.size() * options.rays_per_row.size() * options.strategies.size();
  for (IndirectMethod method : options.methods)
    for (int rays : options.rays_per_row) {
      SampleOperatorOptions base = options.base;
      base.indirect = method;
      base.form_factors.rays_per_patch = rays;
      const GoalRows goals = compute_goal_rows(scene, caster, goal_patches, points, sources, base);
      for (SampleStrategy strategy : options.strategies) {
        base.strategy = strategy;
        const int pilot =
            std::min(population, std::max(2, static_cast<int>(std::lround(options.pilot_fraction * population))));
        study.predictions.push_back(
            {strategy, method, rays, predict_sample_error(scene, caster, goals, flux, base, pilot, options.error_samples)});
        const ErrorPrediction& prediction = study.predictions.back().prediction;
        for (const int k : sizes) {
          const double fraction = static_cast<double>(k) / population;
          for (int s = 0; s < seeds_of(k); ++s) {
            SampleOperatorOptions o = base;
            o.sample_size = k;
            o.sample_seed = options.base.sample_seed + 100 + static_cast<std::uint64_t>(s);
            const SampleOperator op = build_sample_operator(scene, caster, goals, o);
            AccuracyRow row;
            row.strategy = strategy;
            row.method = method;
            row.sample_fraction = fraction;
            row.sample_size = k;
            row.sample_patches = op.stats.sample_patches;
            row.rays_per_row = rays;
            row.sample_seed = o.sample_seed;
            row.build_seconds = op.stats.build_seconds();
            row.evaluation_microseconds = time_evaluation_microseconds(op, flux, options.evaluation_repeats);
            measure(op.illuminance_lux(flux), op.direct_lux(flux), row);
            row.predicted_rms_error_total = prediction.predicted_rms_error(k);
            row.goal_fallback_rows = op.stats.goal_fallback_rows;
            row.condition_estimate = op.stats.condition_estimate;
            study.rows.push_back(row);
            if (progress) progress("accuracy study", study.rows.size(), builds);
          }
        }
      }
    }
  return study;
}

}  // namespace ilp
