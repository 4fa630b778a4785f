// The sample operator with the reflected light of some sources blended from others'.
//
// A luminaire's reflected light at a receiver (everything after its first reflection)
// is a smooth function of where the luminaire is: it arrives from the walls, ceiling and
// floor it lights, each seen over a wide solid angle. Its direct light is not (a chair
// back beside a grid point casts a shadow that moves with the luminaire). So T's
// columns for candidates on a regular grid can take their direct light from every
// candidate and their reflected light from every second (or n-th) one, blended
// linearly between: the operator's costly phases (direct light at the sample and at
// the patches the rows hit, the k x k solve) then run over a quarter of the columns.
//
//   T(:, s) = D(:, s) + sum_c R(:, c) w(c, s),   R = T_computed - D_computed
//
// where c runs over the computed sources. A source with w(c, s) = 1 for c = s alone is
// computed as it would be without a blend: its column is the plain operator's.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

#include "core/operator/sample_operator.h"

namespace ilp {

struct ReflectedBlend {
  // The sources whose reflected light is computed, ascending (indices into GoalRows::sources).
  std::vector<int> computed;
  // #computed x #sources: column s holds the weights of the computed sources' reflected
  // light that make source s's (non-negative, summing to 1).
  Eigen::SparseMatrix<double> weights;
};

// Every source computed (weights the identity).
ReflectedBlend identity_blend(std::size_t sources);

// Throws std::invalid_argument when `blend` does not fit `sources` sources: a computed
// index out of range, unsorted or repeated, a weight column not summing to 1, negative
// weights, or a computed source whose column is not its own unit vector.
void check_blend(const ReflectedBlend& blend, std::size_t sources);

// GoalRows for the computed sources only: their columns of the direct light and form
// factors, and the rows themselves (moved: they do not depend on the sources).
GoalRows select_sources(GoalRows&& goals, const std::vector<int>& computed);

// build_sample_operator over the computed sources, then every source's column of T as
// above (and of the reflected radiosity likewise; D is every source's own). With every
// source computed, exactly build_sample_operator's result. Adds a log line that says
// how many sources were computed.
SampleOperator build_blended_sample_operator(const Scene& scene, const RayCaster& caster, GoalRows goals,
                                             const SampleOperatorOptions& options, const ReflectedBlend& blend,
                                             const ProgressCallback& progress = {});

}  // namespace ilp
