// A single-room job's plan run from start to finish: every variant (or every luminaire
// group's) prepared, the layout searched and verified, what each phase took. What `ilp
// run` does for one room before it writes the room's files.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "core/base/progress.h"
#include "job/group_runner.h"
#include "job/plan.h"
#include "job/variant_search.h"

namespace ilp {

// Where a run reports: progress bars, the run log's lines, each prepared variant (its
// operator's build line).
struct RunHooks {
  ProgressCallback progress;
  LogSink log;
  std::function<void(const PreparedJob&)> prepared_log;
};

struct PlanRun {
  PreparedGroups groups;  // the prepared variants (a single search: groups.prepared alone)
  VariantChoice chosen;
  // scene, BVH, operator (or "operator from cache"), search, verification, total: s.
  std::vector<std::pair<std::string, double>> timings;
  const PreparedJob& prepared() const { return groups.prepared[chosen.variant]; }
};

// Prepares, searches and verifies `plan` at its own goals. With `prebuilt` (the plan's
// variants prepared already: a split build, which took prebuilt_seconds) it searches
// and verifies those.
PlanRun run_plan(const JobPlan& plan, const RunOptions& run, const RunHooks& hooks, const std::string& cache_dir,
                 std::vector<PreparedJob> prebuilt = {}, double prebuilt_seconds = 0.0);

}  // namespace ilp
