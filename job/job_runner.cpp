#include "job/job_runner.h"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <numeric>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "core/base/error.h"
#include "core/exact/exact_solver.h"
#include "core/glare/ugr.h"
#include "job/plan.h"
#include "core/exact/point_illuminance.h"
#include "optimizer/goal_metrics.h"
#include "core/operator/sample_operator.h"
#include "job/job_cost.h"
#include "job/model_cache.h"
#include "job/round_calibration.h"
#include "job/scenario.h"
#include "job/verification_margin.h"

namespace ilp {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The verification's rays are independent of the operator's.
constexpr std::uint64_t kVerificationSeedSalt = 0x5EED5EEDull;

// The decisive points' second look (decisive_points, job/verification_margin.h): their
// own gathers at verification.decisive_rays rays (at least rays_per_patch), and the
// patches each gathers at least kDominantShare of its reflected light from made precise
// with rows of a sixteenth as many (at least rays_per_patch).
// A grid's lowest point is one gather over a few nearby patches (a desk, a chair back)
// whose rows at the other patches' few rays would otherwise be its error; points within
// kDecisiveBand of the lowest may swap places, so all are looked at (one pass: a second
// changed nothing on the classroom).
constexpr double kDecisiveBand = 0.05;
constexpr double kDecisiveStandardErrors = 3.0;
constexpr double kDominantShare = 0.002;
constexpr std::uint64_t kDecisiveSeedSalt = 0xDEC1DEull;
// The Gauss-Seidel residual of the verification's steps before its last (relative to the
// exitance's norm): far below the percent the refinement's doubling moves a goal.
constexpr double kStepResidual = 1e-5;

int decisive_rays(const VerificationSettings& s) { return std::max(s.rays_per_patch, s.decisive_rays); }
int dominant_rays(const VerificationSettings& s) { return std::max(s.rays_per_patch, s.decisive_rays / 16); }

// The `decisive` goal points (ascending) gathered again from the solve's radiosity with
// more rays of their own, their values in `out` replaced; returns their gathers (rows in
// `decisive` order).
PointIlluminance gather_decisive(const PreparedJob& prepared, const Scene& scene, const ProgressiveExactSolve& solve,
                                 const ExactSolveOptions& options, const ProgressCallback& progress,
                                 const std::vector<int>& decisive, Verification& out) {
  std::vector<ReceiverPoint> points;
  for (int q : decisive) points.push_back(prepared.model.goal_points.at(static_cast<std::size_t>(q)));
  FormFactorOptions rows = options.form_factors;
  rows.rays_per_patch = decisive_rays(prepared.plan.verification.settings);
  rows.seed ^= kDecisiveSeedSalt;
  const auto start = Clock::now();
  PointIlluminance again = exact_point_illuminance(scene, solve.caster(), solve.solution().radiosity, points, rows,
                                                   options.direct_light, progress);
  out.point_gather_seconds += seconds_since(start);
  for (std::size_t r = 0; r < decisive.size(); ++r) {
    const auto q = static_cast<Eigen::Index>(decisive[r]), k = static_cast<Eigen::Index>(r);
    out.point_lux[q] = again.total_lux[k];
    out.point_direct_lux[q] = again.direct_lux[k];
    out.point_error_lux[q] = again.indirect_standard_error_lux[k];
  }
  return again;
}

// The exact solve's results at every patch and, gathered from its radiosity, at the goal
// points; the `decisive` ones (ascending, maybe none) gathered again (gather_decisive).
void take_exact_solution(const PreparedJob& prepared, const Scene& scene, const ProgressiveExactSolve& solve,
                         const ExactSolveOptions& options, const ProgressCallback& progress,
                         const std::vector<int>& decisive, Verification& out) {
  out.method = "exact";
  out.patches = scene.all_patches();
  out.lux = solve.solution().radiosity.total_lux;
  out.direct_lux = solve.solution().radiosity.direct_lux;
  out.indirect_rays_per_patch = solve.other_rays();
  if (prepared.model.goal_points.empty()) return;
  const auto start = Clock::now();
  const PointIlluminance at = exact_point_illuminance(scene, solve.caster(), solve.solution().radiosity,
                                                      prepared.model.goal_points, options.form_factors,
                                                      options.direct_light, progress);
  out.point_gather_seconds += seconds_since(start);
  out.point_lux = at.total_lux;
  out.point_direct_lux = at.direct_lux;
  out.point_error_lux = at.indirect_standard_error_lux;
  if (!decisive.empty()) gather_decisive(prepared, scene, solve, options, progress, decisive, out);
}

// The other patches' rows from verification.first_indirect_rays, doubled while a goal
// still moves by more than its margin allows (refinement_settled); the last step's
// change at each goal point joins its gather's own error (the same gather rays each
// step, so the change is the radiosity's).
// `scene` with every patch's exitance scaled by its surface's fraction in `state`.
Scene lit_scene(const Scene& scene, const LitState& state) {
  if (state.surface_fraction.size() != scene.surfaces.size())
    throw std::logic_error("verification: a lighting state of another scene");
  Scene lit = scene;
  for (Patch& p : lit.patches) p.exitance_lm_per_m2 *= state.surface_fraction[static_cast<std::size_t>(p.surface)];
  return lit;
}

// The other lighting states on the exact solve's rows: each solved from its own
// exitance, read at the goal patches and gathered at the goal points.
void verify_states_exactly(const PreparedJob& prepared, const Scene& scene, const ProgressiveExactSolve& solve,
                           const ExactSolveOptions& options, const std::vector<LitState>& states,
                           const ProgressCallback& progress, Verification& out) {
  const LightingModel& model = prepared.model;
  for (const LitState& state : states) {
    const Scene lit = lit_scene(scene, state);
    const RadiositySolution solution = solve.solve_lit(lit);
    const Eigen::VectorXd& at_patches = state.direct_only ? solution.direct_lux : solution.total_lux;
    Eigen::VectorXd lux(model.goal_rows());
    for (std::size_t r = 0; r < model.goal_patches.size(); ++r)
      lux[static_cast<Eigen::Index>(r)] = at_patches[model.goal_patches[r]];
    if (!model.goal_points.empty()) {
      const PointIlluminance at = exact_point_illuminance(lit, solve.caster(), solution, model.goal_points,
                                                          options.form_factors, options.direct_light, progress);
      lux.tail(static_cast<Eigen::Index>(model.goal_points.size())) = state.direct_only ? at.direct_lux : at.total_lux;
    }
    out.state_lux.push_back(std::move(lux));
  }
}

void verify_exact_progressively(const PreparedJob& prepared, const Scene& scene, const ExactSolveOptions& options,
                                const std::vector<LitState>& states, const ProgressCallback& progress,
                                Verification& out) {
  const VerificationSettings& settings = prepared.plan.verification.settings;
  const LightingModel& model = prepared.model;
  // The steps before the last solve only to kStepResidual: their values decide whether to
  // refine and which points are decisive, against changes of a percent; the last solve
  // goes on from there to solver.relative_residual.
  const double tight = options.radiosity.relative_residual;
  ExactSolveOptions steps = options;
  steps.radiosity.relative_residual = std::max(tight, kStepResidual);
  ProgressiveExactSolve solve(scene, steps, settings.first_indirect_rays, progress);
  take_exact_solution(prepared, scene, solve, options, progress, {}, out);
  out.first_indirect_rays = solve.other_rays();
  Eigen::VectorXd change = Eigen::VectorXd::Zero(model.goal_rows());
  while (solve.can_refine()) {
    const Eigen::VectorXd before = verified_goal_lux(model, out);
    solve.refine();
    take_exact_solution(prepared, scene, solve, options, progress, {}, out);
    const Eigen::VectorXd after = verified_goal_lux(model, out);
    change = after - before;
    out.refinement_change = largest_goal_change(model, prepared.plan.search.goals, before, after);
    if (refinement_settled(model, prepared.plan.search.goals, before, after, out.point_error_lux,
                           settings.margin))
      break;
  }
  // The points deciding a minimum, uniformity or maximum: their gathers with more rays,
  // and the patches they gather most from made precise, then every point again.
  const auto decisive_start = Clock::now();
  std::vector<int> decisive;
  if (settings.decisive_rays > 0)
    decisive = decisive_points(model, prepared.plan.search.goals, verified_goal_lux(model, out), out.point_error_lux,
                               kDecisiveBand, kDecisiveStandardErrors);
  if (!decisive.empty()) {
    std::vector<int> rows(decisive.size());  // every decisive point's row in its gathers
    std::iota(rows.begin(), rows.end(), 0);
    const PointIlluminance again = gather_decisive(prepared, scene, solve, options, progress, decisive, out);
    const std::vector<int> patches = dominant_patches(scene, again.rows, solve.solution().radiosity, rows, kDominantShare);
    solve.set_relative_residual(tight);
    out.precise_patches = solve.make_precise(patches, dominant_rays(settings));
    if (out.precise_patches == 0) solve.tighten();
    take_exact_solution(prepared, scene, solve, options, progress, decisive, out);
  } else {
    solve.set_relative_residual(tight);
    if (solve.tighten()) take_exact_solution(prepared, scene, solve, options, progress, {}, out);
  }
  out.decisive_points = decisive.size();
  out.decisive_seconds = seconds_since(decisive_start);
  if (!decisive.empty()) {
    out.decisive_rays = decisive_rays(settings);
    out.precise_rays = dominant_rays(settings);
  }
  out.bvh_reused = solve.caster().reuses_base();
  verify_states_exactly(prepared, scene, solve, options, states, progress, out);
  const ExactSolveSummary& summary = solve.solution().summary;
  out.parts_s = {{"BVH", summary.bvh_seconds},
                 {"rows", summary.form_factor_seconds},
                 {"direct light", summary.direct_light_seconds},
                 {"solves", summary.solve_seconds},
                 {"goal points' gathers", out.point_gather_seconds}};
  const Eigen::Index points = out.point_error_lux.size();
  if (points > 0)
    out.point_error_lux = (out.point_error_lux.array().square() + change.tail(points).array().square()).sqrt().matrix();
}

}  // namespace

