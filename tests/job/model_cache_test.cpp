// The operator cache: a saved and loaded model is the built one bit for bit; the
// key changes with what the operator depends on and only with that; a damaged,
// stale or foreign file is reported, rebuilt and replaced; an unwritable cache
// folder does not fail the job.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "core/base/key_hash.h"
#include "job/config.h"
#include "job/job_runner.h"
#include "job/model_cache.h"
#include "job/products.h"
#include "job/plan.h"
#include "optimizer/layout_search.h"
#include "tests/key_coverage.h"
#include "tests/optimizer/optimizer_test_scenes.h"

namespace ilp {
namespace {

using test::Contains;
using test::expect_key_covers_fields;
using test::left_out;
using test::room_job;
using test::room_obj;
using test::StartsWith;
using test::TempDir;

const char* kLuminaires =
    "  size_m: 0.3\n  flux_lm: [10, 20000]\n  efficacy_lm_per_w: 100\n  mounting_surface: ceiling\n"
    "  mount_offset_m: 0.02\n  candidate_spacing_m: 0.5\n  count: 1\n";
const char* kOptimizer = "optimizer:\n  max_evaluations: 1500\n  local_max_evaluations: 1500\n  seed: 4\n";

// The small room of layout_search_test.cpp with a second mat, reflectance 0.5 (so
// the operator has a sample), one goal on the first mat.
JobConfig cache_job(const TempDir& dir, const std::string& reflectance = "0.5") {
  dir.write("room.obj", room_obj({{"mat", {1.3, 1.7}}, {"other", {3.0, 2.5}}}));
  return load_job_config(
      dir.write("job.yaml", room_job(reflectance, kLuminaires, "  - surface: mat\n    average_lux: 200\n", kOptimizer)));
}

template <class M>
::testing::AssertionResult SameBits(const M& a, const M& b, const char* what) {
  if (a.rows() != b.rows() || a.cols() != b.cols())
    return ::testing::AssertionFailure() << what << ": " << a.rows() << " x " << a.cols() << " against " << b.rows()
                                         << " x " << b.cols();
  if (a.size() > 0 && std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) != 0)
    return ::testing::AssertionFailure() << what << ": the values differ";
  return ::testing::AssertionSuccess();
}

// The operator part of two models; with `timings`, also the seconds (only a model
// saved and loaded has the same ones).
void expect_same_operator(const LightingModel& a, const LightingModel& b, bool timings) {
  EXPECT_TRUE(SameBits(a.fixed_lux, b.fixed_lux, "fixed_lux"));
  EXPECT_TRUE(SameBits(a.fixed_direct_lux, b.fixed_direct_lux, "fixed_direct_lux"));
  EXPECT_TRUE(SameBits(a.candidate_lux_per_lm, b.candidate_lux_per_lm, "candidate_lux_per_lm"));
  EXPECT_TRUE(SameBits(a.candidate_direct_lux_per_lm, b.candidate_direct_lux_per_lm, "candidate_direct_lux_per_lm"));
  EXPECT_EQ(a.fixed_flux_lm, b.fixed_flux_lm);
  EXPECT_EQ(a.sample_size, b.sample_size);
  EXPECT_EQ(a.log, b.log);
  const SampleOperatorStats &s = a.stats, &t = b.stats;
  EXPECT_EQ(s.patches, t.patches);
  EXPECT_EQ(s.population, t.population);
  EXPECT_EQ(s.sample_patches, t.sample_patches);
  EXPECT_EQ(s.census, t.census);
  EXPECT_EQ(s.direct_only, t.direct_only);
  EXPECT_EQ(s.channels, t.channels);
  EXPECT_EQ(s.goal_patches, t.goal_patches);
  EXPECT_EQ(s.direct_rows, t.direct_rows);
  EXPECT_EQ(s.cheap_direct_rows, t.cheap_direct_rows);
  EXPECT_EQ(s.goal_fallback_rows, t.goal_fallback_rows);
  EXPECT_EQ(s.goal_fallback_area_fraction, t.goal_fallback_area_fraction);
  EXPECT_EQ(s.sample_fallback_rows, t.sample_fallback_rows);
  EXPECT_EQ(s.condition_estimate, t.condition_estimate);
  EXPECT_EQ(s.max_row_sum, t.max_row_sum);
  EXPECT_EQ(s.condition_bound_inf, t.condition_bound_inf);
  EXPECT_EQ(s.rays_cast, t.rays_cast);
  if (timings) {
    EXPECT_EQ(s.goal_seconds, t.goal_seconds);
    EXPECT_EQ(s.sample_row_seconds, t.sample_row_seconds);
    EXPECT_EQ(s.direct_seconds, t.direct_seconds);
    EXPECT_EQ(s.solve_seconds, t.solve_seconds);
    EXPECT_EQ(s.response_seconds, t.response_seconds);
    EXPECT_EQ(a.build_seconds, b.build_seconds);
  }
}

// The job's one variant (the plain panel): its stages' inputs.
VariantPlan plan_of(const JobConfig& job, const RunOptions& run = {}) { return plan_job(job, run).variants.front(); }

std::string key_of(const JobConfig& job, const RunOptions& run = {}) {
  return lighting_model_key(scene_spec(job), plan_of(job, run).model);
}

PreparedJob prepare(const JobConfig& job, const std::string& cache_dir = "") {
  return prepare_job(scene_spec(job), plan_of(job), {}, {}, cache_dir);
}

// A model with only the geometry part, as prepare_job has it before the cache.
LightingModel geometry_of(const PreparedJob& prepared) {
  return lighting_model_geometry(prepared.loaded.scene, prepared.plan.model, prepared.caster.get());
}

std::string cache_file(const std::string& cache_dir, const JobConfig& job) {
  return (std::filesystem::path(cache_dir) / (key_of(job) + ".ilpmodel")).string();
}

TEST(ModelCache, SavedAndLoadedModelIsTheBuiltOneBitForBit) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const PreparedJob built = prepare(job);
  ASSERT_GT(built.model.sample_size, 0) << "reflectance 0.5: the operator has a sample";
  ASSERT_GT(built.model.candidate_lux_per_lm.size(), 0);
  EXPECT_FALSE(built.loaded_from_cache);
  EXPECT_EQ(built.cache_status, "") << "no cache folder, no cache";

