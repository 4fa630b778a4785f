// result.json written and read back, and the errors for files that are not results.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "output/result_record.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

ResultRecord sample_record() {
  ResultRecord r;
  r.program_version = "ilp 0.1.0";
  r.config = "configs/office.yaml";
  r.objective = "min_power";
  r.luminaires = {{"L1", 1.5, 1.0, 2.95, 3400.26, 27.202, "", 0.0}, {"L2", 4.5, 3.0, 2.95, 1234.5, 9.876, "", 0.0}};
  GoalRecord desks{"desks", {"desk_1", "desk_2"}, "average", "lx", 500.0, 508.6, 500.0, true, false, 1e-4, ""};
  GoalRecord floor{"floor", {"floor"}, "minimum", "lx", 100.0, 100.0, 88.66, false, true, 1e-4, ""};
  GoalRecord unverified{"desks", {"desk_1", "desk_2"}, "uniformity", "", 0.6, 0.7, std::nullopt, true, false, 1e-4, ""};
  r.goals = {desks, floor, unverified};
  r.power_w = 37.078;
  r.mounting_area_m2 = 24.0;
  r.power_density_w_per_m2 = 37.078 / 24.0;
  r.feasible = true;
  r.all_met = false;
  r.flux_correction = 1.0027;
  r.verification = "exact";
  r.verification_rays_per_patch = 1024;
  r.sample_size = 517;
  r.population = 10330;
  r.patches = 10330;
  r.candidates = 96;
  r.seed = 1;
  r.optimizer_seed = 9007199254740993ull;  // above 2^53: must survive as an integer
  r.evaluations = 70654;
  r.searches = 2;
  r.direct_checks = 3;
  r.direct_check_note = "2 x 4 field: work_plane uniformity 0.41 with the luminaires' own direct light (predicted 0.64)";
  r.calibration = {"round 1: floor minimum predicted 100, verified 88.66; the next search aims at 113 for 100"};
  r.timings_s = {{"scene", 0.01}, {"operator", 1.41}, {"total", 8.27}};
  r.verification_parts_s = {{"rows", 1.25}, {"direct light", 0.5}, {"the rest", 0.25}};
  r.attempts = {{4, 6643, 0.32, true, 123.4, "evaluation budget used", "step tolerance reached"}};
  return r;
}

TEST(ResultJson, RoundTripsEveryField) {
  test::TempDir dir;
  ResultRecord r = sample_record();
  r.search_max_seconds = 60.0;
  write_result_json(dir.file("result.json"), r);
  write_timings_json(dir.file("timings.json"), r);
  const ResultRecord back = read_result_json(dir.file("result.json"));
  std::ostringstream a, b;
  print_result(a, r);
  print_result(b, back);
  EXPECT_EQ(a.str(), b.str());
  ASSERT_EQ(back.luminaires.size(), 2u);
  EXPECT_EQ(back.luminaires[1].flux_lm, 1234.5);
  EXPECT_EQ(back.goals[1].verified, 88.66);
  EXPECT_FALSE(back.goals[2].verified.has_value());
  EXPECT_TRUE(back.goals[1].fails_only_on_verification);
  EXPECT_EQ(back.optimizer_seed, 9007199254740993ull);
  ASSERT_EQ(back.timings_s.size(), 3u);
  EXPECT_EQ(back.timings_s[1].first, "operator") << "phases keep their order";
  EXPECT_EQ(back.verification_parts_s, r.verification_parts_s) << "from timings.json, in order";
  EXPECT_EQ(back.calibration, r.calibration);
  EXPECT_EQ(back.direct_checks, 3);
  EXPECT_EQ(back.direct_check_note, r.direct_check_note);
  EXPECT_EQ(back.attempts[0].local_stop, "step tolerance reached");
  EXPECT_EQ(back.attempts[0].seconds, 0.32) << "from timings.json";
  EXPECT_EQ(back.search_max_seconds, 60.0);
  EXPECT_TRUE(test::Contains(a.str(), "wall-clock limit 60.0 s (optimizer.max_seconds)", "report"));
}