Verification verify_layout(const PreparedJob& prepared, const std::vector<PlacedLuminaire>& layout,
                           const ProgressCallback& progress) {
  if (prepared.plan.verification.settings.method == VerificationMethod::none) return {};
  JobOutcome placed;
  placed.luminaires = layout;
  return verify_scene(prepared, scene_with_layout(prepared, placed), static_cast<int>(layout.size()), progress);
}

Verification verify_scene(const PreparedJob& prepared, const Scene& scene, int luminaires,
                          const ProgressCallback& progress, const std::vector<LitState>& states) {
  const VerificationSpec& spec = prepared.plan.verification;
  const VerificationSettings& settings = spec.settings;
  Verification out;
  if (settings.method == VerificationMethod::none) return out;
  const auto start = Clock::now();
  // auto resolves by the cost model: exact while its sparse rows fit, else a sample that fits.
  const VerificationPlan plan =
      plan_verification(settings, scene.patches.size(), reflecting_patches(scene).size(), prepared.model.goal_patches.size(),
                        luminaires, memory_budget_bytes(prepared.run.max_memory_bytes));
  const bool exact = plan.method == VerificationMethod::exact;
  out.rays_per_patch = settings.rays_per_patch;
  if (exact) {
    ExactSolveOptions options = spec.exact;
    options.form_factors.rays_per_patch = settings.rays_per_patch;
    options.form_factors.seed = spec.exact.form_factors.seed ^ kVerificationSeedSalt;
    options.direct_light.seed = options.form_factors.seed;
    // Elsewhere direct light and each row's rays are only reflected (grid points gather
    // their own rays); with no goal patches, no patch is precise.
    options.precise_patches = prepared.model.goal_patches;
    options.other_rays_per_patch = settings.indirect_rays_per_patch;
    options.base_caster = prepared.caster;
    verify_exact_progressively(prepared, scene, options, states, progress, out);
  } else {
    const RayCaster caster(prepared.caster, scene, spec.threads);
    out.bvh_reused = caster.reuses_base();
    const std::vector<LightSource> sources = scene_light_sources(scene);
    SampleOperatorOptions options = spec.sample;
    options.form_factors.rays_per_patch = settings.rays_per_patch;
    options.form_factors.seed = spec.sample.form_factors.seed ^ kVerificationSeedSalt;
    options.direct_light.seed = options.form_factors.seed;
    options.sample_seed = spec.sample.sample_seed ^ kVerificationSeedSalt;
    options.sample_size = std::max(1, plan.sample_size);
    const GoalRows rows = compute_goal_rows(scene, caster, prepared.model.goal_patches, prepared.model.goal_points,
                                            sources, options, progress);
    const SampleOperator op = build_sample_operator(scene, caster, rows, options, progress);
    const Eigen::VectorXd flux = source_flux_lm(scene, sources);
    out.method = "sample";
    out.sample_size = op.stats.direct_only ? 0 : static_cast<int>(op.stats.sample_patches);
    out.patches = prepared.model.goal_patches;
    const Eigen::VectorXd lux = op.illuminance_lux(flux), direct = op.direct_lux(flux);
    const Eigen::Index G = static_cast<Eigen::Index>(out.patches.size()), Q = lux.size() - G;
    out.lux = lux.head(G);
    out.direct_lux = direct.head(G);
    out.point_lux = lux.tail(Q);
    out.point_direct_lux = direct.tail(Q);
    // The other states through the same sample operator, each source's flux scaled.
    for (const LitState& state : states) {
      Eigen::VectorXd scaled = flux;
      for (std::size_t s = 0; s < sources.size(); ++s)
        scaled[static_cast<Eigen::Index>(s)] *= state.surface_fraction.at(static_cast<std::size_t>(sources[s].surface));
      const Eigen::VectorXd at = state.direct_only ? op.direct_lux(scaled) : op.illuminance_lux(scaled);
      Eigen::VectorXd rows(prepared.model.goal_rows());
      rows.head(G) = at.head(G);
      rows.tail(Q) = at.tail(Q);
      out.state_lux.push_back(std::move(rows));
    }
  }
  out.seconds = seconds_since(start);
  if (!out.parts_s.empty()) {
    double listed = 0.0;
    for (const auto& part : out.parts_s) listed += part.second;
    out.parts_s.emplace_back("the rest", std::max(0.0, out.seconds - listed));
  }
  return out;
}

