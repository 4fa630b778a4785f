#include "job/constraint_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ilp {
namespace {

ConstraintOutcome judged(ConstraintOutcome line) {
  line.tolerance = kConstraintLineTolerance;
  line.met = constraint_met(line.rule, line.target, line.target_max, line.value, line.tolerance);
  return line;
}

// The least distance between two centres in plan, as the search measures it.
double least_centre_distance_m(const std::vector<PlacedLuminaire>& layout) {
  double least = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < layout.size(); ++j)
    for (std::size_t k = j + 1; k < layout.size(); ++k)
      least = std::min(least, (layout[j].position_m - layout[k].position_m).head<2>().norm());
  return least;
}

// The largest overlap of two outlines, as a share of the footprint (0: none overlap).
double largest_outline_overlap(const std::vector<PlacedLuminaire>& layout, const Eigen::Vector2d& extent_m) {
  double largest = 0.0;
  for (std::size_t j = 0; j < layout.size(); ++j)
    for (std::size_t k = j + 1; k < layout.size(); ++k) {
      const Eigen::Vector2d gap = (layout[j].position_m - layout[k].position_m).head<2>().cwiseAbs();
      if (gap.x() < extent_m.x() && gap.y() < extent_m.y())
        largest = std::max(largest, std::min((extent_m.x() - gap.x()) / extent_m.x(), (extent_m.y() - gap.y()) / extent_m.y()));
    }
  return largest;
}

// The least distance from an outline to the edges of the mounting surface's plan box
// (the candidates keep the wall distance from that box). On a wall the box is a line:
// only its ends count (across it, the luminaires stand in front of the wall).
double least_wall_distance_m(const std::vector<PlacedLuminaire>& layout, const Eigen::AlignedBox2d& box,
                             const Eigen::Vector2d& half_m) {
  constexpr double kLineM = 1e-6;
  double least = std::numeric_limits<double>::infinity();
  for (const PlacedLuminaire& l : layout) {
    const Eigen::Vector2d xy = l.position_m.head<2>();
    const Eigen::Vector2d low = xy - half_m - box.min(), high = box.max() - xy - half_m;
    for (int axis = 0; axis < 2; ++axis)
      if (box.max()[axis] - box.min()[axis] > kLineM) least = std::min({least, low[axis], high[axis]});
  }
  return least;
}

}  // namespace

double PowerDensityCap::max_power_w() const {
  return max_w_per_m2 && area_m2 > 0.0 ? *max_w_per_m2 * area_m2 : std::numeric_limits<double>::infinity();
}

bool constraint_met(ConstraintRule rule, double target, double target_max, double value, double tolerance) {
  auto slack = [&](double bound) { return tolerance * (bound != 0.0 ? std::abs(bound) : 1.0); };
  switch (rule) {
    case ConstraintRule::at_least: return value >= target - slack(target);
    case ConstraintRule::at_most: return value <= target + slack(target);
    case ConstraintRule::within: return value >= target - slack(target) && value <= target_max + slack(target_max);
  }
  return false;
}

std::vector<ConstraintOutcome> check_constraints(const SearchSpec& spec, const Eigen::AlignedBox2d& surface_box_m,
                                                 double wall_distance_m, const std::vector<PlacedLuminaire>& layout,
                                                 const PowerDensityCap& power) {
  const LayoutSpec& l = spec.layout;
  const SearchLuminaire& s = spec.luminaire;
  std::vector<ConstraintOutcome> out;
  const bool array = l.family == LayoutFamily::array;
  const double count_min = array ? l.array_rows * l.array_columns : l.count_min;
  const double count_max = array ? l.array_rows * l.array_columns : l.count_max;
  out.push_back(judged({.name = "count", .what = "luminaires", .unit = "", .rule = ConstraintRule::within,
                        .target = count_min, .target_max = count_max, .value = static_cast<double>(layout.size())}));
  if (layout.empty()) return out;
  if (l.min_distance_m > 0.0 && layout.size() >= 2)
    out.push_back(judged({.name = "min_distance_m", .what = "least distance between centres", .unit = "m",
                          .rule = ConstraintRule::at_least, .target = l.min_distance_m,
                          .value = least_centre_distance_m(layout)}));
  const Eigen::Vector2d half_m = s.type.half_footprint_m(s.rotation_deg, s.tilt_deg);
  if (layout.size() >= 2)
    out.push_back(judged({.name = "outline_overlap", .what = "largest overlap of two outlines (share of one)",
                          .unit = "", .rule = ConstraintRule::at_most, .target = 0.0,
                          .value = largest_outline_overlap(layout, 2.0 * half_m)}));
  if (wall_distance_m > 0.0)
    out.push_back(judged({.name = "wall_distance_m", .what = "least distance from an outline to the mounting surface's edges",
                          .unit = "m", .rule = ConstraintRule::at_least, .target = wall_distance_m,
                          .value = least_wall_distance_m(layout, surface_box_m, half_m)}));
  double low = std::numeric_limits<double>::infinity(), high = 0.0;
  for (const PlacedLuminaire& p : layout) {
    low = std::min(low, p.flux_lm);
    high = std::max(high, p.flux_lm);
  }
  if (s.uniform_output || low == high) {
    out.push_back(judged({.name = "flux_lm", .what = "flux per luminaire", .unit = "lm", .rule = ConstraintRule::within,
                          .target = s.flux_min_lm, .target_max = s.flux_max_lm, .value = high}));
  } else {
    out.push_back(judged({.name = "flux_lm", .what = "lowest flux of a luminaire", .unit = "lm",
                          .rule = ConstraintRule::at_least, .target = s.flux_min_lm, .value = low}));
    out.push_back(judged({.name = "flux_lm", .what = "highest flux of a luminaire", .unit = "lm",
                          .rule = ConstraintRule::at_most, .target = s.flux_max_lm, .value = high}));
  }
  if (power.max_w_per_m2 && power.area_m2 > 0.0) {
    double power_w = 0.0;
    for (const PlacedLuminaire& p : layout) power_w += p.power_w;
    out.push_back(judged({.name = "max_power_density_w_per_m2", .what = "power density over the " + power.area_source,
                          .unit = "W/m²", .rule = ConstraintRule::at_most, .target = *power.max_w_per_m2,
                          .value = power_w / power.area_m2}));
  }
  return out;
}

}  // namespace ilp
