// What `ilp run` does for one single-room job, shared by a single-room run
// (apps/run_command.cpp) and each room of a building job (apps/building_command.cpp).
#pragma once

#include <string>
#include <vector>

#include "apps/grid_outputs.h"
#include "apps/commands.h"
#include "core/base/progress.h"
#include "job/config.h"
#include "job/group_runner.h"
#include "job/variant_search.h"
#include "run/room_run.h"
#include "output/atomic_file.h"
#include "output/result_record.h"

namespace ilp::cli {

inline constexpr const char* kProgramVersion = "ilp 0.1.0";

// One single-room job run: its plan run (run/room_run.h), the grids' light and the
// record (timings of this room only).
struct RoomRun {
  PlanRun run;
  std::vector<GridResult> grids;
  ResultRecord record;
  const PreparedJob& prepared() const { return run.prepared(); }
};

// Runs `plan`, the plan of `job` (a single-room job), logging to stderr, and maps what it
// found to the room's record; with `prebuilt` (its variants, prepared already: a split
// build, which took prebuilt_seconds) it searches and verifies those.
RoomRun run_room(const JobConfig& job, const JobPlan& plan, const RunOptions& run, const ProgressCallback& progress,
                 const std::string& cache, std::vector<PreparedJob> prebuilt = {}, double prebuilt_seconds = 0.0);

// Every file `ilp run` may write for a single-room job (all formats), or those its
// output.formats selects; the names are the folder's own (result.json, plan.svg, ...).
std::vector<std::string> run_output_names(const JobConfig& job, bool selected_only);

// Stages the formats job.output selects for `room` in `set` (at its current sub-folder);
// the caller commits.
void stage_room_outputs(OutputSet& set, const JobConfig& job, const RoomRun& room);

// Every goal and constraint met, with a layout.
bool room_met(const RoomRun& room);

// `ilp run` of a building job (job.rooms): each room through run_room, its files in
// rooms/<name>/, the building's result.json; one output set for all. 0 when every room
// meets its goals, 2 when one does not.
int run_building(const RunArgs& args, const JobConfig& job);

}  // namespace ilp::cli