Eigen::VectorXd verified_goal_lux(const LightingModel& model, const Verification& v) {
  Eigen::VectorXd out(model.goal_rows());
  if (v.point_lux.size() != static_cast<Eigen::Index>(model.goal_points.size()))
    throw std::logic_error("verification: the goal points were not solved");
  out.tail(v.point_lux.size()) = v.point_lux;
  std::size_t k = 0;
  for (std::size_t r = 0; r < model.goal_patches.size(); ++r) {
    while (k < v.patches.size() && v.patches[k] < model.goal_patches[r]) ++k;  // both ascending
    if (k == v.patches.size() || v.patches[k] != model.goal_patches[r])
      throw std::logic_error("verification: goal patch " + std::to_string(model.goal_patches[r]) + " was not solved");
    out[static_cast<Eigen::Index>(r)] = v.lux[static_cast<Eigen::Index>(k)];
  }
  return out;
}

// The flux scale that makes the verified values meet the lower-bound goals with their
// margins, target x (1 + margin), within what the upper-bound goals allow (min_power), or fit the average targets best
// (closest_to_target): illuminance is linear in flux, so scaling every flux scales the
// verified values exactly.
double verified_flux_scale(const SearchSpec& spec, const std::vector<GoalJudgement>& verified,
                           const std::vector<GoalMargin>& margins, const std::vector<double>& flux_lm,
                           const std::vector<double>& flux_min_lm, const std::vector<double>& flux_max_lm,
                           bool& limited) {
  limited = false;
  double scale = 0.0, least = 0.0, num = 0.0, den = 0.0;
  double cap = std::numeric_limits<double>::infinity();  // the upper-bound goals' (UGR, maximum) largest scale
  for (std::size_t k = 0; k < verified.size(); ++k) {
    const GoalJudgement& g = verified[k];
    if (is_target_goal(spec.objective, g.metric)) {
      num += g.value / g.target;
      den += g.value * g.value / (g.target * g.target);
    } else if (metric_rule(g.metric).scale_closed_form && g.target > 0.0) {
      if (!(g.value > 0.0)) return 1.0;
      scale = std::max(scale, g.target * (1.0 + margins[k].margin) / g.value);
      least = std::max(least, g.target / g.value);
    } else if (const auto largest = largest_flux_scale(g.metric, g.value, g.target)) {
      cap = std::min(cap, *largest);
    }
  }
  if (objective_rule(spec.objective).averages_are_targets) scale = den > 0.0 ? num / den : 1.0;
  if (!(scale > 0.0)) return 1.0;
  // Raising every flux raises the UGR by 8 log10(scale): give up margin, not a met upper
  // bound; when even the targets themselves need more than the cap, the lower bounds win
  // and the UGR line says by how much it is missed.
  if (scale > cap && cap >= least) scale = cap;
  const double wanted = scale;
  double most = std::numeric_limits<double>::infinity(), least_range = 0.0;
  for (std::size_t j = 0; j < flux_lm.size(); ++j)
    if (flux_lm[j] > 0.0) {
      most = std::min(most, flux_max_lm[j] / flux_lm[j]);
      least_range = std::max(least_range, flux_min_lm[j] / flux_lm[j]);
    }
  scale = std::max(std::min(scale, most), least_range);
  limited = std::abs(scale - wanted) > 1e-12 * wanted;
  return scale;
}

