// `ilp run` of a building job (rooms:, docs/building.md) on two rooms side by side
// (tests/building_scene.h): each room's results are those of the same room run as a
// single-room job, no light crosses a closed wall, a room that misses its goals makes
// exit 2 and a bad room exit 1 with nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <tuple>
#include <string>
#include <vector>

#include "output/building_record.h"
#include "output/result_record.h"
#include "tests/apps/cli_runner.h"
#include "tests/building_scene.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::OutputContains;
using ilp::test::read_file;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;
using ilp::test::two_rooms_job;
using ilp::test::two_rooms_obj;
using ilp::test::two_rooms_room;

void expect_exit(const RunResult& r, int code) {
  EXPECT_EQ(r.exit_code, code) << "stdout:\n" << r.out << "\nstderr:\n" << r.err;
}

// Room `name` of two_rooms_room as a single-room job of its own: the building's shared
// keys, the other room's surfaces left out (what the room's surfaces: [name_*] does).
std::string single_room_job(const std::string& name, double average_lux, const std::string& other) {
  std::ostringstream os;
  os << "scene:\n  mesh: rooms.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0.5\n"
     << "  exclude_surfaces: [" << other << "_floor, " << other << "_ceiling, " << other << "_walls]\n"
     << "maintenance_factor: 0.8\n"
     << "solver:\n  rays_per_patch: 64\n  seed: 3\n  sample_fraction: 0.2\n"
     << "optimizer:\n  max_evaluations: 200\n  local_max_evaluations: 100\n  seed: 2\n"
     << "verification:\n  method: exact\n  rays_per_patch: 128\n"
     << "output:\n  formats: [json, csv, svg]\n"
     << "luminaires:\n  size_m: 0.3\n  flux_lm: [100, 4000]\n  efficacy_lm_per_w: 100\n"
     << "  mounting_surface: " << name << "_ceiling\n  candidate_spacing_m: 0.5\n"
     << "  layout: field\n  field: {rows: [1, 2], columns: [1, 2]}\n"
     << "goals:\n  - {surface: " << name << "_floor, average_lux: " << average_lux << "}\n";
  return os.str();
}

void expect_same_lines(const std::vector<ilp::VerdictLine>& a, const std::vector<ilp::VerdictLine>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    SCOPED_TRACE(a[k].name);
    EXPECT_EQ(a[k].target, b[k].target);
    EXPECT_EQ(a[k].predicted, b[k].predicted);
    EXPECT_EQ(a[k].verified, b[k].verified);
    EXPECT_EQ(a[k].met, b[k].met);
  }
}

// The same seed and the same scene: identical layouts and values, to the last bit.
TEST(IlpBuilding, EachRoomGivesWhatItGivesRunAlone) {
  TempDir dir;
  dir.write("rooms.obj", two_rooms_obj());
  const std::string building = dir.write("building.yaml", two_rooms_job(two_rooms_room("a", 150) + two_rooms_room("b", 300)));
  const RunResult run = run_ilp(dir, {"run", building, "--out", dir.file("out"), "--quiet"});
  expect_exit(run, 0);
  EXPECT_TRUE(OutputContains(run.out, "2 of 2 rooms meet their goals"));
  for (const auto& [name, lux, other] : {std::tuple{"a", 150.0, "b"}, std::tuple{"b", 300.0, "a"}}) {
    SCOPED_TRACE(name);
    const std::string single = dir.write(std::string(name) + ".yaml", single_room_job(name, lux, other));
    const std::string out = dir.file(std::string("single_") + name);
    expect_exit(run_ilp(dir, {"run", single, "--out", out, "--quiet"}), 0);
    const ilp::ResultRecord alone = ilp::read_result_json(out + "/result.json");
    const ilp::ResultRecord in_building =
        ilp::read_result_json(dir.file(std::string("out/rooms/") + name + "/result.json"));
    ASSERT_EQ(in_building.luminaires.size(), alone.luminaires.size());
    ASSERT_FALSE(alone.luminaires.empty());
    for (std::size_t j = 0; j < alone.luminaires.size(); ++j) {
      EXPECT_EQ(in_building.luminaires[j].x_m, alone.luminaires[j].x_m);
      EXPECT_EQ(in_building.luminaires[j].y_m, alone.luminaires[j].y_m);
      EXPECT_EQ(in_building.luminaires[j].flux_lm, alone.luminaires[j].flux_lm);
    }
    EXPECT_EQ(in_building.power_w, alone.power_w);
    expect_same_lines(in_building.goals, alone.goals);
    EXPECT_TRUE(fs::exists(dir.file(std::string("out/rooms/") + name + "/plan.svg")));
  }
  // The building's record: the rooms in order, the power summed, W/m² over the summed areas.
  const ilp::BuildingRecord b = ilp::read_building_json(dir.file("out/result.json"));
  ASSERT_EQ(b.rooms.size(), 2u);
  EXPECT_EQ(b.rooms[0].name, "a");
  const ilp::ResultRecord a = ilp::read_result_json(dir.file("out/rooms/a/result.json"));
  const ilp::ResultRecord r_b = ilp::read_result_json(dir.file("out/rooms/b/result.json"));
  EXPECT_DOUBLE_EQ(b.power_w, a.power_w + r_b.power_w);
  EXPECT_DOUBLE_EQ(b.power_density_w_per_m2, (a.power_w + r_b.power_w) / (a.floor_area_m2 + r_b.floor_area_m2));
  EXPECT_TRUE(b.all_met);
  // ilp print reads the building's result back.
  const RunResult print = run_ilp(dir, {"print", dir.file("out/result.json")});
  expect_exit(print, 0);
  EXPECT_TRUE(OutputContains(print.out, "building: 2 rooms"));
}

