// The search for a luminaire layout: NLopt over positions on the mounting surface and
// relative fluxes, a global stage then a local refinement, on the lighting model.
//
// The overall flux scale is not searched: illuminance is linear in flux, so for given
// positions and relative fluxes w the least scale alpha that meets every lower-bound
// goal (average, minimum) is a closed-form maximum of ratios, and the scale closest to
// the average targets a closed-form least-squares fit. alpha is then clamped to the
// flux range. What cannot be met that way (uniformity with fixed sources present,
// maximum goals, the distance between luminaires, a scale beyond the flux range)
// enters an exact penalty: objective + 10 x the sum of relative violations, which is
// zero exactly when every goal holds, so a feasible layout always beats an infeasible one.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/base/progress.h"
#include "optimizer/goal_metrics.h"
#include "optimizer/goal_spec.h"
#include "optimizer/lighting_model.h"
#include "optimizer/search_spec.h"

namespace ilp {

struct PlacedLuminaire {
  Eigen::Vector3d position_m;  // centre of the emitting face
  double flux_lm = 0.0;
  double power_w = 0.0;
  GridPoint blend;             // candidates whose T columns make its light
};

// One goal line judged on an illuminance vector.
struct GoalJudgement {
  std::string name;
  GoalMetric metric = GoalMetric::average;
  double target = 0.0;     // initial: the job's (maintained) target / maintenance_factor for lux metrics
  double value = 0.0;      // lux (initial, as the luminaires are new), or the U0 ratio
  double violation = 0.0;  // relative shortfall (or excess for maximum), >= 0; for closest_to_target
                           // average goals, the relative deviation |value - target| / target
};

struct LayoutEvaluation {
  std::vector<PlacedLuminaire> luminaires;
  std::vector<GoalJudgement> goals;   // in SearchSpec::goals order
  double distance_violation = 0.0;    // sum over pairs of (min_distance - d) / min_distance where d is less
  double power_w = 0.0;               // of the luminaires placed by the search
  double objective = 0.0;             // what the search minimised, penalty included
  bool feasible = false;              // every constraint within tolerance
  Eigen::VectorXd lux;                // total illuminance at the goal patches
  Eigen::VectorXd eye_indirect_lux;   // per model observer: indirect illuminance at the eye (empty without observers)
  Eigen::VectorXd glare;              // per model observer: sum of the luminaires' L^2 omega / p^2
  std::string arrangement;            // a regular layout's ("3 x 4 field"); empty for free and array layouts
  Eigen::Vector2d spacing_m = Eigen::Vector2d::Zero();  // a regular layout's, along x and y
  double flux_scale = 0.0;            // flux per unit of relative flux
  // Checked against the luminaires' own direct light (SearchChecks): lux added at the
  // goal rows to the blend of the candidates' direct columns (0 at goal patches); empty
  // when not checked.
  Eigen::VectorXd direct_correction_lux;
};

// Judges goals on a layout's light: illuminance at the goal rows (LightingModel::goal_patches,
// then goal_points) and, for glare goals, per observer the indirect light at the eye and the
// glare terms. The overload on illuminance alone throws std::logic_error for a glare goal.
std::vector<GoalJudgement> judge_goals(const LightingModel& model, const SearchSpec& spec, const GoalLight& light);
std::vector<GoalJudgement> judge_goals(const LightingModel& model, const SearchSpec& spec, const Eigen::VectorXd& lux);
// Relative violation allowed before a constraint counts as missed (and, for
// closest_to_target, the deviation of an average goal from its target).
double goal_tolerance(Objective objective, GoalMetric metric);

struct CountAttempt {
  int luminaires = 0;
  std::string arrangement;  // a regular layout's ("3 x 4 field"); empty for free and array layouts
  int evaluations = 0;
  double seconds = 0.0;
  bool feasible = false;
  double power_w = 0.0;
  double objective = 0.0;
  std::string global_stop, local_stop;  // why each NLopt stage ended
};

struct SearchResult {
  LayoutEvaluation best;
  std::vector<CountAttempt> attempts;  // one per luminaire count tried
  int evaluations = 0;
  double seconds = 0.0;
  bool time_limited = false;           // the time budget, not the evaluation budget, ended a stage
  // No count was searched: none could draw less than the power to beat. `best` is
  // then empty (no luminaires) and means nothing. Also set (min_power) when the best
  // layout found draws, as predicted, no less than bounds.power_to_beat_w or meets
  // no goal set as predicted while that power is given: nothing worth verifying;
  // beaten_note then says what was found.
  bool beaten = false;
  std::string beaten_note;
  // A regular layout none of whose arrangements can be mounted: why (the first
  // refusal). `beaten` is then true too: there is nothing to verify.
  std::string refused;
  // Regular layouts with a PointDirectLight: arrangements re-judged with the luminaires'
  // own direct light, and the first goal that check found missed ("2 x 4 field, edges
  // ...: work_plane uniformity 0.41 with ... (predicted 0.64)"), empty when none was.
  int direct_checks = 0;
  std::string direct_check_note;
};

// The luminaires' own direct light at the goal points (LightingModel::goal_points, in
// order), lux at each luminaire's flux_lm, summed over them. The blend of candidate
// columns misses a shadow that moves with the luminaire (a chair back beside a desk-top
// point falls across the luminaire's opening only from some positions), so a regular
// search re-judges its best arrangements on this before it settles.
using PointDirectLight = std::function<Eigen::VectorXd(const std::vector<PlacedLuminaire>&)>;

// No power to beat: every count that can reach the average targets is searched.
inline constexpr double kNoPowerToBeat = std::numeric_limits<double>::infinity();

// What is known before a search that lets it leave counts out (min_power only).
struct SearchBounds {
  double power_to_beat_w = kNoPowerToBeat;  // a layout already found with every goal met (another product's)
  // What a search of the same job at targets no harder than these found (an earlier
  // verification round: its targets only rise), the latest attempt of each count
  // searched. A count found infeasible there is not searched again; one found feasible
  // is searched first when it drew the least power, and not at all when it drew no
  // less than a layout already found: harder targets do not lower its power.
  std::vector<CountAttempt> easier;
};

// Searches spec.layout's family for spec.objective under spec.goals. Regular
// families (field, rows, bays; optimizer/regular_layout.h) are enumerated on the
// model's mounting zone: every arrangement is judged at its one output, and one with
// a member farther than layout.position_tolerance_m from a legal mounting point is
// infeasible (its attempt names the member's position), never moved. Deterministic
// for spec.options.seed: the evaluation budgets end each stage unless
// spec.options.max_seconds sets a wall-clock budget (0, the default, sets none).
//
// min_power: a count is not searched when it cannot draw less than
// bounds.power_to_beat_w (e.g. a layout of another product already found) nor less
// than a feasible layout found at another count: its least power is bounded from
// below by each luminaire's minimum output and by the total flux the best-lit
// candidate needs to reach each average target (with the blend's margin), so the skip
// never loses a better layout. A count that cannot reach an average target even at
// full output is not searched either. Nor, taking the earlier search as the best that
// count can do, is one that bounds.easier found infeasible (except the largest count
// when no power to beat is given), or found to draw no less than a layout already
// found. Counts bounds.easier found feasible are searched first, least power first,
// then the rest from the fewest luminaires up; result.attempts are in count order.
// When a power to beat is given and the best layout found draws no less (or misses a
// goal) as predicted, the result is beaten too, with a note: not worth verifying.
//
// With point_direct, a regular search takes its feasible arrangements best first and
// re-judges each with the luminaires' own direct light at the goal points (the blend's
// direct columns replaced there; its reflected light kept), at most 64 of them, until
// one still meets every goal and is no worse than the next one's prediction: the best
// re-judged one is the result (infeasible when none met every goal).
SearchResult search_layout(const LightingModel& model, const SearchSpec& spec, const ProgressCallback& progress = {},
                           const SearchBounds& bounds = {}, const PointDirectLight& point_direct = {});

// The least electric power (W) any searched count can draw while reaching every
// average target: the bound above, over the counts. kNoPowerToBeat when none reaches.
double least_layout_power_w(const LightingModel& model, const SearchSpec& spec);

// Evaluates layouts as the search does, reusing its set-up (goal areas, a thread
// arena, scratch space) across calls: for measuring and for many evaluations of one
// model. One call at a time: its scratch space is shared by the calls.
class LayoutEvaluator {
 public:
  LayoutEvaluator(const LightingModel& model, const SearchSpec& spec);
  ~LayoutEvaluator();
  LayoutEvaluator(const LayoutEvaluator&) = delete;
  LayoutEvaluator& operator=(const LayoutEvaluator&) = delete;
  // One entry per luminaire in each; relative fluxes in (0, 1].
  LayoutEvaluation operator()(const std::vector<Eigen::Vector2d>& xy_m, const std::vector<double>& relative_flux) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A regular arrangement (field, rows, bays) and its light with every luminaire at 1 lm,
// blended from the candidates as the search blends them, without the fixed sources: at a
// flux phi per luminaire the arrangement adds phi x lux_per_lm at the goal rows, phi x
// eye_indirect_per_lm at the observers' eyes and phi^2 x glare_per_lm2 to their glare
// terms. What a joint search of several groups (optimizer/group_search.h) combines.
struct ArrangementLight {
  std::string label;                                    // "3 x 4 field"
  Eigen::Vector2d spacing_m = Eigen::Vector2d::Zero();
  std::vector<PlacedLuminaire> luminaires;              // at 1 lm each (power 0)
  Eigen::VectorXd lux_per_lm, eye_indirect_per_lm, glare_per_lm2;
};

struct RegularLights {
  std::vector<ArrangementLight> arrangements;  // those that can be mounted and built, fewest luminaires first
  int refused = 0;                             // arrangements with a member off its mounting or crowded
  std::string first_refusal;                   // why the first was refused
};

// Every arrangement of spec.layout's regular family on the model, with its light at 1 lm
// per luminaire. Throws ConfigError (at spec.layout.loc) when the family makes no
// arrangement in its count range, std::invalid_argument for free and array layouts.
RegularLights regular_arrangement_lights(const LightingModel& model, const SearchSpec& spec);

// The layout at given positions and relative fluxes (the scale as the search sets it):
// for tests and for re-evaluating a saved layout. xy and relative_flux have one entry
// per luminaire; relative fluxes in (0, 1].
LayoutEvaluation evaluate_layout(const LightingModel& model, const SearchSpec& spec,
                                 const std::vector<Eigen::Vector2d>& xy_m, const std::vector<double>& relative_flux);

}  // namespace ilp