  const std::string key = key_of(job);
  EXPECT_EQ(key.size(), 32u);
  save_lighting_model(dir.file("model.ilpmodel"), built.model, key);
  LightingModel loaded = geometry_of(built);
  ASSERT_EQ(loaded.candidate_lux_per_lm.size(), 0);
  const std::optional<std::string> not_used = load_lighting_model(dir.file("model.ilpmodel"), key, loaded);
  ASSERT_FALSE(not_used) << *not_used;
  expect_same_operator(built.model, loaded, true);

  // The search on it finds the same layout along the same path.
  const SearchResult a = search_layout(built.model, built.plan.search), b = search_layout(loaded, built.plan.search);
  EXPECT_EQ(a.evaluations, b.evaluations);
  ASSERT_EQ(a.best.luminaires.size(), b.best.luminaires.size());
  ASSERT_EQ(a.best.luminaires.size(), 1u);
  for (std::size_t j = 0; j < a.best.luminaires.size(); ++j) {
    EXPECT_EQ(a.best.luminaires[j].position_m, b.best.luminaires[j].position_m);
    EXPECT_EQ(a.best.luminaires[j].flux_lm, b.best.luminaires[j].flux_lm);
  }
  EXPECT_TRUE(SameBits(a.best.lux, b.best.lux, "the best layout's lux"));
}

