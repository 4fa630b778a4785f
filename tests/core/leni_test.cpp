// LENI by EN 15193-1's simplified method (core/energy/leni.h) against values worked by
// hand, the building types' default hours, and the inputs it refuses.
#include <gtest/gtest.h>

#include <stdexcept>

#include "core/energy/leni.h"

namespace {

// Worked by hand: 1000 W over 50 m² of office (t_D 2250 h, t_N 250 h) with occupancy
// control F_O 0.9, daylight control F_D 0.8, constant-illuminance control at MF 0.8
// (F_C = (1 + 0.8) / 2 = 0.9):
//   W_L = 1000 W x 0.9 x (2250 h x 0.9 x 0.8 + 250 h x 0.9) / 1000 = 0.9 x 1845 = 1660.5 kWh
//   W_P = 6 kWh/m² x 50 m² = 300 kWh;  W = 1960.5 kWh;  LENI = 1960.5 / 50 = 39.21 kWh/(m²·a)
TEST(Leni, MatchesAHandWorkedOfficeWithControls) {
  ilp::LeniInputs in;
  in.installed_power_w = 1000.0;
  in.floor_area_m2 = 50.0;
  in.day_h = 2250.0;
  in.night_h = 250.0;
  in.occupancy_factor = 0.9;
  in.daylight_factor = 0.8;
  in.constant_illuminance = ilp::constant_illuminance_factor(0.8);
  EXPECT_DOUBLE_EQ(in.constant_illuminance, 0.9);
  const ilp::LeniResult r = ilp::compute_leni(in);
  EXPECT_NEAR(r.lighting_kwh, 1660.5, 1e-9);
  EXPECT_NEAR(r.parasitic_kwh, 300.0, 1e-9);
  EXPECT_NEAR(r.total_kwh, 1960.5, 1e-9);
  EXPECT_NEAR(r.leni_kwh_per_m2, 39.21, 1e-9);
}

// Without controls every factor is 1: W_L = P (t_D + t_N) / 1000. 212.5 W over 35 m² of
// office: 212.5 x 2500 / 1000 = 531.25 kWh; + 0 parasitic: LENI = 15.178571... kWh/(m²·a).
TEST(Leni, WithoutControlsIsPowerTimesHours) {
  ilp::LeniInputs in;
  in.installed_power_w = 212.5;
  in.floor_area_m2 = 35.0;
  in.day_h = 2250.0;
  in.night_h = 250.0;
  in.parasitic_kwh_per_m2 = 0.0;
  const ilp::LeniResult r = ilp::compute_leni(in);
  EXPECT_NEAR(r.lighting_kwh, 531.25, 1e-9);
  EXPECT_NEAR(r.leni_kwh_per_m2, 531.25 / 35.0, 1e-12);
}

// Daylight control acts on the daytime hours only: F_D = 0 leaves the night's energy.
TEST(Leni, DaylightFactorActsOnDaytimeHoursOnly) {
  ilp::LeniInputs in;
  in.installed_power_w = 100.0;
  in.floor_area_m2 = 10.0;
  in.day_h = 3000.0;
  in.night_h = 2000.0;
  in.daylight_factor = 0.0;
  in.parasitic_kwh_per_m2 = 0.0;
  EXPECT_NEAR(ilp::compute_leni(in).lighting_kwh, 200.0, 1e-9);  // 100 W x 2000 h
}

TEST(Leni, BuildingTypesCarryTheStandardsDefaultHours) {
  const auto office = ilp::find_building_type("office");
  ASSERT_TRUE(office);
  EXPECT_EQ(office->day_h, 2250.0);
  EXPECT_EQ(office->night_h, 250.0);
  const auto education = ilp::find_building_type("education");
  ASSERT_TRUE(education);
  EXPECT_EQ(education->day_h, 1800.0);
  EXPECT_EQ(education->night_h, 200.0);
  EXPECT_FALSE(ilp::find_building_type("warehouse"));
  for (const ilp::BuildingHours& b : ilp::building_types()) {
    EXPECT_GT(b.day_h, 0.0) << b.key;
    EXPECT_LE(b.day_h + b.night_h, 8760.0) << b.key;
  }
  EXPECT_EQ(ilp::building_types().size(), 8u);
}

TEST(Leni, RefusesInputsOutsideTheirRange) {
  const ilp::LeniInputs good{100.0, 10.0, 2250.0, 250.0, 1.0, 1.0, 1.0, 6.0};
  EXPECT_NO_THROW((void)ilp::compute_leni(good));
  auto refused = [&](auto change) {
    ilp::LeniInputs in = good;
    change(in);
    EXPECT_THROW((void)ilp::compute_leni(in), std::invalid_argument);
  };
  refused([](ilp::LeniInputs& in) { in.floor_area_m2 = 0.0; });
  refused([](ilp::LeniInputs& in) { in.installed_power_w = -1.0; });
  refused([](ilp::LeniInputs& in) { in.day_h = 8000.0; in.night_h = 1000.0; });
  refused([](ilp::LeniInputs& in) { in.occupancy_factor = 0.0; });
  refused([](ilp::LeniInputs& in) { in.daylight_factor = 1.5; });
  refused([](ilp::LeniInputs& in) { in.constant_illuminance = 0.0; });
  refused([](ilp::LeniInputs& in) { in.parasitic_kwh_per_m2 = -0.1; });
  EXPECT_THROW((void)ilp::constant_illuminance_factor(0.0), std::invalid_argument);
  EXPECT_THROW((void)ilp::constant_illuminance_factor(1.2), std::invalid_argument);
}

}  // namespace
