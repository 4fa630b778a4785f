// The shipped office_products job end to end (issue 19): the layout a designer would
// build, a regular field of real luminaires, judged from the result.json it writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "output/result_record.h"
#include "tests/apps/cli_runner.h"
#include "tests/test_support.h"

namespace {

using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;

// The distinct values of a coordinate (within 1 mm), ascending.
std::vector<double> distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::vector<double> out;
  for (double x : v)
    if (out.empty() || x - out.back() > 1e-3) out.push_back(x);
  return out;
}

// Equal steps between sorted values, within the tolerance.
void expect_equal_spacing(const std::vector<double>& at, double tolerance_m, const char* axis) {
  for (std::size_t i = 2; i < at.size(); ++i)
    EXPECT_NEAR(at[i] - at[i - 1], at[1] - at[0], tolerance_m) << axis << " spacing " << i;
}

// A shipped job's text with its ../data/ paths made absolute (the test writes it elsewhere).
std::string shipped_job(const std::string& name) {
  std::string text = ilp::test::read_file(ILP_SOURCE_DIR "/configs/" + name);
  for (std::size_t at; (at = text.find("../data/")) != std::string::npos;) text.replace(at, 8, ILP_SOURCE_DIR "/data/");
  return text;
}

// That job, its verification at 256 rays (the shipped 1024 take longer), written to `dir`.
std::string shipped_job_at_256_rays(const TempDir& dir, const std::string& name) {
  std::string text = shipped_job(name);
  const std::size_t rays = text.find("  rays_per_patch: 1024");
  EXPECT_NE(rays, std::string::npos) << name;
  if (rays != std::string::npos) text.replace(rays, 22, "  rays_per_patch: 256");
  return dir.write(name, text);
}

// The shipped job with its field block replaced by `layout: free` (the mesh and
// photometry paths made absolute): the same job searched without regularity.
std::string office_products_free(const TempDir& dir) {
  std::string text = shipped_job("office_products.yaml");
  const std::size_t layout = text.find("  layout: field");
  const std::size_t ratio = text.find("edge_ratio", layout);
  EXPECT_NE(layout, std::string::npos);
  EXPECT_NE(ratio, std::string::npos);
  if (layout == std::string::npos || ratio == std::string::npos) return "";
  text.replace(layout, text.find('\n', ratio) - layout, "  layout: free");
  return dir.write("office_products_free.yaml", text);
}