TEST(ModelCache, SecondPrepareLoadsTheOperator) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const std::string cache = dir.file("cache");  // created by prepare_job
  const PreparedJob first = prepare(job, cache);
  EXPECT_FALSE(first.loaded_from_cache);
  EXPECT_EQ(first.cache_status, "operator built and cached in " + cache_file(cache, job));
  ASSERT_TRUE(std::filesystem::is_regular_file(cache_file(cache, job)));
  int files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(cache)) ++files;
  EXPECT_EQ(files, 1) << "the cache file alone: no temporary left behind";

  const PreparedJob second = prepare(job, cache);
  EXPECT_TRUE(second.loaded_from_cache);
  EXPECT_TRUE(StartsWith(second.cache_status, "operator loaded from cache " + cache_file(cache, job) + " (built in "));
  expect_same_operator(first.model, second.model, true);
  // And both are what a build without a cache gives.
  expect_same_operator(prepare(job).model, second.model, false);
  // The geometry part is the job's own, untouched by the cache.
  EXPECT_EQ(second.model.goal_patches, first.model.goal_patches);
  EXPECT_EQ(second.model.grid.size(), first.model.grid.size());
}

TEST(ModelCache, TargetsAndSearchSettingsKeepTheKey) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const std::string key = key_of(job);
  EXPECT_EQ(key_of(job), key) << "the key is a function of the job";
  auto same = [&](const char* what, auto change) {
    JobConfig other = job;
    change(other);
    EXPECT_EQ(key_of(other), key) << what;
  };
  same("goal target", [](JobConfig& j) { set_goal_parameter(j, "goals.mat.average_lux", 400.0); });
  same("another metric on the same goal", [](JobConfig& j) {
    GoalSetting g = j.goals[0];
    g.metric = GoalMetric::uniformity;
    g.target = 0.5;
    j.goals.push_back(g);
  });
  same("flux range", [](JobConfig& j) {
    j.search->flux_min_lm = 100.0;
    j.search->flux_max_lm = 5000.0;
  });
  same("efficacy and count", [](JobConfig& j) {
    j.search->efficacy_lm_per_w = 150.0;
    j.search->count_max = 3;
  });
  same("optimizer seed", [](JobConfig& j) { j.optimizer.seed = 99; });
  same("threads", [](JobConfig& j) { j.form_factors.threads = j.direct_light.threads = 1; });
  same("verification", [](JobConfig& j) { j.verification.rays_per_patch = 64; });
  same("output folder", [](JobConfig& j) { j.output.directory = "elsewhere"; });
  same("constraints", [](JobConfig& j) { j.constraints.min_distance_m = 1.0; });
  same("maintenance factor", [](JobConfig& j) { j.maintenance_factor = 0.8; });
}

