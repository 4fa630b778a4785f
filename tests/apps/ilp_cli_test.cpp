// Runs the real `ilp` program (ILP_BINARY) on small jobs written to a temporary
// folder and checks its contract: exit status, one "error: file:line: ..." line on
// stderr for bad input, nothing on stdout and no output file after a failure, and
// the illuminance table and per-patch CSV after a good run.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::read_file;
using ilp::test::TempDir;

// For EXPECT_TRUE: what the program wrote contains `part`.
::testing::AssertionResult Contains(const std::string& text, const std::string& part) {
  return ilp::test::Contains(text, part, "output");
}

std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct RunResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Runs `ilp <args>` with stdout and stderr captured to files in `dir`.
RunResult run_ilp(const TempDir& dir, const std::vector<std::string>& args) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  std::ostringstream command;  // (string + on GCC 12 trips a false -Wrestrict)
  command << quoted(ILP_BINARY);
  for (const std::string& a : args) command << ' ' << quoted(a);
  command << " >" << quoted(out) << " 2>" << quoted(err) << " </dev/null";
  const int status = std::system(command.str().c_str());
  RunResult r;
  r.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::istringstream in(line);
  for (std::string field; std::getline(in, field, ',');) out.push_back(field);
  return out;
}

// The error contract: non-zero exit, one stderr line "error: <file>:<line>:...",
// nothing on stdout, no CSV (nor its temporary) left behind.
void expect_clean_failure(const RunResult& r, const std::string& located, const std::string& csv) {
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.out, "") << "stdout must stay empty on failure";
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "stderr must be one line:\n" << r.err;
  EXPECT_EQ(r.err.back(), '\n');
  EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
  EXPECT_TRUE(Contains(r.err, "error: " + located)) << "location must come first";
  EXPECT_FALSE(fs::exists(csv)) << csv;
  EXPECT_FALSE(fs::exists(csv + ".tmp")) << csv << ".tmp";
}

// Runs `ilp solve <yaml> --csv <dir>/out.csv`, which must fail cleanly with the
// error located at `located` (see expect_clean_failure).
RunResult solve_fails_cleanly(const TempDir& dir, const std::string& yaml, const std::string& located) {
  const std::string csv = dir.file("out.csv");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--csv", csv});
  expect_clean_failure(r, located, csv);
  return r;
}

// A closed 2 m cube, every face towards the inside (counter-clockwise seen from
// within): groups floor, ceiling, walls.
const char* kBoxObj =
    "# 2 m box, faces pointing in\n"
    "v 0 0 0\n"
    "v 2 0 0\n"
    "v 2 2 0\n"
    "v 0 2 0\n"
    "v 0 0 2\n"
    "v 2 0 2\n"
    "v 2 2 2\n"
    "v 0 2 2\n"
    "g floor\n"
    "f 1 2 3 4\n"
    "g ceiling\n"
    "f 5 8 7 6\n"
    "g walls\n"
    "f 1 5 6 2\n"
    "f 4 3 7 8\n"
    "f 1 4 8 5\n"
    "f 2 6 7 3\n";

const char* kBoxYaml =
    "scene:\n"
    "  mesh: box.obj\n"
    "  max_patch_edge_m: 0.5\n"
    "  reflectance:\n"
    "    floor: 0.5\n"
    "    ceiling: 0.5\n"
    "    walls: 0.5\n"
    "luminaires:\n"
    "  size_m: 0.4\n"
    "  placed:\n"
    "    - {name: L1, position_m: [1, 1, 1.95], flux_lm: 1000}\n"
    "solver:\n"
    "  rays_per_patch: 64\n"
    "  seed: 3\n";

// Each 2 m face: two right triangles with a 2.83 m hypotenuse, cut into 6 x 6 = 36
// patches each; 6 faces, plus the luminaire's 2 patches.
constexpr std::size_t kBoxPatches = 6 * 2 * 36 + 2;

TEST(IlpCli, BadReflectanceFailsCleanly) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: box.obj\n"
                                     "  reflectance:\n"
                                     "    floor: 1.5\n"
                                     "    ceiling: 0.5\n"
                                     "    walls: 0.5\n");
  const RunResult r = solve_fails_cleanly(dir, yaml, yaml + ":4:");
  EXPECT_TRUE(Contains(r.err, "scene.reflectance.floor"));
  EXPECT_TRUE(Contains(r.err, "[0, 1)"));
}

