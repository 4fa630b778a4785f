// grid.csv: the illuminance at every point of the calculation grids, one row a point,
// for spreadsheets and other tools. Header (units in the names):
//   grid,point,x_m,y_m,z_m,direct_initial_lux,total_initial_lux,maintenance_factor,
//   direct_maintained_lux,total_maintained_lux
// "initial" is the new installation's illuminance; "maintained" = initial x the
// maintenance factor (what EN 12464-1 targets are stated in). Coordinates in metres
// with 4 decimals, lux with 2, the factor with 4; RFC 4180 quoting for grid names.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace ilp {

struct GridCsvPoint {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  double direct_initial_lux = 0.0;  // from the luminaires straight
  double total_initial_lux = 0.0;   // direct + interreflected
};

struct GridCsvGrid {
  std::string name;                 // any text; quoted in the file when it needs it
  double maintenance_factor = 1.0;  // in (0, 1]
  std::vector<GridCsvPoint> points; // the grid's points in its own order (column "point" counts from 0)
};

// The file's text, grids in order. Throws std::invalid_argument for a non-finite
// coordinate or value or a maintenance factor outside (0, 1].
std::string grid_csv(const std::vector<GridCsvGrid>& grids);

// Writes grid_csv(grids) to `path` atomically (output/atomic_file.h).
void write_grid_csv(const std::string& path, const std::vector<GridCsvGrid>& grids);

// Reads a grid.csv back (rows of one grid name together form one grid, in order of
// first appearance; the maintained columns are checked against initial x factor to
// the file's rounding). Throws IlpError "<source>:<line>: ..." for a wrong header, a
// row of the wrong number of fields, a field that is not a number, a point index out
// of order or a maintained value that does not match.
std::vector<GridCsvGrid> parse_grid_csv(const std::string& text, const std::string& source);

}  // namespace ilp
