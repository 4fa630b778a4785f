// Issue 24 through the real program: a crash on unreachable goals, jobs refused for
// memory (calculation-grid points, a cgroup limit) before any work, a FIFO as the job
// file, a vendor's escape codes, and the output folder (--out '', a symbolic link,
// staging folders of killed runs, a full disk). docs/reliability.md.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <set>
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
using ilp::test::quoted;
using ilp::test::read_file;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;

// `ilp <args>` run by the shell after `prefix` (environment, ulimit, trap), killed
// after 60 s (a hang fails the test instead of stopping the suite), with its time.
struct TimedRun {
  RunResult r;
  double seconds = 0.0;
};
TimedRun run_ilp_with(const TempDir& dir, const std::string& prefix, const std::vector<std::string>& args) {
  std::ostringstream command;
  command << prefix << " XDG_CACHE_HOME=" << quoted(dir.file("xdg-cache"))
          << " ILP_MACHINE_DIR=" << quoted(ilp::test::suite_machine_dir()) << " timeout 60 " << quoted(ILP_BINARY);
  for (const std::string& a : args) command << ' ' << quoted(a);
  command << " >" << quoted(dir.file("stdout.txt")) << " 2>" << quoted(dir.file("stderr.txt")) << " </dev/null";
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system(command.str().c_str());
  TimedRun t;
  t.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  t.r.exit_code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  t.r.out = read_file(dir.file("stdout.txt"));
  t.r.err = read_file(dir.file("stderr.txt"));
  return t;
}

void expect_exit(const RunResult& r, int code) {
  EXPECT_EQ(r.exit_code, code) << "stdout:\n" << r.out << "\nstderr:\n" << r.err;
}

const std::string kSearch =
    "  size_m: 0.3\n  flux_lm: [10, 20000]\n  efficacy_lm_per_w: 100\n  mounting_surface: ceiling\n"
    "  candidate_spacing_m: 0.5\n  count: 1\n";
const std::string kQuick = "optimizer:\n  max_evaluations: 200\n  local_max_evaluations: 200\n";

// The mat room's search job with `goals` and `extra` (grids, output, ...) before them.
std::string job_with(const TempDir& dir, const std::string& extra, const std::string& goals,
                     const std::string& luminaires = kSearch) {
  dir.write("room.obj", ilp::test::room_obj({{"mat", {1.3, 1.7}}}));
  std::string job = ilp::test::room_job("0.4", luminaires, goals, kQuick);
  job.insert(job.find("goals:\n"), extra);
  return dir.write("job.yaml", job);
}

std::string mat_job(const TempDir& dir) { return job_with(dir, "", "  - surface: mat\n    average_lux: 100\n"); }

// A vertical grid on the wall at x = 0 facing out of the room: no light reaches it at
// any count. Every count was screened out, the outcome had no verification and the
// grid report indexed an empty vector (SIGSEGV, exit 139).
TEST(IlpLimits, UnreachableGridAverageIsAMissNotACrash) {
  TempDir dir;
  const std::string grid =
      "grids:\n  - name: outside\n    vertical: {from_m: [0, 0.5], to_m: [0, 3.5], bottom_m: 0.5, top_m: 2, "
      "facing: left}\n    spacing_m: 0.5\n";
  const std::string job = job_with(dir, grid, "  - grid: outside\n    average_lux: 100\n");
  const std::string out = dir.file("out");
  const RunResult r = run_ilp(dir, {"run", job, "--out", out, "-q", "--no-cache"});
  expect_exit(r, 2);
  EXPECT_TRUE(OutputContains(r.out, "INFEASIBLE"));
  EXPECT_TRUE(fs::exists(out + "/result.json"));
  EXPECT_TRUE(fs::exists(out + "/plan.svg"));
}

// A FIFO as the job file blocked open() for ever (run and inspect).
TEST(IlpLimits, FifoAsTheJobFileIsRefusedAtOnce) {
  TempDir dir;
  const std::string fifo = dir.file("job.yaml");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const char* command : {"run", "inspect", "solve"}) {
    const TimedRun t = run_ilp_with(dir, "", {command, fifo});
    expect_exit(t.r, 1);
    EXPECT_TRUE(OutputContains(t.r.err, fifo + ": is a FIFO (named pipe), not a config file")) << command;
    EXPECT_LT(t.seconds, 10.0);
  }
}

