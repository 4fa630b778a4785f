// An inverse-lighting job from start to finish: the scene and the lighting model
// (built once, shared by every sweep point), the layout search, and the verification
// that places the luminaires found as real ones and solves again with the exact
// direct light and a high-accuracy indirect term.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "job/constraint_check.h"
#include "job/job_cost.h"
#include "job/job_scene.h"
#include "job/plan.h"
#include "job/verification_margin.h"
#include "core/base/progress.h"
#include "core/transport/ray_caster.h"
#include "optimizer/goal_metrics.h"
#include "optimizer/layout_search.h"
#include "optimizer/lighting_model.h"
#include "optimizer/scenario_spec.h"

namespace ilp {

// The expensive part, independent of goal targets.
struct PreparedJob {
  VariantPlan plan;            // the product searched and the stages' specs
  RunOptions run;
  JobScene loaded;
  std::shared_ptr<const RayCaster> caster;  // the scene's BVH, shared by a job's variants
  LightingModel model;         // loaded from the cache: build_seconds is the original build's
  double scene_seconds = 0.0;  // mesh loading and meshing
  double bvh_seconds = 0.0;
  bool loaded_from_cache = false;  // the operator came from the cache folder
  std::string cache_status;        // for the run log; empty without a cache folder
  double cache_seconds = 0.0;      // computing the key and reading, or writing, the cache file
  std::vector<std::string> estimate_log;  // the cost model's estimate (core/cost/cost_model.h), for the run log
};

// The variant of a job whose scene `scene` describes, prepared: the scene read and
// meshed, its BVH built, the lighting model's geometry costed (a job that cannot fit is
// refused: ConfigError) and its operator built or read from the cache.
//
// With a cache folder (job/model_cache.h), the operator is read from
// cache_dir/KEY.ilpmodel when that file is valid for the job; otherwise it is built
// and written there (the folder is created; a stale or corrupt file is replaced). A
// cache that cannot be read or written never fails the job: cache_status says why.
// An empty cache_dir: no cache.
// `log`, when given, receives the run log's lines as soon as each phase has them (the
// scene's before the operator is built, which can take a minute); they are also kept
// in loaded.log and model.log.
using LogSink = std::function<void(const std::string& line)>;
PreparedJob prepare_job(const SceneSpec& scene, const VariantPlan& plan, const RunOptions& run = {},
                        const ProgressCallback& progress = {}, const std::string& cache_dir = "", const LogSink& log = {});

// The scene and its BVH, read once for every variant of a job (neither depends on the
// product). load_shared_scene limits the meshing to the memory the run may use (about 1
// kB a patch), as prepare_job does; its log lines are in loaded->log.
struct SharedScene {
  std::shared_ptr<JobScene> loaded;
  std::shared_ptr<const RayCaster> caster;
  double scene_seconds = 0.0, bvh_seconds = 0.0;
};
// `threads`: the BVH build's worker threads (0: every core).
SharedScene load_shared_scene(const SceneSpec& scene, int threads, const RunOptions& run);
// Its log lines, then the machine's speed the estimates that follow are made at
// (run.machine: core/cost/machine_speed.h).
void log_shared_scene(const SharedScene& shared, const RunOptions& run, const LogSink& log);
// prepare_job on a scene already read, with the variant's costed geometry
// (costed_geometry on shared.loaded->scene with shared.caster), which it logs and refuses
// as prepare_job does; it does not log the scene's lines. `last`: no later variant uses
// `shared`, whose scene is then moved into the PreparedJob rather than copied.
PreparedJob prepare_variant(SharedScene& shared, bool last, CostedGeometry costed, const SceneSpec& scene,
                            const VariantPlan& plan, const RunOptions& run, const ProgressCallback& progress,
                            const std::string& cache_dir, const LogSink& log);

struct GoalOutcome {
  GoalJudgement predicted;                 // through the operator
  std::optional<GoalJudgement> verified;   // through the verification solve
  bool met = false;                        // judged on the verified value (predicted if unverified)
  bool fails_only_on_verification = false;  // met as searched (before the flux correction), missed as verified
  double searched_value = 0.0;             // the value as searched, before the flux correction
  double tolerance = 0.0;                  // relative violation accepted as met
  // The verification's relative standard error of the verified value, when it has an
  // estimate, and the margin the flux correction kept above the target (relative; 0
  // for goals it does not scale to: job/verification_margin.h).
  std::optional<double> relative_error;
  double margin = 0.0;
};

// A lighting state the verification solves beside the layout's own (a scenario,
// job/scenario.h): each surface's exitance scaled by its fraction; all the light, or only
// its direct part.
struct LitState {
  std::vector<double> surface_fraction;  // per surface of the verification's scene
  bool direct_only = false;
};

struct Verification {
  std::string method = "none";  // "exact", "sample" or "none"
  int rays_per_patch = 0;
  int sample_size = 0;          // sample method: k
  double seconds = 0.0;
  std::vector<int> patches;     // where lux is known: every patch (exact) or the goal patches (sample)
  Eigen::VectorXd lux, direct_lux;
  // At the model's goal points (LightingModel::goal_points order): exact, each point's
  // gather of the exact radiosity with rays_per_patch rays; sample, the sample operator's rows.
  Eigen::VectorXd point_lux, point_direct_lux;
  // Exact: each goal point's statistical error (lux, one standard error, of its gather;
  // core/exact/point_illuminance.h). Empty when there is no estimate (sample).
  Eigen::VectorXd point_error_lux;
  // Exact: rays per row of the patches that are not goals, where the progressive
  // refinement stopped and where it started (verification.first_indirect_rays), and
  // the largest relative change of a goal's value at its last step (0: one step).
  int indirect_rays_per_patch = 0;
  int first_indirect_rays = 0;
  double refinement_change = 0.0;
  // Exact: the goal points that decide a minimum, uniformity or maximum goal, gathered
  // again with more rays, and the patches made precise for them (verify_exact_progressively).
  std::size_t decisive_points = 0;
  int decisive_rays = 0;            // each decisive point's gather
  std::size_t precise_patches = 0;
  int precise_rays = 0;             // those patches' rows
  double decisive_seconds = 0.0;    // all of it (a share of `seconds`)
  double point_gather_seconds = 0.0;  // the goal points' gathers, every step's
  bool bvh_reused = false;            // the job scene's BVH served the verification's scene (RayCaster)
  // Exact: where `seconds` went (timings.json's verification_parts_s): the BVH, the rows,
  // the direct light, the Gauss-Seidel solves, the goal points' gathers (the decisive
  // ones' included) and the rest; each summed over the refinement's steps.
  std::vector<std::pair<std::string, double>> parts_s;
  // Per LitState asked for: its verified illuminance at the model's goal rows (patches,
  // then points), on the same rows or operator as the layout's own.
  std::vector<Eigen::VectorXd> state_lux;
};

// Places `layout` as real luminaires in the job's scene and solves it as
// the plan's VerificationSpec says (exact, or a sample of verification.sample_fraction), with
// rays independent of the operator's. Method "none" returns an empty Verification.
Verification verify_layout(const PreparedJob& prepared, const std::vector<PlacedLuminaire>& layout,
                           const ProgressCallback& progress = {});

// The verified illuminance at the model's goal rows: goal patches, then goal points.
Eigen::VectorXd verified_goal_lux(const LightingModel& model, const Verification& verification);

// One group of a layout of several (luminaires.groups): what it placed and where its
// luminaires are in JobOutcome::luminaires.
struct OutcomeGroup {
  std::string name;
  std::string label_prefix;            // its luminaires are named A1, A2, ... (B1, ... for the second)
  VariantPlan plan;                    // the product variant it placed
  std::size_t first = 0, count = 0;    // its luminaires: luminaires[first .. first + count)
  std::string arrangement;             // "4 x 3 field"
  Eigen::Vector2d spacing_m = Eigen::Vector2d::Zero();
  double power_w = 0.0;                // after the flux correction
};

// A scenario of the plan judged on the installation found (job/scenario.h).
struct ScenarioOutcome {
  std::string name;
  LightCounted light = LightCounted::total;
  std::vector<double> fractions;  // per luminaire of the outcome
  std::size_t lit = 0;            // luminaires with a fraction above 0
  double power_w = 0.0;           // the layout's power at those fractions (proportional to output)
  std::vector<GoalOutcome> goals;
  bool all_met = false;
  Eigen::VectorXd predicted_lux, verified_lux;  // at the model's goal rows (verified: empty when not)
};

struct JobOutcome {
  std::vector<PlacedLuminaire> luminaires;  // named L1, L2, ... in this order (groups: A1, ..., B1, ...)
  std::vector<OutcomeGroup> groups;         // several groups searched together; empty for one
  std::vector<GoalOutcome> goals;
  std::vector<ConstraintOutcome> constraints;  // the job's constraints on the final layout (job/constraint_check.h)
  double margin_floor = 0.0;                // verification.margin: the least margin above a scaled goal's target
  double power_w = 0.0;                     // of the luminaires placed
  double fixed_flux_lm = 0.0;               // placed in the config (not counted in power_w)
  double mounting_area_m2 = 0.0;
  // The power density's area, the first known: the floor luminaires.floor_surface names,
  // the floor under the first horizontal grid laid over a floor-level surface, the own
  // area of the first horizontal grid drawn as a rectangle or polygon, else the mounting
  // surface's plan area (floor_area_source says which).
  double floor_area_m2 = 0.0;
  std::string floor_area_source;            // what floor_area_m2 is the area of
  double power_density_w_per_m2 = 0.0;      // power_w / floor_area_m2
  // W/m² per 100 lx: the power density over the first average goal's (maintained) value / 100.
  double power_density_w_per_m2_per_100_lx = 0.0;
  double maintenance_factor = 1.0;          // maintained = initial x this
  bool feasible = false;                    // predicted: every constraint met
  bool all_met = false;                     // every goal met (judged as `met` is) and every constraint
  double flux_correction = 1.0;             // every flux was scaled by this after verification
  bool flux_correction_limited = false;     // the flux range kept it from the scale the goals wanted
  SearchResult search;
  Verification verification;
  Eigen::VectorXd predicted_lux, predicted_direct_lux;  // at model.goal_patches
  double verify_seconds = 0.0;             // all verification rounds
  int searches = 1;                         // search rounds run (see VerificationSettings::rounds)
  std::vector<std::string> calibration;     // what each round changed in the search targets
  std::vector<ScenarioOutcome> scenarios;   // the plan's other lighting states, judged on this layout
};

// A layout's light at the model's goal rows and observers (GoalLight's values).
struct LayoutLight {
  Eigen::VectorXd lux, eye_indirect_lux, glare;
  GoalLight goal_light() const { return {lux, eye_indirect_lux, glare}; }
};

// What a search found, before its verification: the layout at the fluxes found, its light
// as predicted, and its goals as judged then at the real targets.
struct FoundLayout {
  std::vector<PlacedLuminaire> luminaires;
  std::vector<OutcomeGroup> groups;  // several groups: what each placed; empty for a single search
  LayoutLight light;                 // as predicted
  Eigen::VectorXd direct_lux;        // the direct part of light.lux
  std::vector<GoalJudgement> as_searched;
  bool feasible = false;             // as predicted: the distances and the power cap (groups: every goal too)
  std::vector<const LightingModel*> models;  // per luminaire, the model it was searched on (empty: the primary's)
};

// The constraint lines of an outcome's final layout (after the flux correction).
using ConstraintLines = std::function<std::vector<ConstraintOutcome>(const JobOutcome&)>;

// The one verification and outcome assembly of every search, a single one and one of
// luminaire groups: the found layout placed as real luminaires (each of its variant,
// scene_with_layout) and solved as the plan's VerificationSpec says, the one flux correction for
// every luminaire, each goal as predicted, searched and verified, the constraints, power
// and power density. `real`: the goals at their real (initial) targets and the objective.
// The outcome's search is left for the caller.
JobOutcome verify_found(const PreparedJob& primary, const SearchSpec& real, FoundLayout found,
                        const PowerDensityCap& power_cap, const ConstraintLines& constraints,
                        const ProgressCallback& progress = {});

// One goal line judged: as predicted, as searched (met as predicted is judged there), as
// verified when there is a verification (then met is judged on it), within `tolerance`.
GoalOutcome judged_line(const GoalJudgement& predicted, const GoalJudgement& as_searched,
                        const std::optional<GoalJudgement>& verified, double tolerance);

// The job's scene with the outcome's luminaires placed as real ones: each of its own
// variant (outcome_plan), named as the outcome names it (L1, ... or A1, B1, ...).
Scene scene_with_layout(const PreparedJob& primary, const JobOutcome& outcome);

// Is a better than b: every goal met (as verified) first, then least power, then the
// search's own order.
bool better_outcome(const JobOutcome& a, const JobOutcome& b);

// Adds the layout's luminaires to `scene` as real ones, named L1, L2, ..., of the
// search's type at its rotation: how a layout found is placed everywhere (the
// verification, the benchmark's full solve).
void add_layout(Scene& scene, const SearchLuminaire& luminaire, const std::vector<PlacedLuminaire>& layout);

// "L1", "L2", ...: the name of the j-th (0-based) luminaire of a layout.
std::string luminaire_name(std::size_t j);

// The j-th luminaire of an outcome: its group (nullptr for a single group), its name
// (L1, ... or its group's A1, ...) and the variant that placed it.
const OutcomeGroup* outcome_group(const JobOutcome& outcome, std::size_t j);
std::string outcome_luminaire_name(const JobOutcome& outcome, std::size_t j);
const VariantPlan& outcome_plan(const PreparedJob& prepared, const JobOutcome& outcome, std::size_t j);

// Solves the job's scene with `scene` (the job's, the layout's `luminaires` real
// luminaires added) as the plan's VerificationSpec says: what verify_layout does once it has placed them.
// `states`: the other lighting states to verify on the same solve (Verification::state_lux).
Verification verify_scene(const PreparedJob& prepared, const Scene& scene, int luminaires,
                          const ProgressCallback& progress = {}, const std::vector<LitState>& states = {});

// The power density's area and what it is the area of (JobOutcome::floor_area_m2).
std::pair<double, std::string> power_density_area(const PreparedJob& prepared);

// The flux correction after verification: the one scale of every flux that brings the
// verified lower-bound goals to their targets with their margins, within what the
// upper-bound goals allow, each luminaire j kept within [flux_min_lm[j], flux_max_lm[j]]
// (`limited` says when that range held it back).
double verified_flux_scale(const SearchSpec& spec, const std::vector<GoalJudgement>& verified,
                           const std::vector<GoalMargin>& margins, const std::vector<double>& flux_lm,
                           const std::vector<double>& flux_min_lm, const std::vector<double>& flux_max_lm,
                           bool& limited);

// Searches and verifies with `goals` (the plan's own, prepared.plan.goals, or a sweep
// point's). When a goal fails only on verification (met as predicted, missed as
// verified), searches again, up to verification.rounds searches in all, with that goal's
// search target scaled by predicted / verified (a copy of `goals` edited); returns the
// best round (every goal met and least power first). search.evaluations, search.seconds
// and verify_seconds add up all rounds; search.attempts are the returned round's.
// `goals` may differ from the plan's in targets only; the goal areas must be the same.
// power_to_beat_w (min_power): the power of a layout already found with every goal
// met (another product's); counts that cannot draw less are not searched, and when
// none can, the outcome's search.beaten is set and nothing is searched or verified.
JobOutcome solve_prepared(const PreparedJob& prepared, const JobGoals& goals, const ProgressCallback& progress = {},
                          double power_to_beat_w = kNoPowerToBeat);

}  // namespace ilp
