// Issue 24 (docs/reliability.md): bounds on what a user or a vendor's file can put in
// (string lengths, nesting, the maintenance factor, candela values), what is not a
// regular file, photometric openings of every sign, the memory budget under a cgroup,
// and the cost of calculation-grid points. Each case was accepted, hung or misled
// before.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/light/luminaire_product.h"
#include "core/light/photometry.h"
#include "core/cost/cost_model.h"
#include "core/scene/mesh.h"
#include "job/config.h"
#include "tests/core/config_room.h"
#include "tests/test_support.h"
#include "job/setting_keys.h"

namespace ilp {
namespace {

namespace fs = std::filesystem;
using test::Contains;
using test::error_of;
using test::TempDir;

using test::config_error;
using test::kRoomObj;
const std::string kScene = test::kRoomScene;

// ---------------------------------------------------------------------------------
// Strings, nesting and the maintenance factor of a job file

// A 50 MB product name ran for minutes and wrote a 200 MB result.json; names are now
// bounded at their key, and the message shows the value shortened.
TEST(LimitsConfig, OverlongNamesAreRefusedAtTheirKey) {
  TempDir dir;
  const std::string name(300, 'n');
  for (const std::string& yaml :
       {kScene + "luminaires:\n  mounting_surface: " + name + "\n  flux_lm: [10, 1000]\n",
        kScene + "report:\n  surfaces: [" + name + "]\n"}) {
    const std::string message = config_error(dir, yaml);
    EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":5:"));
    EXPECT_TRUE(Contains(message, "300 characters long, more than 256"));
    EXPECT_LT(message.size(), 400u) << "the value is echoed whole";
  }
}

// A 300-character grid name was refused only after the whole run, by the file system,
// naming the staging folder: the grid's file names (isolux_NAME.png) must fit.
TEST(LimitsConfig, GridNameTooLongForItsFilesIsRefusedUpFront) {
  TempDir dir;
  const std::string message =
      config_error(dir, kScene + "grids:\n  - name: " + std::string(220, 'g') + "\n    over_surface: floor\n");
  EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":5:"));
  EXPECT_TRUE(Contains(message, "grids[0].name"));
  EXPECT_TRUE(Contains(message, "more than 200 characters"));
}

TEST(LimitsConfig, ControlCharactersInANameAreRefused) {
  TempDir dir;
  const std::string message = config_error(dir, kScene + "report:\n  surfaces: [\"flo\\e[31mor\"]\n");
  EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":5:"));
  EXPECT_TRUE(Contains(message, "control characters"));
  EXPECT_TRUE(Contains(message, "\\x1b[31m"));  // shown escaped, not obeyed
  EXPECT_FALSE(Contains(message, "\x1b", "message"));
}

// 100,000 nested brackets were "malformed YAML: bad file".
TEST(LimitsConfig, DeepNestingIsRefusedWithItsLine) {
  TempDir dir;
  std::string dashes = "\n    ";  // a block sequence in a block sequence in ...: "- - - ... x"
  for (int i = 0; i < 100; ++i) dashes += "- ";
  for (const auto& [deep, line] : std::vector<std::pair<std::string, int>>{
           {std::string(100000, '['), 5}, {std::string(100, '{'), 5}, {dashes + "x", 6}}) {
    const std::string message = config_error(dir, kScene + "report:\n  surfaces: " + deep + "\n");
    EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":" + std::to_string(line) + ":"));
    EXPECT_TRUE(Contains(message, "nesting deeper than 64 levels"));
  }
}

// maintenance_factor 1e-300 printed a 300-digit W/m2; 5e-324 crashed the run.
TEST(LimitsConfig, MaintenanceFactorIsBoundedAsAProducts) {
  TempDir dir;
  for (const char* mf : {"1e-300", "5e-324", "0.05"}) {
    const std::string message = config_error(dir, kScene + "maintenance_factor: " + mf + "\n");
    EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":4:"));
    EXPECT_TRUE(Contains(message, "must be in [0.1, 1]"));
  }
}