// --out '' fell back to output.directory without a word.
TEST(IlpLimits, EmptyOutIsRefused) {
  TempDir dir;
  const std::string job = job_with(dir, "", "  - surface: mat\n    average_lux: 100\n");
  std::string text = read_file(job);
  text += "output:\n  directory: " + dir.file("configured") + "\n";
  dir.write("job.yaml", text);
  const RunResult r = run_ilp(dir, {"run", job, "--out", "", "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, "--out"));
  EXPECT_TRUE(OutputContains(r.err, "must not be empty"));
  EXPECT_FALSE(fs::exists(dir.file("configured")));
}

// --out link, link -> a folder: the link was replaced by a real folder and the old
// results stayed in the target.
TEST(IlpLimits, OutThroughASymbolicLinkWritesIntoItsTargetAndKeepsTheLink) {
  TempDir dir;
  const std::string job = mat_job(dir);
  fs::create_directories(dir.file("target"));
  dir.write("target/notes.txt", "mine\n");
  fs::create_directory_symlink(dir.file("target"), dir.file("link"));
  const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("link"), "-q", "--no-cache"});
  expect_exit(r, 0);
  EXPECT_TRUE(fs::is_symlink(dir.file("link")));
  EXPECT_TRUE(fs::exists(dir.file("target/result.json")));
  EXPECT_EQ(read_file(dir.file("target/notes.txt")), "mine\n");
  EXPECT_TRUE(OutputContains(r.out, "wrote " + dir.file("link") + "/result.json"));
}

// Staging folders of killed runs piled up until a run completed into the same parent:
// a run now removes them at its start, whether or not it completes.
TEST(IlpLimits, StagingFoldersOfKilledRunsAreRemovedAtTheStart) {
  TempDir dir;
  const std::string job = mat_job(dir);
  const std::string stale = dir.file(".out.ilp-tmp-4194303-deadbeef");  // above any PID this test machine runs
  fs::create_directories(stale);
  dir.write(".out.ilp-tmp-4194303-deadbeef/result.json", "{}");
  const TimedRun t = run_ilp_with(dir, "ILP_TEST_OUTPUT_FAIL=1", {"run", job, "--out", dir.file("out"), "-q", "--no-cache"});
  expect_exit(t.r, 1);  // the first file fails: no commit
  EXPECT_FALSE(fs::exists(stale));
}

// A disk-full failure named the temporary staging path ("scene.ply: write failed"
// under .out.ilp-tmp-...): now the output folder and the space left.
TEST(IlpLimits, FullDiskNamesTheOutputFolderNotTheStagingFolder) {
  TempDir dir;
  const std::string job = mat_job(dir);
  const std::string out = dir.file("out");
  // A file size limit of 16 blocks: writes beyond it fail with EFBIG (SIGXFSZ ignored).
  const TimedRun t = run_ilp_with(dir, "trap '' XFSZ; ulimit -f 16;", {"run", job, "--out", out, "-q", "--no-cache"});
  expect_exit(t.r, 1);
  EXPECT_TRUE(OutputContains(t.r.err, "error: " + out + "/"));
  EXPECT_TRUE(OutputContains(t.r.err, "write failed"));
  EXPECT_TRUE(OutputContains(t.r.err, "MB free on its file system"));
  EXPECT_FALSE(OutputContains(t.r.err, ".ilp-tmp-"));
  EXPECT_FALSE(fs::exists(out));
}

// Under a cgroup limit the budget was the machine's MemAvailable: a job that could not
// fit started anyway. A fake hierarchy (ILP_CGROUP_ROOT) with memory.max = 40 MB.
TEST(IlpLimits, CgroupLimitRefusesTheJobWithinFiveSeconds) {
  TempDir dir;
  const std::string job = mat_job(dir);
  fs::create_directories(dir.file("cgroup"));
  dir.write("cgroup/memory.max", "41943040\n");
  const TimedRun t = run_ilp_with(dir, "ILP_CGROUP_ROOT=" + quoted(dir.file("cgroup")),
                                  {"run", job, "--out", dir.file("out"), "-q", "--no-cache"});
  expect_exit(t.r, 1);
  EXPECT_LT(t.seconds, 5.0);
  EXPECT_TRUE(OutputContains(t.r.err, "refused before any work"));
  EXPECT_TRUE(OutputContains(t.r.err, "the cgroup limit in " + dir.file("cgroup") + "/memory.max"));
  EXPECT_FALSE(fs::exists(dir.file("out")));
}

// A grid of 562,500 points under --max-memory 300M was estimated without its points
// ("52 MB, 0.1 s"), laid (minutes of rays) and run at gigabytes: now refused from its
// cells before a point is laid.
TEST(IlpLimits, GridTooLargeForTheBudgetIsRefusedBeforeItIsLaid) {
  TempDir dir;
  const std::string grid =
      "grids:\n  - name: fine\n    over_surface: floor\n    spacing_m: 0.004\n    max_points: 1000000\n";
  const std::string job = job_with(dir, grid, "  - grid: fine\n    average_lux: 100\n");
  const TimedRun t =
      run_ilp_with(dir, "", {"run", job, "--out", dir.file("out"), "-q", "--no-cache", "--max-memory", "300M"});
  expect_exit(t.r, 1);
  EXPECT_LT(t.seconds, 10.0);
  EXPECT_TRUE(OutputContains(t.r.err, "estimate: laying grids (562500 points at most)"));
  EXPECT_TRUE(OutputContains(t.r.err, "change grids[].spacing_m"));
  EXPECT_TRUE(OutputContains(t.r.err, "(--max-memory)"));
  EXPECT_FALSE(OutputContains(t.r.err, "grid 'fine':"));  // the laying's log line: not laid
}

