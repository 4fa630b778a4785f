// How many reflecting patches the sample-based operator draws (k): as given, a
// fraction of the population capped, or the smallest k whose predicted RMS error
// meets a target, from pilot samples (core/operator/sample_error.h).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>

#include "core/base/progress.h"
#include "core/operator/sample_operator.h"
#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

struct SampleSizeRule {
  std::optional<int> size;             // k as given; else fraction x population
  double fraction = 0.05;
  int max_size = 4000;                 // the largest k fraction or target_error gives
  std::optional<double> target_error;  // choose k so the predicted RMS relative error is at most this
  int error_samples = 4;               // eta pilot samples behind the prediction
  double pilot_fraction = 0.02;        // their size, of the reflecting patches

  // k for a population of reflecting patches (at least 1): size, else fraction x
  // population capped at max_size.
  int size_for(std::size_t population) const;
};

// The operator cache's key (core/base/key_hash.h): every field.
void hash_fields(KeyWriter& k, const SampleSizeRule& r);

struct SampleSizeChoice {
  int sample_size = 1;
  std::string log;  // how it was chosen, when a prediction chose it
};

// k as the rule gives it, or (target_error) the smallest whose predicted RMS error for
// the source fluxes `flux_lm` meets the target, from pilot samples.
SampleSizeChoice choose_sample_size(const SampleSizeRule& rule, const Scene& scene, const RayCaster& caster,
                                    const GoalRows& goals, const Eigen::VectorXd& flux_lm,
                                    const SampleOperatorOptions& options, const ProgressCallback& progress = {});

}  // namespace ilp
