// Building jobs (rooms:, docs/building.md) below the program: each room read over the
// building's shared keys, errors in a room's keys at their file, line and key, a room's
// scene holding its part of the model only, and the building summary from the rooms'
// records (sums, area-weighted W/m² and LENI, the bill of materials by product).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "job/building.h"
#include "job/plan.h"
#include "job/config.h"
#include "job/job_scene.h"
#include "job/room_exchange.h"
#include "tests/building_scene.h"
#include "tests/test_support.h"

namespace {

using ilp::test::error_of;
using ilp::test::expect_message;
using ilp::test::TempDir;
using ilp::test::two_rooms_job;
using ilp::test::two_rooms_obj;
using ilp::test::two_rooms_room;

// 1-based line of the first occurrence of `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << needle;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

std::string write_job(const TempDir& dir, const std::string& text, bool door = false) {
  dir.write("rooms.obj", two_rooms_obj(door));
  return dir.write("job.yaml", text);
}

// `text` fails to load with "<job.yaml>:<line of needle>:" and each of `says`.
void expect_room_error(const std::string& text, const std::string& needle, const std::vector<std::string>& says) {
  TempDir dir;
  const std::string yaml = write_job(dir, text);
  const std::string msg = error_of<ilp::ConfigError>([&] { (void)ilp::load_job_config(yaml); });
  expect_message(msg, yaml + ":" + std::to_string(line_of(text, needle)) + ":", says);
}

TEST(BuildingConfig, EachRoomIsTheSharedKeysWithItsOwnOver) {
  TempDir dir;
  const std::string text = two_rooms_job(
      two_rooms_room("a", 200) +
          two_rooms_room("b", 300, "    use: store\n    maintenance_factor: 0.67\n    energy: {occupancy_factor: 0.5}\n"
                                   "    coupled_with: [a]\n"),
      "energy: {building_type: education}\n");
  const ilp::JobConfig job = ilp::load_job_config(write_job(dir, text));
  ASSERT_EQ(job.rooms.size(), 2u);
  EXPECT_TRUE(job.goals.empty());
  const ilp::JobConfig& a = ilp::room_job(job, 0);
  const ilp::JobConfig& b = ilp::room_job(job, 1);
  EXPECT_EQ(job.rooms[0].name, "a");
  EXPECT_EQ(job.rooms[1].use, "store");
  EXPECT_EQ(ilp::room_folder(job, 1), "rooms/b");
  ASSERT_EQ(a.goals.size(), 1u);
  EXPECT_EQ(a.goals[0].surfaces, std::vector<std::string>{"a_floor"});
  EXPECT_EQ(a.goals[0].target, 200.0);
  EXPECT_EQ(b.goals[0].target, 300.0);
  ASSERT_TRUE(a.search && b.search);
  EXPECT_EQ(b.search->mounting_surface, "b_ceiling");
  EXPECT_EQ(a.maintenance_factor, 0.8);  // the building's
  EXPECT_EQ(b.maintenance_factor, 0.67);  // its own
  EXPECT_EQ(a.energy.building_type, "education");
  EXPECT_EQ(b.energy.building_type, "education");
  EXPECT_EQ(a.energy.occupancy_factor, 1.0);
  EXPECT_EQ(b.energy.occupancy_factor, 0.5);
  EXPECT_EQ(a.form_factors.rays_per_patch, 64);  // the shared solver
  EXPECT_EQ(b.optimizer.seed, 2u);
  ASSERT_EQ(a.keep_surfaces.size(), 1u);
  EXPECT_EQ(a.keep_surfaces[0].pattern, "a_*");
  ASSERT_EQ(b.keep_surfaces.size(), 2u);  // its own, then the coupled room's
  EXPECT_EQ(b.keep_surfaces[1].pattern, "a_*");
  EXPECT_TRUE(a.rooms.empty());
}

TEST(BuildingConfig, ErrorsInARoomNameFileLineAndKey) {
  const std::string a = two_rooms_room("a", 200);
  expect_room_error(two_rooms_job(a + two_rooms_room("b", 300, "    goalz: 1\n")), "goalz",
                    {"unknown key 'rooms[1].goalz'"});
  expect_room_error(two_rooms_job(a + two_rooms_room("b", 300, "    maintenance_factor: 1.5\n")),
                    "maintenance_factor: 1.5", {"rooms[1].maintenance_factor = 1.5", "must be in [0.1, 1]"});
  expect_room_error(two_rooms_job(a + two_rooms_room("b", -5)), "average_lux: -5",
                    {"rooms[1].goals[0].average_lux = -5"});
  {  // the second "name: a" is the error's line
    TempDir dir;
    const std::string text = two_rooms_job(a + two_rooms_room("a", 300));
    const std::string yaml = write_job(dir, text);
    const auto at = text.rfind("- name: a");
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
    expect_message(error_of<ilp::ConfigError>([&] { (void)ilp::load_job_config(yaml); }),
                   yaml + ":" + std::to_string(line) + ":", {"rooms[1].name = a", "another room has this name"});
  }
  expect_room_error(two_rooms_job(a + two_rooms_room("b", 300, "    coupled_with: [c]\n")), "coupled_with: [c]",
                    {"rooms[1].coupled_with[0] = c", "no room of this name"});
  expect_room_error(two_rooms_job(a + two_rooms_room("b/c", 300)), "name: b/c", {"rooms[1].name = b/c", "folder"});
  // A single room's key at the building's level is refused, named.
  expect_room_error(two_rooms_job(a, "goals:\n  - {surface: a_floor, average_lux: 100}\n"), "goals:\n  - {surface: a_floor",
                    {"goals: with rooms, each room states its own"});
}

TEST(BuildingConfig, ARoomChoosesProductsOfTheBuildingsCatalogueByName) {
  TempDir dir;
  const std::string shared =
      "luminaires:\n  products:\n    - {name: panel, model: square_lambertian, size_m: 0.6, flux_lm: 3000, power_w: 25}\n"
      "    - {name: small, model: square_lambertian, size_m: 0.3, flux_lm: 1000, power_w: 9}\n";
  auto room = [](const std::string& name, const std::string& products) {
    return "  - name: " + name + "\n    luminaires:\n      products: " + products + "\n      mounting_surface: " + name +
           "_ceiling\n    goals:\n      - {surface: " + name + "_floor, average_lux: 100}\n";
  };
  const ilp::JobConfig job = ilp::load_job_config(write_job(dir, two_rooms_job(room("a", "[small]") + room("b", "[panel, small]"), shared)));
  ASSERT_EQ(ilp::room_job(job, 0).products.size(), 1u);
  EXPECT_EQ(ilp::room_job(job, 0).products[0].name, "small");
  EXPECT_EQ(ilp::room_job(job, 1).products.size(), 2u);
  expect_room_error(two_rooms_job(room("a", "[big]"), shared), "[big]",
                    {"rooms[0].luminaires.products[0] = big", "unknown product"});
}

// A room's scene holds its part of the model: none of the other room's patches.
TEST(BuildingScene, ARoomsSceneHoldsOnlyItsSurfaces) {
  TempDir dir;
  const std::string text = two_rooms_job(two_rooms_room("a", 200) + two_rooms_room("b", 300));
  const ilp::JobConfig job = ilp::load_job_config(write_job(dir, text));
  for (std::size_t r = 0; r < 2; ++r) {
    const ilp::JobScene loaded = ilp::load_job_scene(scene_spec(ilp::room_job(job, r)));
    const std::string own = job.rooms[r].name + "_";
    std::size_t patches = 0;
    for (const ilp::Patch& p : loaded.scene.patches) {
      const std::string& surface = loaded.scene.surfaces[static_cast<std::size_t>(p.surface)].name;
      EXPECT_EQ(surface.rfind(own, 0), 0u) << "room " << job.rooms[r].name << " holds a patch of " << surface;
      ++patches;
    }
    EXPECT_GT(patches, 0u);
  }
}

TEST(BuildingScene, ASurfacePatternMatchingNothingIsAnErrorAtItsLine) {
  TempDir dir;
  std::string room_b = two_rooms_room("b", 300);
  room_b.replace(room_b.find("[b_*]"), 5, "[b_*, c_*]");
  const std::string text = two_rooms_job(two_rooms_room("a", 200) + room_b);
  const ilp::JobConfig job = ilp::load_job_config(write_job(dir, text));
  const std::string msg = error_of<ilp::ConfigError>([&] { (void)ilp::load_job_scene(scene_spec(ilp::room_job(job, 1))); });
  expect_message(msg, dir.file("job.yaml") + ":" + std::to_string(line_of(text, "c_*")) + ":",
                 {"rooms[1].surfaces[1] = c_*", "no surface of the mesh matches it"});
}

ilp::ResultRecord record(double power_w, double area_m2, double energy_kwh, bool met,
                         const std::vector<ilp::BillLine>& bill) {
  ilp::ResultRecord r;
  r.power_w = power_w;
  r.floor_area_m2 = area_m2;
  r.power_density_w_per_m2 = power_w / area_m2;
  r.all_met = met;
  r.energy = ilp::EnergyRecord{};
  r.energy->area_m2 = area_m2;
  r.energy->total_kwh = energy_kwh;
  r.energy->leni_kwh_per_m2 = energy_kwh / area_m2;
  r.bill_of_materials = bill;
  for (const ilp::BillLine& b : bill)
    for (int k = 0; k < b.count; ++k) r.luminaires.push_back({});
  if (!met) {
    ilp::VerdictLine line;
    line.name = "floor";
    line.metric = "average";
    line.unit = "lx";
    line.target = 500;
    line.predicted = 400;
    r.goals.push_back(line);
  }
  return r;
}

TEST(BuildingSummary, TotalsAreSumsAndDensitiesAreAreaWeighted) {
  ilp::JobConfig building;
  building.path = "floor.yaml";
  building.rooms.resize(3);
  building.rooms[0].name = "big";
  building.rooms[1].name = "small";
  building.rooms[2].name = "hall";
  const ilp::BillLine led{.product = "led", .source = "led.ldt", .count = 4, .rated_flux_lm = 2000,
                          .unit_power_w = 20, .output_fraction = 0.5, .total_power_w = 40};
  const ilp::BillLine led_full{.product = "led", .source = "led.ldt", .count = 2, .rated_flux_lm = 2000,
                               .unit_power_w = 20, .output_fraction = 1.0, .total_power_w = 40};
  const ilp::BillLine down{.product = "down", .source = "down.ldt", .count = 3, .rated_flux_lm = 600,
                           .unit_power_w = 7, .output_fraction = 1.0, .total_power_w = 21};
  // 40 W over 40 m², 40 W over 10 m², 21 W over 30 m²: mean of densities 1.925 W/m², area-weighted 1.2625.
  const std::vector<ilp::ResultRecord> rooms{record(40, 40, 400, true, {led}), record(40, 10, 300, false, {led_full}),
                                             record(21, 30, 90, true, {down})};
  const ilp::BuildingRecord b = ilp::summarize_building("ilp test", building, rooms);
  ASSERT_EQ(b.rooms.size(), 3u);
  EXPECT_EQ(b.rooms[1].name, "small");
  EXPECT_EQ(b.rooms[1].folder, "rooms/small");
  EXPECT_DOUBLE_EQ(b.power_w, 101.0);
  EXPECT_DOUBLE_EQ(b.floor_area_m2, 80.0);
  EXPECT_DOUBLE_EQ(b.power_density_w_per_m2, 101.0 / 80.0);
  EXPECT_DOUBLE_EQ(b.energy_kwh, 790.0);
  EXPECT_DOUBLE_EQ(b.leni_kwh_per_m2, 790.0 / 80.0);
  EXPECT_EQ(b.luminaires, 9);
  EXPECT_EQ(b.rooms_met, 2);
  EXPECT_FALSE(b.all_met);
  EXPECT_NE(b.rooms[1].not_met.find("floor average"), std::string::npos) << b.rooms[1].not_met;
  EXPECT_TRUE(b.rooms[0].not_met.empty());
  ASSERT_EQ(b.bill_of_materials.size(), 2u);
  EXPECT_EQ(b.bill_of_materials[0].product, "led");  // first seen
  EXPECT_EQ(b.bill_of_materials[0].count, 6);
  EXPECT_DOUBLE_EQ(b.bill_of_materials[0].total_power_w, 80.0);
  EXPECT_DOUBLE_EQ(b.bill_of_materials[0].output_fraction, 80.0 / 120.0);
  EXPECT_EQ(b.bill_of_materials[1].count, 3);
  // Every room met: the building is.
  std::vector<ilp::ResultRecord> met = rooms;
  met[1] = record(40, 10, 300, true, {led_full});
  EXPECT_TRUE(ilp::summarize_building("ilp test", building, met).all_met);
  EXPECT_THROW((void)ilp::summarize_building("ilp test", building, {rooms[0]}), std::invalid_argument);
}

// What a rank sends rank 0 in a distributed building run (docs/cluster.md): its rooms'
// records, times and files, or its first failure, read back as they were; the
// building's result.json from the records received is the bytes of the one from the
// records themselves.
TEST(RoomExchange, ARanksReportRoundTrips) {
  ilp::JobConfig building;
  building.path = "floor.yaml";
  building.rooms.resize(2);
  building.rooms[0].name = "office";
  building.rooms[1].name = "hall";
  const ilp::BillLine led{.product = "led", .source = "led.ldt", .count = 4, .rated_flux_lm = 2111.37,
                          .unit_power_w = 22.3, .output_fraction = 0.4912345678901234, .total_power_w = 43.817};
  std::vector<ilp::ResultRecord> rooms{record(43.817, 30.000000001, 401.1 / 3.0, true, {led}),
                                       record(1.0 / 3.0, 9.7, 300, false, {led})};
  rooms[1].timings_s = {{"prepare", 1.25}, {"search", 0.1}};
  rooms[1].no_layout = "";
  ilp::RankReport report;
  report.rooms.push_back({0, 3.5, rooms[0], {{"rooms/office/result.json", "{}\n"}, {"rooms/office/plan.png", std::string("\0\x89PNG\r\n", 7)}}});
  report.rooms.push_back({1, 0.25, rooms[1], {}});
  const ilp::RankReport back = ilp::decode_rank_report(ilp::encode_rank_report(report));
  ASSERT_EQ(back.rooms.size(), 2u);
  EXPECT_FALSE(back.failure);
  EXPECT_EQ(back.rooms[0].room, 0u);
  EXPECT_EQ(back.rooms[1].room, 1u);
  EXPECT_EQ(back.rooms[0].seconds, 3.5);
  EXPECT_EQ(back.rooms[0].files, report.rooms[0].files);
  EXPECT_TRUE(back.rooms[1].files.empty());
  for (std::size_t r = 0; r < 2; ++r)
    EXPECT_EQ(ilp::result_record_bytes(back.rooms[r].record), ilp::result_record_bytes(rooms[r])) << r;
  EXPECT_EQ(back.rooms[1].record.timings_s.size(), 2u);
  // The building's files from the records received are the same bytes.
  const std::vector<ilp::ResultRecord> received{back.rooms[0].record, back.rooms[1].record};
  TempDir dir;
  ilp::write_building_json(dir.file("a.json"), ilp::summarize_building("ilp test", building, rooms));
  ilp::write_building_json(dir.file("b.json"), ilp::summarize_building("ilp test", building, received));
  EXPECT_EQ(ilp::test::read_file(dir.file("a.json")), ilp::test::read_file(dir.file("b.json")));

  ilp::RankReport failed;
  failed.failure = ilp::RoomFailure{5, "floor.yaml:12:3: rooms[5].mounting_surface = x: no such surface"};
  const ilp::RankReport f = ilp::decode_rank_report(ilp::encode_rank_report(failed));
  ASSERT_TRUE(f.failure);
  EXPECT_EQ(f.failure->room, 5u);
  EXPECT_EQ(f.failure->message, failed.failure->message);
  EXPECT_TRUE(f.rooms.empty());
  // Bytes cut short or of something else are refused, not read as a report.
  const std::string bytes = ilp::encode_rank_report(report);
  EXPECT_THROW((void)ilp::decode_rank_report(bytes.substr(0, bytes.size() - 3)), std::runtime_error);
  EXPECT_THROW((void)ilp::decode_rank_report("not a report"), std::runtime_error);
  EXPECT_THROW((void)ilp::decode_rank_report(bytes + "x"), std::runtime_error);
}

TEST(RoomExchange, RoomsGoRoundRobinOverRanks) {
  EXPECT_EQ(ilp::room_rank(0, 1), 0);
  EXPECT_EQ(ilp::room_rank(6, 1), 0);
  EXPECT_EQ(ilp::room_rank(3, 2), 1);
  EXPECT_EQ(ilp::room_rank(4, 2), 0);
  EXPECT_EQ(ilp::room_rank(7, 4), 3);
}

}  // namespace