// ---------------------------------------------------------------------------------
// Not a regular file: a FIFO blocked open() for ever

TEST(LimitsFiles, FifoAsConfigMeshOrMaterialIsRefusedWithoutOpening) {
  TempDir dir;
  ASSERT_EQ(::mkfifo(dir.file("job.yaml").c_str(), 0600), 0);
  EXPECT_TRUE(Contains(error_of<ConfigError>([&] { (void)load_job_config(dir.file("job.yaml")); }),
                       dir.file("job.yaml") + ": is a FIFO (named pipe), not a config file"));
  ASSERT_EQ(::mkfifo(dir.file("room.obj").c_str(), 0600), 0);
  EXPECT_TRUE(Contains(error_of<SceneError>([&] { (void)load_mesh(dir.file("room.obj"), {}); }),
                       dir.file("room.obj") + ": is a FIFO (named pipe), not a mesh file"));
  ASSERT_EQ(::mkfifo(dir.file("room.mtl").c_str(), 0600), 0);
  const std::string obj = dir.write("m.obj", "mtllib room.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(Contains(error_of<SceneError>([&] { (void)load_mesh(obj, {}); }), "is a FIFO (named pipe), not a material file"));
  EXPECT_EQ(not_a_regular_file(obj, "mesh"), "");
  EXPECT_EQ(not_a_regular_file(dir.file("missing"), "mesh"), "");
  EXPECT_EQ(not_a_regular_file("/dev/null", "mesh"), "/dev/null: is a device, not a mesh file");
}

TEST(LimitsFiles, PrintableEscapesControlCharacters) {
  EXPECT_EQ(printable("a\x1b[31mb\x7f\tc"), "a\\x1b[31mb\\x7f\tc");
  EXPECT_EQ(printable("x\ny"), "x\\x0ay");
  EXPECT_EQ(printable("x\ny", true), "x\ny");
  EXPECT_EQ(shortened(std::string(100, 'a'), 10), std::string(10, 'a') + "... (100 characters)");
}

// ---------------------------------------------------------------------------------
// Photometric files

// A type C IES file with one vertical angle set and the opening `sizes` (width length height, metres).
std::string ies_with(const std::string& sizes, const std::string& candela = "100 80 0", const std::string& keywords = "") {
  return "IESNA:LM-63-2002\n[TEST] t\n[MANUFAC] m\n" + keywords + "TILT=NONE\n1 1000 1 3 1 1 2 " + sizes +
         "\n1.0 1.0 50\n0 45 90\n0\n" + candela + "\n";
}

struct Opening {
  std::string sizes;  // width length height
  OpeningShape shape;
  OutlineShape outline;
  double length_m, width_m;  // of the outline
};

// Width 0 and length 1.2 m became a 1.2 m disc without a word (also width -0.3).
TEST(LimitsPhotometry, EveryOpeningSignCombinationHasItsShape) {
  const std::vector<Opening> cases{
      {"0 0 0", OpeningShape::point, OutlineShape::disc, 0.1, 0.1},
      {"0 0 0.2", OpeningShape::point, OutlineShape::disc, 0.1, 0.1},
      {"0.3 1.2 0", OpeningShape::rectangle, OutlineShape::rectangle, 1.2, 0.3},
      {"0.3 1.2 0.1", OpeningShape::rectangle, OutlineShape::rectangle, 1.2, 0.3},
      {"0.3 1.2 -0.1", OpeningShape::rectangle, OutlineShape::rectangle, 1.2, 0.3},
      {"0 1.2 0", OpeningShape::line, OutlineShape::rectangle, 1.2, 0.02},
      {"0.8 0 0", OpeningShape::line, OutlineShape::rectangle, 0.02, 0.8},
      {"0 1.2 0.05", OpeningShape::line, OutlineShape::rectangle, 1.2, 0.02},
      {"-0.3 1.2 0", OpeningShape::rectangle, OutlineShape::rectangle, 1.2, 0.3},
      {"-0.3 1.2 -0.3", OpeningShape::rectangle, OutlineShape::rectangle, 1.2, 0.3},
      {"0.3 -1.2 0", OpeningShape::rectangle, OutlineShape::rectangle, 1.2, 0.3},
      {"-0.2 -0.2 0", OpeningShape::disc, OutlineShape::disc, 0.2, 0.2},
      {"-0.2 -0.4 0", OpeningShape::disc, OutlineShape::disc, 0.4, 0.4},
      {"-0.2 -0.2 0.3", OpeningShape::cylinder, OutlineShape::disc, 0.2, 0.2},
      {"-0.2 -0.2 -0.2", OpeningShape::cylinder, OutlineShape::disc, 0.2, 0.2},
      {"-0.2 0 0", OpeningShape::disc, OutlineShape::disc, 0.2, 0.2},
      {"0 -0.2 -0.2", OpeningShape::disc, OutlineShape::disc, 0.2, 0.2},
  };
  for (const Opening& c : cases) {
    SCOPED_TRACE(c.sizes);
    auto p = std::make_shared<Photometry>(parse_ies(ies_with(c.sizes), "o.ies"));
    EXPECT_EQ(p->opening.shape, c.shape);
    const LuminaireType t = photometric_luminaire_type("o", p);
    EXPECT_EQ(t.shape, c.outline);
    EXPECT_NEAR(t.length_m, c.length_m, 1e-12);
    EXPECT_NEAR(t.width_m, c.width_m, 1e-12);
  }
  // Mixed signs and ellipses say what they were taken as.
  const Photometry mixed = parse_ies(ies_with("-0.3 1.2 0"), "o.ies");
  ASSERT_FALSE(mixed.warnings.empty());
  EXPECT_TRUE(Contains(mixed.warnings.back(), "horizontal cylinder"));
}

// 4e-320 cd passed and ended as "direct light: non-finite value -nan" naming neither
// file nor product.
TEST(LimitsPhotometry, SubnormalCandelaIsRefusedAtItsLine) {
  for (const std::string value : {"4e-320", "1e-35"}) {
    const std::string message =
        error_of<PhotometryError>([&] { (void)parse_ies(ies_with("0.3 0.3 0", value + " 0 0"), "tiny.ies"); });
    EXPECT_TRUE(Contains(message, "tiny.ies:9:"));
    EXPECT_TRUE(Contains(message, "candela[C=0, gamma=0]"));
    EXPECT_TRUE(Contains(message, "below 1e-30 cd"));
  }
  EXPECT_NO_THROW((void)parse_ies(ies_with("0.3 0.3 0", "100 6.1e-14 0"), "ok.ies"));  // round-off of cos 90°
}

// A [LUMINAIRE] of 300 characters: refused at its line and keyword.
TEST(LimitsPhotometry, OverlongKeywordIsRefusedAtItsLine) {
  const std::string message = error_of<PhotometryError>(
      [&] { (void)parse_ies(ies_with("0.3 0.3 0", "100 80 0", "[LUMINAIRE] " + std::string(300, 'x') + "\n"), "k.ies"); });
  EXPECT_TRUE(Contains(message, "k.ies:4:"));
  EXPECT_TRUE(Contains(message, "LUMINAIRE"));
  EXPECT_TRUE(Contains(message, "more than 256"));
}

// ---------------------------------------------------------------------------------
// The memory budget: MemAvailable, the cgroup limit, --max-memory

// A fake /proc/self/cgroup and hierarchy under `dir`; returns the files.
CgroupFiles fake_cgroup(const TempDir& dir, const std::string& self, const std::string& file, const std::string& value) {
  fs::create_directories(fs::path(dir.file("cg") + "/" + file).parent_path());
  dir.write("cg/" + file, value + "\n");
  return {dir.write("self_cgroup", self), dir.file("cg")};
}

TEST(LimitsMemory, CgroupV2LimitOfTheProcessOrAnAncestorApplies) {
  TempDir dir;
  CgroupFiles files = fake_cgroup(dir, "0::/job/step\n", "job/memory.max", "104857600");
  fs::create_directories(dir.file("cg/job/step"));
  dir.write("cg/job/step/memory.max", "max\n");
  const auto limit = cgroup_memory_limit(files);
  ASSERT_TRUE(limit);
  EXPECT_DOUBLE_EQ(limit->bytes, 104857600.0);
  EXPECT_TRUE(Contains(limit->source, "the cgroup limit in " + dir.file("cg/job/memory.max")));
  const auto budget = memory_budget(std::nullopt, files);
  ASSERT_TRUE(budget);
  EXPECT_DOUBLE_EQ(budget->bytes, 104857600.0);  // less than this machine's MemAvailable
  EXPECT_EQ(memory_budget(50e6, files)->source, "--max-memory");
}

TEST(LimitsMemory, CgroupV1LimitIsReadAndNoLimitIsNone) {
  TempDir dir;
  const CgroupFiles v1 = fake_cgroup(dir, "4:cpu,memory:/slurm/job\n1:cpu:/\n", "memory/slurm/job/memory.limit_in_bytes",
                                     "6442450944");
  const auto limit = cgroup_memory_limit(v1);
  ASSERT_TRUE(limit);
  EXPECT_DOUBLE_EQ(limit->bytes, 6442450944.0);
  EXPECT_TRUE(Contains(limit->source, "memory.limit_in_bytes"));
  TempDir other;
  EXPECT_FALSE(cgroup_memory_limit(fake_cgroup(other, "4:memory:/\n", "memory/memory.limit_in_bytes",
                                               "9223372036854771712")));
  EXPECT_FALSE(cgroup_memory_limit({other.file("no_such_file"), other.file("cg")}));
}

TEST(LimitsMemory, RefusalNamesTheBudgetThatApplied) {
  CostCounts c;
  c.patches = c.population = 100000;
  c.goal_patches = 1000;
  c.sources = 100;
  c.sample_size = 20000;
  const CostEstimate e = estimate_job_cost(c);
  const std::string message = error_of<ConfigError>(
      [&] { require_fits(e, MemoryBudget{1e6, "the cgroup limit in /sys/fs/cgroup/memory.max"}, "job.yaml"); });
  EXPECT_TRUE(Contains(message, "job.yaml: the job would need about"));
  EXPECT_TRUE(Contains(message, "(the cgroup limit in /sys/fs/cgroup/memory.max)"));
}

// ---------------------------------------------------------------------------------
// Calculation-grid points in the cost model

// A grid of 9.8e5 points was estimated at "52 MB, 0.1 s" (no point counted).
TEST(LimitsCost, GridPointsCountInRowsMemoryAndLaying) {
  name_settings_by_key();  // as load_job_config and the ilp command do: messages name the job file's keys
  CostCounts c;
  c.patches = c.population = 2000;
  c.goal_patches = 100;
  c.sources = 150;
  c.sample_size = 400;
  const CostEstimate without = estimate_job_cost(c);
  c.grid_points = 980000;
  c.grid_outline_tests = 980000;
  const CostEstimate with = estimate_job_cost(c);
  // Each point: a row of D and T (8 bytes x sources, twice) and a gather row of 4 x 128 rays.
  EXPECT_GT(with.peak_bytes() - without.peak_bytes(), 980000.0 * 150 * 8 * 2);
  EXPECT_GT(with.peak_bytes(), 300.0 * 1024 * 1024);
  EXPECT_GT(with.total_seconds(), without.total_seconds() + 980000.0 * 4 * 128 / 5.3e6);
  bool laying = false;
  for (const PhaseEstimate& p : with.phases) laying = laying || Contains(p.name, "laying grids (980000 points");
  EXPECT_TRUE(laying);
  const std::string message = error_of<ConfigError>([&] { require_fits(with, 300.0 * 1024 * 1024, "job.yaml"); });
  EXPECT_TRUE(Contains(message, "grids[].spacing_m"));
}

}  // namespace
}  // namespace ilp