const OutcomeGroup* outcome_group(const JobOutcome& outcome, std::size_t j) {
  for (const OutcomeGroup& g : outcome.groups)
    if (j >= g.first && j < g.first + g.count) return &g;
  return nullptr;
}

std::string outcome_luminaire_name(const JobOutcome& outcome, std::size_t j) {
  const OutcomeGroup* g = outcome_group(outcome, j);
  return g ? g->label_prefix + std::to_string(j - g->first + 1) : luminaire_name(j);
}

const VariantPlan& outcome_plan(const PreparedJob& prepared, const JobOutcome& outcome, std::size_t j) {
  const OutcomeGroup* g = outcome_group(outcome, j);
  return g ? g->plan : prepared.plan;
}

GoalOutcome judged_line(const GoalJudgement& predicted, const GoalJudgement& as_searched,
                        const std::optional<GoalJudgement>& verified, double tolerance) {
  GoalOutcome o;
  o.predicted = predicted;
  o.searched_value = as_searched.value;
  o.tolerance = tolerance;
  // The closed-form scale meets goals to round-off; allow for it.
  const bool predicted_met = as_searched.violation <= tolerance + 1e-9;
  if (verified) {
    o.verified = verified;
    o.met = verified->violation <= tolerance + 1e-9;
    o.fails_only_on_verification = predicted_met && !o.met;
  } else {
    o.met = predicted_met;
  }
  return o;
}

Scene scene_with_layout(const PreparedJob& primary, const JobOutcome& outcome) {
  Scene scene = primary.loaded.scene;
  for (std::size_t j = 0; j < outcome.luminaires.size(); ++j) {
    const SearchLuminaire& s = outcome_plan(primary, outcome, j).search.luminaire;
    const PlacedLuminaire& l = outcome.luminaires[j];
    add_luminaire(scene, outcome_luminaire_name(outcome, j), s.type, {l.position_m, s.rotation_deg, s.tilt_deg}, l.flux_lm);
  }
  return scene;
}

void add_layout(Scene& scene, const SearchLuminaire& search, const std::vector<PlacedLuminaire>& layout) {
  for (std::size_t j = 0; j < layout.size(); ++j)
    add_luminaire(scene, luminaire_name(j), search.type, {layout[j].position_m, search.rotation_deg, search.tilt_deg},
                  layout[j].flux_lm);
}

bool better_outcome(const JobOutcome& a, const JobOutcome& b) {
  if (a.all_met != b.all_met) return a.all_met;
  if (a.feasible != b.feasible) return a.feasible;
  if (a.all_met || a.feasible) return a.power_w < b.power_w;
  return a.search.best.objective < b.search.best.objective;
}

std::string luminaire_name(std::size_t j) {
  std::string name = "L";  // (not "L" + ...: GCC 12 warns falsely on operator+(const char*, string&&))
  return name.append(std::to_string(j + 1));
}

SharedScene load_shared_scene(const SceneSpec& scene, int threads, const RunOptions& run) {
  SharedScene out;
  auto start = Clock::now();
  // Meshing stops before it makes more patches than the memory could ever hold
  // (a scene, its BVH and the least build take about 1 kB a patch).
  const std::optional<MemoryBudget> memory = memory_budget(run.max_memory_bytes);
  SceneSpec limited = scene;
  if (memory) limited.scene.max_patches = std::min(scene.scene.max_patches, static_cast<std::size_t>(memory->bytes / 1024.0));
  // A model read through assimp: its reading process may use no more than the job may.
  if (memory) limited.mesh_read.import_limits.max_memory_bytes = memory->bytes;
  try {
    out.loaded = std::make_shared<JobScene>(load_job_scene(limited));
  } catch (const ConfigError& e) {
    if (!memory || limited.scene.max_patches == scene.scene.max_patches) throw;
    throw ConfigError(std::string(e.what()) + " (about 1 kB a patch within the " + format_bytes(memory->bytes) +
                      " of memory the job may use: " + memory->source + ")");
  }
  out.scene_seconds = seconds_since(start);
  start = Clock::now();
  out.caster = std::make_shared<const RayCaster>(out.loaded->scene, threads);
  out.bvh_seconds = seconds_since(start);
  return out;
}

void log_shared_scene(const SharedScene& shared, const RunOptions& run, const LogSink& log) {
  if (!log) return;
  for (const std::string& line : shared.loaded->log) log(line);
  log(describe(run.machine));
}

PreparedJob prepare_job(const SceneSpec& scene, const VariantPlan& plan, const RunOptions& run,
                        const ProgressCallback& progress, const std::string& cache_dir, const LogSink& log) {
  SharedScene shared = load_shared_scene(scene, plan.model.threads, run);
  log_shared_scene(shared, run, log);
  CostedGeometry costed =
      costed_geometry(plan, shared.loaded->scene, memory_budget(run.max_memory_bytes),
                      job_machine_costs(plan.model.threads, run), shared.caster.get());
  return prepare_variant(shared, true, std::move(costed), scene, plan, run, progress, cache_dir, log);
}

