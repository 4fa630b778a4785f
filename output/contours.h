// Isolines (contour lines) of a scalar field sampled on a regular lattice, by
// marching squares: the lines an isolux plan draws at its lux levels.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace ilp {

// Values at the nodes of a regular lattice: node (i, j), 0 <= i < nx, 0 <= j < ny,
// sits at origin_m + (i * spacing_m.x(), j * spacing_m.y()) and holds
// values[j * nx + i] (row-major, rows along x). NaN marks a node without a value.
struct LatticeField {
  int nx = 0, ny = 0;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d spacing_m = Eigen::Vector2d::Ones();  // both > 0
  std::vector<double> values;                           // nx * ny

  Eigen::Vector2d node_m(int i, int j) const {
    return origin_m + Eigen::Vector2d(i * spacing_m.x(), j * spacing_m.y());
  }
};

// One isoline: points in metres joined in order; a closed line repeats no point (its
// last point joins its first).
struct ContourLine {
  double level = 0.0;
  std::vector<Eigen::Vector2d> points_m;
  bool closed = false;
};

// The isolines of `field` at `level`, through the lattice's squares (four neighbouring
// nodes). A node counts as above the level when its value is >= level; a line crosses
// each square edge whose ends are on different sides, at the point found by linear
// interpolation along the edge. A square with a NaN corner has no line through it, so
// a line ends where it meets a missing node's squares. A saddle square (diagonal
// corners above, the others below) is resolved by the mean of its four corners: above
// it, the two above corners are joined through the centre. Segments are chained into
// polylines through their shared edge points; a polyline that comes back to its start
// is closed. Deterministic: lines come in the order of their first square (row-major).
// Throws std::invalid_argument when values has not nx * ny entries, nx or ny is
// negative, a spacing is not > 0, or the level is not finite.
std::vector<ContourLine> contour_lines(const LatticeField& field, double level);

}  // namespace ilp
