#include "job/variant_search.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "job/job_cost.h"
#include "job/job_scene.h"
#include "job/result_mapping.h"

namespace ilp {
namespace {

// The search luminaire's least power for every count, at the targets of `goals`.
double least_power_w(const PreparedJob& prepared, const JobGoals& goals) {
  return least_layout_power_w(prepared.model, search_at(prepared.plan, goals));
}

// The names of the lines an outcome does not meet: "desks uniformity, min_distance_m".
std::string missed_lines(const JobOutcome& outcome) {
  std::string out;
  auto add = [&](const std::string& name) { out += (out.empty() ? "" : ", ") + name; };
  for (const GoalOutcome& g : outcome.goals)
    if (!g.met) add(g.predicted.name + " " + std::string(to_string(g.predicted.metric)));
  for (const ConstraintOutcome& c : outcome.constraints)
    if (!c.met) add(c.name);
  return out;
}

// "PRODUCT at R deg: ..." for the run log and result.json's variants: no timings, so
// that result.json is the same on any machine (the run log adds them: timing_note).
std::string tried_line(const VariantPlan& plan, const JobOutcome& outcome, double least_w, double to_beat) {
  std::ostringstream line;
  line << std::fixed << std::setprecision(1) << plan.product.product << " at " << plan.product.rotation_deg << " deg: ";
  if (!outcome.search.refused.empty())
    line << "not searched: " << outcome.search.refused;
  else if (outcome.search.beaten && !outcome.search.beaten_note.empty())
    line << "searched, not verified: " << outcome.search.beaten_note;
  else if (outcome.search.beaten && !std::isfinite(least_w))
    line << "not searched: no count reaches an average target at full output";
  else if (outcome.search.beaten)
    line << "not searched: at least " << least_w << " W, no less than the " << to_beat << " W already found";
  else
    line << outcome.luminaires.size() << " luminaires, " << outcome.power_w << " W, "
         << (outcome.all_met ? "every goal and constraint met" : "not met: " + missed_lines(outcome));
  return line.str();
}

// " (search S s, verification V s)" after a searched variant's line in the run log.
std::string timing_note(const JobOutcome& outcome) {
  if (!outcome.search.refused.empty() || outcome.search.beaten) return {};
  std::ostringstream note;
  note << std::fixed << std::setprecision(2) << " (search " << outcome.search.seconds << " s, verification "
       << outcome.verify_seconds << " s)";
  return note.str();
}

}  // namespace

std::vector<CostedGeometry> cost_variants(const SharedScene& shared, const std::vector<VariantPlan>& plans,
                                          const RunOptions& run) {
  const std::optional<MemoryBudget> memory = memory_budget(run.max_memory_bytes);
  std::vector<CostedGeometry> costed;
  for (const VariantPlan& plan : plans)
    costed.push_back(costed_geometry(plan, shared.loaded->scene, memory, job_machine_costs(plan.model.threads, run),
                                     shared.caster.get()));
  return costed;
}

std::vector<CostEstimate> estimates_of(const std::vector<CostedGeometry>& costed) {
  std::vector<CostEstimate> out;
  for (const CostedGeometry& c : costed) out.push_back(c.estimate);
  return out;
}

std::vector<PreparedJob> prepare_costed(SharedScene& shared, bool takes_scene, std::vector<CostedGeometry> costed,
                                        const SceneSpec& scene, const std::vector<VariantPlan>& plans,
                                        const RunOptions& run, const ProgressCallback& progress,
                                        const std::string& cache_dir, const LogSink& log,
                                        const std::function<void(const PreparedJob&)>& prepared_log) {
  std::vector<PreparedJob> out;
  for (std::size_t v = 0; v < plans.size(); ++v) {
    const VariantPlan& plan = plans[v];
    if (plan.listed && log) {
      std::ostringstream line;
      line << "variant " << v + 1 << " of " << plans.size() << ": " << plan.product.product << " at "
           << plan.product.rotation_deg << " degrees";
      log(line.str());
      for (const std::string& note : plan.product.notes) log(note);
    }
    out.push_back(prepare_variant(shared, takes_scene && v + 1 == plans.size(), std::move(costed[v]), scene, plan, run,
                                  progress, cache_dir, log));
    if (prepared_log) prepared_log(out.back());
  }
  return out;
}

std::vector<PreparedJob> prepare_variants(const JobPlan& job, const RunOptions& run, const ProgressCallback& progress,
                                          const std::string& cache_dir, const LogSink& log,
                                          const std::function<void(const PreparedJob&)>& prepared_log) {
  const std::vector<VariantPlan>& plans = job.variants;
  if (plans.empty()) return {};
  // The scene, its BVH and every variant's geometry once (none depends on another variant).
  SharedScene shared = load_shared_scene(job.scene, job.threads, run);
  log_shared_scene(shared, run, log);
  std::vector<CostedGeometry> costed = cost_variants(shared, plans, run);
  if (plans.size() > 1 && log) {
    // The whole run's estimate before the first variant: what a user plans with.
    std::ostringstream line;
    line << "estimate: the whole run, building every variant's operator and verifying its layout: about "
         << std::fixed << std::setprecision(1) << whole_run_seconds(job.goals.objective, estimates_of(costed)) << " s for its "
         << plans.size() << " variants, one after another";
    log(line.str());
  }
  return prepare_costed(shared, true, std::move(costed), job.scene, plans, run, progress, cache_dir, log, prepared_log);
}

VariantChoice solve_variants(const std::vector<PreparedJob>& prepared, const JobGoals& goals,
                             const ProgressCallback& progress, const LogSink& log) {
  std::vector<double> least_w;
  for (const PreparedJob& p : prepared) least_w.push_back(least_power_w(p, goals));
  std::vector<std::size_t> order(prepared.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const bool bounded = prepared.size() > 1 && objective_rule(goals.objective).minimises_power;
  if (bounded) std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return least_w[a] < least_w[b]; });
  VariantChoice best;
  bool have = false;
  std::string refusal;  // the first variant whose layout could not be mounted
  best.tried.resize(prepared.size());
  best.records.resize(prepared.size());
  for (const std::size_t v : order) {
    const double to_beat = bounded && have && best.outcome.all_met ? best.outcome.power_w : kNoPowerToBeat;
    JobOutcome outcome = solve_prepared(prepared[v], goals, progress, to_beat);
    if (prepared[v].plan.listed) {
      best.tried[v] = tried_line(prepared[v].plan, outcome, least_w[v], to_beat);
      best.records[v] = variant_record(prepared[v], goals, outcome, best.tried[v], false);
      if (log) log("variant " + std::to_string(v + 1) + ": " + best.tried[v] + timing_note(outcome));
    }
    best.search_seconds += outcome.search.seconds;
    best.verify_seconds += outcome.verify_seconds;
    if (outcome.search.beaten) {
      if (refusal.empty() && !outcome.search.refused.empty()) refusal = outcome.search.refused;
      continue;
    }
    if (!have || better_outcome(outcome, best.outcome)) {
      best.variant = v;
      best.outcome = std::move(outcome);
      have = true;
    }
  }
  if (!have && !refusal.empty()) {
    const LayoutSpec& layout = prepared.front().plan.search.layout;
    throw ConfigError(located(layout.loc, "luminaires.layout: " + refusal));
  }
  if (!prepared.front().plan.listed) {
    best.tried.clear();
    best.records.clear();
  } else if (have) {
    best.records[best.variant].chosen = true;
  }
  return best;
}

}  // namespace ilp
