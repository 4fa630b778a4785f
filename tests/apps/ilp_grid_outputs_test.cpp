// The calculation grids' files through the real program: `ilp run` writes grid.csv and
// an isolux plan per grid (SVG and PNG) from the values it reports, output.formats
// selects them (a bad entry is an error at its line), `ilp solve` prints the per-grid
// table for the placed luminaires and writes the grid files, and `ilp accuracy`
// measures the operator at grid points.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tests/apps/cli_runner.h"
#include "tests/optimizer/optimizer_test_scenes.h"
#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::lines_of;
using ilp::test::OutputContains;
using ilp::test::read_file;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, sep);)
    if (sep != ' ' || !field.empty()) out.push_back(field);
  return out;
}

// A work plane over the 4 x 4 m floor less a 0.5 m band at 0.5 m: 6 x 6 = 36 points;
// a strip without a goal: 3 x 0.5 m at 0.5 m, 6 x 1 = 6 points.
constexpr int kWorkPlanePoints = 36, kStripPoints = 6;
const char* kGrids =
    "grids:\n"
    "  - name: work_plane\n"
    "    over_surface: floor\n"
    "    height_m: 0.8\n"
    "    border_m: 0.5\n"
    "    spacing_m: 0.5\n"
    "  - name: strip\n"
    "    rectangle_m: [[0.5, 0.5], [3.5, 1.0]]\n"
    "    height_m: 0.8\n"
    "    border_m: 0\n"
    "    spacing_m: 0.5\n"
    "maintenance_factor: 0.8\n";

// The search job: one luminaire, the work plane 200 lx maintained on average.
std::string grid_job(const TempDir& dir, const std::string& output = "") {
  dir.write("room.obj", ilp::test::room_obj({{"mat", {1.3, 1.7}}}));
  const std::string luminaires =
      "  size_m: 0.3\n  flux_lm: [10, 20000]\n  efficacy_lm_per_w: 100\n  mounting_surface: ceiling\n"
      "  candidate_spacing_m: 0.5\n  count: 1\n";
  const std::string goals = "  - grid: work_plane\n    average_lux: 200\n";
  std::string job = ilp::test::room_job("0.4", luminaires, goals,
                                        "optimizer:\n  max_evaluations: 400\n  local_max_evaluations: 400\n" + output);
  job.insert(job.find("goals:\n"), kGrids);
  return dir.write("job.yaml", job);
}

// The fixed job for `ilp solve`: one placed luminaire, the same grids, no search.
std::string fixed_grid_job(const TempDir& dir) {
  dir.write("room.obj", ilp::test::room_obj({{"mat", {1.3, 1.7}}}));
  return dir.write("fixed.yaml", std::string("scene:\n  mesh: room.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0.4\n"
                                             "luminaires:\n  size_m: 0.3\n  placed:\n"
                                             "    - {name: P1, position_m: [2, 2, 2.45], flux_lm: 4000}\n") +
                                     kGrids + "solver:\n  rays_per_patch: 64\n  seed: 3\n  sample_fraction: 0.5\n");
}

// The report's per-grid line after the name: points, Em, Emin, Emax, U0, then maintained Em, Emin, Emax.
std::vector<double> grid_line(const std::string& report, const std::string& grid) {
  for (const std::string& line : lines_of(report)) {
    const std::vector<std::string> f = split(line, ' ');
    // The goal lines start with the name too ("work_plane average (lx)"): the table's has a count next.
    if (f.size() >= 10 && f[0] == grid && f[1].find_first_not_of("0123456789") == std::string::npos) {
      std::vector<double> v;
      for (std::size_t k = 1; k < 9; ++k) v.push_back(std::stod(f[k]));
      return v;
    }
  }
  return {};
}

struct CsvGrid {
  int points = 0;
  double total_initial = 0.0, total_maintained = 0.0;  // sums
};

// grid.csv by grid name.
std::map<std::string, CsvGrid> read_grid_csv(const std::string& path) {
  const std::vector<std::string> rows = lines_of(read_file(path));
  EXPECT_FALSE(rows.empty());
  if (rows.empty()) return {};
  EXPECT_EQ(rows[0],
            "grid,point,x_m,y_m,z_m,direct_initial_lux,total_initial_lux,maintenance_factor,direct_maintained_lux,"
            "total_maintained_lux");
  std::map<std::string, CsvGrid> out;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string> f = split(rows[i], ',');
    EXPECT_EQ(f.size(), 10u) << rows[i];
    if (f.size() != 10u) continue;
    CsvGrid& g = out[f[0]];
    EXPECT_EQ(std::stoi(f[1]), g.points) << "points in order";
    ++g.points;
    g.total_initial += std::stod(f[6]);
    g.total_maintained += std::stod(f[9]);
  }
  return out;
}

