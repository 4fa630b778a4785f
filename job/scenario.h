// The lighting states of an installation beside its normal one (optimizer/scenario_spec.h):
// each scenario's fractions per luminaire, the LitState its verification solves on the
// layout's own rows, and its goal lines as predicted through the operator's columns and
// as verified. Part of the one outcome assembly (verify_found), not a pipeline of its own.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "job/job_runner.h"
#include "optimizer/scenario_spec.h"

namespace ilp {

// Per luminaire of the outcome (its order), its fraction in the scenario: `fraction`,
// then each level over it (a level naming a group the outcome lacks takes none).
std::vector<double> scenario_fractions(const ScenarioSpec& scenario, const JobOutcome& outcome);

// The states the verification solves for the scenarios, on `scene` (the job's scene with
// the outcome's luminaires placed: scene_with_layout): the layout's luminaires at their
// fractions, the job's own sources at fixed_fraction.
std::vector<LitState> scenario_states(const std::vector<ScenarioSpec>& scenarios, const Scene& scene,
                                      const JobOutcome& outcome);

// A scenario's light at the model's goal rows through the operator's columns: each
// luminaire's blend of its variant's candidate columns (all the light, or their direct
// part) at its fraction of its flux (`fractions`: scenario_fractions), plus the fixed
// sources' at fixed_fraction. models[j]: the lighting model luminaire j was searched on.
Eigen::VectorXd predicted_scenario_lux(const ScenarioSpec& scenario, const std::vector<double>& fractions,
                                       const LightingModel& primary, const std::vector<const LightingModel*>& models,
                                       const JobOutcome& outcome);

// Every scenario of the plan judged on the outcome (after its flux correction): predicted
// through the operator's columns, verified from Verification::state_lux (one per scenario,
// when verified).
std::vector<ScenarioOutcome> judge_scenarios(const std::vector<ScenarioSpec>& scenarios, const LightingModel& primary,
                                             const std::vector<const LightingModel*>& models, Objective objective,
                                             const JobOutcome& outcome);

}  // namespace ilp
