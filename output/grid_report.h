// From a calculation grid and its light to what the grid writers take: the rows of
// grid.csv (output/grid_csv.h) and the isolux plan's view (output/isolux_plan.h), with
// the room outline under the grid and the luminaires at their real size. `ilp run` and
// `ilp solve` call these; the writers stay free of scene types.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "core/grid/calc_grid.h"
#include "core/light/luminaire.h"
#include "output/grid_csv.h"
#include "output/isolux_plan.h"

namespace ilp {

// One grid's illuminance at its kept points (CalcGrid::points order), initial values.
struct GridLight {
  Eigen::VectorXd direct_initial_lux, total_initial_lux;
  double maintenance_factor = 1.0;  // maintained = initial x this, in (0, 1]
  // The maintained Em target of the goal on this grid (the plan's colour scale); NaN: none.
  double target_lux = std::numeric_limits<double>::quiet_NaN();
  std::string basis;                // how the values were found, e.g. "verified, exact"
};

// A luminaire to draw: the type gives its outline, the placement where and how turned.
struct DrawnLuminaire {
  std::string id, product;
  LuminaireType type;
  LuminairePlacement at;
};

// The plan's coordinates of a point of the grid's plane: x, y for a horizontal grid;
// for a vertical one the distance along the segment from from_m and the height z.
Eigen::Vector2d grid_plan_position_m(const CalcGrid& grid, const Eigen::Vector3d& point_m);

// The outline the grid lies over, in plan coordinates: a horizontal grid's polygon, or
// the boundary of its floor surface's triangles facing up (traced on a raster of about
// kOutlineRasterCells across and simplified to half a raster cell, so T-junctions and
// cracks between the floor's triangles leave no lines inside); a vertical grid's plane.
constexpr int kOutlineRasterCells = 400;
std::vector<std::vector<Eigen::Vector2d>> grid_room_outline_m(const CalcGrid& grid);

// The luminaires as the plan draws them: seen from above over a horizontal grid (real
// length, width, rotation, discs round); projected on a vertical grid's plane (the
// outline's extent along the plane and in height, at least 2 cm thick).
std::vector<IsoluxLuminaire> isolux_luminaires(const CalcGrid& grid, const std::vector<DrawnLuminaire>& luminaires);

// The isolux plan's view: the lattice of cells, maintained values (NaN where no point
// was kept), the target, the outline and the luminaires. Throws std::invalid_argument
// when the light has not one value per point or the factor is outside (0, 1].
IsoluxGridView isolux_grid_view(const CalcGrid& grid, const GridLight& light,
                                const std::vector<DrawnLuminaire>& luminaires);

// grid.csv's rows of one grid. Throws as isolux_grid_view.
GridCsvGrid grid_csv_grid(const CalcGrid& grid, const GridLight& light);

// File stems "isolux_<name>" for the grids in order: characters other than letters,
// digits, '-', '_' and '.' become '_', and a stem already taken gets "_2", "_3", ...
std::vector<std::string> isolux_file_stems(const std::vector<std::string>& grid_names);

}  // namespace ilp
