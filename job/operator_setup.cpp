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

}  // namespace ilp