TEST(ModelCache, WhatTheOperatorDependsOnChangesTheKey) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const std::string key = key_of(job);
  auto differs = [&](const char* what, auto change) {
    JobConfig other = job;
    change(other);
    EXPECT_NE(key_of(other), key) << what;
  };
  differs("default reflectance", [](JobConfig& j) { j.default_reflectance = Eigen::Vector3d::Constant(0.6); });
  differs("a surface's reflectance", [](JobConfig& j) {
    j.reflectance.push_back({"walls", Eigen::Vector3d::Constant(0.3), {}});
  });
  differs("rays_per_patch", [](JobConfig& j) { j.form_factors.rays_per_patch = 128; });
  differs("max_sample_size (it caps sample_fraction's k)", [](JobConfig& j) { j.sample.max_size_for_target = 100; });
  differs("ray seed", [](JobConfig& j) { j.form_factors.seed = 7; });
  differs("shadow rays", [](JobConfig& j) { j.direct_light.shadow_rays = 16; });
  differs("sample fraction", [](JobConfig& j) { j.sample.fraction = 0.3; });
  differs("candidate_spacing_m", [](JobConfig& j) { j.search->candidate_spacing_m = 0.4; });
  differs("mount offset", [](JobConfig& j) { j.search->mount_offset_m = 0.05; });
  differs("luminaire size", [](JobConfig& j) { j.luminaire_size_m = 0.4; });
  // Grid goals: the grid's every placing value.
  JobConfig on_grid = job;
  CalcGridSetting plane;
  plane.name = "plane";
  plane.over_surface = "floor";
  on_grid.grids.push_back(plane);
  on_grid.goals[0].grid = "plane";
  on_grid.goals[0].surfaces.clear();
  EXPECT_NE(key_of(on_grid), key) << "a goal on a grid";
  const std::string grid_key = key_of(on_grid);
  auto grid_differs = [&](const char* what, auto change) {
    JobConfig other = on_grid;
    change(other.grids[0]);
    EXPECT_NE(key_of(other), grid_key) << what;
  };
  grid_differs("grid height", [](CalcGridSetting& g) { g.height_m = 0.75; });
  grid_differs("grid band", [](CalcGridSetting& g) { g.border_m = 0.3; });
  grid_differs("grid spacing", [](CalcGridSetting& g) { g.spacing_m = 0.3; });
  grid_differs("grid outline", [](CalcGridSetting& g) {
    g.over_surface.clear();
    g.polygon_m = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(1, 1)};
  });
  differs("an added floor", [](JobConfig& j) {
    j.add_floors.push_back({"extra", Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 0.0, Eigen::Vector3d::Constant(0.3), {}});
  });
  differs("a goal's surface", [](JobConfig& j) { j.goals[0].surfaces = {"other"}; });
  differs("a placed luminaire", [](JobConfig& j) {
    LuminaireSetting old;
    old.name = "old";
    old.position_m = {0.5, 0.5, 2.4};
    old.flux_lm = 2000.0;
    j.luminaires.push_back(old);
  });
  differs("patch size", [](JobConfig& j) { j.scene.max_patch_edge_m = 0.3; });
  differs("a goal's facing", [](JobConfig& j) { j.goals[0].facing = GoalFacing::up; });
  differs("an excluded surface", [](JobConfig& j) { j.exclude_surfaces.push_back("walls"); });
  differs("a two-sided surface", [](JobConfig& j) { j.two_sided_surfaces.push_back("walls"); });
  differs("every surface two-sided", [](JobConfig& j) { j.two_sided_all = true; });

  // The mesh's bytes: a comment changes no geometry but is another file.
  {
    std::ofstream obj(job.mesh_path, std::ios::app | std::ios::binary);
    obj << "# a comment\n";
  }
  EXPECT_NE(key_of(job), key) << "the mesh file's bytes";
}

TEST(ModelCache, MaterialFilesAreInTheKey) {
  TempDir dir;
  JobConfig job = cache_job(dir);
  dir.write("room.obj", "mtllib room.mtl\n" + room_obj({{"mat", {1.3, 1.7}}, {"other", {3.0, 2.5}}}));
  dir.write("room.mtl", "newmtl white\nKd 0.5 0.5 0.5\n");
  const std::string with_mtl = key_of(job);
  dir.write("room.mtl", "newmtl white\nKd 0.6 0.6 0.6\n");
  const std::string changed = key_of(job);
  EXPECT_NE(changed, with_mtl) << "the MTL's bytes";
  std::filesystem::remove(dir.file("room.mtl"));
  const std::string missing = key_of(job);  // no throw: a missing MTL contributes a marker
  EXPECT_NE(missing, with_mtl);
  EXPECT_NE(missing, changed);
  dir.write("room.mtl", "newmtl white\nKd 0.5 0.5 0.5\n");
  EXPECT_EQ(key_of(job), with_mtl) << "the same bytes, the same key";
}

TEST(ModelCache, TheFluxRangeCountsOnlyWithATargetError) {
  TempDir dir;
  JobConfig job = cache_job(dir);
  job.sample.target_error = 0.05;  // k is then chosen with every candidate at the top of the flux range
  const std::string key = key_of(job);
  JobConfig other = job;
  other.search->flux_max_lm = 5000.0;
  EXPECT_NE(key_of(other), key);
  other = job;
  other.search->flux_min_lm = 100.0;
  EXPECT_EQ(key_of(other), key);
}

