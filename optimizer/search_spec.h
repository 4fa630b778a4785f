// What a layout search is asked (optimizer/layout_search.h): the luminaire it places,
// the layouts it may try, the goals, the objective and NLopt's budgets. The job
// (job/plan.h) fills it from the job file, once per product variant.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
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
  std::string product;            // the product's name; empty for the plain panel
  bool uniform_output = false;    // every luminaire of a layout at one output (a product), else each its own
  double flux_min_lm = 0.0, flux_max_lm = 0.0;
  double efficacy_lm_per_w = 100.0;  // electric power = flux / efficacy
};

enum class LayoutFamily {
  free,   // each luminaire anywhere on the mounting surface, each its own flux
  array,  // a regular rows x columns array, one flux for all
};

// The layouts searched: how many luminaires and how they may stand.
struct LayoutSpec {
  LayoutFamily family = LayoutFamily::free;
  int count_min = 1, count_max = 1;  // free: the counts searched (already capped by any maximum)
  // array: rows x columns; spacing and offset (the first luminaire's centre, from the
  // mounting surface's lower x, y corner) fixed when given, else searched.
  int array_rows = 0, array_columns = 0;
  std::optional<Eigen::Vector2d> array_spacing_m, array_offset_m;
  double ceiling_module_m = 0.0;     // > 0: the layout found snaps to the module's cell centres
  double min_distance_m = 0.0;       // between luminaire centres
  std::string mounting_surface;      // for messages
  FileLoc loc;                       // of the array settings, for a refusal
};

// NLopt's algorithms and budgets (nlopt::algorithm names, or "none" to skip a stage).
struct SearchOptions {
  std::string global_algorithm = "GN_CRS2_LM";
  std::string local_algorithm = "LN_SBPLX";
  int max_evaluations = 20000;     // global stage, per luminaire count tried
  int local_max_evaluations = 4000;
  double max_seconds = 60.0;       // wall-clock budget of the whole search
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
