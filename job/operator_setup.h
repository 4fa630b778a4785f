// From a job's solver section to the solvers' options (the sample-based operator's,
// with its sample size, and the exact solver's); shared by every command.
#pragma once

#include <Eigen/Core>
#include <string>

#include "job/config.h"
#include "core/exact/exact_solver.h"
#include "core/base/progress.h"
#include "core/rays/ray_caster.h"
#include "core/operator/sample_operator.h"
#include "core/operator/sample_size.h"
#include "core/scene/scene.h"

namespace ilp {

// The solver section as operator options (sample_size still unset: see below).
SampleOperatorOptions sample_operator_options(const JobConfig& job);

// The solver section as the exact solver's options (precise direct light everywhere).
ExactSolveOptions exact_solve_options(const JobConfig& job);

}  // namespace ilp