// A damaged or foreign cache file: load_lighting_model says why and leaves the model
// as it was; prepare_job rebuilds (the model is a fresh build's) and rewrites the
// file, which the next prepare_job loads.
void expect_rebuilt(const TempDir& dir, const JobConfig& job, const std::string& reason_start,
                    const std::function<void(const std::string& file, const LightingModel& model)>& damage) {
  const std::string cache = dir.file("cache");
  const PreparedJob fresh = prepare(job);
  const PreparedJob first = prepare(job, cache);
  ASSERT_FALSE(first.loaded_from_cache);
  const std::string file = cache_file(cache, job);
  damage(file, first.model);

  LightingModel model = geometry_of(first);
  const std::size_t log_lines = model.log.size();
  const std::optional<std::string> not_used = load_lighting_model(file, key_of(job), model);
  ASSERT_TRUE(not_used) << "the damaged file was used";
  EXPECT_TRUE(StartsWith(*not_used, reason_start));
  EXPECT_EQ(model.fixed_lux.size(), 0) << "the model was touched";
  EXPECT_EQ(model.candidate_lux_per_lm.size(), 0) << "the model was touched";
  EXPECT_EQ(model.sample_size, 0);
  EXPECT_EQ(model.log.size(), log_lines);

  const PreparedJob second = prepare(job, cache);
  EXPECT_FALSE(second.loaded_from_cache);
  EXPECT_TRUE(Contains(second.cache_status, "operator built and cached in " + file));
  EXPECT_TRUE(Contains(second.cache_status, "the cached file was not used: " + reason_start));
  expect_same_operator(fresh.model, second.model, false);

  const PreparedJob third = prepare(job, cache);
  EXPECT_TRUE(third.loaded_from_cache) << third.cache_status;
  expect_same_operator(second.model, third.model, true);
}

// A run killed while writing the cache left "KEY.ilpmodel.tmp.PID.N" for ever. The
// next read or write of the folder removes those of processes that have gone, and
// leaves a running process's alone.
TEST(ModelCache, TemporariesOfKilledRunsAreRemoved) {
  TempDir dir;
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);  // a process id that no longer runs
  const std::string stale = dir.write("abc.ilpmodel.tmp." + std::to_string(child) + ".0", "half a model");
  const std::string mine = dir.write("abc.ilpmodel.tmp." + std::to_string(::getpid()) + ".7", "being written");
  const std::string other = dir.write("notes.tmp.1.2", "not the cache's");
  LightingModel model;
  EXPECT_TRUE(load_lighting_model(dir.file("abc.ilpmodel"), "abc", model).has_value());  // no cache file
  EXPECT_FALSE(std::filesystem::exists(stale));
  EXPECT_TRUE(std::filesystem::exists(mine));
  EXPECT_TRUE(std::filesystem::exists(other));
}

// A cache folder shared by a cluster's nodes (docs/cluster.md): a temporary named with
// another machine is that machine's to remove (its process id means nothing here); one
// named with this machine and a process that has gone is removed.
TEST(ModelCache, AnotherMachinesTemporariesAreLeftAlone) {
  TempDir dir;
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  char host[256] = {};
  ASSERT_EQ(gethostname(host, sizeof host - 1), 0);
  std::string here(host);
  for (char& c : here)
    if (c == '/' || c == '.') c = '_';
  const std::string tmp = "abc.ilpmodel.tmp." + std::to_string(child) + ".0.";
  const std::string theirs = dir.write(tmp + "node_" + here, "another node writing");
  const std::string ours = dir.write(tmp + here, "half a model");
  LightingModel model;
  EXPECT_TRUE(load_lighting_model(dir.file("abc.ilpmodel"), "abc", model).has_value());
  EXPECT_TRUE(std::filesystem::exists(theirs));
  EXPECT_FALSE(std::filesystem::exists(ours));
}