PreparedJob prepare_variant(SharedScene& shared, bool last, CostedGeometry costed, const SceneSpec& scene,
                            const VariantPlan& plan, const RunOptions& run, const ProgressCallback& progress,
                            const std::string& cache_dir, const LogSink& log) {
  auto emit = [&](const std::vector<std::string>& lines, std::size_t from) {
    if (log)
      for (std::size_t k = from; k < lines.size(); ++k) log(lines[k]);
  };
  PreparedJob out;
  out.plan = plan;
  out.run = run;
  // The first variant carries the scene's and the BVH's time (timings.json sums them).
  out.scene_seconds = std::exchange(shared.scene_seconds, 0.0);
  out.bvh_seconds = std::exchange(shared.bvh_seconds, 0.0);
  out.loaded = last ? std::move(*shared.loaded) : *shared.loaded;
  out.caster = shared.caster;
  const std::optional<MemoryBudget> memory = memory_budget(run.max_memory_bytes);
  {
    // The cost model: printed, and a job that cannot fit is refused now, not minutes
    // later (before its grids are laid). (Kept apart from the model's log, which the
    // cache compares with the file's.)
    out.model = std::move(costed.model);
    out.estimate_log = format_estimate(costed.estimate);
    if (memory) out.estimate_log.push_back("memory available to the job: " + format_bytes(memory->bytes) + ", " + memory->source);
    emit(out.model.log, 0);
    emit(out.estimate_log, 0);
    if (!costed.refusal.empty()) throw ConfigError(costed.refusal);
  }
  const std::size_t geometry_lines = out.model.log.size();
  if (cache_dir.empty()) {
    compute_lighting_operator(out.model, out.loaded.scene, *out.caster, plan.model, progress);
    emit(out.model.log, geometry_lines);
    return out;
  }

  auto start = Clock::now();
  const std::string key = lighting_model_key(scene, plan.model);
  const std::string file = (std::filesystem::path(cache_dir) / (key + ".ilpmodel")).string();
  const std::optional<std::string> not_used = load_lighting_model(file, key, out.model);
  out.cache_seconds = seconds_since(start);
  if (!not_used) {
    out.loaded_from_cache = true;
    std::ostringstream status;
    status << std::fixed << std::setprecision(3) << "operator loaded from cache " << file << " (built in "
           << out.model.build_seconds << " s originally)";
    out.cache_status = status.str();
    emit(out.model.log, geometry_lines);
    return out;
  }
  compute_lighting_operator(out.model, out.loaded.scene, *out.caster, plan.model, progress);
  emit(out.model.log, geometry_lines);
  // The file was missing, or is replaced: a failure to write it leaves the job as it is.
  const std::string previous = *not_used == "no cache file" ? "" : "the cached file was not used: " + *not_used;
  start = Clock::now();
  try {
    std::error_code ec;
    std::filesystem::create_directories(cache_dir, ec);
    if (ec) throw IlpError(cache_dir + ": cannot create the cache folder (" + ec.message() + ")");
    save_lighting_model(file, out.model, key);
    out.cache_status = "operator built and cached in " + file + (previous.empty() ? "" : " (" + previous + ")");
  } catch (const std::exception& e) {
    out.cache_status = std::string("operator built; cache not used: ") + e.what() +
                       (previous.empty() ? "" : "; " + previous);
  }
  out.cache_seconds += seconds_since(start);
  return out;
}

namespace {

// The area of a surface's patches facing up, and the height of the highest of them.
std::pair<double, double> upward_area_m2(const Scene& scene, int surface) {
  double area = 0.0, highest_m = -std::numeric_limits<double>::infinity();
  for (const Patch& p : scene.patches)
    if (p.surface == surface && p.normal.z() >= 0.9) {
      area += p.area_m2;
      highest_m = std::max(highest_m, p.centroid_m.z());
    }
  return {area, highest_m};
}

// The power density's area, the first that applies: the finished floor the job names
// (luminaires.floor_surface); the floor under the first horizontal grid laid over a
// surface whose upward patches lie at the room's lowest level; the own area (its cells,
// named as such) of the first horizontal grid drawn as a rectangle or polygon (a grid
// over a raised surface, a table top, is a task area and gives none); else the
// mounting surface's plan area.
}  // namespace

std::pair<double, std::string> power_density_area(const PreparedJob& prepared) {
  const Scene& scene = prepared.loaded.scene;
  const CandidateSpec& c = prepared.plan.model.candidates;
  if (!c.floor_surface.empty()) {
    const double area = upward_area_m2(scene, scene.find_surface(c.floor_surface)).first;
    if (area > 0.0) return {area, "floor '" + c.floor_surface + "' (luminaires.floor_surface)"};
  }
  for (const CalcGridSetting& g : prepared.plan.model.grids)
    if (g.kind == GridKind::horizontal && !g.over_surface.empty()) {
      const auto [area, highest_m] = upward_area_m2(scene, scene.find_surface(g.over_surface));
      if (area > 0.0 && highest_m <= scene.bounds_m.min().z() + kFloorLevelTolerance_m)
        return {area, "floor '" + g.over_surface + "' (under grid '" + g.name + "')"};
      break;
    }
  for (std::size_t k = 0; k < prepared.model.grids.size(); ++k) {
    const CalcGrid& g = prepared.model.grids[k];
    if (g.kind == GridKind::horizontal && prepared.plan.model.grids[k].over_surface.empty() && g.area_m2 > 0.0)
      return {g.area_m2, "area of grid '" + g.name + "' (no floor surface known)"};
  }
  return {prepared.model.grid.mounting_area_m2(),
          c.suspended_height_m ? std::string("plan area of the suspension zone")
                               : "plan area of the mounting surface '" + c.mounting_surface + "'"};
}