TEST(IlpCli, MissingMeshFailsCleanly) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "# the mesh is not there\n"
                                     "scene:\n"
                                     "  mesh: gone.obj\n"
                                     "  default_reflectance: 0.5\n");
  const RunResult r = solve_fails_cleanly(dir, yaml, yaml + ":3:");
  EXPECT_TRUE(Contains(r.err, "scene.mesh"));
  EXPECT_TRUE(Contains(r.err, dir.file("gone.obj")));
}

TEST(IlpCli, BadMeshLineFailsCleanly) {
  TempDir dir;
  const std::string obj = dir.write("box.obj", std::string(kBoxObj) + "v 1 nan 1\n");
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const RunResult r = solve_fails_cleanly(dir, yaml, yaml + ":2:");
  EXPECT_TRUE(Contains(r.err, obj + ":19:"));
}

TEST(IlpCli, FailureLeavesAnExistingCsvAlone) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: box.obj\n  up_axis: x\n");
  const std::string csv = dir.write("out.csv", "old results\n");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--csv", csv});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(Contains(r.err, yaml + ":3:"));
  EXPECT_TRUE(Contains(r.err, "scene.up_axis"));
  EXPECT_EQ(read_file(csv), "old results\n");
}

TEST(IlpCli, MissingConfigFile) {
  TempDir dir;
  const std::string yaml = dir.file("nothere.yaml");
  const std::string csv = dir.file("out.csv");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--csv", csv});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(Contains(r.err, yaml));
  EXPECT_FALSE(fs::exists(csv));
}

TEST(IlpCli, NoSubcommandIsAnError) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(Contains(r.err, "subcommand"));
}

TEST(IlpCli, SolveHelp) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"solve", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(Contains(r.out, "--csv"));
  EXPECT_TRUE(Contains(r.out, "--threads"));
  EXPECT_TRUE(Contains(r.out, "config"));
}

TEST(IlpCli, SolvesATinyBox) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const std::string csv = dir.file("out.csv");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--csv", csv, "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << "stderr:\n" << r.err;
  EXPECT_TRUE(Contains(r.out, "Eavg lux"));
  EXPECT_TRUE(Contains(r.out, "U0"));
  for (const char* surface : {"floor", "ceiling", "walls", "L1"}) {
    bool listed = false;
    for (const std::string& line : lines_of(r.out)) listed |= line.rfind(surface, 0) == 0;
    EXPECT_TRUE(listed) << surface << " has no row in\n" << r.out;
  }
  EXPECT_TRUE(Contains(r.out, csv));
  EXPECT_FALSE(fs::exists(csv + ".tmp"));

  ASSERT_TRUE(fs::exists(csv));
  const std::vector<std::string> rows = lines_of(read_file(csv));
  ASSERT_EQ(rows.size(), 1 + kBoxPatches);
  const std::vector<std::string> header = split_csv(rows[0]);
  ASSERT_EQ(header.size(), 12u) << rows[0];
  EXPECT_EQ(header[0], "patch");
  EXPECT_EQ(header[1], "surface");
  EXPECT_EQ(header[8], "area_m2");
  EXPECT_EQ(header[9], "direct_lux");
  EXPECT_EQ(header[10], "total_lux");

  // Every emitted lumen lands on the closed box: the direct flux adds up to the
  // luminaire's 1000 lm, and interreflection (rho = 0.5) adds to it.
  double area = 0.0, direct_flux = 0.0, total_flux = 0.0, floor_min = 1e300;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const std::vector<std::string> f = split_csv(rows[i]);
    ASSERT_EQ(f.size(), 12u) << rows[i];
    EXPECT_EQ(f[0], std::to_string(i - 1));
    const double a = std::stod(f[8]), direct = std::stod(f[9]), total = std::stod(f[10]);
    ASSERT_TRUE(std::isfinite(direct) && std::isfinite(total)) << rows[i];
    EXPECT_GE(total, direct - 1e-9) << rows[i];
    if (f[1] == "L1") continue;
    area += a;
    direct_flux += a * direct;
    total_flux += a * total;
    if (f[1] == "floor") floor_min = std::min(floor_min, direct);
  }
  EXPECT_NEAR(area, 24.0, 1e-6);
  EXPECT_NEAR(direct_flux, 1000.0, 50.0);
  EXPECT_GT(total_flux, 1.5 * direct_flux);
  EXPECT_LT(total_flux, 2.05 * direct_flux);
  EXPECT_GT(floor_min, 0.0);  // the whole floor sees the panel
}

}  // namespace
