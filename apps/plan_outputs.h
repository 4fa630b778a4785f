// What `ilp run` hands the plan writers: the architecture cut from the job's scene (at
// output.plan_cut_height_m over the floor, or the work plane's height), the plan view of
// the result (goal patches and grids coloured maintained, the luminaires with their
// heights over the floor, the title block from the bill of materials) and its files.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "apps/grid_outputs.h"
#include "job/config.h"
#include "job/job_runner.h"
#include "output/atomic_file.h"
#include "output/plan_architecture.h"
#include "output/plan_svg.h"
#include "output/result_record.h"

namespace ilp::cli {

// The floor the plan's heights count from: the job's floor surface, else the scene's lowest point.
double plan_floor_z_m(const Scene& scene, const std::optional<double>& floor_z_m);

// The section height over the floor: output.plan_cut_height_m, else the first horizontal
// grid's height over the floor, else 0.8 m.
double plan_cut_height_m(const JobConfig& job, const std::vector<CalcGrid>& grids, double floor_z_m);

// The architecture of the scene cut at that height; the wall cut for dimensions 0.1 m
// under the lowest luminaire centre (lowest_luminaire_z_m; NaN: none), when that is
// above the cut.
PlanArchitecture job_architecture(const JobConfig& job, const Scene& scene, const std::vector<CalcGrid>& grids,
                                  double floor_z_m, double lowest_luminaire_z_m);

// job_architecture for a prepared job and the luminaires drawn (the isolux plans').
PlanArchitecture run_architecture(const PreparedJob& prepared, const JobConfig& job,
                                  const std::vector<DrawnLuminaire>& luminaires);

struct PlanInputs {
  const PreparedJob& prepared;
  const JobConfig& job;
  const JobOutcome& outcome;
  const ResultRecord& record;
  const std::vector<GridResult>& grids;
  Eigen::VectorXd goal_lux;             // at the model's goal patches, initial: verified where known
  std::vector<std::string> grid_files;  // per grid, the file with its values (isolux plan or grid.csv); may be empty
};

// The plan of a run's result (or, without a layout, the room and the reason).
PlanView run_plan_view(const PlanInputs& in);

// plan.svg or plan.png (2 px per SVG px) of the view, staged in the set.
void stage_plan(OutputSet& set, const Scene& scene, const PlanView& view, const std::string& name);

}  // namespace ilp::cli
