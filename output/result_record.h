// The result of an inverse-lighting job as it is saved (result.json) and printed:
// plain data, so `ilp print` can show a saved result without the scene.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace ilp {

struct LuminaireRecord {
  std::string id;
  double x_m = 0.0, y_m = 0.0, z_m = 0.0;  // centre of the emitting face
  double flux_lm = 0.0;
  double power_w = 0.0;
  std::string product;      // the product's name ("" for the plain panel)
  double rotation_deg = 0.0;
  std::optional<double> above_floor_m = std::nullopt;  // the emitting face's height above the finished floor, when known
  double tilt_deg = 0.0;    // aim: the nadir swung toward C0 by this, [0, 90] (core/light/luminaire.h)
  std::string group = {};   // its luminaire group (luminaires.groups); "" for a single group
};

// One line of the bill of materials: a product and how many of it the layout uses.
struct BillLine {
  std::string product;
  std::string source;       // the photometric file, or "square_lambertian"
  int count = 0;
  double rated_flux_lm = 0.0;
  double unit_power_w = 0.0;   // at full output
  double output_fraction = 1.0;  // the output they are set to (dimming), of the rated
  double total_power_w = 0.0;    // as set
  std::string group = {};        // the luminaire group (luminaires.groups); "" for a single group
};

// One line of the verdict: a goal or a constraint, its target, its value and whether it
// is met. Goals carry a predicted value (through the operator) and a verified one;
// constraints (count, min_distance_m, ...) are facts of the layout: one value, kept in
// `predicted`. A layout is met only when every line is.
struct VerdictLine {
  std::string name;         // goal: its name; constraint: the job's key (min_distance_m, count, ...)
  std::vector<std::string> surfaces;
  std::string metric;       // goal: average, minimum, maximum, uniformity; constraint: what the value is
  std::string unit;         // "lx", "m", "lm", or "" for ratios and counts
  double target = 0.0;      // maintained (as the job states it); the lower end of a range
  double predicted = 0.0;   // maintained: initial x maintenance factor (lux metrics); a constraint's value
  std::optional<double> verified;
  bool met = false;         // judged on the verified value when there is one
  bool fails_only_on_verification = false;
  double tolerance = 0.0;   // relative
  std::string grid;         // the calculation grid, or "" for surfaces
  std::string kind = "goal";  // "goal" or "constraint"
  // How the value meets the target: ">=", "<=", "in" ([target, target_max]) or "="
  // (a target to hit within the tolerance). Empty (files before it): by the metric.
  std::string rule = {};
  double target_max = 0.0;  // rule "in": the upper end
  // The verification's relative standard error of the verified value, when estimated,
  // and the margin (relative) the flux correction kept above the target (0: none).
  std::optional<double> relative_error = std::nullopt;
  double margin = 0.0;

  double value() const { return verified ? *verified : predicted; }
};
using GoalRecord = VerdictLine;

// A line's value and target as the printout shows them: "508.6 lx", ">= 500.0 lx",
// "8 .. 12" (lux and lumens with one decimal, metres and ratios with three, counts whole).
std::string verdict_value_text(const VerdictLine& line, double value);
std::string verdict_target_text(const VerdictLine& line);

// "min_distance_m 1.965 m < 2.000 m (by 0.035 m)": a line that is not met, and why.
std::string failing_line_text(const VerdictLine& line);
struct ResultRecord;
// Every goal and constraint line of `record` that is not met, as failing_line_text
// gives them, joined by "; " ("" when every line is met).
std::string failing_lines_text(const ResultRecord& record);

// Em, Emin, Emax (lx) and U0 over one set of values.
struct GridValues {
  double average_lux = 0.0, min_lux = 0.0, max_lux = 0.0, uniformity = 0.0;
};

// One calculation grid's values: initial (new luminaires) and maintained (x MF),
// verified where the job was verified, else predicted.
struct GridRecord {
  std::string name;
  int points = 0;
  double area_m2 = 0.0;
  double spacing_m = 0.0;
  int inside_solid = 0;     // points dropped inside solid objects
  bool verified = false;
  GridValues initial, maintained;
};