// `ilp inspect` printed another estimate than `ilp run` (no grid points, the first
// variant only): both now print costed_geometry's lines, each product's.
TEST(IlpLimits, InspectGivesTheEstimateOfRunProductsAndGridsIncluded) {
  TempDir dir;
  const std::string products =
      "  products:\n    - name: downlight\n      photometry: " + std::string(ILP_SOURCE_DIR) +
      "/data/photometry/erco_iku_downlight.ldt\n  mounting_surface: ceiling\n  candidate_spacing_m: 0.5\n  count: 1\n";
  const std::string grid = "grids:\n  - name: work\n    over_surface: floor\n    spacing_m: 0.5\n";
  const std::string job = job_with(dir, grid, "  - grid: work\n    average_lux: 50\n", products);
  const RunResult inspect = run_ilp(dir, {"inspect", job, "--max-memory", "4G"});
  expect_exit(inspect, 0);
  const RunResult run = run_ilp(dir, {"run", job, "--out", dir.file("out"), "-q", "--no-cache", "--max-memory", "4G"});
  expect_exit(run, 0);
  std::vector<std::string> from_inspect, from_run;
  for (const std::string& line : lines_of(inspect.out))
    if (line.rfind("  estimate: ", 0) == 0) from_inspect.push_back(line.substr(2));
  for (const std::string& line : lines_of(run.err))
    if (line.rfind("estimate: ", 0) == 0) from_run.push_back(line);
  ASSERT_FALSE(from_run.empty());
  EXPECT_EQ(from_inspect, from_run);
  EXPECT_TRUE(OutputContains(inspect.out, "estimate: laying grids (36 points at most)"));
}

// A vendor's [LUMINAIRE] line with terminal escape codes was echoed raw.
TEST(IlpLimits, EscapeCodesInAVendorsFileAreShownNotObeyed) {
  TempDir dir;
  dir.write("evil.ies",
            "IESNA:LM-63-2002\n[TEST] t\n[MANUFAC] m\n[LUMINAIRE] \x1b]0;owned\x07\x1b[2J wiped\nTILT=NONE\n"
            "1 1000 1 3 1 1 2 0.3 0.3 0\n1.0 1.0 50\n0 45 90\n0\n300 200 0\n");
  const std::string products = "  products:\n    - name: evil\n      photometry: evil.ies\n"
                               "  mounting_surface: ceiling\n  candidate_spacing_m: 0.5\n  count: 1\n";
  const std::string job = job_with(dir, "", "  - surface: mat\n    average_lux: 50\n", products);
  const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out"), "-q", "--no-cache"});
  EXPECT_LT(r.exit_code, 3) << r.err;
  EXPECT_FALSE(OutputContains(r.out + r.err, "\x1b"));
  EXPECT_FALSE(OutputContains(r.out + r.err, "\x07"));
  EXPECT_TRUE(OutputContains(r.err, "\\x1b[2J wiped"));
}

}  // namespace

namespace {

// A mesh's group names reach the terminal through `ilp inspect` (and every table):
// everything ilp writes to stdout and stderr has its control characters escaped.
TEST(IlpLimits, EscapeCodesInAMeshGroupAreShownNotObeyed) {
  TempDir dir;
  std::string obj = ilp::test::room_obj({{"mat", {1.3, 1.7}}});
  obj.replace(obj.find("g mat"), 5, "g m\x1b[2Jat");
  const std::string mesh = dir.write("room.obj", obj);
  const RunResult r = run_ilp(dir, {"inspect", mesh});
  expect_exit(r, 0);
  EXPECT_FALSE(OutputContains(r.out + r.err, "\x1b"));
  EXPECT_TRUE(OutputContains(r.out, "m\\x1b[2Jat"));
}

}  // namespace

namespace {

// `ilp solve` counts its grids' points too, before laying them.
TEST(IlpLimits, SolveRefusesAGridTooLargeBeforeItIsLaid) {
  TempDir dir;
  dir.write("room.obj", ilp::test::room_obj({{"mat", {1.3, 1.7}}}));
  const std::string job = dir.write(
      "fixed.yaml", "scene:\n  mesh: room.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0.4\n"
                    "luminaires:\n  size_m: 0.3\n  placed:\n    - {name: P1, position_m: [2, 2, 2.45], flux_lm: 4000}\n"
                    "grids:\n  - name: fine\n    over_surface: floor\n    spacing_m: 0.004\n    max_points: 1000000\n");
  const TimedRun t = run_ilp_with(dir, "", {"solve", job, "-q", "--max-memory", "300M"});
  expect_exit(t.r, 1);
  EXPECT_LT(t.seconds, 10.0);
  EXPECT_TRUE(OutputContains(t.r.err, "estimate: laying grids (562500 points at most)"));
  EXPECT_TRUE(OutputContains(t.r.err, "refused before any work"));
}

}  // namespace