TEST(ModelCache, FlippedByteIsCorrupt) {
  TempDir dir;
  expect_rebuilt(dir, cache_job(dir), "corrupt: checksum mismatch", [](const std::string& file, const LightingModel&) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(0, std::ios::end);
    const std::streamoff middle = f.tellg() / 2;
    f.seekg(middle);
    char c = 0;
    f.get(c);
    f.seekp(middle);
    f.put(static_cast<char>(c ^ 0x01));
  });
}

TEST(ModelCache, TruncatedFileIsTruncated) {
  TempDir dir;
  expect_rebuilt(dir, cache_job(dir), "truncated", [](const std::string& file, const LightingModel&) {
    std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
  });
}

TEST(ModelCache, FileWithAnotherKeyIsStale) {
  TempDir dir;
  expect_rebuilt(dir, cache_job(dir), "stale: the key differs", [](const std::string& file, const LightingModel& model) {
    save_lighting_model(file, model, std::string(32, '0'));
  });
}

TEST(ModelCache, AnotherFormatVersionIsNotUsed) {
  TempDir dir;
  expect_rebuilt(dir, cache_job(dir), "written by another format version",
                 [](const std::string& file, const LightingModel&) {
                   std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
                   f.seekp(8);  // after the magic: u32 version, little-endian
                   const char version[4] = {static_cast<char>(kLightingModelCacheVersion + 1), 0, 0, 0};
                   f.write(version, 4);
                 });
}

TEST(ModelCache, MissingOrForeignFilesAreReported) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const PreparedJob built = prepare(job);
  LightingModel model = geometry_of(built);
  const std::string key = key_of(job);
  EXPECT_EQ(load_lighting_model(dir.file("none.ilpmodel"), key, model), "no cache file");
  EXPECT_TRUE(StartsWith(load_lighting_model(dir.write("foreign.ilpmodel", "hello, world\n"), key, model).value(),
                         "corrupt: not an ilp model cache file"));
  EXPECT_TRUE(StartsWith(load_lighting_model(dir.write("empty.ilpmodel", ""), key, model).value(), "truncated"));
  // A model of other sizes under the right key: the sizes are checked against the scene.
  JobConfig coarse = job;
  coarse.search->candidate_spacing_m = 1.0;
  const PreparedJob other = prepare(coarse);
  ASSERT_NE(other.model.grid.size(), built.model.grid.size());
  save_lighting_model(dir.file("other.ilpmodel"), other.model, key);
  EXPECT_TRUE(StartsWith(load_lighting_model(dir.file("other.ilpmodel"), key, model).value(),
                         "sizes do not match the scene's goal patches/candidates"));
  EXPECT_EQ(model.candidate_lux_per_lm.size(), 0);
  // A file, not a folder, where the cache file should be written: an error that names it.
  EXPECT_THROW(save_lighting_model(dir.file("job.yaml") + "/x.ilpmodel", built.model, key), IlpError);
}

TEST(ModelCache, UnwritableCacheFolderStillCompletesTheJob) {
  TempDir dir;
  JobConfig job = cache_job(dir);
  job.verification.method = VerificationMethod::none;
  // A folder inside a regular file can be neither created nor written (even as root).
  const std::string cache = dir.write("not_a_folder", "") + "/cache";
  const PreparedJob prepared = prepare(job, cache);
  EXPECT_FALSE(prepared.loaded_from_cache);
  EXPECT_TRUE(StartsWith(prepared.cache_status, "operator built; cache not used: ")) << prepared.cache_status;
  EXPECT_TRUE(Contains(prepared.cache_status, cache));
  expect_same_operator(prepare(job).model, prepared.model, false);
  const JobOutcome outcome = solve_prepared(prepared, plan_job(job).goals);
  EXPECT_EQ(outcome.luminaires.size(), 1u);
  EXPECT_TRUE(outcome.feasible);
}