// Issue 21: result.json is the same bytes whatever the run's times; they go to
// timings.json, and a result.json read without it has none.
TEST(ResultJson, HoldsNoWallClockTimes) {
  test::TempDir dir;
  ResultRecord fast = sample_record(), slow = sample_record();
  slow.timings_s = {{"scene", 0.5}, {"operator", 9.0}, {"total", 80.0}};
  slow.attempts[0].seconds = 7.5;
  write_result_json(dir.file("fast.json"), fast);
  write_result_json(dir.file("slow.json"), slow);
  EXPECT_EQ(test::read_file(dir.file("fast.json")), test::read_file(dir.file("slow.json")));
  EXPECT_TRUE(test::Contains(test::read_file(dir.file("fast.json")), "\"depends_on_machine\": false", "result.json"));
  const ResultRecord back = read_result_json(dir.file("fast.json"));  // no timings.json beside it
  EXPECT_TRUE(back.timings_s.empty());
  std::ostringstream printed;
  print_result(printed, back);
  EXPECT_FALSE(test::Contains(printed.str(), "timings:", "report"));
}

// A result.json of an older version holds its times itself; they are still read.
TEST(ResultJson, ReadsTheTimesOfAnOlderResultJson) {
  test::TempDir dir;
  write_result_json(dir.file("result.json"), sample_record());
  std::string json = test::read_file(dir.file("result.json"));
  const std::string anchor = "  \"attempts\": [";
  json.replace(json.find(anchor), anchor.size(), "  \"timings_s\": {\"scene\": 0.25, \"total\": 3.5},\n" + anchor);
  dir.write("result.json", json);
  const ResultRecord back = read_result_json(dir.file("result.json"));
  ASSERT_EQ(back.timings_s.size(), 2u);
  EXPECT_EQ(back.timings_s[1].second, 3.5);
}