// One surface of the room as the report lists it: its area, its reflectance (the
// luminance-weighted mean over its patches, area-weighted) and its height above the floor.
struct SurfaceRecord {
  std::string name;
  double area_m2 = 0.0;
  double reflectance = 0.0;         // in [0, 1)
  double bottom_m = 0.0, top_m = 0.0;  // lowest and highest point above the floor (or the scene's z without a floor)
};

// The room the job lit: the extent of the model's surfaces (luminaires left out), the
// floor's height in the scene and every surface.
struct RoomRecord {
  std::string mesh;                  // the model's file name (never its folder)
  double length_x_m = 0.0, width_y_m = 0.0, height_z_m = 0.0;
  std::optional<double> floor_z_m = std::nullopt;  // the finished floor, when known
  std::vector<SurfaceRecord> surfaces;
};

// Annual lighting energy and LENI by EN 15193-1's simplified method (core/energy/leni.h)
// for the layout's power over floor_area_m2.
struct EnergyRecord {
  std::string building_type;         // the row whose hours were taken (energy.building_type)
  bool assumed = false;              // the job has no energy section: an office without controls
  double hours_day_h = 0.0, hours_night_h = 0.0;
  double occupancy_factor = 1.0, daylight_factor = 1.0, constant_illuminance_factor = 1.0;
  double parasitic_kwh_per_m2 = 0.0;
  double installed_power_w = 0.0, area_m2 = 0.0;
  double lighting_kwh = 0.0, parasitic_kwh = 0.0, total_kwh = 0.0;  // per year
  double leni_kwh_per_m2 = 0.0;      // kWh/(m²·a)
};

struct AttemptRecord {
  int luminaires = 0;
  int evaluations = 0;
  double seconds = 0.0;
  bool feasible = false;
  double power_w = 0.0;
  std::string global_stop, local_stop;
  std::string arrangement = {};  // a regular layout's ("3 x 4 field"); empty for free and array layouts
};

// One product variant (product x rotation) the run tried: its summary line and, when it
// was searched, its layout's power and its own goal and constraint lines, so a rejected
// alternative can be explained.
struct VariantRecord {
  std::string product;
  double rotation_deg = 0.0;
  std::string summary;          // "PRODUCT at R deg: 6 luminaires, 240.0 W, every goal met (...)"
  bool searched = false;        // a layout was searched and verified
  bool chosen = false;          // the layout reported
  int luminaires = 0;
  double power_w = 0.0;
  bool all_met = false;
  std::vector<VerdictLine> goals, constraints;
};

// A scenario of the job judged on the layout (job/scenario.h): another lighting state of
// the same luminaires, its goal lines as every goal's (maintained values).
struct ScenarioRecord {
  std::string name;
  std::string light;     // "total" (every reflection) or "direct" (straight from the luminaires)
  int lit = 0;           // luminaires of the layout lit (fraction above 0)
  int luminaires = 0;    // of the layout
  double power_w = 0.0;  // at those fractions
  bool all_met = false;
  std::vector<VerdictLine> goals;
};

