// What a layout search is asked (optimizer/layout_search.h): the luminaire it places,
// the layouts it may try, the goals, the objective and NLopt's budgets. The job
// (job/plan.h) fills it from the job file, once per product variant.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/base/error.h"
#include "core/light/luminaire.h"
#include "optimizer/goal_spec.h"

namespace ilp {

// What the search places: one luminaire type at one rotation (a product's, or the
// plain panel's), its output range and efficacy.
struct SearchLuminaire {
  LuminaireType type = LuminaireType::square_lambertian(0.6);
  double rotation_deg = 0.0;
  double tilt_deg = 0.0;          // aim, [0, 90]: the nadir swings toward C0 (core/light/luminaire.h)
  std::string product;            // the product's name; empty for the plain panel
  bool uniform_output = true;     // every luminaire of a layout at one output (dimmed together), else each its own
  double flux_min_lm = 0.0, flux_max_lm = 0.0;
  double efficacy_lm_per_w = 100.0;  // electric power = flux / efficacy
};

enum class LayoutFamily {
  free,   // each luminaire anywhere in the zone (positions searched by NLopt)
  array,  // a rows x columns array, its spacing and offset fixed or searched
  field,  // regular fields: rows x columns over ranges, equal spacing per axis, centred on the zone
  rows,   // rows of luminaires along their length, evenly spaced or end to end, rows spaced evenly across
  bays,   // n luminaires per bay of an architectural grid (module and origin)
};

// The family's key in the job file: free, array, field, rows, bays.
inline std::string_view layout_family_key(LayoutFamily f) {
  constexpr std::string_view keys[] = {"free", "array", "field", "rows", "bays"};
  return keys[static_cast<int>(f)];
}

// A whole-number range [min, max] of a layout parameter.
struct CountRange {
  int min = 1, max = 1;
};

// A regular layout's parameters (field, rows, bays), as the job gives them.
struct RegularLayoutParams {
  // field: rows (along y) and columns (along x); rows: `rows` rows of `columns`
  // luminaires each, along the luminaires' length. Spacing s per axis puts the
  // outer luminaires edge_ratio x s from the zone's edge (0.5: half a spacing); with
  // a range, every ratio from the largest down in steps of 0.05, per axis, is tried.
  CountRange rows{1, 12}, columns{1, 12};
  double edge_ratio_min = 0.5, edge_ratio_max = 0.5;
  bool continuous = false;          // rows: luminaires end to end along each row
  double max_spacing_ratio = 2.0;   // field: the larger spacing at most this times the smaller
  // bays: the bays' module (x, y) and a corner of one bay; per_bay luminaires in each
  // bay whose centre lies in the zone.
  Eigen::Vector2d bay_module_m = Eigen::Vector2d::Zero(), bay_origin_m = Eigen::Vector2d::Zero();
  CountRange per_bay;
  // A member of a field, row or bay must have a legal mounting point within this of
  // its position, else that arrangement is infeasible (it never moves).
  double position_tolerance_m = 0.05;
};

// The layouts searched: how many luminaires and how they may stand.
struct LayoutSpec {
  LayoutFamily family = LayoutFamily::free;
  int count_min = 1, count_max = 1;  // the counts searched (already capped by any maximum)
  // array: rows x columns; spacing and offset (the first luminaire's centre, from the
  // mounting surface's lower x, y corner) fixed when given, else searched.
  int array_rows = 0, array_columns = 0;
  std::optional<Eigen::Vector2d> array_spacing_m, array_offset_m;
  RegularLayoutParams regular;       // field, rows, bays
  double ceiling_module_m = 0.0;     // > 0: the layout found snaps to the module's cell centres
  double min_distance_m = 0.0;       // between luminaire centres
  // The layout's electric power at most this (W): a power-density cap times its area.
  // A layout above it is infeasible (its excess, relative, is a penalty); under
  // closest_to_target the flux scale is held to it.
  double max_power_w = std::numeric_limits<double>::infinity();
  std::string mounting_surface;      // for messages
  FileLoc loc;                       // of the layout settings, for a refusal
};

// NLopt's algorithms and budgets (nlopt::algorithm names, or "none" to skip a stage).
struct SearchOptions {
  std::string global_algorithm = "GN_CRS2_LM";
  std::string local_algorithm = "LN_SBPLX";
  int max_evaluations = 20000;     // global stage, per luminaire count tried
  int local_max_evaluations = 4000;
  // Wall-clock budget of the whole search; 0: none (the default), so that the evaluation
  // budgets alone end each stage and the layout is the same on any machine. A budget
  // makes the layout depend on the machine's speed and load (the report says so).
  double max_seconds = 0.0;
  std::uint64_t seed = 1;          // NLopt's random seed: same seed, same layout
  int threads = 0;                 // for an evaluation's rows; 0: every core
};

// Everything a search needs besides the lighting model.
struct SearchSpec {
  SearchLuminaire luminaire;
  LayoutSpec layout;
  std::vector<GoalSpec> goals;  // each names a GoalArea of the model
  Objective objective = Objective::min_power;
  SearchOptions options;
};

}  // namespace ilp
