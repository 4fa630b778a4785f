// A job of several luminaire groups (JobPlan::groups): each group's product variants
// prepared as a single search's are (prepare_variant: its own candidates, the same goal
// rows), the arrangements and outputs with the least power searched together
// (optimizer/group_search.h), then one verification with every group placed and one
// flux correction for all.
#pragma once

#include <string>
#include <vector>

#include "job/job_runner.h"
#include "job/variant_search.h"

namespace ilp {

// A group as the messages name it: its name and where the job gives it.
struct GroupName {
  std::string name;
  FileLoc loc;
};

struct PreparedGroups {
  std::vector<PreparedJob> prepared;  // every group's variants, group after group
  std::vector<std::size_t> group;     // per prepared: its index in names (the plan's groups)
  std::vector<GroupName> names;       // per group
};

// Every group of job.groups prepared on one scene (read once). Empty without groups.
PreparedGroups prepare_groups(const JobPlan& job, const RunOptions& run, const ProgressCallback& progress,
                              const std::string& cache_dir, const LogSink& log,
                              const std::function<void(const PreparedJob&)>& prepared_log = {});

// The groups' arrangements and outputs with the least power meeting every goal at the
// targets of `goals` (else the ones that miss least), verified. The choice's `variant` is group 0's prepared variant (the one the outputs
// are drawn from); its outcome's groups say what each group placed. Throws ConfigError
// (file, line of the group) for a group that serves no goal (its candidates light none
// of the goal rows), a group none of whose arrangements can be mounted, groups whose
// products have different maintenance factors, or an objective other than min_power.
VariantChoice solve_groups(const PreparedGroups& groups, const JobGoals& goals, const ProgressCallback& progress,
                           const LogSink& log);

}  // namespace ilp
