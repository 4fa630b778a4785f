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

#include "tests/apps/cli_runner.h"
#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::lines_of;
using ilp::test::OutputContains;
using ilp::test::read_file;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;


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
  EXPECT_TRUE(OutputContains(r.err, "error: " + located)) << "location must come first";
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

// The box job: `scene` holds the scene section's keys after the mesh, `solver` the
// solver section's keys after the ray count.
std::string box_job(const std::string& scene, const std::string& solver = "  seed: 3\n") {
  return "scene:\n"
         "  mesh: box.obj\n" +
         scene +
         "luminaires:\n"
         "  size_m: 0.4\n"
         "  placed:\n"
         "    - {name: L1, position_m: [1, 1, 1.95], flux_lm: 1000}\n"
         "solver:\n"
         "  rays_per_patch: 64\n" +
         solver;
}

const std::string kBoxYaml = box_job(
    "  max_patch_edge_m: 0.5\n"
    "  reflectance:\n"
    "    floor: 0.5\n"
    "    ceiling: 0.5\n"
    "    walls: 0.5\n");

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
  EXPECT_TRUE(OutputContains(r.err, "scene.reflectance.floor"));
  EXPECT_TRUE(OutputContains(r.err, "[0, 1)"));
}

TEST(IlpCli, MissingMeshFailsCleanly) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "# the mesh is not there\n"
                                     "scene:\n"
                                     "  mesh: gone.obj\n"
                                     "  default_reflectance: 0.5\n");
  const RunResult r = solve_fails_cleanly(dir, yaml, yaml + ":3:");
  EXPECT_TRUE(OutputContains(r.err, "scene.mesh"));
  EXPECT_TRUE(OutputContains(r.err, dir.file("gone.obj")));
}

TEST(IlpCli, BadMeshLineFailsCleanly) {
  TempDir dir;
  const std::string obj = dir.write("box.obj", std::string(kBoxObj) + "v 1 nan 1\n");
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const RunResult r = solve_fails_cleanly(dir, yaml, yaml + ":2:");
  EXPECT_TRUE(OutputContains(r.err, obj + ":19:"));
}

TEST(IlpCli, FailureLeavesAnExistingCsvAlone) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: box.obj\n  up_axis: x\n");
  const std::string csv = dir.write("out.csv", "old results\n");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--csv", csv});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(OutputContains(r.err, yaml + ":3:"));
  EXPECT_TRUE(OutputContains(r.err, "scene.up_axis"));
  EXPECT_EQ(read_file(csv), "old results\n");
}

TEST(IlpCli, MissingConfigFile) {
  TempDir dir;
  const std::string yaml = dir.file("nothere.yaml");
  const std::string csv = dir.file("out.csv");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--csv", csv});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(OutputContains(r.err, yaml));
  EXPECT_FALSE(fs::exists(csv));
}

TEST(IlpCli, NoSubcommandIsAnError) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(OutputContains(r.err, "subcommand"));
}

TEST(IlpCli, SolveHelp) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"solve", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(OutputContains(r.out, "--csv"));
  EXPECT_TRUE(OutputContains(r.out, "--threads"));
  EXPECT_TRUE(OutputContains(r.out, "config"));
}

TEST(IlpCli, SolvesATinyBox) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const std::string csv = dir.file("out.csv");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--csv", csv, "--threads", "2"});
  ASSERT_EQ(r.exit_code, 0) << "stderr:\n" << r.err;
  EXPECT_TRUE(OutputContains(r.out, "Eavg lux"));
  EXPECT_TRUE(OutputContains(r.out, "U0"));
  for (const char* surface : {"floor", "ceiling", "walls", "L1"}) {
    bool listed = false;
    for (const std::string& line : lines_of(r.out)) listed |= line.rfind(surface, 0) == 0;
    EXPECT_TRUE(listed) << surface << " has no row in\n" << r.out;
  }
  EXPECT_TRUE(OutputContains(r.out, csv));
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

// The whitespace-separated fields of the table row for `surface` on stdout; empty
// when there is none.
std::vector<std::string> table_row(const std::string& out, const std::string& surface) {
  for (const std::string& line : lines_of(out)) {
    std::istringstream in(line);
    std::vector<std::string> fields;
    for (std::string f; in >> f;) fields.push_back(f);
    if (!fields.empty() && fields[0] == surface) return fields;
  }
  return {};
}