// Issue 19: the field meets every goal with one output, centred, equally spaced, and
// draws at most 3 % more than the free search of the same job (the operator is
// shared through the cache: both jobs lay the same candidates).
TEST(IlpLayouts, OfficeProductsIsACentredFieldAtOneOutputThatMeetsEveryGoal) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"run", ILP_SOURCE_DIR "/configs/office_products.yaml", "--out", dir.file("out"),
                                    "--cache", dir.file("cache"), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ilp::ResultRecord result = ilp::read_result_json(dir.file("out/result.json"));
  EXPECT_EQ(result.layout_family, "field");
  EXPECT_NE(result.arrangement.find("field"), std::string::npos);
  ASSERT_GE(result.luminaires.size(), 2u);
  std::vector<double> xs, ys;
  for (const ilp::LuminaireRecord& l : result.luminaires) {
    xs.push_back(l.x_m);
    ys.push_back(l.y_m);
    EXPECT_EQ(l.flux_lm, result.luminaires[0].flux_lm) << l.id << ": one output for the field";
    EXPECT_EQ(l.product, result.luminaires[0].product);
  }
  const std::vector<double> columns = distinct(xs), rows = distinct(ys);
  EXPECT_EQ(columns.size() * rows.size(), result.luminaires.size()) << "every row has every column";
  expect_equal_spacing(columns, 0.01, "x");
  expect_equal_spacing(rows, 0.01, "y");
  // The office's room is [0, 6] x [0, 4] m.
  EXPECT_NEAR(0.5 * (columns.front() + columns.back()), 3.0, 0.02);
  EXPECT_NEAR(0.5 * (rows.front() + rows.back()), 2.0, 0.02);
  EXPECT_TRUE(result.all_met);
  for (const ilp::GoalRecord& g : result.goals) {
    ASSERT_TRUE(g.verified.has_value()) << g.name;
    EXPECT_TRUE(g.met) << g.name << " " << g.metric;
  }
  // Issue 20: the office row of EN 12464-1:2021 (preset office_writing) as verified lines:
  // UGR_L 19 at the four seated observers, Ez,m 150 lx (U0 0.10) at 1.2 m, walls 150 lx and
  // ceiling 100 lx (U0 0.10), each with its value.
  std::map<std::string, const ilp::GoalRecord*> line;
  for (const ilp::GoalRecord& g : result.goals) line[g.name + " " + g.metric] = &g;
  const std::map<std::string, double> row = {{"work_plane UGR", 19.0},        {"work_plane cylindrical", 150.0},
                                             {"work_plane cylindrical U0", 0.10}, {"walls average", 150.0},
                                             {"walls uniformity", 0.10},      {"ceiling average", 100.0},
                                             {"ceiling uniformity", 0.10}};
  for (const auto& [label, target] : row) {
    ASSERT_TRUE(line.count(label)) << label;
    const ilp::GoalRecord& g = *line[label];
    EXPECT_DOUBLE_EQ(g.target, target) << label;
    ASSERT_TRUE(g.verified) << label;
    if (label == "work_plane UGR") {
      EXPECT_LE(*g.verified, 19.0);
      EXPECT_GT(*g.verified, 10.0) << "a value, not a placeholder";
    } else {
      EXPECT_GE(*g.verified, target) << label;
    }
  }

  const std::string free_job = office_products_free(dir);
  const RunResult f = run_ilp(dir, {"run", free_job, "--out", dir.file("free"), "--cache", dir.file("cache"), "-q"});
  ASSERT_EQ(f.exit_code, 0) << f.err;
  const ilp::ResultRecord free = ilp::read_result_json(dir.file("free/result.json"));
  EXPECT_EQ(free.layout_family, "free");
  EXPECT_TRUE(free.all_met);
  EXPECT_LE(result.power_w, 1.03 * free.power_w) << "field " << result.power_w << " W, free " << free.power_w << " W";
}

// Issue 19, items 4 and 5: the shipped two-group job. The ceiling field is placed, the
// wall row searched: every luminaire it places stands on the south wall (y = 0) at 2.6 m
// above the floor, one row at one output of the tilted product, and the feature wall's
// grid and the work plane meet their goals as verified. Verification at 256 rays (the
// job's 1024 take longer; the figures in docs/layouts.md are at 1024).
TEST(IlpLayouts, OfficeWallWashIsAWallRowAimedAtTheFeatureWallThatMeetsEveryGoal) {
  TempDir dir;
  const std::string job = shipped_job_at_256_rays(dir, "office_wallwash.yaml");
  const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out"), "--cache", dir.file("cache"), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ilp::ResultRecord result = ilp::read_result_json(dir.file("out/result.json"));
  EXPECT_EQ(result.layout_family, "rows");
  ASSERT_GE(result.luminaires.size(), 1u);
  for (const ilp::LuminaireRecord& l : result.luminaires) {
    EXPECT_EQ(l.product, "wall linear LED") << l.id << ": the tilted product";
    EXPECT_LT(l.y_m, 0.1) << l.id << ": on the south wall";
    EXPECT_NEAR(l.y_m, result.luminaires[0].y_m, 1e-9) << l.id << ": one line";
    ASSERT_TRUE(l.above_floor_m.has_value()) << l.id;
    EXPECT_NEAR(*l.above_floor_m, 2.6, 1e-9) << l.id;
    EXPECT_EQ(l.flux_lm, result.luminaires[0].flux_lm) << l.id << ": one output";
    EXPECT_EQ(l.tilt_deg, 65.0) << l.id << ": aimed as the product says";
    EXPECT_EQ(l.rotation_deg, 90.0) << l.id << ": C0 along +y, into the room";
  }
  EXPECT_TRUE(result.all_met);
  bool wall_goal = false;
  for (const ilp::GoalRecord& g : result.goals) {
    ASSERT_TRUE(g.verified.has_value()) << g.name;
    EXPECT_TRUE(g.met) << g.name << " " << g.metric;
    if (g.name == "north_wall" && g.metric == "average") {
      wall_goal = true;
      EXPECT_GE(*g.verified, 650.0);
    }
  }
  EXPECT_TRUE(wall_goal) << "the feature wall's average is a goal line";
}