namespace {

// As verified: the indirect light at each observer's eye from the verification's solve,
// and the glare terms of the real luminaires at their positions (not blended), each of
// its own variant, plus the fixed ones'.
LayoutLight verified_light(const PreparedJob& primary, const JobOutcome& out) {
  const LightingModel& model = primary.model;
  const Verification& v = out.verification;
  LayoutLight light{verified_goal_lux(model, v), Eigen::VectorXd(), model.fixed_glare};
  const auto n = static_cast<Eigen::Index>(model.observers.size());
  light.eye_indirect_lux.resize(n);
  const auto patches = static_cast<Eigen::Index>(model.goal_patches.size());
  for (Eigen::Index o = 0; o < n; ++o) {
    const Eigen::Index q = model.observer_rows[static_cast<std::size_t>(o)] - patches;
    light.eye_indirect_lux[o] = std::max(0.0, v.point_lux[q] - v.point_direct_lux[q]);
    for (std::size_t j = 0; j < out.luminaires.size(); ++j) {
      const SearchLuminaire& s = outcome_plan(primary, out, j).search.luminaire;
      const PlacedLuminaire& l = out.luminaires[j];
      light.glare[o] += glare_term(glare_source(s.type, {l.position_m, s.rotation_deg, s.tilt_deg}, l.flux_lm),
                                   model.observers[static_cast<std::size_t>(o)]);
    }
  }
  return light;
}

// The search layout's direct light at the goal rows, through the candidates' direct columns
// (and the luminaires' own at the goal points where the search checked them).
Eigen::VectorXd predicted_direct_lux(const LightingModel& model, const LayoutEvaluation& best) {
  Eigen::VectorXd a = model.fixed_direct_lux;
  for (const PlacedLuminaire& l : best.luminaires)
    for (int k = 0; k < GridPoint::kMaxCandidates; ++k)
      if (l.blend.candidates[k] >= 0)
        a += (l.flux_lm * l.blend.weights[k]) * model.candidate_direct_lux_per_lm.col(l.blend.candidates[k]);
  a = a.cwiseMax(0.0);
  if (best.direct_correction_lux.size() == a.size()) a = (a + best.direct_correction_lux).cwiseMax(0.0);
  return a;
}

// The search's check of its best arrangements (PointDirectLight): the luminaires at the
// goal points as the verification computes direct light there (its options and seed),
// each alone in a scene of its own, shadowed by the job scene through its BVH (the
// luminaires do not shade one another, as the candidates do not).
PointDirectLight point_direct_light(const PreparedJob& prepared, const SearchLuminaire& s) {
  if (prepared.model.goal_points.empty() || !prepared.caster) return {};
  DirectLightOptions options = prepared.plan.verification.exact.direct_light;
  options.seed = prepared.plan.verification.exact.form_factors.seed;
  return [&prepared, s, options](const std::vector<PlacedLuminaire>& luminaires) {
    Scene alone;
    alone.channels = prepared.loaded.scene.channels;
    std::vector<int> surfaces;
    for (std::size_t j = 0; j < luminaires.size(); ++j)
      surfaces.push_back(add_luminaire(alone, luminaire_name(j), s.type,
                                       {luminaires[j].position_m, s.rotation_deg, s.tilt_deg}, luminaires[j].flux_lm));
    const LuminaireLight light =
        compute_luminaire_light_at_points(alone, *prepared.caster, prepared.model.goal_points, surfaces, options);
    Eigen::VectorXd lux = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(prepared.model.goal_points.size()));
    for (std::size_t j = 0; j < luminaires.size(); ++j)
      lux += luminaires[j].flux_lm * light.lux_per_lm.col(static_cast<Eigen::Index>(j));
    return lux;
  };
}

// Every flux of the outcome and its light scaled by `scale` (illuminance is linear in
// every flux together): the luminaires, the prediction and the verification.
void scale_outcome(JobOutcome& out, double scale) {
  for (PlacedLuminaire& l : out.luminaires) {
    l.flux_lm *= scale;
    l.power_w *= scale;
  }
  out.predicted_lux *= scale;
  out.predicted_direct_lux *= scale;
  Verification& v = out.verification;
  for (Eigen::VectorXd& state : v.state_lux) state *= scale;
  v.lux *= scale;
  v.direct_lux *= scale;
  v.point_lux *= scale;
  v.point_direct_lux *= scale;
  v.point_error_lux *= scale;
}

// The one flux scale for every luminaire (each within its own variant's range) that the
// verified goals ask for (verified_flux_scale).
double flux_correction(const PreparedJob& primary, const SearchSpec& real, const JobOutcome& out,
                       const std::vector<GoalJudgement>& verified, const std::vector<GoalMargin>& margins,
                       bool& limited) {
  std::vector<double> flux, lo, hi;
  for (std::size_t j = 0; j < out.luminaires.size(); ++j) {
    const SearchLuminaire& s = outcome_plan(primary, out, j).search.luminaire;
    flux.push_back(out.luminaires[j].flux_lm);
    lo.push_back(s.flux_min_lm);
    hi.push_back(s.flux_max_lm);
  }
  return verified_flux_scale(real, verified, margins, flux, lo, hi, limited);
}