struct ResultRecord {
  std::string program_version;
  std::string config;
  std::string objective;                    // min_power or closest_to_target
  std::vector<LuminaireRecord> luminaires;
  std::string layout_family;                // free, array, field, rows or bays
  std::string arrangement;                  // a regular layout's ("3 x 4 field"); empty otherwise
  double spacing_x_m = 0.0, spacing_y_m = 0.0;  // a regular layout's spacing between neighbours (0 where one)
  std::vector<GoalRecord> goals;
  double power_w = 0.0;
  double mounting_area_m2 = 0.0;
  double power_density_w_per_m2 = 0.0;     // power_w / floor_area_m2
  double floor_area_m2 = 0.0;
  std::string floor_area_source;
  double power_density_w_per_m2_per_100_lx = 0.0;
  double maintenance_factor = 1.0;
  std::vector<GridRecord> grids;
  double fixed_flux_lm = 0.0;
  bool feasible = false;                    // predicted
  bool all_met = false;
  std::string no_layout;                    // why no layout was found (every count screened out); empty: one was
  double flux_correction = 1.0;
  bool flux_correction_limited = false;     // the flux range allowed less than the goals wanted
  std::string verification;                 // exact, sample or none
  int verification_rays_per_patch = 0;
  // exact: the other patches' rows (rays per row) where the progressive refinement
  // stopped and started, and the goals' largest relative change at its last step.
  int verification_indirect_rays_per_patch = 0;
  int verification_first_indirect_rays = 0;
  double verification_refinement_change = 0.0;
  // exact: the grid points deciding a minimum, uniformity or maximum goal, gathered again
  // with decisive_rays rays, and the patches they gather most from, solved with precise
  // direct light and rows of dominant_rays rays (0: none).
  int verification_decisive_points = 0;
  int verification_decisive_rays = 0;
  int verification_dominant_patches = 0;
  int verification_dominant_rays = 0;
  int sample_size = 0;
  int population = 0;                       // reflecting patches
  int patches = 0;
  int candidates = 0;
  unsigned long long seed = 0;              // rays
  unsigned long long optimizer_seed = 0;
  int evaluations = 0;
  int searches = 1;                         // search rounds (verification-driven re-searches + 1)
  // Regular layouts: arrangements re-judged with the luminaires' own direct light at the
  // grid points, and the first goal such a check found missed (empty: none).
  int direct_checks = 0;
  std::string direct_check_note;
  std::vector<std::string> calibration;     // what each extra round changed
  bool time_limited = false;                // the wall-clock budget ended a search stage
  double search_max_seconds = 0.0;          // optimizer.max_seconds; 0: none (the layout is the machine's own when set)
  // Wall-clock times: in timings.json, not result.json, which is the same for a job and
  // seed on any machine under any load (the attempts' seconds go there too).
  std::vector<std::pair<std::string, double>> timings_s;  // phase, seconds, in order
  std::vector<std::pair<std::string, double>> verification_parts_s;  // exact: where its seconds went, in order
  std::vector<AttemptRecord> attempts;
  std::vector<BillLine> bill_of_materials;
  std::vector<VerdictLine> constraints;     // every constraint the job states, judged on the layout
  std::vector<ScenarioRecord> scenarios;    // the job's other lighting states (result.json's key only when any)
  double margin_floor = 0.0;                // verification.margin: the least margin kept above a scaled goal
  std::vector<VariantRecord> variants;      // each product and rotation tried, with its outcome and lines
  std::vector<std::string> files;           // the files the run writes into its output folder (names), result.json included
  std::optional<RoomRecord> room = std::nullopt;      // absent in results written before the report
  std::optional<EnergyRecord> energy = std::nullopt;  // absent without a layout
};

// result.json holds everything but wall-clock times, so that the same job and seed
// give the same bytes on any machine; timings.json holds the times (timings_s and each
// attempt's seconds). read_result_json reads timings.json beside the result file when
// there is one (a result.json of an older version may hold its times itself).
// Throws std::runtime_error naming the file on unreadable or malformed input.
void write_result_json(const std::string& path, const ResultRecord& result);
void write_timings_json(const std::string& path, const ResultRecord& result);
ResultRecord read_result_json(const std::string& path);
// The record as bytes and back (result.json's document with timings.json's beside it,
// doubles in their shortest round-trip form): what a rank sends rank 0 for each room
// (docs/cluster.md). Throws std::runtime_error on malformed bytes.
std::string result_record_bytes(const ResultRecord& result);
ResultRecord result_record_from_bytes(const std::string& bytes);

// The report `ilp run` and `ilp print` show: layout table, goals (target, predicted,
// verified), power, timings.
void print_result(std::ostream& os, const ResultRecord& result);

// The per-grid table of print_result: points, Em, Emin, Emax, U0 initial and maintained
// Em, Emin, Emax (nothing for no grids). `basis` ends each line, e.g. "verified"; empty:
// each record's own (verified or predicted).
void print_grid_table(std::ostream& os, const std::vector<GridRecord>& grids, const std::string& basis = "");

}  // namespace ilp
