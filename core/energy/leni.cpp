#include "core/energy/leni.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ilp {
namespace {

constexpr double kHoursPerYear = 8760.0;

// EN 15193-1 default annual operating hours by building type (docs/energy.md names
// the source of each row).
constexpr BuildingHours kBuildingTypes[] = {
    {"office", "offices", 2250.0, 250.0},
    {"education", "education buildings", 1800.0, 200.0},
    {"hospital", "hospitals", 3000.0, 2000.0},
    {"hotel", "hotels", 3000.0, 2000.0},
    {"restaurant", "restaurants", 1250.0, 1250.0},
    {"sport", "sports facilities", 2000.0, 2000.0},
    {"retail", "wholesale and retail services", 3000.0, 2000.0},
    {"manufacturing", "manufacturing factories", 4500.0, 2500.0},
};

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("LENI: " + what);
}

}  // namespace

std::span<const BuildingHours> building_types() { return kBuildingTypes; }

std::optional<BuildingHours> find_building_type(std::string_view key) {
  for (const BuildingHours& b : kBuildingTypes)
    if (b.key == key) return b;
  return std::nullopt;
}

double constant_illuminance_factor(double maintenance_factor) {
  require(maintenance_factor > 0.0 && maintenance_factor <= 1.0, "the maintenance factor must be in (0, 1]");
  return (1.0 + maintenance_factor) / 2.0;
}

LeniResult compute_leni(const LeniInputs& in) {
  require(std::isfinite(in.installed_power_w) && in.installed_power_w >= 0.0, "the installed power must be >= 0 W");
  require(std::isfinite(in.floor_area_m2) && in.floor_area_m2 > 0.0, "the floor area must be > 0 m²");
  require(std::isfinite(in.day_h) && std::isfinite(in.night_h) && in.day_h >= 0.0 && in.night_h >= 0.0 &&
              in.day_h + in.night_h <= kHoursPerYear,
          "the operating hours must be >= 0 h and together at most 8760 h");
  require(in.occupancy_factor > 0.0 && in.occupancy_factor <= 1.0, "the occupancy factor F_O must be in (0, 1]");
  require(in.daylight_factor >= 0.0 && in.daylight_factor <= 1.0, "the daylight factor F_D must be in [0, 1]");
  require(in.constant_illuminance > 0.0 && in.constant_illuminance <= 1.0,
          "the constant-illuminance factor F_C must be in (0, 1]");
  require(std::isfinite(in.parasitic_kwh_per_m2) && in.parasitic_kwh_per_m2 >= 0.0,
          "the parasitic energy must be >= 0 kWh/(m²·a)");
  LeniResult r;
  const double hours = in.day_h * in.occupancy_factor * in.daylight_factor + in.night_h * in.occupancy_factor;
  r.lighting_kwh = in.installed_power_w * in.constant_illuminance * hours / 1000.0;
  r.parasitic_kwh = in.parasitic_kwh_per_m2 * in.floor_area_m2;
  r.total_kwh = r.lighting_kwh + r.parasitic_kwh;
  r.leni_kwh_per_m2 = r.total_kwh / in.floor_area_m2;
  return r;
}

}  // namespace ilp