// Eavg lux of `surface` in the illuminance table (columns: surface, patches,
// area m2, Eavg, Emin, Emax, U0); NaN when there is no such row.
double table_eavg(const std::string& out, const std::string& surface) {
  const std::vector<std::string> f = table_row(out, surface);
  if (f.size() != 7) return std::nan("");
  return std::strtod(f[3].c_str(), nullptr);
}

// A number, and whether the whole field was one and finite.
bool finite_number(const std::string& field, double* value = nullptr) {
  char* end = nullptr;
  const double v = std::strtod(field.c_str(), &end);
  if (value) *value = v;
  return !field.empty() && end == field.c_str() + field.size() && std::isfinite(v);
}

TEST(IlpCli, SolveMethodsExactAndSampleAgree) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const RunResult exact = run_ilp(dir, {"solve", yaml, "--method", "exact", "--threads", "2", "-q"});
  ASSERT_EQ(exact.exit_code, 0) << "stderr:\n" << exact.err;
  EXPECT_TRUE(OutputContains(exact.out, "exact radiosity"));
  const RunResult sample = run_ilp(dir, {"solve", yaml, "--method", "sample", "--threads", "2", "-q"});
  ASSERT_EQ(sample.exit_code, 0) << "stderr:\n" << sample.err;
  EXPECT_TRUE(OutputContains(sample.out, "sample-based operator"));
  for (const RunResult* r : {&exact, &sample}) {
    EXPECT_TRUE(OutputContains(r->out, "Eavg lux"));
    for (const char* surface : {"floor", "ceiling", "walls", "L1"})
      EXPECT_EQ(table_row(r->out, surface).size(), 7u) << surface << " has no row in\n" << r->out;
  }
  // What the sample run did, in its log.
  EXPECT_TRUE(OutputContains(sample.err, "sample:"));
  EXPECT_TRUE(OutputContains(sample.err, "condition estimate"));

  const double floor_exact = table_eavg(exact.out, "floor"), floor_sample = table_eavg(sample.out, "floor");
  ASSERT_TRUE(std::isfinite(floor_exact) && floor_exact > 0.0) << exact.out;
  ASSERT_TRUE(std::isfinite(floor_sample) && floor_sample > 0.0) << sample.out;
  EXPECT_NEAR(floor_sample / floor_exact, 1.0, 0.05) << "exact:\n" << exact.out << "sample:\n" << sample.out;
}

TEST(IlpCli, SolveMethodFromTheJobAndOverride) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml + "  method: exact\n");
  const RunResult from_job = run_ilp(dir, {"solve", yaml, "--threads", "2", "-q"});
  ASSERT_EQ(from_job.exit_code, 0) << "stderr:\n" << from_job.err;
  EXPECT_TRUE(OutputContains(from_job.out, "exact radiosity"));
  const RunResult overridden = run_ilp(dir, {"solve", yaml, "--method", "sample", "--threads", "2", "-q"});
  ASSERT_EQ(overridden.exit_code, 0) << "stderr:\n" << overridden.err;
  EXPECT_TRUE(OutputContains(overridden.out, "sample-based operator"));
}

