// How far the sample-based operator's illuminance is from the truth (METHOD section 5):
// measured against a reference solution, and predicted without one from the spread
// of eta independent samples, which shrinks like sqrt((1/k - 1/n) / (1/k0 - 1/n))
// for k of n patches drawn (the finite-population correction makes k = n exact).
#pragma once

#include <Eigen/Core>
#include <span>

#include "core/base/progress.h"
#include "core/transport/ray_caster.h"
#include "core/operator/sample_operator.h"
#include "core/scene/scene.h"

namespace ilp {

// Relative errors over goal patches; RMS values are area-weighted. Indirect =
// total - direct. A patch whose reference value is below 1e-9 of the largest is
// left out of the relative errors (0/0 says nothing).
struct IlluminanceError {
  double rms_relative_total = 0.0;
  double max_relative_total = 0.0;
  double rms_relative_indirect = 0.0;
  double max_relative_indirect = 0.0;
};

IlluminanceError compare_illuminance(const Scene& scene, std::span<const int> goal_patches,
                                     const Eigen::VectorXd& total_lux, const Eigen::VectorXd& direct_lux,
                                     const Eigen::VectorXd& reference_total_lux,
                                     const Eigen::VectorXd& reference_direct_lux);

struct ErrorPrediction {
  int pilot_size = 0;            // k0 of each pilot sample
  int samples = 0;               // eta
  std::size_t population = 0;    // reflecting patches, n
  // Area-weighted RMS over goal patches of (standard deviation / mean) across the
  // eta samples, of total and of indirect illuminance, at k0.
  double rms_relative_spread_total = 0.0;
  double rms_relative_spread_indirect = 0.0;
  double seconds = 0.0;          // the eta builds

  // Expected RMS relative error of total illuminance at sample size k.
  double predicted_rms_error(int k) const;
  // Smallest k whose predicted error is at most target (> 0); the population size
  // when only the census meets it.
  int recommended_sample_size(double target) const;
};

// Builds eta operators of size pilot_size (capped at the population) with sample seeds base.sample_seed + 1 ..
// + eta (the goal rows are shared) and measures their spread for the given source
// fluxes. Throws std::invalid_argument when eta < 2.
ErrorPrediction predict_sample_error(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                     const Eigen::VectorXd& flux_lm, const SampleOperatorOptions& base,
                                     int pilot_size, int samples, const ProgressCallback& progress = {});

}  // namespace ilp