// From the job file to the key: every field of the sections plan_job translates into
// the lighting model's spec reaches the key when it changes the operator (each stage
// struct's own fields are checked in tests/core/key_hash_test.cpp and cache_key_test.cpp;
// this checks the translation drops none).
TEST(ModelCache, EverySolverSettingThatChangesTheOperatorReachesTheKey) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const FileLoc at{"job.yaml", 9, 3};
  expect_key_covers_fields<SampleSettings>("SampleSettings", job.sample, {
      {"size", [](SampleSettings& s) { s.size = 50; }},
      {"fraction", [](SampleSettings& s) { s.fraction = 0.3; }},
      left_out<SampleSettings>("size_loc", [&](SampleSettings& s) { s.size_loc = at; }),
      {"strategy", [](SampleSettings& s) { s.strategy = SampleStrategy::uniform; }},
      {"seed", [](SampleSettings& s) { s.seed = 5; }},
      {"indirect", [](SampleSettings& s) { s.indirect = IndirectMethod::sample_gather; }},
      {"target_error", [](SampleSettings& s) { s.target_error = 0.05; }},
      left_out<SampleSettings>("target_error_loc", [&](SampleSettings& s) { s.target_error_loc = at; }),
      {"error_samples", [](SampleSettings& s) { s.error_samples = 8; }},
      {"pilot_fraction", [](SampleSettings& s) { s.pilot_fraction = 0.04; }},
      {"max_size_for_target", [](SampleSettings& s) { s.max_size_for_target = 100; }},
      left_out<SampleSettings>("max_size_loc", [&](SampleSettings& s) { s.max_size_loc = at; }),
      {"reflected_stride", [](SampleSettings& s) { s.reflected_stride = 3; }},
      {"hit_block_patches", [](SampleSettings& s) { s.hit_block_patches = 97; }},
  }, [&](const SampleSettings& sample) {
    JobConfig j = job;
    j.sample = sample;
    return key_of(j);
  });
}

TEST(ModelCache, EveryLuminaireSettingThatChangesTheCandidatesReachesTheKey) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const FileLoc at{"job.yaml", 9, 3};
  expect_key_covers_fields<LuminaireSearch>("LuminaireSearch", *job.search, {
      left_out<LuminaireSearch>("model", [](LuminaireSearch& s) { s.model = "another"; }),  // the only model: not read
      left_out<LuminaireSearch>("flux_min_lm", [](LuminaireSearch& s) { s.flux_min_lm = 100.0; }),
      // (the top of the range counts only with a target error: TheFluxRangeCountsOnlyWithATargetError)
      left_out<LuminaireSearch>("flux_max_lm", [](LuminaireSearch& s) { s.flux_max_lm = 5000.0; }),
      left_out<LuminaireSearch>("flux_loc", [&](LuminaireSearch& s) { s.flux_loc = at; }),
      left_out<LuminaireSearch>("efficacy_lm_per_w", [](LuminaireSearch& s) { s.efficacy_lm_per_w = 150.0; }),
      {"mounting_surface", [](LuminaireSearch& s) { s.mounting_surface = "floor"; }},
      left_out<LuminaireSearch>("mounting_loc", [&](LuminaireSearch& s) { s.mounting_loc = at; }),
      {"mount_offset_m", [](LuminaireSearch& s) { s.mount_offset_m = 0.05; }},
      left_out<LuminaireSearch>("offset_loc", [&](LuminaireSearch& s) { s.offset_loc = at; }),
      {"candidate_spacing_m", [](LuminaireSearch& s) { s.candidate_spacing_m = 0.4; }},
      left_out<LuminaireSearch>("spacing_loc", [&](LuminaireSearch& s) { s.spacing_loc = at; }),
      left_out<LuminaireSearch>("count_min", [](LuminaireSearch& s) { s.count_min = 2; }),
      left_out<LuminaireSearch>("count_max", [](LuminaireSearch& s) { s.count_max = 3; }),
      left_out<LuminaireSearch>("count_loc", [&](LuminaireSearch& s) { s.count_loc = at; }),
      {"wall_distance_m", [](LuminaireSearch& s) { s.wall_distance_m = 0.3; }},
      {"ceiling_module_m", [](LuminaireSearch& s) { s.ceiling_module_m = 0.6; }},
      // An array keeps the whole surface (no zone from the goals): the candidates change.
      {"layout", [](LuminaireSearch& s) { s.layout = LayoutFamily::array; }},
      left_out<LuminaireSearch>("array_rows", [](LuminaireSearch& s) { s.array_rows = 2; }),
      left_out<LuminaireSearch>("array_columns", [](LuminaireSearch& s) { s.array_columns = 2; }),
      left_out<LuminaireSearch>("array_spacing_m", [](LuminaireSearch& s) { s.array_spacing_m = Eigen::Vector2d(1, 1); }),
      left_out<LuminaireSearch>("array_offset_m", [](LuminaireSearch& s) { s.array_offset_m = Eigen::Vector2d(0.5, 0.5); }),
      left_out<LuminaireSearch>("layout_loc", [&](LuminaireSearch& s) { s.layout_loc = at; }),
      left_out<LuminaireSearch>("regular", [](LuminaireSearch& s) { s.regular.rows = {2, 3}; }),
      left_out<LuminaireSearch>("individual_output", [](LuminaireSearch& s) { s.individual_output = true; }),
      {"zone_m", [](LuminaireSearch& s) { s.zone_m = std::make_pair(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)); }},
      {"zone_margin_m", [](LuminaireSearch& s) { s.zone_margin_m = 1.0; }},
      left_out<LuminaireSearch>("zone_set", [](LuminaireSearch& s) { s.zone_set = true; }),  // matters for arrays only
      left_out<LuminaireSearch>("zone_loc", [&](LuminaireSearch& s) { s.zone_loc = at; }),
      {"suspended_height_m", [](LuminaireSearch& s) { s.suspended_height_m = 2.0; }},
      left_out<LuminaireSearch>("suspended_loc", [&](LuminaireSearch& s) { s.suspended_loc = at; }),
      {"on_wall", [](LuminaireSearch& s) { s.on_wall = WallMountSpec{}; }},
      {"floor_surface", [](LuminaireSearch& s) { s.floor_surface = "floor"; }},
      left_out<LuminaireSearch>("floor_loc", [&](LuminaireSearch& s) { s.floor_loc = at; }),
  }, [&](const LuminaireSearch& search) {
    JobConfig j = job;
    j.search = search;
    return key_of(j);
  });
}