// inspect: each room's estimate on its own part of the model, and their sum.
TEST(IlpBuilding, InspectGivesEachRoomsEstimateAndTheSum) {
  TempDir dir;
  dir.write("rooms.obj", two_rooms_obj());
  const std::string building = dir.write("building.yaml", two_rooms_job(two_rooms_room("a", 150) + two_rooms_room("b", 300)));
  const RunResult r = run_ilp(dir, {"inspect", building});
  expect_exit(r, 0);
  EXPECT_TRUE(OutputContains(r.out, "room a ("));
  EXPECT_TRUE(OutputContains(r.out, "room b ("));
  EXPECT_TRUE(OutputContains(r.out, "cost estimate of the building: about"));
  EXPECT_TRUE(OutputContains(r.out, "for its 2 rooms"));
}

// The surface table line of `surface` in `ilp solve` output.
std::string solve_line(const std::string& out, const std::string& surface) {
  for (const std::string& line : ilp::test::lines_of(out))
    if (line.rfind(surface + " ", 0) == 0) return line;
  return {};
}

// Doors closed (the model's own walls), the rooms are optically independent: a lamp in
// a leaves b dark, in the exact solve. With the door open, light reaches b (the check
// can fail).
TEST(IlpBuilding, NoLightCrossesAClosedWall) {
  for (const bool door : {false, true}) {
    SCOPED_TRACE(door ? "door open" : "door closed");
    TempDir dir;
    dir.write("rooms.obj", two_rooms_obj(door));
    const std::string job = dir.write(
        "solve.yaml",
        "scene:\n  mesh: rooms.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0.5\n"
        "luminaires:\n  size_m: 0.3\n  placed:\n    - {name: L1, position_m: [2.0, 1.5, 2.45], flux_lm: 3000}\n"
        "solver:\n  rays_per_patch: 256\n  seed: 3\n"
        "report:\n  surfaces: [a_floor, b_floor, b_walls]\n");
    const RunResult r = run_ilp(dir, {"solve", job, "--method", "exact", "--quiet"});
    expect_exit(r, 0);
    const std::string a = solve_line(r.out, "a_floor"), b = solve_line(r.out, "b_floor");
    ASSERT_FALSE(a.empty()) << r.out;
    ASSERT_FALSE(b.empty()) << r.out;
    std::istringstream as(a.substr(a.find(' '))), bs(b.substr(b.find(' ')));
    double patches = 0.0, area = 0.0, a_avg = 0.0, b_avg = 0.0;  // the columns: patches, area m2, Eavg lux
    as >> patches >> area >> a_avg;
    bs >> patches >> area >> b_avg;
    EXPECT_GT(a_avg, 50.0) << a;
    if (door) EXPECT_GT(b_avg, 0.5) << b;
    else EXPECT_EQ(b_avg, 0.0) << b;
  }
}

TEST(IlpBuilding, ARoomMissingItsGoalsMakesExitTwo) {
  TempDir dir;
  dir.write("rooms.obj", two_rooms_obj());
  const std::string building =
      dir.write("building.yaml", two_rooms_job(two_rooms_room("a", 150) + two_rooms_room("b", 50000)));
  const RunResult run = run_ilp(dir, {"run", building, "--out", dir.file("out"), "--quiet"});
  expect_exit(run, 2);
  EXPECT_TRUE(OutputContains(run.out, "1 of 2 rooms meet their goals"));
  EXPECT_TRUE(OutputContains(run.out, "NOT MET: b_floor average"));
  const ilp::BuildingRecord b = ilp::read_building_json(dir.file("out/result.json"));
  EXPECT_FALSE(b.all_met);
  EXPECT_TRUE(b.rooms[0].all_met);
  EXPECT_FALSE(b.rooms[1].all_met);
  EXPECT_TRUE(fs::exists(dir.file("out/rooms/b/result.json")));
}

// Room b's mounting surface is not in the model: found when b is prepared, after a has
// run; the error names the file, line and key, and the previous output stays as it was.
TEST(IlpBuilding, ABadRoomExitsOneAndWritesNothing) {
  TempDir dir;
  dir.write("rooms.obj", two_rooms_obj());
  std::string room_b = two_rooms_room("b", 300);
  room_b.replace(room_b.find("mounting_surface: b_ceiling"), 27, "mounting_surface: b_roof");
  const std::string text = two_rooms_job(two_rooms_room("a", 150) + room_b);
  const std::string building = dir.write("building.yaml", text);
  fs::create_directories(dir.file("out"));
  dir.write("out/result.json", "previous\n");
  const RunResult run = run_ilp(dir, {"run", building, "--out", dir.file("out"), "--quiet"});
  expect_exit(run, 1);
  const auto at = text.find("b_roof");
  const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
  EXPECT_TRUE(OutputContains(run.err, building + ":" + std::to_string(line) + ":"));
  EXPECT_TRUE(OutputContains(run.err, "mounting_surface"));
  EXPECT_EQ(read_file(dir.file("out/result.json")), "previous\n");
  EXPECT_FALSE(fs::exists(dir.file("out/rooms")));
  // A bad key in a room's entry: refused before any work.
  const std::string bad = dir.write("bad.yaml", two_rooms_job(two_rooms_room("a", 150) + two_rooms_room("b", 300, "    colour: red\n")));
  const RunResult refused = run_ilp(dir, {"run", bad, "--out", dir.file("out2"), "--quiet"});
  expect_exit(refused, 1);
  EXPECT_TRUE(OutputContains(refused.err, "unknown key 'rooms[1].colour'"));
  EXPECT_FALSE(fs::exists(dir.file("out2")));
}

}  // namespace