TEST(ResultJson, RoundTripsGridsMaintenanceAndFloorArea) {
  test::TempDir dir;
  ResultRecord r = sample_record();
  r.maintenance_factor = 0.8;
  r.floor_area_m2 = 24.0;
  r.floor_area_source = "floor 'floor' (under grid 'work_plane')";
  r.power_density_w_per_m2 = 5.85;
  r.power_density_w_per_m2_per_100_lx = 1.17;
  r.goals[0].grid = "work_plane";
  r.grids.push_back({"work_plane", 40, 15.0, 0.616, 2, true, {625.0, 375.5, 890.2, 0.601}, {500.0, 300.4, 712.16, 0.601}});
  write_result_json(dir.file("result.json"), r);
  const ResultRecord back = read_result_json(dir.file("result.json"));
  ASSERT_EQ(back.grids.size(), 1u);
  EXPECT_EQ(back.grids[0].points, 40);
  EXPECT_EQ(back.grids[0].inside_solid, 2);
  EXPECT_EQ(back.grids[0].initial.average_lux, 625.0);
  EXPECT_EQ(back.grids[0].maintained.max_lux, 712.16);
  EXPECT_EQ(back.goals[0].grid, "work_plane");
  EXPECT_EQ(back.maintenance_factor, 0.8);
  EXPECT_EQ(back.floor_area_source, r.floor_area_source);
  std::ostringstream out;
  print_result(out, back);
  EXPECT_NE(out.str().find("5.85 W/m² over 24.00 m² (floor 'floor' (under grid 'work_plane')), 1.17 W/m² per 100 lx"),
            std::string::npos) << out.str();
  EXPECT_NE(out.str().find("maintenance factor 0.80"), std::string::npos);
  EXPECT_NE(out.str().find("work_plane               40    625.0    375.5    890.2  0.601"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("500.0    300.4    712.2"), std::string::npos) << out.str();
}

// The room and the energy (LENI) go into result.json and come back; the printout has
// the LENI line; a result written before them reads back without either.
TEST(ResultJson, RoundTripsRoomAndEnergy) {
  test::TempDir dir;
  ResultRecord r = sample_record();
  r.room = RoomRecord{"office.obj", 6.0, 4.0, 3.0, 0.0, {{"floor", 24.0, 0.2, 0.0, 0.0}, {"partition", 6.86, 0.5, 0.0, 1.5}}};
  r.energy = EnergyRecord{"office", true, 2250.0, 250.0, 1.0, 1.0, 0.9, 6.0, 212.5, 24.0, 478.125, 144.0, 622.125, 25.921875};
  write_result_json(dir.file("result.json"), r);
  const ResultRecord back = read_result_json(dir.file("result.json"));
  ASSERT_TRUE(back.room.has_value());
  EXPECT_EQ(back.room->mesh, "office.obj");
  EXPECT_EQ(back.room->width_y_m, 4.0);
  EXPECT_EQ(back.room->floor_z_m, 0.0);
  ASSERT_EQ(back.room->surfaces.size(), 2u);
  EXPECT_EQ(back.room->surfaces[1].top_m, 1.5);
  ASSERT_TRUE(back.energy.has_value());
  EXPECT_EQ(back.energy->leni_kwh_per_m2, 25.921875);
  EXPECT_TRUE(back.energy->assumed);
  EXPECT_EQ(back.energy->constant_illuminance_factor, 0.9);
  std::ostringstream out;
  print_result(out, back);
  EXPECT_NE(out.str().find("LENI 25.92 kWh/(m²·a) (EN 15193-1: 622 kWh/a over 24.00 m²; office assumed, t_D 2250 h, t_N 250 h"),
            std::string::npos) << out.str();
  const ResultRecord old = sample_record();
  write_result_json(dir.file("old.json"), old);
  const ResultRecord old_back = read_result_json(dir.file("old.json"));
  EXPECT_FALSE(old_back.room.has_value());
  EXPECT_FALSE(old_back.energy.has_value());
}

TEST(ResultJson, PrintShowsLayoutGoalsAndMisses) {
  std::ostringstream os;
  print_result(os, sample_record());
  const std::string text = os.str();
  for (const char* part : {"NOT MET on verification", "L1", "3400.3", "27.20", "Total power 37.1 W", "1.54 W/m²",
                           "desks average (lx)", "508.6", "MISSED by 11.3 % (fails on verification only)",
                           "every flux scaled by 1.0027", "2 rounds", "round 1: floor minimum"})
    EXPECT_TRUE(test::Contains(text, part, "report")) << part;
}

// Issue 20: "NOT MET" was printed with every goal line met (a constraint had failed,
// and constraints were no lines). Now the miss names each failing line and by how much.
TEST(ResultJson, NotMetNamesEveryFailingLineAndMetPrintsNone) {
  ResultRecord r = sample_record();
  r.goals[1].verified = 100.5;
  r.goals[1].met = true;
  r.goals[1].fails_only_on_verification = false;
  VerdictLine distance;
  distance.kind = "constraint";
  distance.name = "min_distance_m";
  distance.metric = "least distance between centres";
  distance.unit = "m";
  distance.rule = ">=";
  distance.target = 2.0;
  distance.predicted = 1.965;
  distance.tolerance = 1e-4;
  VerdictLine count = distance;
  count.name = "count";
  count.unit = "";
  count.rule = "in";
  count.target = 4;
  count.target_max = 6;
  count.predicted = 6;
  count.met = true;
  r.constraints = {count, distance};
  r.all_met = false;
  std::ostringstream os;
  print_result(os, r);
  const std::string text = os.str();
  EXPECT_TRUE(test::Contains(text, "NOT MET: min_distance_m 1.965 m < 2.000 m (by 0.035 m)\n", "report"));
  EXPECT_TRUE(test::Contains(text, "INFEASIBLE: no layout found meets every goal and constraint", "report"));
  EXPECT_TRUE(test::Contains(text, "count                                   4 .. 6           6  met", "report"));
  // Every line met: no miss is printed.
  r.constraints[1].predicted = 2.0;
  r.constraints[1].met = true;
  r.all_met = true;
  std::ostringstream met;
  print_result(met, r);
  EXPECT_FALSE(test::Contains(met.str(), "NOT MET", "report"));
  EXPECT_FALSE(test::Contains(met.str(), "INFEASIBLE", "report"));
}

TEST(ResultJson, FailingLinesSayWhichBoundAndByHowMuch) {
  VerdictLine u0{"work_plane", {}, "uniformity", "", 0.6, 0.61, 0.025313, false, false, 1e-4, "work_plane"};
  EXPECT_EQ(failing_line_text(u0), "work_plane uniformity 0.025 < 0.600 (by 0.575)");
  VerdictLine floor{"floor", {"floor"}, "minimum", "lx", 100.0, 100.0, 88.66, false, true, 1e-4, ""};
  EXPECT_EQ(failing_line_text(floor), "floor minimum 88.7 lx < 100.0 lx (by 11.3 lx, 11.3 %) on verification only");
  VerdictLine glare{"desks", {}, "maximum", "lx", 2000.0, 2100.0, std::nullopt, false, false, 1e-4, ""};
  EXPECT_EQ(failing_line_text(glare), "desks maximum 2100.0 lx > 2000.0 lx (by 100.0 lx, 5.0 %)");
  VerdictLine flux;
  flux.kind = "constraint";
  flux.name = "flux_lm";
  flux.unit = "lm";
  flux.rule = "in";
  flux.target = 1000.0;
  flux.target_max = 8000.0;
  flux.predicted = 8400.0;
  EXPECT_EQ(failing_line_text(flux), "flux_lm 8400.0 lm > 8000.0 lm (by 400.0 lm)");
}

TEST(ResultJson, RoundTripsConstraintsMarginsAndVariantTables) {
  test::TempDir dir;
  ResultRecord r = sample_record();
  r.goals[0].rule = ">=";
  r.goals[0].relative_error = 0.0021;
  r.goals[0].margin = 0.005;
  r.margin_floor = 0.005;
  VerdictLine distance;
  distance.kind = "constraint";
  distance.name = "min_distance_m";
  distance.unit = "m";
  distance.rule = ">=";
  distance.target = 2.0;
  distance.predicted = 2.5;
  distance.met = true;
  r.constraints = {distance};
  VariantRecord chosen, rejected, skipped;
  chosen.product = "panel";
  chosen.summary = "panel at 0.0 deg: 6 luminaires, 191.2 W, every goal and constraint met";
  chosen.searched = chosen.chosen = chosen.all_met = true;
  chosen.luminaires = 6;
  chosen.power_w = 191.2;
  chosen.goals = r.goals;
  rejected = chosen;
  rejected.product = "downlight";
  rejected.rotation_deg = 90.0;
  rejected.summary = "downlight at 90.0 deg: 12 luminaires, 1200.0 W, not met: floor minimum";
  rejected.chosen = rejected.all_met = false;
  rejected.power_w = 1200.0;
  skipped.product = "spot";
  skipped.summary = "spot at 0.0 deg: not searched: at least 300.0 W, no less than the 191.2 W already found";
  r.variants = {chosen, rejected, skipped};
  write_result_json(dir.file("result.json"), r);
  write_timings_json(dir.file("timings.json"), r);  // the times print_result shows
  const ResultRecord back = read_result_json(dir.file("result.json"));
  ASSERT_EQ(back.constraints.size(), 1u);
  EXPECT_EQ(back.constraints[0].kind, "constraint");
  EXPECT_EQ(back.constraints[0].predicted, 2.5);
  EXPECT_EQ(back.goals[0].relative_error, 0.0021);
  EXPECT_EQ(back.goals[0].margin, 0.005);
  EXPECT_FALSE(back.goals[1].relative_error.has_value());
  EXPECT_EQ(back.margin_floor, 0.005);
  ASSERT_EQ(back.variants.size(), 3u);
  EXPECT_EQ(back.variants[1].rotation_deg, 90.0);
  EXPECT_EQ(back.variants[1].power_w, 1200.0);
  ASSERT_EQ(back.variants[1].goals.size(), r.goals.size());
  EXPECT_EQ(back.variants[1].goals[1].verified, 88.66);
  EXPECT_FALSE(back.variants[2].searched);
  std::ostringstream a, b;
  print_result(a, r);
  print_result(b, back);
  EXPECT_EQ(a.str(), b.str());
  // The rejected alternative is explained by its own failing line.
  EXPECT_TRUE(test::Contains(b.str(), "downlight at 90.0 deg: 12 luminaires, 1200.0 W, not met: floor minimum\n"
                                      "      not met: floor minimum 88.7 lx < 100.0 lx (by 11.3 lx, 11.3 %) on verification only",
                             "report"));
  EXPECT_TRUE(test::Contains(b.str(), "  * panel at 0.0 deg", "report"));
  EXPECT_TRUE(test::Contains(b.str(), "0.50 %", "report")) << "the margin column";
}

// A result.json written before verdict lines (goals without kind or rule, variants as
// one-line strings, no constraints) still reads and prints.
TEST(ResultJson, AnOlderResultWithoutVerdictLinesStillReads) {
  test::TempDir dir;
  ResultRecord r = sample_record();
  write_result_json(dir.file("new.json"), r);
  std::string text = test::read_file(dir.file("new.json"));
  // Drops each line holding `key`; a dropped last member takes the comma before it along.
  auto drop_line = [&](const std::string& key) {
    for (auto at = text.find(key); at != std::string::npos; at = text.find(key)) {
      const auto begin = text.rfind('\n', at), end = text.find('\n', at);
      const bool last = text[end - 1] != ',';
      text.erase(begin, end - begin);
      if (last && text[begin - 1] == ',') text.erase(begin - 1, 1);
    }
  };
  for (const char* key : {"\"kind\"", "\"rule\"", "\"relative_error\"", "\"margin\"", "\"margin_floor\""}) drop_line(key);
  drop_line("\"constraints\": []");
  const auto variants = text.find("\"variants\": []");
  ASSERT_NE(variants, std::string::npos);
  text.replace(variants, std::string("\"variants\": []").size(), "\"variants\": [\"panel at 0.0 deg: 6 luminaires, goals missed\"]");
  const std::string old = dir.write("old.json", text);
  const ResultRecord back = read_result_json(old);
  EXPECT_TRUE(back.constraints.empty());
  ASSERT_EQ(back.variants.size(), 1u);
  EXPECT_EQ(back.variants[0].summary, "panel at 0.0 deg: 6 luminaires, goals missed");
  EXPECT_EQ(back.goals[1].kind, "goal");
  std::ostringstream os;
  print_result(os, back);
  EXPECT_TRUE(test::Contains(os.str(), "NOT MET: floor minimum 88.7 lx < 100.0 lx (by 11.3 lx, 11.3 %) on verification only",
                             "report"));
  EXPECT_TRUE(test::Contains(os.str(), "panel at 0.0 deg: 6 luminaires, goals missed", "report"));
}

// A count left out before any search reads as its reason alone; it printed as
// "infeasible as searched, 0 evaluations" though it was never searched.
TEST(ResultJson, ACountNotSearchedSaysWhyNotThatItWasInfeasible) {
  ResultRecord r = sample_record();
  const std::string why = "not searched: drew 205.3 W at the easier targets of an earlier round";
  r.attempts.push_back({5, 0, 0.0, false, 0.0, why, why});
  std::ostringstream os;
  print_result(os, r);
  const std::string text = os.str();
  EXPECT_TRUE(test::Contains(text, "  5 luminaires: " + why + "\n", "report"));
  EXPECT_FALSE(test::Contains(text, "5 luminaires: infeasible", "report"));
  EXPECT_TRUE(test::Contains(text, "4 luminaires: 123.4 W as searched, 6643 evaluations", "report"));
}

// An outcome without a layout (issue 24: every count screened out crashed the report)
// says so on the terminal and in result.json; names from files are shown escaped.
TEST(ResultJson, AnOutcomeWithoutALayoutSaysWhyAndEscapesControlCharacters) {
  ResultRecord r = sample_record();
  r.luminaires.clear();
  r.no_layout = "no luminaire count was searched (none can reach an average target at full output)";
  r.variants.resize(1);
  r.variants[0].summary = "evil\x1b[2J at 0.0 deg: not searched";
  std::ostringstream os;
  print_result(os, r);
  EXPECT_TRUE(test::Contains(os.str(), "NO LAYOUT: no luminaire count was searched", "report"));
  EXPECT_TRUE(test::Contains(os.str(), "evil\\x1b[2J", "report"));
  EXPECT_FALSE(test::Contains(os.str(), "\x1b", "report"));
  test::TempDir dir;
  write_result_json(dir.file("result.json"), r);
  EXPECT_EQ(read_result_json(dir.file("result.json")).no_layout, r.no_layout);
}

TEST(ResultJson, NotAResultIsAClearError) {
  test::TempDir dir;
  const std::string missing = dir.file("none.json");
  EXPECT_TRUE(test::Contains(test::error_of<std::runtime_error>([&] { read_result_json(missing); }),
                             missing + ": cannot open the result file"));
  const std::string broken = dir.write("broken.json", "{\"luminaires\": [");
  EXPECT_TRUE(test::Contains(test::error_of<std::runtime_error>([&] { read_result_json(broken); }),
                             broken + ": not valid JSON"));
  const std::string other = dir.write("other.json", "{\"luminaires\": []}");
  EXPECT_TRUE(test::Contains(test::error_of<std::runtime_error>([&] { read_result_json(other); }),
                             other + ": not an ilp result"));
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// Scenarios (issue 38) round-trip, print under their name, and a missed scenario line is
// named in the verdict (NOT MET names every failing line, a scenario's too).
TEST(ResultJson, ScenariosRoundTripAndAMissedScenarioLineIsNamed) {
  test::TempDir dir;
  ResultRecord r = sample_record();
  r.goals[1].met = true;  // every goal met: only the scenario misses
  r.goals[1].fails_only_on_verification = false;
  GoalRecord emergency{"floor", {"floor"}, "minimum", "lx", 1.0, 0.6, 0.55, false, false, 1e-4, ""};
  r.scenarios = {{"emergency", "direct", 1, 2, 2.72, false, {emergency}}};
  write_result_json(dir.file("result.json"), r);
  const ResultRecord back = read_result_json(dir.file("result.json"));
  ASSERT_EQ(back.scenarios.size(), 1u);
  EXPECT_EQ(back.scenarios[0].name, "emergency");
  EXPECT_EQ(back.scenarios[0].light, "direct");
  EXPECT_EQ(back.scenarios[0].lit, 1);
  EXPECT_EQ(back.scenarios[0].luminaires, 2);
  EXPECT_EQ(back.scenarios[0].power_w, 2.72);
  ASSERT_EQ(back.scenarios[0].goals.size(), 1u);
  EXPECT_EQ(back.scenarios[0].goals[0].verified, 0.55);
  std::ostringstream text;
  print_result(text, back);
  EXPECT_TRUE(test::Contains(text.str(), "Scenario 'emergency' (direct light, 1 of 2 luminaires lit, 2.7 W): NOT MET", "heading"));
  EXPECT_TRUE(test::Contains(text.str(), "scenario 'emergency': floor minimum", "verdict"));
  EXPECT_TRUE(test::Contains(text.str(), "NOT MET in a scenario", "kind of miss"));
  EXPECT_FALSE(test::Contains(text.str(), "older ilp", "no false alarm"));
  // Without scenarios result.json has no key for them (the shipped jobs' files unchanged).
  ResultRecord none = sample_record();
  write_result_json(dir.file("none.json"), none);
  EXPECT_FALSE(test::Contains(test::read_file(dir.file("none.json")), "\"scenarios\"", "no key"));
}

}  // namespace
}  // namespace ilp
