#include "job/scenario.h"

#include <stdexcept>

namespace ilp {

std::vector<double> scenario_fractions(const ScenarioSpec& scenario, const JobOutcome& outcome) {
  std::vector<double> out(outcome.luminaires.size(), scenario.fraction);
  for (const ScenarioLevel& level : scenario.levels) {
    if (level.group.empty()) {
      for (std::size_t j = 0; j < out.size(); ++j)
        if (scenario_picks(level.pick, j)) out[j] = level.fraction;
      continue;
    }
    for (const OutcomeGroup& g : outcome.groups)
      if (g.name == level.group)
        for (std::size_t j = 0; j < g.count; ++j)
          if (scenario_picks(level.pick, j)) out[g.first + j] = level.fraction;
  }
  return out;
}

std::vector<LitState> scenario_states(const std::vector<ScenarioSpec>& scenarios, const Scene& scene,
                                      const JobOutcome& outcome) {
  std::vector<LitState> out;
  for (const ScenarioSpec& s : scenarios) {
    LitState state;
    state.direct_only = s.light == LightCounted::direct;
    state.surface_fraction.assign(scene.surfaces.size(), s.fixed_fraction);
    const std::vector<double> fractions = scenario_fractions(s, outcome);
    for (std::size_t j = 0; j < fractions.size(); ++j) {
      const int surface = scene.find_surface(outcome_luminaire_name(outcome, j));
      if (surface < 0) throw std::logic_error("scenario '" + s.name + "': luminaire " + outcome_luminaire_name(outcome, j) + " is not in the scene");
      state.surface_fraction[static_cast<std::size_t>(surface)] = fractions[j];
    }
    out.push_back(std::move(state));
  }
  return out;
}

Eigen::VectorXd predicted_scenario_lux(const ScenarioSpec& scenario, const std::vector<double>& fractions,
                                       const LightingModel& primary, const std::vector<const LightingModel*>& models,
                                       const JobOutcome& outcome) {
  const bool direct = scenario.light == LightCounted::direct;
  Eigen::VectorXd lux = scenario.fixed_fraction * (direct ? primary.fixed_direct_lux : primary.fixed_lux);
  for (std::size_t j = 0; j < outcome.luminaires.size(); ++j) {
    if (fractions[j] == 0.0) continue;
    const LightingModel& model = models.empty() ? primary : *models.at(j);
    const Eigen::MatrixXd& columns = direct ? model.candidate_direct_lux_per_lm : model.candidate_lux_per_lm;
    const PlacedLuminaire& l = outcome.luminaires[j];
    for (int k = 0; k < GridPoint::kMaxCandidates; ++k)
      if (l.blend.candidates[k] >= 0) lux += (fractions[j] * l.flux_lm * l.blend.weights[k]) * columns.col(l.blend.candidates[k]);
  }
  return lux.cwiseMax(0.0);
}

std::vector<ScenarioOutcome> judge_scenarios(const std::vector<ScenarioSpec>& scenarios, const LightingModel& primary,
                                             const std::vector<const LightingModel*>& models, Objective objective,
                                             const JobOutcome& outcome) {
  std::vector<ScenarioOutcome> out;
  const auto observers = static_cast<Eigen::Index>(primary.observers.size());
  for (std::size_t s = 0; s < scenarios.size(); ++s) {
    const ScenarioSpec& spec = scenarios[s];
    ScenarioOutcome o;
    o.name = spec.name;
    o.light = spec.light;
    o.fractions = scenario_fractions(spec, outcome);
    for (std::size_t j = 0; j < o.fractions.size(); ++j) {
      o.power_w += o.fractions[j] * outcome.luminaires[j].power_w;
      if (o.fractions[j] > 0.0) ++o.lit;
    }
    o.predicted_lux = predicted_scenario_lux(spec, o.fractions, primary, models, outcome);
    // Illuminance goals only (the config refuses a glare goal in a scenario): no eyes.
    const Eigen::VectorXd none = Eigen::VectorXd::Zero(observers);
    SearchSpec judged;
    judged.goals = spec.goals;
    judged.objective = objective;
    const std::vector<GoalJudgement> predicted = judge_goals(primary, judged, {o.predicted_lux, none, none});
    std::optional<std::vector<GoalJudgement>> verified;
    if (s < outcome.verification.state_lux.size()) {
      o.verified_lux = outcome.verification.state_lux[s];
      verified = judge_goals(primary, judged, {o.verified_lux, none, none});
    }
    o.all_met = true;
    for (std::size_t g = 0; g < predicted.size(); ++g) {
      o.goals.push_back(judged_line(predicted[g], predicted[g], verified ? std::optional((*verified)[g]) : std::nullopt,
                                    goal_tolerance(objective, predicted[g].metric)));
      o.all_met = o.all_met && o.goals.back().met;
    }
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace ilp