// The goal lines of the outcome: as predicted (after the flux correction), as searched,
// as verified, each with its tolerance and margin; feasible and all_met follow them.
void judge_goal_lines(JobOutcome& out, const SearchSpec& real, const std::vector<GoalJudgement>& predicted,
                      const std::vector<GoalJudgement>& as_searched,
                      const std::optional<std::vector<GoalJudgement>>& verified, const std::vector<GoalMargin>& margins) {
  for (std::size_t g = 0; g < predicted.size(); ++g) {
    GoalOutcome o = judged_line(predicted[g], as_searched[g], verified ? std::optional((*verified)[g]) : std::nullopt,
                                goal_tolerance(real.objective, predicted[g].metric));
    o.relative_error = margins[g].relative_error;
    o.margin = margins[g].margin;
    if (verified && margins[g].applies) o.margin = kept_margin(o.margin, o.verified->value, o.verified->target);
    if (!is_target_goal(real.objective, predicted[g].metric))
      out.feasible = out.feasible && as_searched[g].violation <= o.tolerance + 1e-9;
    out.all_met = out.all_met && o.met;
    out.goals.push_back(o);
  }
}

// One search (at the targets of `searched`), as FoundLayout for verify_found.
FoundLayout search_one(const PreparedJob& prepared, const SearchSpec& real, const SearchSpec& searched,
                       const ProgressCallback& progress, const SearchBounds& bounds, SearchResult& result) {
  const LightingModel& model = prepared.model;
  result = search_layout(model, searched, progress, bounds, point_direct_light(prepared, searched.luminaire));
  FoundLayout found;
  if (result.beaten) return found;
  const LayoutEvaluation& best = result.best;
  found.luminaires = best.luminaires;
  found.light = {best.lux, best.eye_indirect_lux, best.glare};
  found.direct_lux = predicted_direct_lux(model, best);
  // Met as predicted is judged on the search's own layout, before any flux correction.
  found.as_searched = judge_goals(model, real, found.light.goal_light());
  // Feasible as predicted: against the real targets, with the distance constraint and the power cap.
  found.feasible = best.distance_violation <= 1e-4 &&
                   constraint_met(ConstraintRule::at_most, real.layout.max_power_w, 0.0, best.power_w, kConstraintLineTolerance);
  return found;
}

}  // namespace

JobOutcome verify_found(const PreparedJob& primary, const SearchSpec& real, FoundLayout found,
                        const PowerDensityCap& power_cap, const ConstraintLines& constraints,
                        const ProgressCallback& progress) {
  const LightingModel& model = primary.model;
  JobOutcome out;
  out.luminaires = std::move(found.luminaires);
  out.groups = std::move(found.groups);
  out.predicted_lux = found.light.lux;
  out.predicted_direct_lux = std::move(found.direct_lux);
  std::vector<GoalJudgement> predicted = found.as_searched;
  {
    const Scene scene = scene_with_layout(primary, out);
    out.verification = verify_scene(primary, scene, static_cast<int>(out.luminaires.size()), progress,
                                    scenario_states(primary.plan.scenarios, scene, out));
  }
  out.verify_seconds = out.verification.seconds;
  std::optional<std::vector<GoalJudgement>> verified;
  std::vector<GoalMargin> margins(real.goals.size());
  out.margin_floor = primary.plan.verification.settings.margin;
  if (out.verification.method != "none") {
    const LayoutLight light = verified_light(primary, out);
    verified = judge_goals(model, real, light.goal_light());
    margins = goal_margins(model, *verified, light.lux, out.verification.point_error_lux, out.margin_floor,
                           objective_rule(real.objective).averages_are_targets);
    // Without fixed sources every illuminance is proportional to the common flux scale.
    const bool no_fixed = model.fixed_lux.cwiseAbs().maxCoeff() == 0.0;
    if (no_fixed && !out.luminaires.empty()) {
      out.flux_correction = flux_correction(primary, real, out, *verified, margins, out.flux_correction_limited);
      if (std::abs(out.flux_correction - 1.0) > 1e-12) {
        const double scale = out.flux_correction;
        scale_outcome(out, scale);
        const LayoutLight scaled{out.predicted_lux, found.light.eye_indirect_lux * scale,
                                 found.light.glare * (scale * scale)};
        predicted = judge_goals(model, real, scaled.goal_light());
        verified = judge_goals(model, real, verified_light(primary, out).goal_light());
      }
    }
  }
  for (const PlacedLuminaire& l : out.luminaires) out.power_w += l.power_w;
  for (OutcomeGroup& g : out.groups)
    for (std::size_t j = g.first; j < g.first + g.count; ++j) g.power_w += out.luminaires[j].power_w;
  out.fixed_flux_lm = model.fixed_flux_lm;
  out.mounting_area_m2 = model.grid.mounting_area_m2();
  out.maintenance_factor = primary.plan.maintenance_factor;
  out.floor_area_m2 = power_cap.area_m2;
  out.floor_area_source = power_cap.area_source;
  out.power_density_w_per_m2 = out.floor_area_m2 > 0.0 ? out.power_w / out.floor_area_m2 : 0.0;
  out.feasible = found.feasible;
  out.constraints = constraints(out);
  out.all_met = std::all_of(out.constraints.begin(), out.constraints.end(), [](const ConstraintOutcome& c) { return c.met; });
  judge_goal_lines(out, real, predicted, found.as_searched, verified, margins);
  out.scenarios = judge_scenarios(primary.plan.scenarios, model, found.models, real.objective, out);
  for (const ScenarioOutcome& s : out.scenarios) out.all_met = out.all_met && s.all_met;
  for (const GoalOutcome& o : out.goals)
    if (o.predicted.metric == GoalMetric::average) {
      const double maintained = (o.verified ? o.verified->value : o.predicted.value) * out.maintenance_factor;
      if (maintained > 0.0) out.power_density_w_per_m2_per_100_lx = out.power_density_w_per_m2 / (maintained / 100.0);
      break;
    }
  return out;
}

