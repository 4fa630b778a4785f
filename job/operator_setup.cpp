#include "job/operator_setup.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/operator/sample_error.h"

namespace ilp {

SampleOperatorOptions sample_operator_options(const JobConfig& job) {
  SampleOperatorOptions options;
  options.strategy = job.sample.strategy;
  options.sample_seed = job.sample.seed;
  options.indirect = job.sample.indirect;
  options.form_factors = job.form_factors;
  options.direct_light = job.direct_light;
  return options;
}

ExactSolveOptions exact_solve_options(const JobConfig& job) {
  ExactSolveOptions options;
  options.form_factors = job.form_factors;
  options.direct_light = job.direct_light;
  options.radiosity = job.radiosity;
  return options;
}

SampleSizeChoice choose_sample_size(const JobConfig& job, const Scene& scene, const RayCaster& caster,
                                    const GoalRows& goals, const Eigen::VectorXd& flux_lm,
                                    const SampleOperatorOptions& options, const ProgressCallback& progress) {
  const std::size_t population = reflecting_patches(scene).size();
  if (!job.sample.target_error || population == 0) return {job.sample.size_for(population), {}};
  // Pilots of pilot_fraction, at most kLargestPilot patches: the spread they measure
  // scales as 1 / sqrt(k) whatever their size, so a finer mesh needs no larger pilot.
  constexpr double kLargestPilot = 1000.0;
  const int pilot = std::min(static_cast<int>(population),
                             std::max(2, static_cast<int>(std::lround(std::min(kLargestPilot, job.sample.pilot_fraction *
                                                                                                  static_cast<double>(population))))));
  const ErrorPrediction prediction =
      predict_sample_error(scene, caster, goals, flux_lm, options, pilot, job.sample.error_samples, progress);
  const int wanted = prediction.recommended_sample_size(*job.sample.target_error);
  const int k = std::min(wanted, job.sample.max_size_for_target);
  std::ostringstream log;
  log << std::fixed << std::setprecision(2) << "sample size: " << prediction.samples << " pilot samples of " << pilot
      << " patches spread by " << 100.0 * prediction.rms_relative_spread_total << " % (RMS, total illuminance) in "
      << prediction.seconds << " s; target " << 100.0 * *job.sample.target_error << " % needs k = " << k << " of "
      << population << " (" << std::setprecision(1) << 100.0 * k / population << " %)";
  if (k < wanted)
    log << std::setprecision(2) << "; capped from " << wanted << " by solver.max_sample_size (predicted error "
        << 100.0 * prediction.predicted_rms_error(k) << " %)";
  return {k, log.str()};
}

}  // namespace ilp
