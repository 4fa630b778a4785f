// Dimension chains of a plan, as an installer sets out a layout: along x and along y,
// from the wall to the first row (column) of luminaire centres, between neighbouring
// rows (the layout's spacings), and from the last row to the opposite wall.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "output/plan_architecture.h"

namespace ilp {

struct DimensionChain {
  int axis = 0;                  // 0: the chain runs along x (column positions), 1: along y (rows)
  std::vector<double> stops_m;   // coordinates along the axis, ascending: [wall,] centres..., [wall]
  bool wall_first = false, wall_last = false;  // the first / last stop is a wall
  // stops_m[k + 1] - stops_m[k]: what the chain writes, in m.
  std::vector<double> lengths_m() const;
};

// The distinct coordinates of the centres along `axis` (0: x, 1: y), ascending; values
// within tolerance_m of the previous kept one (after sorting) count as the same row.
std::vector<double> distinct_positions(const std::vector<Eigen::Vector2d>& centres_m, int axis, double tolerance_m);

// The chain along `axis`: the distinct positions of the centres, and at each end the
// nearest wall crossed by a ray from the centres of the outer row outward along the
// axis (the least distance over that row's members) against `walls` (polylines, closed
// ones closed); no wall found on a side: that end has none. No centres: no stops.
DimensionChain dimension_chain(const std::vector<Eigen::Vector2d>& centres_m, int axis,
                               const std::vector<SectionLine>& walls, double tolerance_m = 0.01);

}  // namespace ilp
