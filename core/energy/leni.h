// Annual lighting energy and LENI (lighting energy numeric indicator) by the simplified
// method of EN 15193-1: the installed power times the operating hours by day and by
// night, weighted by the occupancy, daylight and constant-illuminance factors, plus the
// parasitic energy of emergency lighting and controls, per m² of floor. Depends on
// nothing but the standard library; docs/energy.md gives the formula and the table.
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace ilp {

// A building type's default annual operating hours (EN 15193-1, docs/energy.md).
struct BuildingHours {
  std::string_view key;      // office, education, ... (the job's energy.building_type)
  std::string_view standard; // the row as the standard names it
  double day_h = 0.0;        // t_D: hours of use while there is daylight
  double night_h = 0.0;      // t_N: hours of use without daylight
};

// The rows, offices first.
std::span<const BuildingHours> building_types();
// The row of `key`, or nothing.
std::optional<BuildingHours> find_building_type(std::string_view key);

// The default parasitic energy of the quick method, kWh/(m²·a): 1 for emergency
// lighting charging + 5 for the controls' standby.
inline constexpr double kDefaultParasitic_kwh_per_m2 = 6.0;

// F_C of constant-illuminance control (the luminaires dimmed to the maintained level
// while new): (1 + MF) / 2. Throws std::invalid_argument unless MF is in (0, 1].
double constant_illuminance_factor(double maintenance_factor);

struct LeniInputs {
  double installed_power_w = 0.0;          // P_n: every luminaire as set, >= 0
  double floor_area_m2 = 0.0;              // A, > 0
  double day_h = 0.0, night_h = 0.0;       // t_D, t_N, each >= 0, t_D + t_N <= 8760
  double occupancy_factor = 1.0;           // F_O in (0, 1]: 1 without occupancy control
  double daylight_factor = 1.0;            // F_D in [0, 1]: 1 without daylight control
  double constant_illuminance = 1.0;       // F_C in (0, 1]: 1 without constant-illuminance control
  double parasitic_kwh_per_m2 = kDefaultParasitic_kwh_per_m2;  // W_P / A, >= 0
};

struct LeniResult {
  double lighting_kwh = 0.0;    // W_L = P_n F_C [t_D F_O F_D + t_N F_O] / 1000, per year
  double parasitic_kwh = 0.0;   // W_P = parasitic_kwh_per_m2 x A, per year
  double total_kwh = 0.0;       // W = W_L + W_P
  double leni_kwh_per_m2 = 0.0; // W / A, kWh/(m²·a)
};

// Throws std::invalid_argument naming the input that breaks its rule.
LeniResult compute_leni(const LeniInputs& in);

}  // namespace ilp
