#include "run/room_run.h"

#include <chrono>

namespace ilp {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Every variant's phases, summed: what the run cost.
std::vector<std::pair<std::string, double>> run_timings(const PlanRun& out, double total_s) {
  double scene_s = 0.0, bvh_s = 0.0, operator_s = 0.0;
  for (const PreparedJob& p : out.groups.prepared) {
    scene_s += p.scene_seconds;
    bvh_s += p.bvh_seconds;
    operator_s += p.loaded_from_cache ? p.cache_seconds : p.model.build_seconds;
  }
  return {{"scene", scene_s},
          {"BVH", bvh_s},
          {out.prepared().loaded_from_cache ? "operator from cache" : "operator", operator_s},
          {"search", out.chosen.search_seconds},
          {"verification", out.chosen.verify_seconds},
          {"total", total_s}};
}

}  // namespace

PlanRun run_plan(const JobPlan& plan, const RunOptions& run, const RunHooks& hooks, const std::string& cache_dir,
                 std::vector<PreparedJob> prebuilt, double prebuilt_seconds) {
  const auto start = Clock::now();
  PlanRun out;
  if (!prebuilt.empty()) out.groups.prepared = std::move(prebuilt);
  else if (plan.groups.empty())
    out.groups.prepared = prepare_variants(plan, run, hooks.progress, cache_dir, hooks.log, hooks.prepared_log);
  else out.groups = prepare_groups(plan, run, hooks.progress, cache_dir, hooks.log, hooks.prepared_log);
  out.chosen = plan.groups.empty() ? solve_variants(out.groups.prepared, plan.goals, hooks.progress, hooks.log)
                                   : solve_groups(out.groups, plan.goals, hooks.progress, hooks.log);
  out.timings = run_timings(out, prebuilt_seconds + seconds_since(start));
  return out;
}

}  // namespace ilp
