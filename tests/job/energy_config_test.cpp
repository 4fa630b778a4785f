// The job's energy section (docs/config.md): read with its defaults from the building
// type, every bad value an error naming file, line and key; and the record's LENI from
// it (job/result_mapping.h).
#include <gtest/gtest.h>

#include <string>

#include "job/config.h"
#include "job/result_mapping.h"
#include "tests/test_support.h"

namespace {

using ilp::test::error_of;
using ilp::test::expect_message;
using ilp::test::TempDir;

const char* kScene = "scene:\n  mesh: room.obj\n";  // line 1-2; the mesh is not read by load_job_config

ilp::JobConfig load(const TempDir& dir, const std::string& energy) {
  return ilp::load_job_config(dir.write("job.yaml", std::string(kScene) + energy));
}

// job.yaml = kScene + `energy` must fail at `line` with each of `says`.
void expect_energy_error(const std::string& energy, int line, const std::vector<std::string>& says) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", std::string(kScene) + energy);
  const std::string msg = error_of<ilp::ConfigError>([&] { (void)ilp::load_job_config(yaml); });
  expect_message(msg, yaml + ":" + std::to_string(line) + ":", says);
}

TEST(EnergyConfig, DefaultsToAnOfficeWithoutControls) {
  TempDir dir;
  const ilp::JobConfig job = load(dir, "");
  EXPECT_FALSE(job.energy.given);
  EXPECT_EQ(job.energy.building_type, "office");
  EXPECT_FALSE(job.energy.hours_day);
  EXPECT_EQ(job.energy.occupancy_factor, 1.0);
  EXPECT_EQ(job.energy.daylight_factor, 1.0);
  EXPECT_FALSE(job.energy.constant_illuminance);
  EXPECT_EQ(job.energy.parasitic_kwh_per_m2, 6.0);
}

TEST(EnergyConfig, ReadsEveryKey) {
  TempDir dir;
  const ilp::JobConfig job = load(dir,
                                  "energy:\n  building_type: education\n  hours_day: 1700\n  hours_night: 100\n"
                                  "  occupancy_factor: 0.9\n  daylight_factor: 0.7\n  constant_illuminance: true\n"
                                  "  parasitic_kwh_per_m2: 1\n");
  EXPECT_TRUE(job.energy.given);
  EXPECT_EQ(job.energy.building_type, "education");
  EXPECT_EQ(job.energy.hours_day.value_or(0), 1700.0);
  EXPECT_EQ(job.energy.hours_night.value_or(0), 100.0);
  EXPECT_EQ(job.energy.occupancy_factor, 0.9);
  EXPECT_EQ(job.energy.daylight_factor, 0.7);
  EXPECT_TRUE(job.energy.constant_illuminance);
  EXPECT_EQ(job.energy.parasitic_kwh_per_m2, 1.0);
}

TEST(EnergyConfig, BadValuesNameFileLineAndKey) {
  expect_energy_error("energy:\n  building_typ: office\n", 4, {"unknown key 'energy.building_typ'"});
  expect_energy_error("energy:\n  building_type: warehouse\n", 4,
                      {"energy.building_type = warehouse", "office, education, hospital"});
  expect_energy_error("energy:\n  occupancy_factor: 0\n", 4, {"energy.occupancy_factor = 0", "(0, 1]"});
  expect_energy_error("energy:\n  daylight_factor: 1.2\n", 4, {"energy.daylight_factor = 1.2", "[0, 1]"});
  expect_energy_error("energy:\n  hours_day: -5\n", 4, {"energy.hours_day = -5"});
  expect_energy_error("energy:\n  hours_day: 8000\n  hours_night: 1000\n", 5,
                      {"energy.hours_night = 1000", "at most 8760 h"});
  expect_energy_error("energy:\n  building_type: manufacturing\n  hours_day: 7000\n", 5,
                      {"energy.hours_day = 7000", "at most 8760 h"});
  expect_energy_error("energy:\n  constant_illuminance: yes\n", 4, {"energy.constant_illuminance = yes", "true or false"});
  expect_energy_error("energy:\n  parasitic_kwh_per_m2: -1\n", 4, {"energy.parasitic_kwh_per_m2 = -1"});
  expect_energy_error("energy: 3\n", 3, {"energy = 3", "must be a map"});
}

// The record's LENI: the building type's hours unless the job gives its own, F_C from
// the maintenance factor. education, hours_night 100, constant illuminance at MF 0.8:
// W_L = 300 W x 0.9 x (1800 h x 0.5 x 0.7 + 100 h x 0.5) / 1000 = 0.27 x 680 = 183.6 kWh;
// W_P = 2 x 60 = 120 kWh; LENI = 303.6 / 60 = 5.06 kWh/(m²·a).
TEST(EnergyConfig, RecordTakesTheTypesHoursAndTheJobsFactors) {
  TempDir dir;
  const ilp::JobConfig job = load(dir,
                                  "energy:\n  building_type: education\n  hours_night: 100\n  occupancy_factor: 0.5\n"
                                  "  daylight_factor: 0.7\n  constant_illuminance: true\n  parasitic_kwh_per_m2: 2\n");
  const auto e = ilp::energy_record(job.energy, 300.0, 60.0, 0.8);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->hours_day_h, 1800.0);
  EXPECT_EQ(e->hours_night_h, 100.0);
  EXPECT_DOUBLE_EQ(e->constant_illuminance_factor, 0.9);
  EXPECT_NEAR(e->lighting_kwh, 183.6, 1e-9);
  EXPECT_NEAR(e->parasitic_kwh, 120.0, 1e-9);
  EXPECT_NEAR(e->leni_kwh_per_m2, 5.06, 1e-12);
  EXPECT_FALSE(e->assumed);
  EXPECT_FALSE(ilp::energy_record(job.energy, 300.0, 0.0, 0.8));  // no floor area: no LENI
}

}  // namespace
