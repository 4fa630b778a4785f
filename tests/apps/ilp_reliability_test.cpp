// The real `ilp` program on input that once crashed it (SIGSEGV, SIGABRT, an Embree
// assertion, a TBB abort) or exited with CLI11's own codes, and the output set as one
// transaction: a run killed at any point (SIGINT, SIGTERM, SIGKILL) leaves the
// previous complete set or the new one, never a mix (docs/reliability.md).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "tests/apps/cli_runner.h"
#include "tests/optimizer/optimizer_test_scenes.h"
#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::OutputContains;
using ilp::test::quoted;
using ilp::test::read_file;
using ilp::test::run_ilp;
using ilp::test::RunResult;
using ilp::test::TempDir;

// A box room (4 x 4 x 2.5 m) with a mat, in folder `sub` of `dir`; returns the job's path.
std::string write_job(const TempDir& dir, const std::string& sub, const std::string& scene_extra,
                      const std::string& rest, Eigen::Vector2d mat = {1.3, 1.7}) {
  fs::create_directories(dir.file(sub));
  const fs::path folder(dir.file(sub));
  std::ofstream((folder / "room.obj").string()) << ilp::test::room_obj({{"mat", mat}});
  std::ofstream((folder / "job.yaml").string())
      << "scene:\n  mesh: room.obj\n  max_patch_edge_m: 0.5\n  default_reflectance: 0.4\n" << scene_extra << rest;
  return (folder / "job.yaml").string();
}

const std::string kPlaced = "luminaires:\n  size_m: 0.3\n  placed:\n    - {name: L1, position_m: [2, 2, 2.4], flux_lm: 3000}\n";
const std::string kReport = "report:\n  surfaces: [mat, floor]\nsolver:\n  rays_per_patch: 64\n";

// Did not die of a signal and exited `code`.
void expect_exit(const RunResult& r, int code) {
  EXPECT_EQ(r.exit_code, code) << "stdout:\n" << r.out << "\nstderr:\n" << r.err;
}

// No light source at all: an empty operator reached clamp_round_off (SIGSEGV). Now
// every illuminance is 0 lx, as the warning says.
TEST(IlpReliability, SolveWithoutAnyLightSourceGivesZeroLux) {
  TempDir dir;
  for (const std::string& lights : {std::string(), std::string("luminaires:\n  size_m: 0.3\n  placed:\n"),
                                    std::string("luminaires:\n  size_m: 0.3\n")}) {
    const std::string job = write_job(dir, "a", "", lights + kReport);
    const RunResult r = run_ilp(dir, {"solve", job, "-q"});
    expect_exit(r, 0);
    EXPECT_TRUE(OutputContains(r.err, "nothing emits light"));
    EXPECT_TRUE(OutputContains(r.out, "mat"));
  }
  const std::string dark =
      write_job(dir, "b", "  emitting_surfaces:\n    - {surface: ceiling, exitance_lm_per_m2: 0}\n", kReport);
  expect_exit(run_ilp(dir, {"solve", dark, "-q"}), 0);
}