// luminaires.products (a JobConfig field since placed luminaires name products too)
// reach the key through the candidates' type.
TEST(ModelCache, AProductInPlaceOfThePanelChangesTheKey) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  ProductSetting panel;
  panel.name = "small panel";
  panel.size_m = 0.3;
  panel.flux_lm = 3000.0;
  panel.power_w = 25.0;
  JobConfig with = job;
  with.products = {panel};
  EXPECT_NE(key_of(with), key_of(job));
}

TEST(ModelCache, TheThreadCountOfTheRunKeepsTheKey) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  RunOptions run;
  run.threads = 1;
  EXPECT_EQ(key_of(job, run), key_of(job));
}

// The key's text is the format version, the scene's inputs and the model's spec, one
// named field a line: two keys' texts show the field they differ in.
TEST(ModelCache, TheKeyTextNamesTheFields) {
  TempDir dir;
  const JobConfig job = cache_job(dir);
  const VariantPlan plan = plan_of(job);
  const std::string text = lighting_model_key_text(scene_spec(job), plan.model);
  EXPECT_TRUE(StartsWith(text, "ilp_lighting_model_cache_format=u" + std::to_string(kLightingModelCacheVersion) + "\n"));
  EXPECT_TRUE(Contains(text, "\nmesh_bytes=s"));
  EXPECT_TRUE(Contains(text, "\nmodel={\ncandidates={\nmounting_surface=s7:ceiling\n"));
  EXPECT_TRUE(Contains(text, "\nrays_per_patch=i64\n"));
  EXPECT_EQ(lighting_model_key(scene_spec(job), plan.model).size(), 32u);
}

}  // namespace
}  // namespace ilp