bool png_header(const std::string& path) {
  const std::string bytes = read_file(path);
  return bytes.size() > 24 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0 && bytes.compare(12, 4, "IHDR") == 0;
}

TEST(IlpRunGrids, WritesGridCsvAndIsoluxPlansFromTheReportedValues) {
  TempDir dir;
  const std::string out = dir.file("out");
  const RunResult r = run_ilp(dir, {"run", grid_job(dir), "--out", out, "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const std::vector<double> plane = grid_line(r.out, "work_plane"), strip = grid_line(r.out, "strip");
  ASSERT_EQ(plane.size(), 8u) << r.out;
  ASSERT_EQ(strip.size(), 8u) << "a grid without a goal is reported too\n" << r.out;
  EXPECT_EQ(plane[0], kWorkPlanePoints);
  EXPECT_EQ(strip[0], kStripPoints);
  EXPECT_NEAR(plane[5], 200.0 * 1.005, 0.05) << "the verified maintained Em meets the target by the 0.5 % margin";

  const std::map<std::string, CsvGrid> csv = read_grid_csv((fs::path(out) / "grid.csv").string());
  ASSERT_EQ(csv.size(), 2u);
  const CsvGrid& wp = csv.at("work_plane");
  EXPECT_EQ(wp.points, kWorkPlanePoints);
  EXPECT_EQ(csv.at("strip").points, kStripPoints);
  // The csv's average is the report's Em (printed to 0.1 lx; the csv holds 0.01 lx).
  EXPECT_NEAR(wp.total_initial / wp.points, plane[1], 0.06);
  EXPECT_NEAR(wp.total_maintained / wp.points, plane[5], 0.06);
  EXPECT_NEAR(csv.at("strip").total_maintained / kStripPoints, strip[5], 0.06);

  for (const char* grid : {"work_plane", "strip"}) {
    const fs::path svg = fs::path(out) / (std::string("isolux_") + grid + ".svg");
    const fs::path png = fs::path(out) / (std::string("isolux_") + grid + ".png");
    ASSERT_TRUE(fs::exists(svg)) << svg;
    EXPECT_TRUE(OutputContains(read_file(svg.string()), "<svg"));
    EXPECT_TRUE(OutputContains(read_file(svg.string()), "L1")) << "the luminaire is drawn";
    EXPECT_TRUE(png_header(png.string())) << png;
  }
  EXPECT_TRUE(OutputContains(read_file((fs::path(out) / "isolux_work_plane.svg").string()), "target"));
  EXPECT_TRUE(OutputContains(read_file((fs::path(out) / "isolux_strip.svg").string()), "no target"));
  const std::string json = read_file((fs::path(out) / "result.json").string());
  for (const char* part : {"\"files\"", "\"grid.csv\"", "\"isolux_work_plane.png\"", "\"isolux_strip.svg\"", "\"grids\""})
    EXPECT_TRUE(OutputContains(json, part)) << part;
  EXPECT_TRUE(OutputContains(r.out, "wrote " + out + "/grid.csv"));
  // Every goal is on a grid, so no goal patch: the PLY's colour scale ran 0 .. 1 lx and
  // painted nearly every face one colour (issue 20). It spans the values it shows now.
  const std::string ply = read_file((fs::path(out) / "scene.ply").string());
  const std::string comment = "comment ilp illuminance, lux from 0 to ";
  const auto at = ply.find(comment);
  ASSERT_NE(at, std::string::npos);
  const double top = std::stod(ply.substr(at + comment.size(), ply.find('\n', at) - at - comment.size()));
  EXPECT_GE(top, 200.0) << "at least the work plane's level";
  EXPECT_LE(top, 20000.0);
}

TEST(IlpRunGrids, OutputFormatsSelectTheGridFilesAndALeftOutOneIsRemoved) {
  TempDir dir;
  const std::string out = dir.file("out");
  ASSERT_EQ(run_ilp(dir, {"run", grid_job(dir), "--out", out, "-q"}).exit_code, 0);
  ASSERT_TRUE(fs::exists(fs::path(out) / "isolux_work_plane.png"));
  const RunResult r =
      run_ilp(dir, {"run", grid_job(dir, "output:\n  formats: [json, grid_csv]\n"), "--out", out, "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(fs::path(out) / "grid.csv"));
  EXPECT_TRUE(fs::exists(fs::path(out) / "result.json"));
  for (const char* gone : {"isolux_work_plane.svg", "isolux_work_plane.png", "isolux_strip.png", "plan.svg"})
    EXPECT_FALSE(fs::exists(fs::path(out) / gone)) << gone << ": the previous run's file of a format left out";
}

TEST(IlpRunGrids, BadOutputFormatIsAnErrorAtItsLine) {
  TempDir dir;
  const std::string job = grid_job(dir, "output:\n  formats: [json, isolux]\n");
  const int line = [&] {
    const std::vector<std::string> lines = lines_of(read_file(job));
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (lines[i].find("formats:") != std::string::npos) return static_cast<int>(i) + 1;
    return -1;
  }();
  const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out")});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(OutputContains(r.err, "error: " + job + ":" + std::to_string(line) + ":")) << r.err;
  EXPECT_TRUE(OutputContains(r.err, "output.formats"));
  EXPECT_TRUE(OutputContains(r.err, "isolux: must be one of json, csv, svg, ply, grid_csv, isolux_svg, isolux_png, plan_png"));
  EXPECT_FALSE(fs::exists(dir.file("out")));

  // A grid format in a job without grids.
  TempDir plain;
  plain.write("room.obj", ilp::test::room_obj({{"mat", {1.3, 1.7}}}));
  const std::string no_grids = plain.write(
      "job.yaml", ilp::test::room_job("0.4", "  size_m: 0.3\n  flux_lm: [10, 20000]\n  mounting_surface: ceiling\n",
                                      "  - surface: mat\n    average_lux: 100\n",
                                      "output:\n  formats: [json, grid_csv]\n"));
  const RunResult e = run_ilp(plain, {"run", no_grids, "--out", plain.file("out")});
  EXPECT_EQ(e.exit_code, 1);
  EXPECT_TRUE(OutputContains(e.err, "grid_csv: needs calculation grids")) << e.err;
}

TEST(IlpSolveGrids, PrintsTheGridTableForThePlacedLuminairesAndWritesTheGridFiles) {
  TempDir dir;
  const std::string job = fixed_grid_job(dir);
  std::map<std::string, std::vector<double>> em;
  for (const char* method : {"sample", "exact"}) {
    SCOPED_TRACE(method);
    const std::string out = dir.file(std::string("solve_") + method);
    const RunResult r = run_ilp(dir, {"solve", job, "--method", method, "--out", out, "-q"});
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(OutputContains(r.out, "Illuminance per calculation grid"));
    const std::vector<double> plane = grid_line(r.out, "work_plane");
    ASSERT_EQ(plane.size(), 8u) << r.out;
    EXPECT_EQ(plane[0], kWorkPlanePoints);
    EXPECT_GT(plane[1], 0.0);
    EXPECT_NEAR(plane[5], 0.8 * plane[1], 0.1) << "maintained = initial x 0.8";
    em[method] = plane;
    const std::map<std::string, CsvGrid> csv = read_grid_csv((fs::path(out) / "grid.csv").string());
    ASSERT_EQ(csv.count("work_plane"), 1u);
    EXPECT_EQ(csv.at("work_plane").points, kWorkPlanePoints);
    EXPECT_NEAR(csv.at("work_plane").total_initial / kWorkPlanePoints, plane[1], 0.06);
    EXPECT_TRUE(png_header((fs::path(out) / "isolux_work_plane.png").string()));
    EXPECT_TRUE(OutputContains(read_file((fs::path(out) / "isolux_work_plane.svg").string()), "P1"));
  }
  // The operator (half the patches sampled) and the exact solve agree on the grid's Em.
  EXPECT_NEAR(em["sample"][1], em["exact"][1], 0.05 * em["exact"][1]);
}

TEST(IlpAccuracyGrids, ReportsTheErrorAtGridPoints) {
  TempDir dir;
  const std::string job = fixed_grid_job(dir), out = dir.file("acc");
  const RunResult r = run_ilp(dir, {"accuracy", job, "--fractions", "0.5,1", "--seeds", "1", "--rays", "64",
                                    "--reference-rays", "256", "--goals", "floor", "--out", out, "-q"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(OutputContains(r.out, "42 grid points"));
  EXPECT_TRUE(OutputContains(r.out, "at grid points"));
  int lines = 0;
  for (const std::string& line : lines_of(r.out)) {
    const std::vector<std::string> f = split(line, ' ');
    const auto at = std::find(f.begin(), f.end(), "work_plane");
    if (at == f.end() || f.end() - at != 4) continue;
    ++lines;
    const double rms = std::stod(at[2]), max = std::stod(at[3]);
    EXPECT_GE(rms, 0.0);
    EXPECT_GE(max, rms);
    EXPECT_LT(rms, 15.0) << line;  // per cent: ray noise of 64- and 256-ray rows at worst
  }
  EXPECT_EQ(lines, 2) << "one line per sample size\n" << r.out;
  const std::vector<std::string> csv = lines_of(read_file((fs::path(out) / "accuracy.csv").string()));
  ASSERT_FALSE(csv.empty());
  EXPECT_TRUE(OutputContains(csv[0], ",grid.work_plane.rms_rel_error_total,grid.work_plane.max_rel_error_total,"
                                     "grid.strip.rms_rel_error_total,grid.strip.max_rel_error_total"));
}

}  // namespace