// ilp accuracy with nothing lit measured errors of 0 lx against 0 lx and failed late
// on plotting them on a log axis ("render_svg_plot: ... not > 0"); now it refuses
// the job before any work, naming it, and writes nothing.
TEST(IlpReliability, AccuracyWithoutAnyLightSourceIsRefusedAtOnce) {
  TempDir dir;
  const std::string job = write_job(dir, "a", "", kReport);
  const std::string out = dir.file("acc");
  const RunResult r = run_ilp(dir, {"accuracy", job, "--fractions", "0.5", "--seeds", "1", "--out", out, "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, job + ": nothing emits light"));
  EXPECT_FALSE(OutputContains(r.err, "render_svg_plot"));
  EXPECT_FALSE(fs::exists(out));
}

// A reported surface that is also excluded: no goal patch (SIGSEGV).
TEST(IlpReliability, ReportedSurfaceThatIsExcludedIsAnError) {
  TempDir dir;
  const std::string job = write_job(dir, "a", "  exclude_surfaces: [mat]\n", kPlaced + kReport);
  const RunResult r = run_ilp(dir, {"solve", job, "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, job + ":"));
  EXPECT_TRUE(OutputContains(r.err, "surface 'mat' has no patch left"));
}

// size_m 1e200 tripped an Embree assertion (SIGABRT).
TEST(IlpReliability, HugeLuminaireIsAnErrorNotAnAssertion) {
  TempDir dir;
  std::string lum = kPlaced;
  lum.replace(lum.find("0.3"), 3, "1e200");
  const std::string job = write_job(dir, "a", "", lum + kReport);
  const RunResult r = run_ilp(dir, {"solve", job, "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, job + ":6:"));
  EXPECT_TRUE(OutputContains(r.err, "luminaires.size_m = 1e200"));
}

// --threads 1000000 crashed inside TBB; --threads -1 exited with CLI11's 105. Every
// command's bad argument now exits 1 (help: 0).
TEST(IlpReliability, BadThreadsAndArgumentsExitOne) {
  TempDir dir;
  const std::string job = write_job(dir, "a", "", kPlaced + kReport);
  for (const char* command : {"solve", "accuracy", "run", "sweep", "bench"})
    for (const char* threads : {"1000000", "-1", "many"}) {
      const RunResult r = run_ilp(dir, {command, job, "--threads", threads, "-q"});
      expect_exit(r, 1);
      EXPECT_TRUE(OutputContains(r.err, "--threads")) << command << " " << threads;
    }
  expect_exit(run_ilp(dir, {"solve"}), 1);                    // a required argument missing
  expect_exit(run_ilp(dir, {"solve", job, "--method", "x"}), 1);
  expect_exit(run_ilp(dir, {"frobnicate"}), 1);
  expect_exit(run_ilp(dir, {"print", "a", "b"}), 1);         // an extra argument
  expect_exit(run_ilp(dir, {"accuracy", job, "--seeds", "0"}), 1);
  expect_exit(run_ilp(dir, {"bench", job, "--luminaires", "0"}), 1);
  expect_exit(run_ilp(dir, {"--help"}), 0);
  expect_exit(run_ilp(dir, {"--version"}), 0);
}

// A folder where a file is expected: "basic_filebuf::underflow" or "the mesh has no
// faces" before, with no file named.
TEST(IlpReliability, FolderGivenForAFileIsNamed) {
  TempDir dir;
  fs::create_directories(dir.file("job.yaml"));
  fs::create_directories(dir.file("result.json"));
  RunResult r = run_ilp(dir, {"solve", dir.file("job.yaml"), "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, dir.file("job.yaml") + ": is a folder, not a config file"));
  r = run_ilp(dir, {"print", dir.file("result.json")});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, dir.file("result.json") + ": is a folder, not a result file"));
  const std::string job = write_job(dir, "a", "", kPlaced + kReport);
  fs::remove(dir.file("a/room.obj"));
  fs::create_directories(dir.file("a/room.obj"));
  r = run_ilp(dir, {"solve", job, "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, "room.obj: is a folder, not a mesh file"));
}

// mount_offset_m 5 under a 2.5 m ceiling put the luminaires below the floor, and the
// run wrote its outputs.
TEST(IlpReliability, MountOffsetBelowTheFloorIsRefused) {
  TempDir dir;
  const std::string job = write_job(
      dir, "a", "",
      "luminaires:\n  size_m: 0.3\n  flux_lm: [10, 20000]\n  mounting_surface: ceiling\n  mount_offset_m: 5\n"
      "  candidate_spacing_m: 0.5\n  count: 1\ngoals:\n  - surface: mat\n    average_lux: 200\n"
      "solver:\n  rays_per_patch: 64\n");
  const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out"), "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, job + ":9:"));
  EXPECT_TRUE(OutputContains(r.err, "luminaires.mount_offset_m"));
  EXPECT_TRUE(OutputContains(r.err, "under the floor"));
  EXPECT_FALSE(fs::exists(dir.file("out")));
}

// candidate_spacing_m 1e-12 overflowed the int grid size and gave 4 candidates; the
// config refuses below 1 mm, and a spacing that makes too many nodes is refused at the key.
TEST(IlpReliability, CandidateGridTooFineIsRefusedAtItsKey) {
  TempDir dir;
  const std::string job = write_job(
      dir, "a", "",
      "luminaires:\n  size_m: 0.3\n  flux_lm: [10, 20000]\n  mounting_surface: ceiling\n"
      "  candidate_spacing_m: 0.001\n  count: 1\n  zone: {margin_m: 10}\ngoals:\n  - surface: mat\n    average_lux: 200\n");
  const RunResult r = run_ilp(dir, {"run", job, "--out", dir.file("out"), "-q", "--no-cache"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, job + ":9:"));
  EXPECT_TRUE(OutputContains(r.err, "luminaires.candidate_spacing_m: 0.001 m"));
  EXPECT_TRUE(OutputContains(r.err, "grid nodes, more than 4e+06"));
  EXPECT_FALSE(fs::exists(dir.file("out")));
}

// ---------------------------------------------------------------------------------
// The output set as one transaction

// The inverse job of the mat, `target` lx, in folder `sub` (its own mat position, so
// that every file of its output set differs from another job's).
std::string mat_job(const TempDir& dir, const std::string& sub, double target, Eigen::Vector2d mat) {
  std::ostringstream rest;
  rest << "luminaires:\n  size_m: 0.3\n  flux_lm: [10, 20000]\n  efficacy_lm_per_w: 100\n"
       << "  mounting_surface: ceiling\n  candidate_spacing_m: 0.5\n  count: 1\n"
       << "goals:\n  - surface: mat\n    average_lux: " << target << "\n"
       << "solver:\n  rays_per_patch: 64\n  seed: 3\n  sample_fraction: 0.2\n"
       << "optimizer:\n  max_evaluations: 300\n  local_max_evaluations: 300\n"
       << "verification:\n  rays_per_patch: 64\n";
  return write_job(dir, sub, "", rest.str(), mat);
}

using Files = std::map<std::string, std::string>;  // name -> bytes

Files files_in(const std::string& folder) {
  Files out;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    out[entry.path().filename().string()] = read_file(entry.path().string());
  return out;
}

// The json format writes result.json and its timings.json.
const std::vector<std::string> kRunFiles = {"result.json", "timings.json", "illuminance.csv", "plan.svg", "scene.ply", "plan.png"};

// Starts `ilp args...` in the background with `env` (NAME=VALUE ...), stderr to `err`.
pid_t start_ilp(const TempDir& dir, const std::string& env, const std::vector<std::string>& args,
                const std::string& err) {
  std::ostringstream command;
  command << "exec env XDG_CACHE_HOME=" << quoted(dir.file("xdg-cache")) << ' ' << env << ' ' << quoted(ILP_BINARY);
  for (const std::string& a : args) command << ' ' << quoted(a);
  command << " >/dev/null 2>" << quoted(err) << " </dev/null";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", command.str().c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// Waits (up to 120 s) until `err` says the writer paused at `point`; false if the
// process ended first.
bool wait_for_pause(pid_t pid, const std::string& err, const std::string& point) {
  for (int i = 0; i < 1200; ++i) {
    if (read_file(err).find("ilp-test: paused at " + point + "\n") != std::string::npos) return true;
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return false;
}

// Which complete set the folder holds: "old" (every file byte for byte the old run's),
// "new" (every file present, none the old run's), else "mixed: ...". The user's own
// file must be there in both.
std::string which_set(const std::string& folder, const Files& old_set) {
  const Files now = files_in(folder);
  if (now.count("notes.txt") == 0 || now.at("notes.txt") != "mine\n") return "mixed: notes.txt lost";
  std::size_t same = 0, present = 0;
  for (const std::string& name : kRunFiles) {
    if (now.count(name) == 0) continue;
    ++present;
    if (now.at(name) == old_set.at(name)) ++same;
  }
  if (now.size() != kRunFiles.size() + 1) return "mixed: " + std::to_string(now.size()) + " entries";
  if (same == kRunFiles.size()) return "old";
  if (same == 0 && present == kRunFiles.size()) return "new";
  return "mixed: " + std::to_string(same) + " old files of " + std::to_string(present);
}

// Staging folders beside `folder` (".NAME.ilp-tmp-...", ".NAME.ilp-old-...").
std::vector<std::string> leftovers_beside(const std::string& folder) {
  std::vector<std::string> out;
  const std::string name = fs::path(folder).filename().string();
  const std::string prefix = "." + name + ".ilp-";
  for (const auto& entry : fs::directory_iterator(fs::path(folder).parent_path()))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) out.push_back(entry.path().filename().string());
  return out;
}

// Kill a run at every point of the writing, with each signal: the folder holds the
// old set or the new one, and the next run removes what the killed one left.
TEST(IlpReliability, KilledRunLeavesTheOldSetOrTheNewNeverAMix) {
  TempDir dir;
  const std::string out = dir.file("out");
  const std::string job_old = mat_job(dir, "old", 200, {1.3, 1.7});
  const std::string job_new = mat_job(dir, "new", 300, {2.6, 2.4});
  ASSERT_EQ(run_ilp(dir, {"run", job_old, "--out", out, "-q"}).exit_code, 0);
  std::ofstream(dir.file("out/notes.txt")) << "mine\n";
  const Files old_set = files_in(out);
  ASSERT_EQ(which_set(out, old_set), "old");
  ASSERT_EQ(run_ilp(dir, {"run", job_new, "--out", dir.file("scratch"), "-q"}).exit_code, 0);  // fills the cache

  int run = 0;
  for (const char* point : {"1", "2", "3", "4", "carried", "swapped"})
    for (int sig : {SIGINT, SIGTERM, SIGKILL}) {
      const std::string err = dir.file("killed" + std::to_string(++run) + ".txt");
      SCOPED_TRACE(std::string("paused at ") + point + ", signal " + std::to_string(sig));
      // Back to the old set when a previous kill let the new one in.
      if (which_set(out, old_set) != "old") {
        fs::remove_all(out);
        fs::create_directories(out);
        for (const auto& [name, bytes] : old_set) std::ofstream(dir.file("out/" + name), std::ios::binary) << bytes;
      }
      const pid_t pid = start_ilp(dir, std::string("ILP_TEST_OUTPUT_PAUSE=") + point, {"run", job_new, "--out", out, "-q"},
                                  err);
      ASSERT_TRUE(wait_for_pause(pid, err, point)) << read_file(err);
      EXPECT_EQ(which_set(out, old_set), std::string(point) == "swapped" ? "new" : "old");  // while paused
      kill(pid, sig);
      int status = 0;
      waitpid(pid, &status, 0);
      EXPECT_TRUE(WIFSIGNALED(status));
      EXPECT_EQ(which_set(out, old_set), std::string(point) == "swapped" ? "new" : "old");
      EXPECT_FALSE(leftovers_beside(out).empty());  // the killed run's staging folder
    }
  // The next run completes the new set and removes every leftover.
  const RunResult r = run_ilp(dir, {"run", job_new, "--out", out, "-q"});
  expect_exit(r, 0);
  EXPECT_EQ(which_set(out, old_set), "new");
  EXPECT_TRUE(leftovers_beside(out).empty());
}

// A failure on a later file (a full disk) keeps the previous set whole.
TEST(IlpReliability, FailureOnTheFourthFileKeepsThePreviousSet) {
  TempDir dir;
  const std::string out = dir.file("out");
  ASSERT_EQ(run_ilp(dir, {"run", mat_job(dir, "old", 200, {1.3, 1.7}), "--out", out, "-q"}).exit_code, 0);
  std::ofstream(dir.file("out/notes.txt")) << "mine\n";
  const Files old_set = files_in(out);
  const std::string err = dir.file("failed.txt");
  const pid_t pid = start_ilp(dir, "ILP_TEST_OUTPUT_FAIL=3", {"run", mat_job(dir, "new", 300, {2.6, 2.4}), "--out", out, "-q"},
                              err);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1) << read_file(err);
  EXPECT_TRUE(OutputContains(read_file(err), "ILP_TEST_OUTPUT_FAIL"));
  EXPECT_EQ(which_set(out, old_set), "old");
  EXPECT_TRUE(leftovers_beside(out).empty());
}

// Concurrent runs into one folder: every one succeeds (the old fixed ".tmp" name made
// 6 of 80 fail) and the folder ends holding one complete set.
TEST(IlpReliability, ConcurrentRunsIntoOneFolderAllSucceed) {
  TempDir dir;
  const std::string out = dir.file("out");
  const std::string job = mat_job(dir, "a", 200, {1.3, 1.7});
  ASSERT_EQ(run_ilp(dir, {"run", job, "--out", dir.file("warm"), "-q"}).exit_code, 0);  // fills the cache
  std::vector<pid_t> pids;
  for (int k = 0; k < 6; ++k) pids.push_back(start_ilp(dir, "", {"run", job, "--out", out, "-q"}, dir.file("err" + std::to_string(k))));
  for (std::size_t k = 0; k < pids.size(); ++k) {
    int status = 0;
    waitpid(pids[k], &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << read_file(dir.file("err" + std::to_string(k)));
  }
  const Files now = files_in(out);
  EXPECT_EQ(now.size(), kRunFiles.size());
  for (const std::string& name : kRunFiles) EXPECT_EQ(now.count(name), 1u) << name;
  EXPECT_TRUE(leftovers_beside(out).empty());
}

// A file where the output folder should be: refused before any work, nothing written.
TEST(IlpReliability, OutputFolderThatIsAFileIsRefusedUpFront) {
  TempDir dir;
  const std::string out = dir.write("out", "a file\n");
  const RunResult r = run_ilp(dir, {"run", mat_job(dir, "a", 200, {1.3, 1.7}), "--out", out, "-q"});
  expect_exit(r, 1);
  EXPECT_TRUE(OutputContains(r.err, out + ": is not a folder"));
  EXPECT_EQ(read_file(out), "a file\n");
  EXPECT_TRUE(leftovers_beside(out).empty());
}

}  // namespace
