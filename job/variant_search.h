// The product-variant policy of `ilp run` and `ilp sweep`: every variant prepared
// (scene, model, operator), then searched and verified in the order of the least power
// each could draw, keeping the best (every goal met, then least power).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "job/job_runner.h"
#include "output/result_record.h"

namespace ilp {

// Every variant of the plan (job.variants) prepared, its notes and the run log's lines
// sent to `log`, then the prepared variant to `prepared_log` (its build line).
std::vector<PreparedJob> prepare_variants(const JobPlan& job, const RunOptions& run, const ProgressCallback& progress,
                                          const std::string& cache_dir, const LogSink& log,
                                          const std::function<void(const PreparedJob&)>& prepared_log = {});

// The two steps of prepare_variants, for jobs that prepare several lists of variants on
// one scene (luminaire groups): every variant's costed geometry on the shared scene (none
// depends on another), then the variants prepared from it (the last one takes the
// shared scene when `takes_scene`).
std::vector<CostedGeometry> cost_variants(const SharedScene& shared, const std::vector<VariantPlan>& plans,
                                          const RunOptions& run);
std::vector<CostEstimate> estimates_of(const std::vector<CostedGeometry>& costed);
std::vector<PreparedJob> prepare_costed(SharedScene& shared, bool takes_scene, std::vector<CostedGeometry> costed,
                                        const SceneSpec& scene, const std::vector<VariantPlan>& plans,
                                        const RunOptions& run, const ProgressCallback& progress,
                                        const std::string& cache_dir, const LogSink& log,
                                        const std::function<void(const PreparedJob&)>& prepared_log = {});

struct VariantChoice {
  std::size_t variant = 0;          // into the prepared variants
  JobOutcome outcome;
  std::vector<std::string> tried;   // one line per listed product variant (none for the plain panel)
  std::vector<VariantRecord> records;  // the same variants with their goal and constraint lines
  double search_seconds = 0.0;      // every variant's search, all rounds
  double verify_seconds = 0.0;      // every variant's verification, all rounds
};

// Solves each variant with the goal targets of `goals` (the plan's, or a sweep point's)
// and keeps the best outcome. min_power: the variants are tried in the order of the
// least power they could draw, and each is searched only for the counts that could draw
// less than the best layout found so far with every goal met (optimizer/layout_search.h),
// so a product that cannot win costs nothing.
VariantChoice solve_variants(const std::vector<PreparedJob>& prepared, const JobGoals& goals,
                             const ProgressCallback& progress, const LogSink& log);

}  // namespace ilp