TEST(IlpCli, SolveBogusMethodIsAUsageError) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const RunResult r = run_ilp(dir, {"solve", yaml, "--method", "bogus"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(OutputContains(r.err, "--method"));
  EXPECT_FALSE(OutputContains(r.out, "Eavg lux")) << "nothing may be solved";
}

TEST(IlpCli, SolveWithoutReflectionIsDirectLightOnly) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", box_job("  max_patch_edge_m: 0.5\n"
                                                         "  reflectance: {floor: 0, ceiling: 0, walls: 0}\n"));
  const RunResult r = run_ilp(dir, {"solve", yaml, "--threads", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << "stderr:\n" << r.err;
  EXPECT_TRUE(OutputContains(r.err, "direct light only"));
  EXPECT_GT(table_eavg(r.out, "floor"), 0.0) << r.out;
}

TEST(IlpCli, SolveTargetErrorChoosesTheSampleSize) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml + "  target_error: 0.05\n");
  const RunResult r = run_ilp(dir, {"solve", yaml, "--threads", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << "stderr:\n" << r.err;
  std::string line;
  for (const std::string& l : lines_of(r.err))
    if (l.rfind("sample size:", 0) == 0) line = l;
  ASSERT_FALSE(line.empty()) << "no \"sample size:\" line in\n" << r.err;
  EXPECT_TRUE(OutputContains(line, "needs k ="));
  EXPECT_TRUE(OutputContains(line, "of 432"));  // the reflecting patches: every patch but the panel's 2
  EXPECT_TRUE(OutputContains(r.out, "Eavg lux"));
}

// The census (every reflecting patch in the sample) is the exact solve by another
// route: same rays (seed), same rows, so the reflecting surfaces agree to the table's
// precision. (The luminaire's own patches are never sampled and so reach the
// sample through reciprocity; they are left out.)
TEST(IlpCli, SolveCensusReproducesTheExactSolve) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml + "  sample_fraction: 1\n");
  const RunResult exact = run_ilp(dir, {"solve", yaml, "--method", "exact", "--threads", "2", "-q"});
  ASSERT_EQ(exact.exit_code, 0) << "stderr:\n" << exact.err;
  const RunResult census = run_ilp(dir, {"solve", yaml, "--threads", "2", "-q"});
  ASSERT_EQ(census.exit_code, 0) << "stderr:\n" << census.err;
  EXPECT_TRUE(OutputContains(census.out, "k = 432 of 432 reflecting patches"));
  EXPECT_TRUE(OutputContains(census.err, "no sampling error"));
  for (const char* surface : {"floor", "ceiling", "walls"}) {
    const std::vector<std::string> a = table_row(exact.out, surface), b = table_row(census.out, surface);
    ASSERT_EQ(a.size(), 7u) << exact.out;
    ASSERT_EQ(b.size(), 7u) << census.out;
    for (std::size_t c = 3; c < 6; ++c)  // Eavg, Emin, Emax (0.1 lux printed)
      EXPECT_NEAR(std::stod(b[c]), std::stod(a[c]), 0.11) << surface << " column " << c;
  }
}

// With n reflecting patches, no sample size above n means anything: the
// recommendation must stay within 1..n (k = n is the census), also when the pilot
// samples (at least 2 patches) are as large as the population.
TEST(IlpCli, SolveTargetErrorRecommendsAtMostThePopulation) {
  TempDir dir;
  // The box unsubdivided, with one floor triangle as the only reflecting patch.
  dir.write("box.obj",
            "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 0 0 2\nv 2 0 2\nv 2 2 2\nv 0 2 2\n"
            "g floor\nf 1 2 3\n"
            "g rest\nf 1 3 4\nf 5 8 7 6\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\n");
  const std::string yaml =
      dir.write("job.yaml", box_job("  reflectance: {floor: 0.5, rest: 0}\n", "  target_error: 0.05\n"));
  const RunResult r = run_ilp(dir, {"solve", yaml, "--threads", "2", "-q"});
  ASSERT_EQ(r.exit_code, 0) << "stderr:\n" << r.err;
  EXPECT_TRUE(OutputContains(r.out, "k = 1 of 1 reflecting patches"));
  std::string line;
  for (const std::string& l : lines_of(r.err))
    if (l.rfind("sample size:", 0) == 0) line = l;
  ASSERT_FALSE(line.empty()) << "no \"sample size:\" line in\n" << r.err;
  EXPECT_TRUE(OutputContains(line, "needs k = 1 of 1 ")) << "the recommendation exceeds the population";
}

// ---------------------------------------------------------------------------------
// ilp accuracy