namespace {

// One search (at the targets of `searched`) and its verification, judged against the
// real targets of `real`.
JobOutcome search_and_verify(const PreparedJob& prepared, const SearchSpec& real, const SearchSpec& searched,
                             const PowerDensityCap& power_cap, const ProgressCallback& progress,
                             const SearchBounds& bounds) {
  SearchResult result;
  FoundLayout found = search_one(prepared, real, searched, progress, bounds, result);
  if (result.beaten) {  // nothing to verify
    JobOutcome out;
    out.search = std::move(result);
    return out;
  }
  const CandidateSpec& c = prepared.plan.model.candidates;
  const Eigen::AlignedBox2d box = prepared.model.grid.surface_box_m();
  JobOutcome out = verify_found(
      prepared, real, std::move(found), power_cap,
      [&](const JobOutcome& o) { return check_constraints(real, box, c.wall_distance_m, o.luminaires, power_cap); },
      progress);
  out.search = std::move(result);
  return out;
}

double total_missed(const JobOutcome& o) {
  double sum = 0.0;
  for (const GoalOutcome& g : o.goals) sum += (g.verified ? g.verified->violation : g.predicted.violation);
  return sum;
}

// Is a better than b? Every goal met first, then less power (min_power) or less
// deviation; otherwise less missed.
bool better_outcome(const JobOutcome& a, const JobOutcome& b, Objective objective) {
  if (a.all_met != b.all_met) return a.all_met;
  if (a.all_met && objective_rule(objective).minimises_power) return a.power_w < b.power_w;
  return total_missed(a) < total_missed(b);
}

}  // namespace

JobOutcome solve_prepared(const PreparedJob& prepared, const JobGoals& goals, const ProgressCallback& progress,
                          double power_to_beat_w) {
  JobGoals search_goals = goals;  // the rounds' targets (maintained)
  std::optional<JobOutcome> best;
  const VerificationSettings& verification = prepared.plan.verification.settings;
  const int rounds = verification.method == VerificationMethod::none ? 1 : verification.rounds;
  int searches = 0, evaluations = 0;
  SearchBounds bounds;
  bounds.power_to_beat_w = power_to_beat_w;
  double search_seconds = 0.0, verify_seconds = 0.0;
  const double mf = prepared.plan.maintenance_factor;
  SearchSpec real = search_at(prepared.plan, goals);
  PowerDensityCap power_cap;
  std::tie(power_cap.area_m2, power_cap.area_source) = power_density_area(prepared);
  power_cap.max_w_per_m2 = goals.max_power_density_w_per_m2;
  real.layout.max_power_w = power_cap.max_power_w();
  for (int round = 0; round < rounds; ++round) {
    SearchSpec searched = real;
    searched.goals = search_at(prepared.plan, search_goals).goals;
    JobOutcome outcome = search_and_verify(prepared, real, searched, power_cap, progress, bounds);
    if (outcome.search.beaten) {
      if (!best) return outcome;  // nothing could beat the power given: nothing searched
      // A later round whose every count drew no less at the easier targets than the
      // power given: the earlier rounds' best stands.
      search_seconds += outcome.search.seconds;
      break;
    }
    // The next round's targets are no easier: what this one found infeasible stays so,
    // and what it found feasible draws no less (optimizer/layout_search.h).
    for (const CountAttempt& a : outcome.search.attempts) {
      if (a.evaluations == 0) continue;
      std::erase_if(bounds.easier, [&](const CountAttempt& e) { return e.luminaires == a.luminaires; });
      bounds.easier.push_back(a);
    }
    ++searches;
    evaluations += outcome.search.evaluations;
    search_seconds += outcome.search.seconds;
    verify_seconds += outcome.verify_seconds;
    // Defect correction: a goal that fails on verification is searched for again with
    // its target scaled by how far the prediction overshot the verified value.
    bool recalibrated = false;
    for (std::size_t g = 0; g < outcome.goals.size(); ++g) {
      const GoalOutcome& o = outcome.goals[g];
      if (round + 1 == rounds) break;  // no search follows
      if (!o.fails_only_on_verification) continue;
      if (is_target_goal(goals.objective, o.predicted.metric)) continue;
      GoalLine& goal = search_goals.lines[g];
      // A lower bound's prediction and verification share the flux correction, so their
      // ratio is the operator's error; an upper bound (UGR, maximum) may be missed by the
      // correction itself (raising every flux raises the UGR), so its next target comes
      // from the value as searched.
      const double predicted_value = metric_rule(goal.metric).lower_bound ? o.predicted.value : o.searched_value;
      const std::optional<double> next =
          next_search_target(goal.metric, goals.lines[g].target, goal.target, predicted_value, o.verified->value);
      if (!next) continue;
      goal.target = *next;
      outcome.calibration.push_back(
          calibration_line(round, mf, goals.lines[g], o.predicted.value, o.verified->value, goal.target));
      recalibrated = true;
    }
    std::vector<std::string> calibration = best ? best->calibration : std::vector<std::string>{};
    calibration.insert(calibration.end(), outcome.calibration.begin(), outcome.calibration.end());
    const bool done = outcome.all_met || !recalibrated;
    if (!best || better_outcome(outcome, *best, goals.objective)) best = std::move(outcome);
    best->calibration = std::move(calibration);
    if (done) break;
  }
  best->searches = searches;
  best->search.evaluations = evaluations;
  best->search.seconds = search_seconds;
  best->verify_seconds = verify_seconds;
  return std::move(*best);
}

}  // namespace ilp
