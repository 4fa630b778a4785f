// This machine's speed for the cost model (core/cost/machine_speed.h): the
// reference constants scaled by kind of work and threads, and the calibration cached
// once per machine, read back as written, and replaced when it cannot be used.
#include "core/cost/machine_speed.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/test_support.h"

namespace ilp {
namespace {

using test::Contains;
using test::TempDir;

TEST(MachineCosts, AtTheReferencesSpeedOnTwoThreadsAreTheReferencesOwn) {
  const MachineCosts reference, m = machine_costs(MachineSpeed{}, 2);
  EXPECT_DOUBLE_EQ(m.gather_ray_s, reference.gather_ray_s);
  EXPECT_DOUBLE_EQ(m.photometric_cheap_pair_s, reference.photometric_cheap_pair_s);
  EXPECT_DOUBLE_EQ(m.gauss_seidel_nnz_s, reference.gauss_seidel_nnz_s);
  EXPECT_DOUBLE_EQ(m.dense_flop_s, reference.dense_flop_s);
  EXPECT_DOUBLE_EQ(m.scene_patch_s, reference.scene_patch_s);
}

TEST(MachineCosts, FollowTheSpeedOfTheirKindOfWork) {
  const MachineCosts r;
  const MachineCosts m = machine_costs(MachineSpeed{2.0, 3.0, 5.0}, 2);
  for (auto [here, there] : {std::pair{m.gather_ray_s, r.gather_ray_s}, {m.precise_pair_ray_s, r.precise_pair_ray_s},
                             {m.cheap_pair_s, r.cheap_pair_s}, {m.photometric_cheap_pair_s, r.photometric_cheap_pair_s},
                             {m.point_source_s, r.point_source_s}, {m.scene_patch_s, r.scene_patch_s},
                             {m.output_patch_s, r.output_patch_s}, {m.output_base_s, r.output_base_s}})
    EXPECT_DOUBLE_EQ(here, 2.0 * there);
  for (auto [here, there] : {std::pair{m.sparse_flop_s, r.sparse_flop_s}, {m.gauss_seidel_nnz_s, r.gauss_seidel_nnz_s},
                             {m.blend_mac_s, r.blend_mac_s}})
    EXPECT_DOUBLE_EQ(here, 3.0 * there);
  EXPECT_DOUBLE_EQ(m.dense_flop_s, 5.0 * r.dense_flop_s);
  // Counts and fits are not times.
  EXPECT_EQ(m.gauss_seidel_sweeps, r.gauss_seidel_sweeps);
  EXPECT_DOUBLE_EQ(m.hit_coverage, r.hit_coverage);
}

TEST(MachineCosts, OneThreadTakesAmdahlsShareLongerButReadingTheModelDoesNot) {
  const MachineCosts r, one = machine_costs(MachineSpeed{}, 1), four = machine_costs(MachineSpeed{}, 4);
  const double slower = 1.0 / (kSerialShare + (1.0 - kSerialShare) / 2.0);
  EXPECT_NEAR(one.gather_ray_s / r.gather_ray_s, slower, 1e-12);
  EXPECT_NEAR(one.gauss_seidel_nnz_s / r.gauss_seidel_nnz_s, slower, 1e-12);
  EXPECT_DOUBLE_EQ(one.scene_patch_s, r.scene_patch_s);
  EXPECT_LT(four.gather_ray_s, r.gather_ray_s);
  // Threads are counted up to the cores: 0 is every core, and more run no faster.
  EXPECT_EQ(usable_threads(1), 1);
  EXPECT_EQ(usable_threads(4096), usable_threads(0));
  EXPECT_GE(usable_threads(0), 1);
  // The classroom ran 1.63x longer on one thread than on two (docs/benchmarks.md).
  EXPECT_NEAR(slower, 1.63, 0.02);
}

// `text` as the calibration file in `folder`.
std::string write_calibration(const std::string& folder, const std::string& text) {
  std::filesystem::create_directories(folder);
  const std::string file = calibration_path(folder);
  std::ofstream(file, std::ios::trunc) << text;
  return file;
}

std::string file_with(const ProbeTimes& p) {
  std::ostringstream os;
  os << "ilp machine calibration 1\nkey: " << machine_key_text() << "\nprobed: 2026-12-03T00:00:00Z\nray_s: " << p.ray_s
     << "\nsparse_nnz_s: " << p.sparse_nnz_s << "\ndense_flop_s: " << p.dense_flop_s << "\n";
  return os.str();
}

TEST(MachineCalibration, IsProbedOnceThenReadAsWritten) {
  TempDir dir;
  const MachineCalibration first = calibrate_machine(dir.file("cache"));
  EXPECT_TRUE(Contains(first.note, "probed now (none cached) and cached in"));
  ASSERT_FALSE(first.file.empty());
  for (double t : {first.probe.ray_s, first.probe.sparse_nnz_s, first.probe.dense_flop_s}) {
    EXPECT_GT(t, 0.0);
    EXPECT_LT(t, 1e-5);
  }
  const MachineCalibration again = calibrate_machine(dir.file("cache"));
  EXPECT_EQ(first.file, calibration_path(dir.file("cache")));
  EXPECT_EQ(again.note, "cached in " + first.file);
  // The figures read back are the ones written, to the 7 digits the file keeps.
  EXPECT_NEAR(again.probe.ray_s / first.probe.ray_s, 1.0, 1e-6);
  EXPECT_NEAR(again.speed.memory / first.speed.memory, 1.0, 1e-6);
  EXPECT_TRUE(Contains(describe(again), "rays "));
}

TEST(MachineCalibration, ACachedFileSetsTheSpeedAgainstTheReference) {
  TempDir dir;
  write_calibration(dir.file("cache"), file_with({2.0 * kReferenceProbe.ray_s, 3.0 * kReferenceProbe.sparse_nnz_s,
                                                 0.5 * kReferenceProbe.dense_flop_s}));
  const MachineCalibration c = calibrate_machine(dir.file("cache"));
  EXPECT_NEAR(c.speed.rays, 2.0, 1e-6);
  EXPECT_NEAR(c.speed.memory, 3.0, 1e-6);
  EXPECT_NEAR(c.speed.dense, 0.5, 1e-6);
}

TEST(MachineCalibration, ACorruptStaleOrForeignFileIsReplacedNeverTrusted) {
  const struct {
    std::string text, why;
  } cases[] = {
      {"", "is not a calibration of this version"},
      {"ilp machine calibration 0\n", "is not a calibration of this version"},
      {"ilp machine calibration 1\nkey: another cpu\nray_s: 1e-7\nsparse_nnz_s: 1e-9\ndense_flop_s: 1e-10\n",
       "is another machine's or build's"},
      {file_with({1e-7, -1e-9, 1e-10}), "is incomplete or corrupt"},
      {file_with({1e-7, 1e-9, std::nan("")}), "is incomplete or corrupt"},
      {file_with({1e-7, 1e-9, 1e300}), "is incomplete or corrupt"},
      {"ilp machine calibration 1\nkey: " + machine_key_text() + "\nray_s: 1e-7\n", "is incomplete or corrupt"},
  };
  for (const auto& c : cases) {
    TempDir dir;
    const std::string file = write_calibration(dir.file("cache"), c.text);
    const MachineCalibration replaced = calibrate_machine(dir.file("cache"));
    EXPECT_TRUE(Contains(replaced.note, c.why)) << c.text;
    EXPECT_TRUE(Contains(replaced.note, "and cached in")) << c.text;
    EXPECT_EQ(calibrate_machine(dir.file("cache")).note, "cached in " + file) << "the replacement is whole";
  }
}

TEST(MachineCalibration, ProbingAgainReplacesTheFile) {
  TempDir dir;
  write_calibration(dir.file("cache"), file_with({1e-4, 1e-4, 1e-4}));  // read as is: no probe replaces it
  EXPECT_FALSE(Contains(calibrate_machine(dir.file("cache")).note, "probed"));
  const MachineCalibration again = calibrate_machine(dir.file("cache"), true);
  EXPECT_TRUE(Contains(again.note, "probed now (asked to probe again) and cached in"));
  EXPECT_LT(calibrate_machine(dir.file("cache")).probe.ray_s, 1e-5);
}

TEST(MachineCalibration, AFolderThatCannotBeWrittenIsProbedNotCached) {
  TempDir dir;
  const std::string not_a_folder = dir.write("plain", "a file where the cache folder would be\n");
  const MachineCalibration c = calibrate_machine(not_a_folder);
  EXPECT_TRUE(c.file.empty());
  EXPECT_TRUE(Contains(c.note, "not cached: cannot write")) << c.note;
  EXPECT_GT(c.speed.rays, 0.0);
  const MachineCalibration none = calibrate_machine("");
  EXPECT_TRUE(Contains(none.note, "probed now (no cache folder), not cached")) << none.note;
}

}  // namespace
}  // namespace ilp
