// The job's constraints judged on the layout found, one line each, as the goals are:
// the luminaire count against its range, the least distance between centres
// (constraints.min_distance_m), outlines that must not overlap, the distance from the
// mounting surface's edges (luminaires.wall_distance_m) and each luminaire's flux
// against the flux (dimming) range, and the power density against its cap. A layout is reported met only when every goal and
// every one of these lines is.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "optimizer/layout_search.h"
#include "optimizer/search_spec.h"

namespace ilp {

// How a constraint's value is judged against its target.
enum class ConstraintRule {
  at_least,  // value >= target
  at_most,   // value <= target
  within,    // target <= value <= target_max
};

struct ConstraintOutcome {
  std::string name;  // the job file's key: count, min_distance_m, wall_distance_m, flux_lm, outline_overlap
  std::string what;  // what the value is, e.g. "least distance between centres"
  std::string unit;  // "m", "lm", or "" for counts and shares
  ConstraintRule rule = ConstraintRule::at_least;
  double target = 0.0, target_max = 0.0;  // target_max: within only
  double value = 0.0;
  double tolerance = 0.0;  // relative to the target (absolute where the target is 0) accepted as met
  bool met = false;
};

// constraints.max_power_density_w_per_m2 with the area the power density is taken over
// (JobOutcome::floor_area_m2 and what it is the area of). No cap: max_w_per_m2 unset.
struct PowerDensityCap {
  std::optional<double> max_w_per_m2;
  double area_m2 = 0.0;
  std::string area_source;
  // The search's cap on the layout's total power: max_w_per_m2 x area_m2 (W), else infinite.
  double max_power_w() const;
};

// Relative tolerance of a constraint line: the search's own (kConstraintTolerance,
// optimizer/layout_search.cpp), so a layout the search calls feasible is met here.
inline constexpr double kConstraintLineTolerance = 1e-4;

// Is `value` within the rule, up to the tolerance?
bool constraint_met(ConstraintRule rule, double target, double target_max, double value, double tolerance);

// The constraint lines of a layout (final fluxes, after any flux correction) searched
// by `spec`, its candidates kept wall_distance_m from surface_box_m (the mounting
// surface's plan box, CandidateGrid::surface_box_m): count always; the others where they apply (min_distance_m when
// > 0, outline_overlap with two or more luminaires, wall_distance_m when > 0, flux_lm
// with a layout, max_power_density_w_per_m2 when `power` has a cap and the layout luminaires).
std::vector<ConstraintOutcome> check_constraints(const SearchSpec& spec, const Eigen::AlignedBox2d& surface_box_m,
                                                 double wall_distance_m, const std::vector<PlacedLuminaire>& layout,
                                                 const PowerDensityCap& power = {});

}  // namespace ilp
