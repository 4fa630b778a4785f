// A job of several luminaire groups (luminaires.groups): each group's product variants
// prepared as a single group's are (group_job, plan_job, prepare_job: its own
// candidates, the same goal rows), the pair of arrangements and outputs with the least
// power searched together (optimizer/group_search.h), then one verification with every
// group placed and one flux correction for all.
#pragma once

#include <string>
#include <vector>

#include "job/job_runner.h"
#include "job/variant_search.h"

namespace ilp {

struct PreparedGroups {
  std::vector<PreparedJob> prepared;  // every group's variants, group after group
  std::vector<std::size_t> group;     // per prepared: its index in job.groups
};

PreparedGroups prepare_groups(const JobConfig& job, const RunOptions& run, const ProgressCallback& progress,
                              const std::string& cache_dir, const LogSink& log,
                              const std::function<void(const PreparedJob&)>& prepared_log = {});

// The pair with the least power meeting every goal (else the one that misses least),
// verified. The choice's `variant` is group 0's prepared variant (the one the outputs
// are drawn from); its outcome's groups say what each group placed. Throws ConfigError
// (file, line of the group) for a group that serves no goal (its candidates light none
// of the goal rows), a group none of whose arrangements can be mounted, groups whose
// products have different maintenance factors, or an objective other than min_power.
VariantChoice solve_groups(const PreparedGroups& groups, const JobConfig& job, const ProgressCallback& progress,
                           const LogSink& log);

}  // namespace ilp
