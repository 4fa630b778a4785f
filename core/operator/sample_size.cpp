#include "core/operator/sample_size.h"

#include "core/base/setting.h"
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/operator/sample_error.h"
#include "core/base/key_hash.h"

namespace ilp {

int SampleSizeRule::size_for(std::size_t population) const {
  if (size) return *size;
  // A fraction of the patches, capped: the sample's error depends on how light moves in
  // the room, not on how finely it is meshed, so a finer mesh needs no larger k.
  const double k = std::min(fraction * static_cast<double>(population), static_cast<double>(max_size));
  return std::max(1, static_cast<int>(std::lround(k)));
}

SampleSizeChoice choose_sample_size(const SampleSizeRule& rule, const Scene& scene, const RayCaster& caster,
                                    const GoalRows& goals, const Eigen::VectorXd& flux_lm,
                                    const SampleOperatorOptions& options, const ProgressCallback& progress) {
  const std::size_t population = reflecting_patches(scene).size();
  if (!rule.target_error || population == 0) return {rule.size_for(population), {}};
  // Pilots of pilot_fraction, at most kLargestPilot patches: the spread they measure
  // scales as 1 / sqrt(k) whatever their size, so a finer mesh needs no larger pilot.
  constexpr double kLargestPilot = 1000.0;
  const int pilot = std::min(static_cast<int>(population),
                             std::max(2, static_cast<int>(std::lround(std::min(kLargestPilot, rule.pilot_fraction *
                                                                                                  static_cast<double>(population))))));
  const ErrorPrediction prediction =
      predict_sample_error(scene, caster, goals, flux_lm, options, pilot, rule.error_samples, progress);
  const int wanted = prediction.recommended_sample_size(*rule.target_error);
  const int k = std::min(wanted, rule.max_size);
  std::ostringstream log;
  log << std::fixed << std::setprecision(2) << "sample size: " << prediction.samples << " pilot samples of " << pilot
      << " patches spread by " << 100.0 * prediction.rms_relative_spread_total << " % (RMS, total illuminance) in "
      << prediction.seconds << " s; target " << 100.0 * *rule.target_error << " % needs k = " << k << " of "
      << population << " (" << std::setprecision(1) << 100.0 * k / population << " %)";
  if (k < wanted)
    log << std::setprecision(2) << "; capped from " << wanted << " by " << setting_name(Setting::max_sample_size) << " (predicted error "
        << 100.0 * prediction.predicted_rms_error(k) << " %)";
  return {k, log.str()};
}

static_assert(field_count<SampleSizeRule>() == 6, "SampleSizeRule changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const SampleSizeRule& r) {
  k.field("size", r.size).field("fraction", r.fraction).field("max_size", r.max_size);
  k.field("target_error", r.target_error).field("error_samples", r.error_samples);
  k.field("pilot_fraction", r.pilot_fraction);
}

}  // namespace ilp
