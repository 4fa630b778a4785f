// Regular layouts, as designers draw them: a field of rows x columns, rows of
// luminaires along their length, n luminaires per bay of an architectural grid. Each
// arrangement is a fixed list of centres; the search (optimizer/layout_search.h) only
// chooses between arrangements and sets their one output, so a member never moves.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "optimizer/search_spec.h"

namespace ilp {

// What an arrangement is laid in.
struct ArrangementFrame {
  Eigen::AlignedBox2d zone_m;                                 // centred on this (x, y)
  Eigen::Vector2d luminaire_extent_m = Eigen::Vector2d::Zero(); // the outline's extent along x and y as placed
  // A ceiling module: spacings become whole modules and centres module cell centres
  // (module_origin_m is one of them). 0: none.
  double module_m = 0.0;
  Eigen::Vector2d module_origin_m = Eigen::Vector2d::Zero();
};

struct Arrangement {
  std::string label;                                       // "3 x 4 field", "2 rows of 5", "2 per bay, 6 bays"
  std::vector<Eigen::Vector2d> xy_m;                       // centres
  Eigen::Vector2d spacing_m = Eigen::Vector2d::Zero();     // between neighbours along x and y (0 where one)
};

// Every arrangement of a field, rows or bays layout whose count lies in
// [count_min, count_max], fewest luminaires first. Throws std::invalid_argument for
// any other family or an empty zone, std::length_error for ranges that make more than
// 100,000 arrangements or 2e7 luminaires in all.
std::vector<Arrangement> regular_arrangements(const LayoutSpec& layout, const ArrangementFrame& frame);

// n positions along [lo, hi] (n >= 1), evenly spaced with the outer ones edge_ratio x
// spacing from the ends: spacing = (hi - lo) / (n - 1 + 2 edge_ratio).
std::vector<double> even_positions(double lo, double hi, int n, double edge_ratio);

}  // namespace ilp
