#include "apps/grid_outputs.h"

#include <limits>

#include "optimizer/goal_metrics.h"
#include "job/config.h"

namespace ilp::cli {
namespace {

std::vector<std::string> grid_names(const JobConfig& job) {
  std::vector<std::string> names;
  for (const CalcGridSetting& g : job.grids) names.push_back(g.name);
  return names;
}

GridValues values_of(const AreaStatistics& s, double factor) {
  return {s.average_lux * factor, s.min_lux * factor, s.max_lux * factor, s.uniformity};
}

// The file stem of each grid result, as isolux_names gives it for the job's grids.
std::vector<std::string> stems_of(const std::vector<GridResult>& grids) {
  std::vector<std::string> names;
  for (const GridResult& g : grids) names.push_back(g.grid->name);
  return isolux_file_stems(names);
}

}  // namespace

double grid_target_lux(const JobConfig& job, const std::string& name) {
  for (const GoalSetting& g : job.goals)
    if (g.grid == name && g.metric == GoalMetric::average) return g.target;
  return std::numeric_limits<double>::quiet_NaN();
}

GridRecord grid_record(const GridResult& r, bool verified) {
  const CalcGrid& grid = *r.grid;
  GoalArea area;
  area.name = grid.name;
  const auto n = static_cast<Eigen::Index>(grid.points.size());
  for (Eigen::Index q = 0; q < n; ++q) area.rows.push_back(q);
  area.area_weights = Eigen::VectorXd::Constant(n, 1.0 / static_cast<double>(n));
  const AreaStatistics s = area_statistics(area, r.light.total_initial_lux);
  return {grid.name, static_cast<int>(n), grid.area_m2, grid.spacing_m, static_cast<int>(grid.inside_solid), verified,
          values_of(s, 1.0), values_of(s, r.light.maintenance_factor)};
}

std::vector<DrawnLuminaire> scene_luminaires(const Scene& scene) {
  std::vector<DrawnLuminaire> out;
  for (const SceneLuminaire& l : scene.luminaires)
    out.push_back({scene.surfaces[static_cast<std::size_t>(l.surface)].name, l.type.name, l.type, l.placement});
  return out;
}

std::vector<std::string> grid_csv_names(const JobConfig& job) {
  return job.grids.empty() ? std::vector<std::string>{} : std::vector<std::string>{kGridCsvName};
}

std::vector<std::string> isolux_names(const JobConfig& job, const std::string& extension) {
  std::vector<std::string> out;
  for (const std::string& stem : isolux_file_stems(grid_names(job))) out.push_back(stem + extension);
  return out;
}

void stage_grid_csv(OutputSet& set, const std::vector<GridResult>& grids) {
  if (grids.empty()) return;
  std::vector<GridCsvGrid> rows;
  for (const GridResult& g : grids) rows.push_back(grid_csv_grid(*g.grid, g.light));
  write_grid_csv(set.staging_path(kGridCsvName), rows);
  set.staged(kGridCsvName);
}

void stage_isolux(OutputSet& set, const std::vector<GridResult>& grids, const std::vector<DrawnLuminaire>& luminaires,
                  const std::string& extension, const PlanArchitecture& architecture) {
  const std::vector<std::string> stems = stems_of(grids);
  for (std::size_t g = 0; g < grids.size(); ++g) {
    const std::string name = stems[g] + extension;
    IsoluxGridView view = isolux_grid_view(*grids[g].grid, grids[g].light, luminaires);
    if (grids[g].grid->kind == GridKind::horizontal) view.architecture = architecture;
    const std::string path = set.staging_path(name);
    write_isolux_plan(extension == ".svg" ? path : "", extension == ".png" ? path : "", view);
    set.staged(name);
  }
}

}  // namespace ilp::cli