// The shipped wall job with one key changed: each refusal names the file, line and key,
// exits 1 and writes nothing.
TEST(IlpLayouts, BadWallMountingExitsOneNamingFileLineAndKeyAndWritesNothing) {
  const std::string shipped = ilp::test::read_file(ILP_SOURCE_DIR "/configs/office_wallwash.yaml");
  struct Case {
    std::string from, to, expected;
  };
  const std::vector<Case> cases = {
      {"height_m: 2.6, facing: +y}", "height_m: 3.2, facing: +y}",
       "luminaires.on_wall.height_m = 3.2: at z = 3.2 m, at or above the top of the scene"},
      {"height_m: 2.6, facing: +y}", "height_m: 2.6, facing: up}", "luminaires.on_wall.facing = up: must be +x"},
      {"on_wall: {surface: walls,", "on_wall: {surface: floor,", "luminaires.on_wall.surface: wall 'floor' has no patch facing +y"},
      {"  layout: rows ", "  zone: {rectangle_m: [[7, 0], [9, 4]]}\n  layout: rows ",
       "luminaires.zone: wall 'walls': the mounting zone x [7, 9] m holds no luminaire position along it"},
      {"tilt_deg: 65 ", "tilt_deg: 95 ", "tilt_deg = 95: must be in [0, 90] degrees"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    TempDir dir;
    std::string text = shipped;
    for (std::size_t at; (at = text.find("../data/")) != std::string::npos;) text.replace(at, 8, ILP_SOURCE_DIR "/data/");
    const std::size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, c.from.size(), c.to);
    const std::string job = dir.write("job.yaml", text);
    const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out"), "--cache", dir.file("cache"), "-q"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(job + ":"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << "nothing written";
  }
}

// The shipped two-group job (configs/office_two_groups.yaml) at 256 verification rays:
// a ceiling field and a wall row searched together, each its own product at its own one
// output, billed together, every goal met as verified.
TEST(IlpLayouts, OfficeTwoGroupsSearchesAFieldAndAWallRowTogetherThatMeetEveryGoal) {
  TempDir dir;
  const std::string job = shipped_job_at_256_rays(dir, "office_two_groups.yaml");
  const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out"), "--cache", dir.file("cache"), "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("groups searched together:"), std::string::npos) << "the run log counts the pairs";
  const ilp::ResultRecord result = ilp::read_result_json(dir.file("out/result.json"));
  std::map<std::string, std::vector<ilp::LuminaireRecord>> by_group;
  for (const ilp::LuminaireRecord& l : result.luminaires) by_group[l.group].push_back(l);
  ASSERT_EQ(by_group.size(), 2u);
  ASSERT_EQ(by_group.count("general"), 1u);
  ASSERT_EQ(by_group.count("wall wash"), 1u);
  double sum_w = 0.0;
  for (const auto& [group, members] : by_group) {
    const std::string prefix = group == "general" ? "A" : "B";
    for (const ilp::LuminaireRecord& l : members) {
      EXPECT_EQ(l.id.substr(0, 1), prefix) << l.id << ": labelled by its group";
      EXPECT_EQ(l.flux_lm, members.front().flux_lm) << l.id << ": one output per group";
      EXPECT_EQ(l.product, group == "general" ? "linear LED 2112 lm" : "wall linear LED") << l.id;
      sum_w += l.power_w;
    }
  }
  for (const ilp::LuminaireRecord& l : by_group["general"]) EXPECT_NEAR(l.z_m, 2.95, 1e-6) << l.id << ": on the ceiling";
  for (const ilp::LuminaireRecord& l : by_group["wall wash"]) {
    EXPECT_LT(l.y_m, 0.1) << l.id << ": on the south wall";
    EXPECT_EQ(l.tilt_deg, 65.0) << l.id;
  }
  EXPECT_NE(by_group["general"].front().flux_lm, by_group["wall wash"].front().flux_lm) << "each group its own output";
  ASSERT_EQ(result.bill_of_materials.size(), 2u);
  double billed_w = 0.0;
  for (const ilp::BillLine& b : result.bill_of_materials) {
    EXPECT_EQ(static_cast<std::size_t>(b.count), by_group[b.group].size()) << b.group;
    billed_w += b.total_power_w;
  }
  EXPECT_NEAR(result.power_w, sum_w, 1e-6);
  EXPECT_NEAR(result.power_w, billed_w, 1e-6);
  EXPECT_NEAR(result.power_density_w_per_m2, result.power_w / result.floor_area_m2, 1e-9);
  EXPECT_TRUE(result.all_met);
  ASSERT_EQ(result.goals.size(), 4u);
  for (const ilp::GoalRecord& g : result.goals) {
    ASSERT_TRUE(g.verified.has_value()) << g.name;
    EXPECT_TRUE(g.met) << g.name << " " << g.metric;
    EXPECT_GE(*g.verified, g.target) << g.name << " " << g.metric;
  }
}

