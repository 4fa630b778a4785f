// From a job's solver section to the sample-based operator's options and sample
// size; shared by every command that builds an operator.
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/config.h"
#include "core/progress.h"
#include "core/ray_caster.h"
#include "core/sample_operator.h"
#include "core/scene.h"

namespace ilp {

// The solver section as operator options (sample_size still unset: see below).
SampleOperatorOptions sample_operator_options(const JobConfig& job);

struct SampleSizeChoice {
  int sample_size = 1;
  std::string log;  // how it was chosen, when a prediction chose it
};

// k as configured, or (solver.target_error) the smallest whose predicted RMS error for
// the source fluxes `flux_lm` meets the target, from pilot samples.
SampleSizeChoice choose_sample_size(const JobConfig& job, const Scene& scene, const RayCaster& caster,
                                    const GoalRows& goals, const Eigen::VectorXd& flux_lm,
                                    const SampleOperatorOptions& options, const ProgressCallback& progress = {});

}  // namespace ilp