TEST(IlpCli, AccuracyStudyOnATinyBox) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const std::string out_dir = dir.file("acc");
  const RunResult r = run_ilp(dir, {"accuracy", yaml, "--fractions", "0.2,1", "--seeds", "2", "--rays", "64",
                                    "--reference-rays", "128", "--goals", "floor", "--threads", "2", "--out", out_dir,
                                    "-q"});
  ASSERT_EQ(r.exit_code, 0) << "stderr:\n" << r.err;
  EXPECT_TRUE(OutputContains(r.out, "RMS tot %"));  // the table's header
  EXPECT_TRUE(OutputContains(r.out, "64 rays, exact 2nd"));

  const std::string csv = (fs::path(out_dir) / "accuracy.csv").string();
  const std::string svg = (fs::path(out_dir) / "accuracy.svg").string();
  ASSERT_TRUE(fs::exists(csv));
  const std::vector<std::string> rows = lines_of(read_file(csv));
  const std::vector<std::string> expected_header{"strategy",
                                                 "indirect",
                                                 "sample_fraction",
                                                 "k",
                                                 "sample_patches",
                                                 "rays_per_row",
                                                 "sample_seed",
                                                 "build_seconds",
                                                 "evaluation_microseconds",
                                                 "rms_rel_error_total",
                                                 "max_rel_error_total",
                                                 "rms_rel_error_indirect",
                                                 "max_rel_error_indirect",
                                                 "predicted_rms_rel_error_total",
                                                 "goal_fallback_patches",
                                                 "condition_estimate"};
  ASSERT_FALSE(rows.empty());
  ASSERT_EQ(split_csv(rows[0]), expected_header);
  // 2 seeds at 20 %, and one census (it does not depend on the seed).
  ASSERT_EQ(rows.size(), 1u + 2u + 1u) << read_file(csv);
  int census_rows = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    SCOPED_TRACE(rows[i]);
    const std::vector<std::string> f = split_csv(rows[i]);
    ASSERT_EQ(f.size(), expected_header.size());
    EXPECT_EQ(f[0], "stratified");
    EXPECT_TRUE(f[1] == "sample_gather" || f[1] == "exact_second_bounce") << f[1];  // one method: the default
    EXPECT_EQ(f[1], split_csv(rows[1])[1]);
    std::vector<double> v(f.size(), 0.0);
    for (std::size_t c = 2; c < f.size(); ++c) EXPECT_TRUE(finite_number(f[c], &v[c])) << expected_header[c];
    EXPECT_EQ(v[5], 64.0);
    if (v[2] == 1.0) {
      ++census_rows;
      EXPECT_EQ(v[3], 432.0);  // k = n
      EXPECT_EQ(v[4], 432.0);
      EXPECT_EQ(v[13], 0.0);   // no sampling error predicted for the census
      EXPECT_LT(v[9], 0.10);   // only the reference's (and the rows') ray noise
    } else {
      EXPECT_EQ(v[3], 86.0);  // 0.2 x 432 = 86.4
      EXPECT_NEAR(v[2], 86.0 / 432.0, 1e-5);  // the fraction actually drawn
      EXPECT_GT(v[13], 0.0);
    }
    EXPECT_GE(v[7], 0.0);
    EXPECT_GE(v[9], 0.0);
    EXPECT_GE(v[10], v[9] - 1e-12);  // max >= RMS
    EXPECT_GE(v[15], 1.0);           // condition number
  }
  EXPECT_EQ(census_rows, 1);
  // The two 20 % rows are different samples.
  EXPECT_NE(split_csv(rows[1])[6], split_csv(rows[2])[6]);

  ASSERT_TRUE(fs::exists(svg));
  EXPECT_EQ(read_file(svg).rfind("<svg", 0), 0u) << read_file(svg).substr(0, 200);
  for (const auto& entry : fs::directory_iterator(out_dir))
    EXPECT_NE(entry.path().extension(), ".tmp") << entry.path();
}

TEST(IlpCli, AccuracyUnknownGoalSurface) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const std::string out_dir = dir.file("acc");
  const RunResult r = run_ilp(dir, {"accuracy", yaml, "--goals", "floor,desk", "--out", out_dir, "-q"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(OutputContains(r.err, "error: "));
  EXPECT_TRUE(OutputContains(r.err, "'desk'"));
  EXPECT_FALSE(fs::exists(fs::path(out_dir) / "accuracy.csv"));
}

TEST(IlpCli, AccuracyBogusStrategy) {
  TempDir dir;
  dir.write("box.obj", kBoxObj);
  const std::string yaml = dir.write("job.yaml", kBoxYaml);
  const std::string out_dir = dir.file("acc");
  const RunResult r = run_ilp(dir, {"accuracy", yaml, "--strategies", "bogus", "--goals", "floor", "--out", out_dir});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(OutputContains(r.err, "bogus"));
  EXPECT_FALSE(fs::exists(fs::path(out_dir) / "accuracy.csv"));
}

TEST(IlpCli, AccuracyHelp) {
  TempDir dir;
  const RunResult r = run_ilp(dir, {"accuracy", "--help"});
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option : {"--fractions", "--rays", "--seeds", "--goals", "--out", "--strategies"})
    EXPECT_TRUE(OutputContains(r.out, option));
}

}  // namespace