// The shipped two-group job with one key changed: each refusal names the file, line and
// key, exits 1 and writes nothing.
TEST(IlpLayouts, BadGroupsExitOneNamingFileLineAndKeyAndWritesNothing) {
  const std::string shipped = shipped_job("office_two_groups.yaml");
  const std::size_t groups_at = shipped.find("  groups:\n"), grids_at = shipped.find("\ngrids:");
  ASSERT_NE(groups_at, std::string::npos);
  ASSERT_NE(grids_at, std::string::npos);
  struct Case {
    std::string from, to, expected;
  };
  const std::vector<Case> cases = {
      {"    - name: wall wash", "    - name: general", "luminaires.groups[1].name = general: group name 'general' is used twice"},
      {shipped.substr(groups_at, grids_at - groups_at), "  groups: []", "luminaires.groups = [...]: must list at least one group"},
      {"  groups:\n", "  mounting_surface: ceiling\n  groups:\n",
       "luminaires.mounting_surface = ceiling: not with luminaires.groups"},
      {"      layout: field\n", "      colour: red\n      layout: field\n", "unknown key 'luminaires.groups[0].colour'"},
      {"      layout: field\n      field: {rows: [1, 4], columns: [1, 6], edge_ratio: [0.3, 1.0]}\n", "      layout: free\n",
       "luminaires.groups[0].layout = free: must be field, rows or bays"},
      {"      products: [wall linear LED]", "      products: [wall washer]", "luminaires.groups[1].products[0] = wall washer: unknown product"},
      {"      mounting_surface: ceiling\n      mount_offset_m: 0.05\n", "      suspended: {height_m: 0.3}\n",
       "luminaires.groups[0] ('general'): serves no goal"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    TempDir dir;
    std::string text = shipped;
    const std::size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos);
    text.replace(at, c.from.size(), c.to);
    const std::string job = dir.write("job.yaml", text);
    const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out"), "--cache", dir.file("cache"), "-q"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(job + ":"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << "nothing written";
  }
  // ilp sweep searches one group: it refuses groups before any work.
  TempDir dir;
  const std::string job = dir.write("job.yaml", shipped);
  const RunResult r = run_ilp(dir, {"sweep", job, "--set", "goals.work_plane.average_lux=400,500", "--out",
                                    dir.file("out"), "--cache", dir.file("cache"), "-q"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("luminaires.groups: ilp sweep searches one luminaire group"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out"))) << "nothing written";
}

}  // namespace
