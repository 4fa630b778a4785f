// What `ilp run` and `ilp solve` write per calculation grid: the grid's record (Em,
// Emin, Emax, U0 initial and maintained), grid.csv and the isolux plans, each staged
// into the command's OutputSet (output/atomic_file.h).
#pragma once

#include <string>
#include <vector>

#include "core/grid/calc_grid.h"
#include "job/config.h"
#include "core/scene/scene.h"
#include "output/atomic_file.h"
#include "output/grid_report.h"
#include "output/result_record.h"

namespace ilp::cli {

// One grid and its light at its points.
struct GridResult {
  const CalcGrid* grid = nullptr;
  GridLight light;
};

// The maintained Em target of the first average_lux goal on grid `name`; NaN without one.
double grid_target_lux(const JobConfig& job, const std::string& name);

// The record of one grid: statistics through optimizer/goal_metrics (equal weights).
GridRecord grid_record(const GridResult& result, bool verified);

// The luminaires of a scene (placed in the config, or a layout added to it) to draw.
std::vector<DrawnLuminaire> scene_luminaires(const Scene& scene);

// Every file the grid formats can write for the job's grids (for OutputSet's owned list):
// "grid.csv" and per grid isolux_<name>.svg and .png, whatever the formats say.
inline constexpr const char* kGridCsvName = "grid.csv";
std::vector<std::string> grid_csv_names(const JobConfig& job);
std::vector<std::string> isolux_names(const JobConfig& job, const std::string& extension);  // ".svg" or ".png"

// The writers, one per format; each stages its files in `set`.
void stage_grid_csv(OutputSet& set, const std::vector<GridResult>& grids);
// `architecture`: drawn on the horizontal grids' plans (cut_height_m 0: none).
void stage_isolux(OutputSet& set, const std::vector<GridResult>& grids, const std::vector<DrawnLuminaire>& luminaires,
                  const std::string& extension, const PlanArchitecture& architecture = {});

}  // namespace ilp::cli
