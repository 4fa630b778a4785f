// Bad input handling of the job file (load_job_config) and of the scene it names
// (load_job_scene): every error must be the right type and say where it is
// (file:line), which key, and what was wrong. Every test writes its own small YAML
// and OBJ files into a fresh temporary folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include "job/config.h"
#include "job/job_scene.h"
#include "job/plan.h"
#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::Contains;
using ilp::test::error_of;
using ilp::test::expect_message;
using ilp::test::TempDir;

std::string config_error(const std::string& yaml) {
  return error_of<ilp::ConfigError>([&] { (void)ilp::load_job_config(yaml); });
}

// Loads config then scene; the config itself must be valid.
template <class E>
std::string scene_error(const std::string& yaml) {
  ilp::JobConfig job;
  try {
    job = ilp::load_job_config(yaml);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "config should load: " << e.what();
    return {};
  }
  return error_of<E>([&] { (void)ilp::load_job_scene(scene_spec(job)); });
}

// `msg` starts with "<file>:<line>:" (line 0: "<file>: ", no line) and contains each
// of `says`.
void expect_error_at(const std::string& msg, const std::string& file, int line, const std::vector<std::string>& says) {
  expect_message(msg, file + (line ? ":" + std::to_string(line) + ":" : std::string(": ")), says);
}

// job.yaml holding `text` must fail load_job_config with a ConfigError at `line`
// (see expect_error_at) that says each of `says`; with `col` > 0 the message must
// start with "<file>:<line>:<col>:".
void expect_config_error(const std::string& text, int line, const std::vector<std::string>& says, int col = 0) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", text);
  if (col > 0)
    expect_message(config_error(yaml), yaml + ":" + std::to_string(line) + ":" + std::to_string(col) + ":", says);
  else
    expect_error_at(config_error(yaml), yaml, line, says);
}

// A unit floor (one quad, group floor) and a wall (one quad, group wall).
const char* kRoomObj =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 1 1 0\n"
    "v 0 1 0\n"
    "v 0 0 1\n"
    "v 1 0 1\n"
    "g floor\n"
    "f 1 2 3 4\n"
    "g wall\n"
    "f 1 5 6 2\n";

// Patches of one surface of a loaded scene.
std::vector<const ilp::Patch*> patches_of(const ilp::Scene& scene, const std::string& surface) {
  std::vector<const ilp::Patch*> out;
  const int s = scene.find_surface(surface);
  for (const ilp::Patch& p : scene.patches)
    if (p.surface == s) out.push_back(&p);
  return out;
}

// Next to room.obj (kRoomObj), job.yaml holding `text` must load, and load_job_scene
// then fail with a ConfigError at `line` (see expect_error_at) that says each of
// `says`.
void expect_room_error(const std::string& text, int line, const std::vector<std::string>& says) {
  TempDir dir;
  dir.write("room.obj", kRoomObj);
  const std::string yaml = dir.write("job.yaml", text);
  expect_error_at(scene_error<ilp::ConfigError>(yaml), yaml, line, says);
}

// Loads the job `yaml` names: the room's two floor and two wall patches must have
// these reflectances, and the scene `channels` channels.
void expect_room_reflectance(const std::string& yaml, const Eigen::Vector3d& floor_rho, const Eigen::Vector3d& wall_rho,
                             int channels) {
  const ilp::JobScene loaded = ilp::load_job_scene(scene_spec(ilp::load_job_config(yaml)));
  const auto floor = patches_of(loaded.scene, "floor");
  const auto wall = patches_of(loaded.scene, "wall");
  ASSERT_EQ(floor.size(), 2u);
  ASSERT_EQ(wall.size(), 2u);
  for (const ilp::Patch* p : floor) EXPECT_EQ(p->reflectance, floor_rho);
  for (const ilp::Patch* p : wall) EXPECT_EQ(p->reflectance, wall_rho);
  EXPECT_EQ(loaded.scene.channels, channels);
}

// ---------------------------------------------------------------------------------
// Valid input

TEST(JobConfig, ReadsEveryKey) {
  TempDir dir;
  dir.write("room.obj", kRoomObj);
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: room.obj\n"
                                     "  up_axis: Y\n"
                                     "  scale_to_m: 0.001\n"
                                     "  max_patch_edge_m: 0.25\n"
                                     "  surfaces_from: material\n"
                                     "  reflectance:\n"
                                     "    floor: 0.2\n"
                                     "    wall: [0.1, 0.2, 0.3]\n"
                                     "  default_reflectance: 0.4\n"
                                     "  emitting_surfaces:\n"
                                     "    - {surface: wall, exitance_lm_per_m2: 12.5}\n"
                                     "luminaires:\n"
                                     "  size_m: 0.3\n"
                                     "  placed:\n"
                                     "    - {name: A, position_m: [1, 2, 3], flux_lm: 1000}\n"
                                     "    - {position_m: [4, 5, 6], flux_lm: 0}\n"
                                     "solver:\n"
                                     "  rays_per_patch: 64\n"
                                     "  seed: 7\n"
                                     "  threads: 2\n"
                                     "  relative_residual: 1.0e-6\n"
                                     "  max_iterations: 500\n"
                                     "  direct_receiver_points: 4\n"
                                     "  direct_shadow_rays: 8\n"
                                     "report:\n"
                                     "  surfaces: [floor, wall]\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_EQ(job.path, yaml);
  EXPECT_EQ(job.mesh_path, dir.file("room.obj"));  // resolved against the config's folder
  EXPECT_EQ(job.mesh_loc.file, yaml);
  EXPECT_EQ(job.mesh_loc.line, 2);
  EXPECT_EQ(job.scene.up_axis, ilp::UpAxis::y);
  EXPECT_DOUBLE_EQ(job.scene.scale_to_m, 0.001);
  EXPECT_DOUBLE_EQ(job.scene.max_patch_edge_m, 0.25);
  EXPECT_EQ(job.mesh_read.surface_naming, ilp::SurfaceNaming::material);
  ASSERT_EQ(job.reflectance.size(), 2u);
  EXPECT_EQ(job.reflectance[0].surface, "floor");
  EXPECT_EQ(job.reflectance[0].rgb, Eigen::Vector3d::Constant(0.2));
  EXPECT_EQ(job.reflectance[0].loc.line, 8);
  EXPECT_EQ(job.reflectance[1].surface, "wall");
  EXPECT_EQ(job.reflectance[1].rgb, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(job.reflectance[1].loc.line, 9);
  ASSERT_TRUE(job.default_reflectance.has_value());
  EXPECT_EQ(*job.default_reflectance, Eigen::Vector3d::Constant(0.4));
  ASSERT_EQ(job.emitting_surfaces.size(), 1u);
  EXPECT_EQ(job.emitting_surfaces[0].surface, "wall");
  EXPECT_DOUBLE_EQ(job.emitting_surfaces[0].exitance_lm_per_m2, 12.5);
  EXPECT_EQ(job.emitting_surfaces[0].loc.line, 12);
  EXPECT_DOUBLE_EQ(job.luminaire_size_m, 0.3);
  ASSERT_EQ(job.luminaires.size(), 2u);
  EXPECT_EQ(job.luminaires[0].name, "A");
  EXPECT_EQ(job.luminaires[0].position_m, Eigen::Vector3d(1, 2, 3));
  EXPECT_DOUBLE_EQ(job.luminaires[0].flux_lm, 1000.0);
  EXPECT_EQ(job.luminaires[0].loc.line, 16);
  EXPECT_EQ(job.luminaires[1].name, "L2");  // unnamed: numbered
  EXPECT_EQ(job.luminaires[1].position_m, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(job.form_factors.rays_per_patch, 64);
  EXPECT_EQ(job.form_factors.seed, 7u);
  EXPECT_EQ(job.direct_light.seed, 7u);
  EXPECT_EQ(job.form_factors.threads, 2);
  EXPECT_EQ(job.direct_light.threads, 2);
  EXPECT_DOUBLE_EQ(job.radiosity.relative_residual, 1e-6);
  EXPECT_EQ(job.radiosity.max_iterations, 500);
  EXPECT_EQ(job.direct_light.receiver_points, 4);
  EXPECT_EQ(job.direct_light.shadow_rays, 8);
  EXPECT_EQ(job.report_surfaces, (std::vector<std::string>{"floor", "wall"}));
  ASSERT_EQ(job.report_surface_locs.size(), 2u);
  EXPECT_EQ(job.report_surface_locs[1].line, 27);
}

TEST(JobConfig, EveryShippedConfigLoads) {
  const fs::path configs = fs::path(ILP_SOURCE_DIR) / "configs";
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(configs))
    if (entry.path().extension() == ".yaml") files.push_back(entry.path());
  ASSERT_FALSE(files.empty()) << "no configs/*.yaml in " << configs;
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    ilp::JobConfig job;
    ASSERT_NO_THROW(job = ilp::load_job_config(file.string()));
    ilp::JobScene loaded;
    ASSERT_NO_THROW(loaded = ilp::load_job_scene(scene_spec(job)));
    EXPECT_GT(loaded.scene.patches.size(), 0u);
    for (const ilp::LuminaireSetting& l : job.luminaires) EXPECT_GE(loaded.scene.find_surface(l.name), 0) << l.name;
    for (const std::string& s : job.report_surfaces) EXPECT_GE(loaded.scene.find_surface(s), 0) << s;
  }
}

// luminaires.groups: each group read by the single group's reader into its own options
// (LuminaireSearch), and group_job gives the job as that group alone.
TEST(JobConfig, GroupsReadEachGroupWithTheSingleGroupsKeys) {
  const ilp::JobConfig job = ilp::load_job_config(ILP_SOURCE_DIR "/configs/office_two_groups.yaml");
  EXPECT_FALSE(job.search.has_value());
  ASSERT_EQ(job.groups.size(), 2u);
  EXPECT_EQ(job.groups[0].name, "general");
  EXPECT_EQ(job.groups[0].products, (std::vector<std::string>{"linear LED 2112 lm"}));
  EXPECT_EQ(job.groups[0].search.layout, ilp::LayoutFamily::field);
  EXPECT_EQ(job.groups[0].search.mounting_surface, "ceiling");
  EXPECT_EQ(job.groups[0].search.regular.rows.max, 4);
  EXPECT_EQ(job.groups[0].search.wall_distance_m, 0.3);
  EXPECT_EQ(job.groups[1].name, "wall wash");
  EXPECT_EQ(job.groups[1].search.layout, ilp::LayoutFamily::rows);
  ASSERT_TRUE(job.groups[1].search.on_wall.has_value());
  EXPECT_EQ(job.groups[1].search.on_wall->height_m, 2.6);
  EXPECT_EQ(job.groups[1].search.candidate_spacing_m, 0.25);
  const ilp::JobConfig wall = ilp::group_job(job, 1);
  ASSERT_TRUE(wall.search.has_value());
  EXPECT_TRUE(wall.groups.empty());
  EXPECT_TRUE(wall.search->on_wall.has_value());
  ASSERT_EQ(wall.products.size(), 1u);
  EXPECT_EQ(wall.products[0].name, "wall linear LED");
  EXPECT_EQ(wall.products[0].tilt_deg, 65.0);
  EXPECT_EQ(wall.goals.size(), job.goals.size());
}

TEST(JobConfigErrors, BadGroupsNameTheLineAndKey) {
  std::string shipped = ilp::test::read_file(ILP_SOURCE_DIR "/configs/office_two_groups.yaml");
  for (std::size_t at; (at = shipped.find("../data/")) != std::string::npos;) shipped.replace(at, 8, ILP_SOURCE_DIR "/data/");
  auto with = [&](const std::string& from, const std::string& to) {
    std::string text = shipped;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    return text;
  };
  // The shipped file: luminaires.groups at line 31, the first group at 32, the second at 40.
  expect_config_error(with("  groups:\n", "  on_wall: {surface: walls, height_m: 2, facing: +y}\n  groups:\n"), 31,
                      {"luminaires.on_wall", "not with luminaires.groups"});
  expect_config_error(with("    - name: wall wash", "    - name: general"), 40,
                      {"luminaires.groups[1].name = general", "group name 'general' is used twice"});
  expect_config_error(with("      layout: rows\n", "      layout: rows\n      tint: warm\n"), 47,
                      {"unknown key 'luminaires.groups[1].tint'"});
  expect_config_error(with("      products: [linear LED 2112 lm]\n", ""), 32,
                      {"luminaires.groups[0].products", "required key is missing"});
  const std::size_t first = shipped.find("    - name: general"), second = shipped.find("    - name: wall wash");
  const std::string group = shipped.substr(first, second - first);
  // Any number of groups up to kMaxSearchedGroups (6): a seventh is refused at its line.
  std::string seven = shipped;
  for (int g = 0; g < 6; ++g) seven.insert(second, group);
  expect_config_error(seven, 80, {"luminaires.groups[6]", "at most 6 groups"});
}

// ---------------------------------------------------------------------------------
// The sample-based operator's keys (solver section)

TEST(JobConfig, SolverSampleDefaults) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: room.obj\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_EQ(job.method, ilp::SolveMethod::sample);
  EXPECT_FALSE(job.sample.size.has_value());
  EXPECT_DOUBLE_EQ(job.sample.fraction, 0.05);
  EXPECT_EQ(job.sample.strategy, ilp::SampleStrategy::stratified);
  EXPECT_EQ(job.sample.seed, 1u);
  EXPECT_EQ(job.sample.indirect, ilp::IndirectMethod::exact_second_bounce);
  EXPECT_FALSE(job.sample.target_error.has_value());
  EXPECT_EQ(job.sample.error_samples, 4);
  EXPECT_DOUBLE_EQ(job.sample.pilot_fraction, 0.02);
}

TEST(JobConfig, ReadsSolverSampleSizeKeys) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: room.obj\n"
                                     "solver:\n"
                                     "  method: exact\n"
                                     "  sample_size: 40\n"
                                     "  sampling: uniform\n"
                                     "  sample_seed: 9\n"
                                     "  indirect: sample_gather\n"
                                     "  error_samples: 6\n"
                                     "  pilot_fraction: 0.1\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_EQ(job.method, ilp::SolveMethod::exact);
  ASSERT_TRUE(job.sample.size.has_value());
  EXPECT_EQ(*job.sample.size, 40);
  EXPECT_EQ(job.sample.size_loc.file, yaml);
  EXPECT_EQ(job.sample.size_loc.line, 5);
  EXPECT_EQ(job.sample.strategy, ilp::SampleStrategy::uniform);
  EXPECT_EQ(job.sample.seed, 9u);
  EXPECT_EQ(job.form_factors.seed, 1u);  // the ray seed is separate
  EXPECT_EQ(job.sample.indirect, ilp::IndirectMethod::sample_gather);
  EXPECT_EQ(job.sample.error_samples, 6);
  EXPECT_DOUBLE_EQ(job.sample.pilot_fraction, 0.1);
  EXPECT_FALSE(job.sample.target_error.has_value());
}

TEST(JobConfig, ReadsSolverSampleFraction) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: room.obj\n"
                                     "solver:\n"
                                     "  method: sample\n"
                                     "  sampling: area\n"
                                     "  indirect: exact_second_bounce\n"
                                     "  sample_fraction: 0.25\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_EQ(job.method, ilp::SolveMethod::sample);
  EXPECT_FALSE(job.sample.size.has_value());
  EXPECT_DOUBLE_EQ(job.sample.fraction, 0.25);
  EXPECT_EQ(job.sample.size_loc.line, 7);
  EXPECT_EQ(job.sample.strategy, ilp::SampleStrategy::area);
  EXPECT_EQ(job.sample.indirect, ilp::IndirectMethod::exact_second_bounce);
}

TEST(JobConfig, SampleFractionOneIsTheCensus) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: room.obj\nsolver:\n  sample_fraction: 1\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_DOUBLE_EQ(job.sample.fraction, 1.0);
  EXPECT_EQ(job.sample.size_for(123), 123);
}

TEST(JobConfig, ReadsSolverTargetError) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: room.obj\n"
                                     "solver:\n"
                                     "  sampling: stratified\n"
                                     "  target_error: 0.03\n"
                                     "  error_samples: 2\n"
                                     "  pilot_fraction: 1\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_TRUE(job.sample.target_error.has_value());
  EXPECT_DOUBLE_EQ(*job.sample.target_error, 0.03);
  EXPECT_EQ(job.sample.target_error_loc.file, yaml);
  EXPECT_EQ(job.sample.target_error_loc.line, 5);
  EXPECT_EQ(job.sample.target_error_loc.column, 17);
  EXPECT_FALSE(job.sample.size.has_value());
  EXPECT_EQ(job.sample.strategy, ilp::SampleStrategy::stratified);
  EXPECT_EQ(job.sample.error_samples, 2);
  EXPECT_DOUBLE_EQ(job.sample.pilot_fraction, 1.0);
}

// Whichever comes first in the file, the two ways of giving a size (or a size and a
// target) are refused, and the message names both keys.
TEST(JobConfigErrors, ExclusiveSampleKeysInEitherOrder) {
  struct Case {
    const char* solver;
    std::vector<std::string> says;
  };
  const std::vector<Case> cases{
      {"  sample_fraction: 0.1\n  sample_size: 10\n", {"sample_size", "sample_fraction", "not both"}},
      {"  target_error: 0.05\n  sample_size: 10\n", {"target_error", "sample_size", "not both"}},
      {"  target_error: 0.05\n  sample_fraction: 0.1\n", {"target_error", "sample_fraction", "not both"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.solver);
    TempDir dir;
    const std::string yaml = dir.write("job.yaml", std::string("scene:\n  mesh: room.obj\nsolver:\n") + c.solver);
    const std::string msg = config_error(yaml);
    EXPECT_TRUE(Contains(msg, yaml + ":4:") || Contains(msg, yaml + ":5:")) << msg;  // at one of the two keys
    for (const std::string& part : c.says) EXPECT_TRUE(Contains(msg, part));
  }
}

TEST(SampleSettings, SizeForIsTheFractionOfThePopulationRounded) {
  ilp::SampleSettings s;  // fraction 0.05
  EXPECT_EQ(s.size_for(1000), 50);
  EXPECT_EQ(s.size_for(432), 22);  // 21.6 rounds up
  EXPECT_EQ(s.size_for(429), 21);  // 21.45 rounds down
  s.fraction = 0.25;
  EXPECT_EQ(s.size_for(10), 3);  // 2.5
  EXPECT_EQ(s.size_for(9), 2);   // 2.25
  s.fraction = 1.0;
  EXPECT_EQ(s.size_for(777), 777);
  // Capped by max_sample_size (default 4000), so a finer mesh does not grow k ...
  s.fraction = 0.05;
  EXPECT_EQ(s.size_for(398000), 4000);
  s.max_size_for_target = 1000;
  EXPECT_EQ(s.size_for(30000), 1000);
  // ... but an explicit size is taken as given.
  s.size = 5000;
  EXPECT_EQ(s.size_for(398000), 5000);
}

TEST(SampleSettings, SizeForIsAtLeastOne) {
  ilp::SampleSettings s;
  EXPECT_EQ(s.size_for(5), 1);  // 0.25
  EXPECT_EQ(s.size_for(1), 1);
  EXPECT_EQ(s.size_for(0), 1);
  s.fraction = 1e-6;
  EXPECT_EQ(s.size_for(100000), 1);  // 0.1
}

TEST(SampleSettings, ExplicitSizeWins) {
  ilp::SampleSettings s;
  s.fraction = 0.5;
  s.size = 7;
  EXPECT_EQ(s.size_for(1000), 7);
  EXPECT_EQ(s.size_for(3), 7);  // as given, even above the population (the sampler takes the census then)
  s.size.reset();
  EXPECT_EQ(s.size_for(1000), 500);
}

// ---------------------------------------------------------------------------------
// Files that cannot be read

TEST(JobConfigErrors, MissingConfigFile) {
  TempDir dir;
  const std::string path = dir.file("nothere.yaml");
  expect_error_at(config_error(path), path, 0, {"cannot open"});
}

TEST(JobConfigErrors, MissingMeshFile) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: meshes/nothere.obj\n"
                                     "  default_reflectance: 0.5\n");
  // The config alone is fine: the mesh is only opened by load_job_scene.
  expect_error_at(scene_error<ilp::SceneError>(yaml), yaml, 2,
                  {"scene.mesh", dir.file("meshes/nothere.obj"), "cannot open"});
}

TEST(JobConfigErrors, MalformedYaml) {
  expect_config_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  reflectance: {floor: [0.1, 0.2, 0.3}\n"
      "solver:\n"
      "  seed: 1\n",
      3, {"malformed YAML"});
}

TEST(JobConfigErrors, MalformedYamlBadIndent) {
  expect_config_error(
      "scene:\n"
      "  mesh: room.obj\n"
      " up_axis: z\n",
      3, {"malformed YAML"});
}

TEST(JobConfigErrors, EmptyConfig) {
  expect_config_error("# nothing here\n", 0, {"map of sections"});
}

// ---------------------------------------------------------------------------------
// Rules of single values

TEST(JobConfigErrors, UnknownSurfaceInReflectance) {
  expect_room_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  reflectance:\n"
      "    floor: 0.2\n"
      "    wal: 0.5\n"
      "  default_reflectance: 0.5\n",
      5, {"scene.reflectance", "unknown surface 'wal'", "floor, wall"});  // lists what the mesh has
}

TEST(JobConfigErrors, UnknownEmittingSurface) {
  expect_room_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  default_reflectance: 0.5\n"
      "  emitting_surfaces:\n"
      "    - {surface: window, exitance_lm_per_m2: 100}\n",
      5, {"scene.emitting_surfaces", "'window'"});
}

TEST(JobConfigErrors, UnknownReportSurface) {
  expect_room_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  default_reflectance: 0.5\n"
      "report:\n"
      "  surfaces:\n"
      "    - floor\n"
      "    - desk\n",
      7, {"report.surfaces", "'desk'"});
}

TEST(JobConfigErrors, LuminaireNamedLikeASurface) {
  expect_room_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  default_reflectance: 0.5\n"
      "luminaires:\n"
      "  placed:\n"
      "    - {name: L1, position_m: [0.5, 0.5, 0.9], flux_lm: 100}\n"
      "    - {name: wall, position_m: [0.5, 0.5, 0.9], flux_lm: 100}\n",
      7, {"luminaires.placed", "'wall'"});
}

TEST(JobConfigErrors, LuminaireOutsideTheSceneIsAnError) {
  expect_room_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  default_reflectance: 0.5\n"
      "luminaires:\n"
      "  placed:\n"
      "    - {name: L1, position_m: [0.5, 0.5, 0.9], flux_lm: 100}\n"
      "    - {name: L2, position_m: [500, 500, 900], flux_lm: 100}\n",  // millimetres by mistake
      7, {"luminaires.placed", "'L2'", "outside the scene"});
}

TEST(JobConfigErrors, DuplicateLuminaireName) {
  expect_config_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "luminaires:\n"
      "  placed:\n"
      "    - {name: L1, position_m: [0.5, 0.5, 0.9], flux_lm: 100}\n"
      "    - {name: L1, position_m: [0.2, 0.5, 0.9], flux_lm: 100}\n",
      6, {"luminaires.placed[1]", "'L1' is used twice"});
}

struct BadValue {
  const char* name;     // test name suffix
  const char* section;  // YAML text up to the bad line (the bad line is the last one)
  const char* key;      // dotted key the message must name
  const char* rule;     // text the message must contain
  int line = 0;         // line the message must name; 0: the last line of `section`
  int col = 0;          // column the message must name (1-based); 0: not checked
};

void PrintTo(const BadValue& v, std::ostream* os) { *os << v.name; }

class JobConfigBadValue : public ::testing::TestWithParam<BadValue> {};

TEST_P(JobConfigBadValue, NamesFileLineAndKey) {
  const BadValue& p = GetParam();
  const std::string text = p.section;
  const int bad_line = p.line ? p.line : static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  expect_config_error(text, bad_line, {p.key, p.rule}, p.col);
}

#define SCENE "scene:\n  mesh: room.obj\n"
#define SCENE_REFL SCENE "  reflectance:\n"

INSTANTIATE_TEST_SUITE_P(
    Values, JobConfigBadValue,
    ::testing::Values(
        // reflectance outside [0, 1)
        BadValue{"ReflectanceOne", SCENE_REFL "    floor: 1.0\n", "scene.reflectance.floor = 1.0", "must be in [0, 1)"},
        BadValue{"ReflectanceNegative", SCENE_REFL "    floor: 0.2\n    wall: -0.1\n", "scene.reflectance.wall = -0.1",
                 "must be in [0, 1)"},
        BadValue{"ReflectanceRgbChannel", SCENE_REFL "    floor: [0.5, 1.2, 0.5]\n", "scene.reflectance.floor[1] = 1.2",
                 "must be in [0, 1)"},
        BadValue{"ReflectanceRgbTwoValues", SCENE_REFL "    floor: [0.5, 0.5]\n", "scene.reflectance.floor",
                 "list [r, g, b]"},
        BadValue{"ReflectanceNotANumber", SCENE_REFL "    floor: grey\n", "scene.reflectance.floor = grey",
                 "must be a number"},
        BadValue{"DefaultReflectanceOne", SCENE "  default_reflectance: 1\n", "scene.default_reflectance = 1",
                 "must be in [0, 1)"},
        // not finite
        BadValue{"ScaleDotNan", SCENE "  scale_to_m: .nan\n", "scene.scale_to_m = .nan", "must be a finite number"},
        BadValue{"ScaleDotNanMixedCase", SCENE "  scale_to_m: .NaN\n", "scene.scale_to_m = .NaN",
                 "must be a finite number"},
        BadValue{"ScaleNan", SCENE "  scale_to_m: nan\n", "scene.scale_to_m = nan", "must be a finite number"},
        BadValue{"ScaleDotInf", SCENE "  scale_to_m: .inf\n", "scene.scale_to_m = .inf", "must be a finite number"},
        BadValue{"ScaleInf", SCENE "  scale_to_m: inf\n", "scene.scale_to_m = inf", "must be a finite number"},
        BadValue{"ScaleOverflow", SCENE "  scale_to_m: 1e999\n", "scene.scale_to_m = 1e999", "must be a finite number"},
        BadValue{"ReflectanceNan", SCENE_REFL "    floor: .nan\n", "scene.reflectance.floor = .nan",
                 "must be a finite number"},
        BadValue{"LuminairePositionNan",
                 SCENE "luminaires:\n  placed:\n    - {name: L1, position_m: [0, 0, nan], flux_lm: 10}\n",
                 "luminaires.placed[0].position_m[2] = nan", "must be a finite number"},
        BadValue{"MaxPatchEdgeNan", SCENE "  max_patch_edge_m: .nan\n", "scene.max_patch_edge_m",
                 "must be a finite number"},
        // unknown keys (typos)
        BadValue{"TypoMaxPatchEdge", SCENE "  max_patch_edge: 0.2\n", "'scene.max_patch_edge'", "unknown key"},
        BadValue{"TypoRaysPerPatch", SCENE "solver:\n  seed: 1\n  rays_per_patc: 64\n", "'solver.rays_per_patc'",
                 "unknown key"},
        BadValue{"TypoSection", SCENE "solvers:\n  seed: 1\n", "'solvers'", "unknown key", 3},
        BadValue{"TypoLuminaireKey",
                 SCENE "luminaires:\n  placed:\n    - {name: L1, position_m: [0, 0, 1], flux_lm: 10}\n"
                       "    - name: L2\n      position_m: [0, 0, 1]\n      flux: 10\n",
                 "'luminaires.placed[1].flux'", "unknown key"},
        BadValue{"TypoEmitterKey", SCENE "  emitting_surfaces:\n    - {surface: wall, exitance: 10}\n",
                 "'scene.emitting_surfaces[0].exitance'", "unknown key"},
        // required keys
        BadValue{"MissingMesh", "scene:\n  up_axis: z\n", "scene.mesh", "required key is missing"},
        BadValue{"MissingScene", "solver:\n  seed: 1\n", "scene", "required key is missing", 1},
        BadValue{"MissingFlux", SCENE "luminaires:\n  placed:\n    - {name: L1, position_m: [0, 0, 1]}\n",
                 "luminaires.placed[0].flux_lm", "required key is missing"},
        BadValue{"MissingExitance", SCENE "  emitting_surfaces:\n    - {surface: wall}\n",
                 "scene.emitting_surfaces[0].exitance_lm_per_m2", "required key is missing"},
        // wrong types and values
        BadValue{"SeedNotANumber", SCENE "solver:\n  seed: abc\n", "solver.seed = abc", "must be a number"},
        BadValue{"SeedFraction", SCENE "solver:\n  seed: 1.5\n", "solver.seed = 1.5", "must be a whole number"},
        BadValue{"SeedNegative", SCENE "solver:\n  seed: -1\n", "solver.seed = -1", "must be between 0 and"},
        BadValue{"RaysPerPatchList", SCENE "solver:\n  rays_per_patch: [64]\n", "solver.rays_per_patch",
                 "must be a number"},
        BadValue{"RaysPerPatchZero", SCENE "solver:\n  rays_per_patch: 0\n", "solver.rays_per_patch = 0",
                 "must be between 1 and"},
        BadValue{"ThreadsTooMany", SCENE "solver:\n  threads: 5000\n", "solver.threads = 5000",
                 "must be between 0 and 1024"},
        BadValue{"ResidualZero", SCENE "solver:\n  relative_residual: 0\n", "solver.relative_residual = 0",
                 "must be in (0, 1)"},
        BadValue{"ResidualOne", SCENE "solver:\n  relative_residual: 1\n", "solver.relative_residual = 1",
                 "must be in (0, 1)"},
        BadValue{"UpAxisX", SCENE "  up_axis: x\n", "scene.up_axis = x", "must be y or z"},
        BadValue{"SurfacesFromBad", SCENE "  surfaces_from: layer\n", "scene.surfaces_from = layer",
                 "must be group, object, material or connected"},
        BadValue{"ScaleZero", SCENE "  scale_to_m: 0\n", "scene.scale_to_m = 0", "must be > 0"},
        BadValue{"MaxPatchEdgeNegative", SCENE "  max_patch_edge_m: -0.5\n", "scene.max_patch_edge_m = -0.5",
                 "must be > 0"},
        BadValue{"MeshNotAString", "scene:\n  default_reflectance: 0.5\n  mesh: [a.obj, b.obj]\n", "scene.mesh",
                 "must be a string"},
        BadValue{"ReflectanceNotAMap", SCENE "  reflectance: [0.5]\n", "scene.reflectance",
                 "must map surface names to reflectances"},
        BadValue{"SceneNotAMap", "scene: room.obj\n", "scene = room.obj", "must be a map of keys"},
        BadValue{"PlacedNotAList", SCENE "luminaires:\n  placed: {name: L1}\n", "luminaires.placed", "must be a list"},
        BadValue{"PositionTwoNumbers", SCENE "luminaires:\n  placed:\n    - {position_m: [0, 1], flux_lm: 10}\n",
                 "luminaires.placed[0].position_m", "list of 3 numbers"},
        BadValue{"FluxNegative", SCENE "luminaires:\n  placed:\n    - {position_m: [0, 0, 1], flux_lm: -5}\n",
                 "luminaires.placed[0].flux_lm = -5", "must be >= 0"},
        BadValue{"ExitanceNegative", SCENE "  emitting_surfaces:\n    - {surface: wall, exitance_lm_per_m2: -1}\n",
                 "scene.emitting_surfaces[0].exitance_lm_per_m2 = -1", "must be >= 0"},
        BadValue{"LuminaireSizeZero", SCENE "luminaires:\n  size_m: 0\n", "luminaires.size_m = 0", "must be > 0"},
        BadValue{"ReportSurfacesNotAList", SCENE "report:\n  surfaces: floor\n", "report.surfaces", "must be a list"},
        // the sample-based operator's keys (solver section); the column is the value's
        BadValue{"MethodFoo", SCENE "solver:\n  method: foo\n", "solver.method = foo", "must be sample or exact", 0,
                 11},
        BadValue{"SamplingRandom", SCENE "solver:\n  sampling: random\n", "solver.sampling = random",
                 "must be uniform, area or stratified", 0, 13},
        BadValue{"IndirectX", SCENE "solver:\n  indirect: x\n", "solver.indirect = x",
                 "must be sample_gather or exact_second_bounce", 0, 13},
        BadValue{"SampleSizeZero", SCENE "solver:\n  sample_size: 0\n", "solver.sample_size = 0",
                 "must be between 1 and", 0, 16},
        BadValue{"SampleSizeFraction", SCENE "solver:\n  sample_size: 2.5\n", "solver.sample_size = 2.5",
                 "must be a whole number", 0, 16},
        BadValue{"SampleSizeNotANumber", SCENE "solver:\n  sample_size: many\n", "solver.sample_size = many",
                 "must be a number", 0, 16},
        BadValue{"SampleFractionZero", SCENE "solver:\n  sample_fraction: 0\n", "solver.sample_fraction = 0",
                 "must be in (0, 1]", 0, 20},
        BadValue{"SampleFractionAboveOne", SCENE "solver:\n  sample_fraction: 1.5\n", "solver.sample_fraction = 1.5",
                 "must be in (0, 1]", 0, 20},
        BadValue{"SampleFractionNan", SCENE "solver:\n  sample_fraction: .nan\n", "solver.sample_fraction = .nan",
                 "must be a finite number", 0, 20},
        BadValue{"TargetErrorZero", SCENE "solver:\n  target_error: 0\n", "solver.target_error = 0",
                 "must be in (0, 1)", 0, 17},
        BadValue{"TargetErrorOne", SCENE "solver:\n  target_error: 1\n", "solver.target_error = 1",
                 "must be in (0, 1)", 0, 17},
        BadValue{"TargetErrorNegative", SCENE "solver:\n  target_error: -0.1\n", "solver.target_error = -0.1",
                 "must be in (0, 1)", 0, 17},
        BadValue{"ErrorSamplesOne", SCENE "solver:\n  error_samples: 1\n", "solver.error_samples = 1",
                 "must be between 2 and 64", 0, 18},
        BadValue{"PilotFractionZero", SCENE "solver:\n  pilot_fraction: 0\n", "solver.pilot_fraction = 0",
                 "must be in (0, 1]", 0, 19},
        BadValue{"SampleSeedNegative", SCENE "solver:\n  sample_seed: -1\n", "solver.sample_seed = -1",
                 "must be between 0 and", 0, 16},
        BadValue{"TypoSampleFraction", SCENE "solver:\n  sample_fracton: 0.1\n", "'solver.sample_fracton'",
                 "unknown key"},
        // keys that exclude each other: the error points at the second and names both
        BadValue{"SampleSizeAndFraction", SCENE "solver:\n  sample_size: 10\n  sample_fraction: 0.1\n",
                 "solver.sample_fraction = 0.1", "give sample_size or sample_fraction, not both", 0, 20},
        BadValue{"TargetErrorAndSampleSize", SCENE "solver:\n  sample_size: 10\n  target_error: 0.05\n",
                 "solver.target_error = 0.05", "give target_error or a sample size", 0, 17},
        BadValue{"TargetErrorAndSampleFraction", SCENE "solver:\n  sample_fraction: 0.1\n  target_error: 0.05\n",
                 "solver.target_error = 0.05", "give target_error or a sample size", 0, 17}),
    [](const ::testing::TestParamInfo<BadValue>& info) { return std::string(info.param.name); });

#undef SCENE_REFL
#undef SCENE

// ---------------------------------------------------------------------------------
// The inverse problem: luminaires to place, goals, constraints, objective, optimizer,
// verification, output and sweep

TEST(ConfigInverse, ReadsAFullInverseJob) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"                                         // 1
                                     "  mesh: room.obj\n"                               // 2
                                     "luminaires:\n"                                    // 3
                                     "  model: square_lambertian\n"                     // 4
                                     "  size_m: 0.6\n"                                  // 5
                                     "  flux_lm: [500, 6000]\n"                         // 6
                                     "  efficacy_lm_per_w: 120\n"                       // 7
                                     "  mounting_surface: ceiling\n"                    // 8
                                     "  mount_offset_m: 0.05\n"                         // 9
                                     "  candidate_spacing_m: 0.4\n"                     // 10
                                     "  count: [2, 6]\n"                                // 11
                                     "  layout: free\n"                                 // 12
                                     "  placed:\n"                                      // 13
                                     "    - {name: L1, position_m: [1, 1, 2.9], flux_lm: 100}\n"  // 14
                                     "goals:\n"                                         // 15
                                     "  - name: desks\n"                                // 16
                                     "    surface: [desk_1, desk_2]\n"                  // 17
                                     "    average_lux: 500\n"                           // 18
                                     "    uniformity: 0.6\n"                            // 19
                                     "  - surface: floor\n"                             // 20
                                     "    max_lux: 900\n"                               // 21
                                     "    min_lux: 150\n"                               // 22
                                     "constraints:\n"                                   // 23
                                     "  max_luminaires: 6\n"                            // 24
                                     "  min_distance_m: 1.0\n"                          // 25
                                     "objective: closest_to_target\n"                   // 26
                                     "optimizer:\n"                                     // 27
                                     "  global_algorithm: GN_ISRES\n"                   // 28
                                     "  local_algorithm: LN_COBYLA\n"                   // 29
                                     "  max_evaluations: 5000\n"                        // 30
                                     "  local_max_evaluations: 300\n"                   // 31
                                     "  max_seconds: 12.5\n"                            // 32
                                     "  seed: 42\n"                                     // 33
                                     "verification:\n"                                  // 34
                                     "  method: sample\n"                               // 35
                                     "  rays_per_patch: 512\n"                          // 36
                                     "  max_exact_patches: 1000\n"                      // 37
                                     "  sample_fraction: 0.5\n"                         // 38
                                     "output:\n"                                        // 39
                                     "  directory: results/office\n"                    // 40
                                     "  formats: [csv, ply]\n"                          // 41
                                     "sweep:\n"                                         // 42
                                     "  key: goals.desks.average_lux\n"                 // 43
                                     "  values: [300, 500, 750, 1000]\n");              // 44
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_TRUE(job.search.has_value());
  const ilp::LuminaireSearch& search = *job.search;
  EXPECT_EQ(search.model, "square_lambertian");
  EXPECT_DOUBLE_EQ(job.luminaire_size_m, 0.6);
  EXPECT_DOUBLE_EQ(search.flux_min_lm, 500.0);
  EXPECT_DOUBLE_EQ(search.flux_max_lm, 6000.0);
  EXPECT_EQ(search.flux_loc.file, yaml);
  EXPECT_EQ(search.flux_loc.line, 6);
  EXPECT_DOUBLE_EQ(search.efficacy_lm_per_w, 120.0);
  EXPECT_EQ(search.mounting_surface, "ceiling");
  EXPECT_EQ(search.mounting_loc.line, 8);
  EXPECT_DOUBLE_EQ(search.mount_offset_m, 0.05);
  EXPECT_DOUBLE_EQ(search.candidate_spacing_m, 0.4);
  EXPECT_EQ(search.spacing_loc.line, 10);
  EXPECT_EQ(search.count_min, 2);
  EXPECT_EQ(search.count_max, 6);
  EXPECT_EQ(search.count_loc.line, 11);
  EXPECT_EQ(search.layout, ilp::LayoutFamily::free);
  EXPECT_EQ(search.layout_loc.line, 12);
  EXPECT_FALSE(search.array_spacing_m.has_value());
  EXPECT_FALSE(search.array_offset_m.has_value());
  ASSERT_EQ(job.luminaires.size(), 1u);  // fixed luminaires next to the search
  EXPECT_EQ(job.luminaires[0].name, "L1");

  // One GoalSetting per metric, in the order average, minimum, maximum, uniformity
  // within an entry, whatever the order in the file.
  ASSERT_EQ(job.goals.size(), 4u);
  const std::vector<std::string> desks{"desk_1", "desk_2"}, floor{"floor"};
  struct Expected {
    const char* name;
    std::vector<std::string> surfaces;
    ilp::GoalMetric metric;
    double target;
    int line, surfaces_line;
  };
  const Expected expected[] = {{"desks", desks, ilp::GoalMetric::average, 500.0, 18, 17},
                               {"desks", desks, ilp::GoalMetric::uniformity, 0.6, 19, 17},
                               {"floor", floor, ilp::GoalMetric::minimum, 150.0, 22, 20},
                               {"floor", floor, ilp::GoalMetric::maximum, 900.0, 21, 20}};
  for (std::size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE(k);
    const ilp::GoalSetting& g = job.goals[k];
    EXPECT_EQ(g.name, expected[k].name);
    EXPECT_EQ(g.surfaces, expected[k].surfaces);
    EXPECT_EQ(g.metric, expected[k].metric);
    EXPECT_DOUBLE_EQ(g.target, expected[k].target);
    EXPECT_EQ(g.loc.file, yaml);
    EXPECT_EQ(g.loc.line, expected[k].line);
    EXPECT_EQ(g.surfaces_loc.line, expected[k].surfaces_line);
  }

  ASSERT_TRUE(job.constraints.max_luminaires.has_value());
  EXPECT_EQ(*job.constraints.max_luminaires, 6);
  EXPECT_EQ(job.constraints.max_luminaires_loc.line, 24);
  EXPECT_DOUBLE_EQ(job.constraints.min_distance_m, 1.0);
  EXPECT_EQ(job.objective, ilp::Objective::closest_to_target);
  EXPECT_EQ(job.optimizer.global_algorithm, "GN_ISRES");
  EXPECT_EQ(job.optimizer.local_algorithm, "LN_COBYLA");
  EXPECT_EQ(job.optimizer.max_evaluations, 5000);
  EXPECT_EQ(job.optimizer.local_max_evaluations, 300);
  EXPECT_DOUBLE_EQ(job.optimizer.max_seconds, 12.5);
  EXPECT_EQ(job.optimizer.seed, 42u);
  EXPECT_EQ(job.verification.method, ilp::VerificationMethod::sample);
  EXPECT_EQ(job.verification.rays_per_patch, 512);
  EXPECT_EQ(job.verification.max_exact_patches, 1000u);
  EXPECT_DOUBLE_EQ(job.verification.sample_fraction, 0.5);
  EXPECT_EQ(job.output.directory, "results/office");
  EXPECT_FALSE(job.output.wants("json"));
  EXPECT_TRUE(job.output.wants("csv"));
  EXPECT_FALSE(job.output.wants("svg"));
  EXPECT_TRUE(job.output.wants("ply"));
  ASSERT_TRUE(job.sweep.has_value());
  EXPECT_EQ(job.sweep->key, "goals.desks.average_lux");
  EXPECT_EQ(job.sweep->values, (std::vector<double>{300, 500, 750, 1000}));
  EXPECT_EQ(job.sweep->loc.line, 43);
  EXPECT_DOUBLE_EQ(job.goals[0].target, 500.0);  // checking the sweep left the goals alone
}

TEST(ConfigInverse, DefaultsWithoutTheInverseSections) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: room.obj\nluminaires:\n  size_m: 0.5\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_FALSE(job.search.has_value());
  EXPECT_TRUE(job.goals.empty());
  EXPECT_FALSE(job.constraints.max_luminaires.has_value());
  EXPECT_DOUBLE_EQ(job.constraints.min_distance_m, 0.0);
  EXPECT_EQ(job.objective, ilp::Objective::min_power);
  EXPECT_EQ(job.optimizer.global_algorithm, "GN_CRS2_LM");
  EXPECT_EQ(job.optimizer.local_algorithm, "LN_SBPLX");
  EXPECT_EQ(job.optimizer.max_evaluations, 20000);
  EXPECT_EQ(job.optimizer.local_max_evaluations, 4000);
  EXPECT_EQ(job.optimizer.max_seconds, 0.0) << "no wall-clock budget unless asked: the same layout on any machine";
  EXPECT_EQ(job.optimizer.seed, 1u);
  EXPECT_EQ(job.verification.method, ilp::VerificationMethod::automatic);
  EXPECT_EQ(job.verification.rays_per_patch, 1024);
  EXPECT_EQ(job.verification.max_exact_patches, 30000u);
  EXPECT_DOUBLE_EQ(job.verification.sample_fraction, 0.25);
  EXPECT_TRUE(job.output.directory.empty());
  EXPECT_TRUE(job.output.wants("json") && job.output.wants("csv") && job.output.wants("svg") && job.output.wants("ply"));
  EXPECT_FALSE(job.sweep.has_value());
}

TEST(ConfigInverse, SearchDefaultsWithOnlyMountingSurfaceAndFlux) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "luminaires:\n"
                                     "  mounting_surface: ceiling\n"
                                     "  flux_lm: [0, 3000]\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_TRUE(job.search.has_value());
  EXPECT_EQ(job.search->model, "square_lambertian");
  EXPECT_DOUBLE_EQ(job.search->flux_min_lm, 0.0);  // 0 is a valid minimum
  EXPECT_DOUBLE_EQ(job.search->flux_max_lm, 3000.0);
  EXPECT_DOUBLE_EQ(job.search->efficacy_lm_per_w, 100.0);
  EXPECT_DOUBLE_EQ(job.search->mount_offset_m, 0.02);
  EXPECT_DOUBLE_EQ(job.search->candidate_spacing_m, 0.5);
  EXPECT_EQ(job.search->count_min, 1);
  EXPECT_EQ(job.search->count_max, 1);
  EXPECT_EQ(job.search->layout, ilp::LayoutFamily::free);
  EXPECT_EQ(job.search->layout_loc.line, 4);  // no layout key: where the search is declared
}

TEST(ConfigInverse, CountAsOneNumber) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "luminaires:\n"
                                     "  mounting_surface: ceiling\n"
                                     "  flux_lm: [100, 3000]\n"
                                     "  count: 4\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_TRUE(job.search.has_value());
  EXPECT_EQ(job.search->count_min, 4);
  EXPECT_EQ(job.search->count_max, 4);
  EXPECT_EQ(job.search->count_loc.line, 6);
}

TEST(ConfigInverse, CountAsRange) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "luminaires:\n"
                                     "  mounting_surface: ceiling\n"
                                     "  count: [1, 64]\n"
                                     "  flux_lm: [100, 3000]\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_TRUE(job.search.has_value());
  EXPECT_EQ(job.search->count_min, 1);
  EXPECT_EQ(job.search->count_max, 64);
  EXPECT_EQ(job.search->count_loc.line, 5);
  // min = max is a range of one
  const std::string same = dir.write("same.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [1, 2]\n  count: [3, 3]\n");
  const ilp::JobConfig job3 = ilp::load_job_config(same);
  EXPECT_EQ(job3.search->count_min, 3);
  EXPECT_EQ(job3.search->count_max, 3);
}

TEST(ConfigInverse, ArrayLayoutWithSpacingAndOffset) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "luminaires:\n"
                                     "  mounting_surface: ceiling\n"
                                     "  flux_lm: [100, 3000]\n"
                                     "  layout: array\n"
                                     "  array: {rows: 2, columns: 3, spacing_m: [2.0, 1.5], offset_m: [1.0, 0]}\n"
                                     "constraints:\n"
                                     "  max_luminaires: 6\n");  // = rows x columns: allowed
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_TRUE(job.search.has_value());
  EXPECT_EQ(job.search->layout, ilp::LayoutFamily::array);
  EXPECT_EQ(job.search->layout_loc.line, 6);
  EXPECT_EQ(job.search->array_rows, 2);
  EXPECT_EQ(job.search->array_columns, 3);
  ASSERT_TRUE(job.search->array_spacing_m.has_value());
  EXPECT_EQ(*job.search->array_spacing_m, Eigen::Vector2d(2.0, 1.5));
  ASSERT_TRUE(job.search->array_offset_m.has_value());
  EXPECT_EQ(*job.search->array_offset_m, Eigen::Vector2d(1.0, 0.0));  // 0 is a valid offset
  EXPECT_EQ(*job.constraints.max_luminaires, 6);
}

TEST(ConfigInverse, ArrayLayoutWithoutSpacingOrOffset) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "luminaires:\n"
                                     "  mounting_surface: ceiling\n"
                                     "  flux_lm: [100, 3000]\n"
                                     "  layout: array\n"
                                     "  array:\n"
                                     "    rows: 1\n"
                                     "    columns: 32\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_TRUE(job.search.has_value());
  EXPECT_EQ(job.search->layout, ilp::LayoutFamily::array);
  EXPECT_EQ(job.search->array_rows, 1);
  EXPECT_EQ(job.search->array_columns, 32);
  EXPECT_FALSE(job.search->array_spacing_m.has_value());  // searched
  EXPECT_FALSE(job.search->array_offset_m.has_value());
}

TEST(ConfigInverse, GoalSurfaceAsOneNameAndDefaultNames) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "goals:\n"
                                     "  - {surface: floor, min_lux: 0}\n"               // 0 is a valid minimum
                                     "  - {surface: [desk_1, desk_2], max_lux: 800}\n"
                                     "  - {surface: floor, max_lux: 1000}\n");           // same goal, another metric
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_EQ(job.goals.size(), 3u);
  EXPECT_EQ(job.goals[0].name, "floor");
  EXPECT_EQ(job.goals[0].surfaces, std::vector<std::string>{"floor"});
  EXPECT_EQ(job.goals[0].metric, ilp::GoalMetric::minimum);
  EXPECT_DOUBLE_EQ(job.goals[0].target, 0.0);
  EXPECT_EQ(job.goals[1].name, "desk_1+desk_2");
  EXPECT_EQ(job.goals[1].metric, ilp::GoalMetric::maximum);
  EXPECT_EQ(job.goals[2].name, "floor");
  EXPECT_EQ(job.goals[2].loc.line, 6);
}

TEST(ConfigInverse, GoalBoundsMayMeet) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "goals:\n"
                                     "  - {surface: floor, min_lux: 300, average_lux: 300, max_lux: 300,\n"
                                     "     uniformity: 1}\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_EQ(job.goals.size(), 4u);
  EXPECT_EQ(job.goals[3].metric, ilp::GoalMetric::uniformity);
  EXPECT_DOUBLE_EQ(job.goals[3].target, 1.0);
}

TEST(ConfigInverse, EveryOutputFormatAndOptimizerNone) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "optimizer:\n  global_algorithm: none\n  local_algorithm: LN_BOBYQA\n"
                                     "verification:\n  method: none\n"
                                     "output:\n  formats: [svg]\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_EQ(job.optimizer.global_algorithm, "none");
  EXPECT_EQ(job.optimizer.local_algorithm, "LN_BOBYQA");
  EXPECT_EQ(job.verification.method, ilp::VerificationMethod::none);
  EXPECT_FALSE(job.output.wants("json"));
  EXPECT_FALSE(job.output.wants("csv"));
  EXPECT_TRUE(job.output.wants("svg"));
  EXPECT_FALSE(job.output.wants("ply"));
  const std::string exact = dir.write("exact.yaml",
                                      "scene:\n  mesh: room.obj\n"
                                      "optimizer:\n  local_algorithm: none\n"
                                      "verification:\n  method: exact\n");
  const ilp::JobConfig job2 = ilp::load_job_config(exact);
  EXPECT_EQ(job2.optimizer.global_algorithm, "GN_CRS2_LM");
  EXPECT_EQ(job2.optimizer.local_algorithm, "none");
  EXPECT_EQ(job2.verification.method, ilp::VerificationMethod::exact);
}

TEST(ConfigInverse, EmptyConfigNamesEverySection) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", "# nothing\n");
  expect_error_at(config_error(yaml), yaml, 0,
                  {"(scene, luminaires, goals, constraints, objective, solver, optimizer, verification, output, "
                   "energy, sweep, report)"});
}

// Every rule of the inverse sections: the message names the key (and value) and the
// rule, at the offending key's line.
class ConfigInverseBadValue : public ::testing::TestWithParam<BadValue> {};

TEST_P(ConfigInverseBadValue, NamesFileLineAndKey) {
  const BadValue& p = GetParam();
  const std::string text = p.section;
  const int bad_line = p.line ? p.line : static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  expect_config_error(text, bad_line, {p.key, p.rule}, p.col);
}

#define SCENE "scene:\n  mesh: room.obj\n"
// lines 3-5
#define SEARCH SCENE "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [500, 6000]\n"
// lines 3-4
#define GOALS SCENE "goals:\n  - {name: desks, surface: desk_1, average_lux: 500, uniformity: 0.6}\n"

INSTANTIATE_TEST_SUITE_P(
    ConfigInverse, ConfigInverseBadValue,
    ::testing::Values(
        // search keys need mounting_surface; mounting_surface needs flux_lm
        BadValue{"ModelWithoutMounting", SCENE "luminaires:\n  size_m: 0.6\n  model: square_lambertian\n",
                 "luminaires.model = square_lambertian", "needs luminaires.mounting_surface"},
        BadValue{"FluxWithoutMounting", SCENE "luminaires:\n  flux_lm: [1, 2]\n", "luminaires.flux_lm",
                 "needs luminaires.mounting_surface"},
        BadValue{"EfficacyWithoutMounting", SCENE "luminaires:\n  efficacy_lm_per_w: 120\n",
                 "luminaires.efficacy_lm_per_w = 120", "needs luminaires.mounting_surface"},
        BadValue{"OffsetWithoutMounting", SCENE "luminaires:\n  mount_offset_m: 0.05\n",
                 "luminaires.mount_offset_m = 0.05", "needs luminaires.mounting_surface"},
        BadValue{"SpacingWithoutMounting", SCENE "luminaires:\n  candidate_spacing_m: 0.5\n",
                 "luminaires.candidate_spacing_m = 0.5", "needs luminaires.mounting_surface"},
        BadValue{"CountWithoutMounting", SCENE "luminaires:\n  count: 3\n", "luminaires.count = 3",
                 "needs luminaires.mounting_surface"},
        BadValue{"LayoutWithoutMounting", SCENE "luminaires:\n  layout: free\n", "luminaires.layout = free",
                 "needs luminaires.mounting_surface"},
        BadValue{"ArrayWithoutMounting", SCENE "luminaires:\n  array: {rows: 1, columns: 1}\n", "luminaires.array",
                 "needs luminaires.mounting_surface"},
        BadValue{"FirstSearchKeyInTheFile", SCENE "luminaires:\n  layout: free\n  count: 3\n",
                 "luminaires.layout = free", "needs luminaires.mounting_surface", 4},
        BadValue{"MountingWithoutFlux", SCENE "luminaires:\n  mounting_surface: ceiling\n  count: 2\n",
                 "luminaires.mounting_surface = ceiling", "needs luminaires.flux_lm: [min, max]", 4},
        BadValue{"MountingEmpty", SCENE "luminaires:\n  flux_lm: [1, 2]\n  mounting_surface: ''\n",
                 "luminaires.mounting_surface", "must name a surface"},
        // search values
        BadValue{"ModelOther", SEARCH "  model: cylinder\n", "luminaires.model = cylinder",
                 "must be square_lambertian"},
        BadValue{"FluxOneNumberZero", SCENE "luminaires:\n  mounting_surface: ceiling\n  flux_lm: 0\n",
                 "luminaires.flux_lm = 0", "must be > 0"},
        BadValue{"FluxThreeNumbers", SCENE "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [1, 2, 3]\n",
                 "luminaires.flux_lm", "must be a list [min, max]"},
        BadValue{"FluxMinNegative", SCENE "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [-1, 100]\n",
                 "luminaires.flux_lm[0] = -1", "must be >= 0"},
        BadValue{"FluxMaxBelowMin", SCENE "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [500, 400]\n",
                 "luminaires.flux_lm[1] = 400", "must be at least the minimum"},
        BadValue{"FluxNotANumber", SCENE "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [a, 500]\n",
                 "luminaires.flux_lm[0] = a", "must be a number"},
        BadValue{"EfficacyZero", SEARCH "  efficacy_lm_per_w: 0\n", "luminaires.efficacy_lm_per_w = 0", "must be > 0"},
        BadValue{"MountOffsetZero", SEARCH "  mount_offset_m: 0\n", "luminaires.mount_offset_m = 0",
                 "must be in (0, 10)"},
        BadValue{"MountOffsetTen", SEARCH "  mount_offset_m: 10\n", "luminaires.mount_offset_m = 10",
                 "must be in (0, 10)"},
        BadValue{"CandidateSpacingNegative", SEARCH "  candidate_spacing_m: -0.5\n",
                 "luminaires.candidate_spacing_m = -0.5", "must be > 0"},
        BadValue{"CountZero", SEARCH "  count: 0\n", "luminaires.count = 0", "must be between 1 and 64"},
        BadValue{"Count65", SEARCH "  count: 65\n", "luminaires.count = 65", "must be between 1 and 64"},
        BadValue{"CountFraction", SEARCH "  count: 2.5\n", "luminaires.count = 2.5", "must be a whole number"},
        BadValue{"CountRangeMinZero", SEARCH "  count: [0, 3]\n", "luminaires.count[0] = 0",
                 "must be between 1 and 64"},
        BadValue{"CountRangeMax65", SEARCH "  count: [1, 65]\n", "luminaires.count[1] = 65",
                 "must be between 1 and 64"},
        BadValue{"CountRangeReversed", SEARCH "  count: [4, 2]\n", "luminaires.count[1] = 2",
                 "must be >= the minimum"},
        BadValue{"CountRangeThree", SEARCH "  count: [1, 2, 3]\n", "luminaires.count",
                 "must be a whole number N or a list [min, max]"},
        BadValue{"LayoutGrid", SEARCH "  layout: grid\n", "luminaires.layout = grid",
                 "must be free, array, field, rows or bays"},
        BadValue{"FieldBlockWithoutFieldLayout", SEARCH "  field: {rows: 2}\n", "luminaires.field",
                 "needs luminaires.layout: field"},
        BadValue{"EdgeRatioZero", SEARCH "  layout: field\n  field: {edge_ratio: 0}\n", "luminaires.field.edge_ratio = 0",
                 "must be in [0.05, 1]"},
        BadValue{"EdgeRatioRangeReversed", SEARCH "  layout: field\n  field: {edge_ratio: [0.5, 0.3]}\n",
                 "luminaires.field.edge_ratio[1] = 0.3", "must be >= the minimum"},
        BadValue{"FieldRowsReversed", SEARCH "  layout: field\n  field: {rows: [3, 1]}\n", "luminaires.field.rows[1] = 1",
                 "must be >= the minimum"},
        BadValue{"RowsPerRowZero", SEARCH "  layout: rows\n  rows: {per_row: 0}\n", "luminaires.rows.per_row = 0",
                 "must be between 1 and 200"},
        BadValue{"BaysWithoutBlock", SEARCH "  layout: bays\n", "luminaires.layout = bays", "needs luminaires.bays"},
        BadValue{"BaysWithoutModule", SEARCH "  layout: bays\n  bays: {per_bay: 2}\n", "luminaires.bays.module_m",
                 "required key is missing"},
        BadValue{"IndividualOutputWithAField", SEARCH "  layout: field\n  output: individual\n", "luminaires.output",
                 "individual output is for free layouts"},
        BadValue{"OutputUnknown", SEARCH "  output: dimmed\n", "luminaires.output = dimmed", "must be equal or individual"},
        BadValue{"ZoneReversed", SEARCH "  zone: {rectangle_m: [[4, 1], [2, 3]]}\n", "luminaires.zone.rectangle_m",
                 "the second corner must lie above the first"},
        BadValue{"ZoneRectangleAndMargin", SEARCH "  zone: {rectangle_m: [[0, 0], [2, 3]], margin_m: 1}\n",
                 "luminaires.zone.margin_m", "not with rectangle_m"},
        BadValue{"ArrayLayoutWithoutBlock", SEARCH "  layout: array\n", "luminaires.layout = array",
                 "needs luminaires.array"},
        BadValue{"ArrayWithFreeLayout", SEARCH "  layout: free\n  array: {rows: 2, columns: 2}\n", "luminaires.array",
                 "needs luminaires.layout: array"},
        BadValue{"ArrayWithoutLayout", SEARCH "  array: {rows: 2, columns: 2}\n", "luminaires.array",
                 "needs luminaires.layout: array"},
        BadValue{"CountWithArrayLayout", SEARCH "  count: 4\n  layout: array\n  array: {rows: 2, columns: 2}\n",
                 "luminaires.count = 4", "the array fixes the count", 6},
        BadValue{"ArrayRowsZero", SEARCH "  layout: array\n  array: {rows: 0, columns: 2}\n",
                 "luminaires.array.rows = 0", "must be between 1 and 32"},
        BadValue{"ArrayColumns33", SEARCH "  layout: array\n  array:\n    rows: 2\n    columns: 33\n",
                 "luminaires.array.columns = 33", "must be between 1 and 32"},
        BadValue{"ArrayWithoutColumns", SEARCH "  layout: array\n  array:\n    rows: 2\n", "luminaires.array.columns",
                 "required key is missing", 8},
        BadValue{"ArrayNotAMap", SEARCH "  layout: array\n  array: [2, 3]\n", "luminaires.array",
                 "must be a map of keys"},
        BadValue{"ArraySpacingOneNumber",
                 SEARCH "  layout: array\n  array:\n    rows: 2\n    columns: 2\n    spacing_m: 2\n",
                 "luminaires.array.spacing_m = 2", "must be a list of 2 numbers"},
        BadValue{"ArraySpacingZero",
                 SEARCH "  layout: array\n  array:\n    rows: 2\n    columns: 2\n    spacing_m: [0, 1]\n",
                 "luminaires.array.spacing_m[0] = 0", "must be > 0"},
        BadValue{"ArrayOffsetNegative",
                 SEARCH "  layout: array\n  array:\n    rows: 2\n    columns: 2\n    offset_m: [1, -1]\n",
                 "luminaires.array.offset_m[1] = -1", "must be >= 0"},
        // unknown keys
        BadValue{"TypoLuminairesMounting", SCENE "luminaires:\n  mounting: ceiling\n", "'luminaires.mounting'",
                 "unknown key"},
        BadValue{"TypoArrayKey",
                 SEARCH "  layout: array\n  array:\n    rows: 2\n    columns: 2\n    spacing: [1, 1]\n",
                 "'luminaires.array.spacing'", "unknown key"},
        BadValue{"TypoGoalKey", SCENE "goals:\n  - {surface: floor, average: 500}\n", "'goals[0].average'",
                 "unknown key"},
        BadValue{"TypoConstraintsKey", SCENE "constraints:\n  min_distance: 1\n", "'constraints.min_distance'",
                 "unknown key"},
        BadValue{"TypoOptimizerKey", SCENE "optimizer:\n  seed: 1\n  algorithm: GN_ESCH\n", "'optimizer.algorithm'",
                 "unknown key"},
        BadValue{"TypoVerificationKey", SCENE "verification:\n  rays: 64\n", "'verification.rays'", "unknown key"},
        BadValue{"TypoOutputKey", SCENE "output:\n  format: [json]\n", "'output.format'", "unknown key"},
        BadValue{"TypoSweepKey", GOALS "sweep:\n  key: goals.desks.average_lux\n  value: [1]\n", "'sweep.value'",
                 "unknown key"},
        BadValue{"TypoGoalSection", SCENE "goal:\n  - {surface: floor, average_lux: 500}\n", "'goal'",
                 "unknown key", 3},
        // goals
        BadValue{"GoalsNotAList", SCENE "goals: {surface: floor, average_lux: 1}\n", "goals", "must be a list"},
        BadValue{"GoalsEmpty", SCENE "goals: []\n", "goals", "must list at least one goal"},
        BadValue{"GoalEntryNotAMap", SCENE "goals:\n  - floor\n", "goals[0] = floor", "must be a map of keys"},
        BadValue{"GoalWithoutMetric", SCENE "goals:\n  - surface: floor\n    name: f\n", "goals[0]",
                 "needs at least one of average_lux, min_lux, max_lux, uniformity", 4},
        BadValue{"GoalWithoutSurface", SCENE "goals:\n  - average_lux: 500\n", "goals[0].surface",
                 "required key is missing"},
        BadValue{"GoalSurfaceEmptyList", SCENE "goals:\n  - surface: []\n    average_lux: 500\n", "goals[0].surface",
                 "must be a surface name or a non-empty list of names", 4},
        BadValue{"GoalSurfaceMap", SCENE "goals:\n  - surface: {a: 1}\n    average_lux: 500\n", "goals[0].surface",
                 "must be a string", 4},
        BadValue{"GoalNameEmpty", SCENE "goals:\n  - surface: floor\n    name: ''\n    average_lux: 5\n",
                 "goals[0].name", "must not be empty", 5},
        BadValue{"AverageZero", SCENE "goals:\n  - surface: floor\n    average_lux: 0\n", "goals[0].average_lux = 0",
                 "must be > 0"},
        BadValue{"MinNegative", SCENE "goals:\n  - surface: floor\n    min_lux: -1\n", "goals[0].min_lux = -1",
                 "must be >= 0"},
        BadValue{"MaxZero", SCENE "goals:\n  - surface: floor\n    max_lux: 0\n", "goals[0].max_lux = 0",
                 "must be > 0"},
        BadValue{"UniformityAboveOne", SCENE "goals:\n  - surface: floor\n    uniformity: 1.5\n",
                 "goals[0].uniformity = 1.5", "must be in (0, 1]"},
        BadValue{"UniformityZero", SCENE "goals:\n  - surface: floor\n    uniformity: 0\n", "goals[0].uniformity = 0",
                 "must be in (0, 1]"},
        BadValue{"AverageNotANumber", SCENE "goals:\n  - surface: floor\n    average_lux: bright\n",
                 "goals[0].average_lux = bright", "must be a number"},
        BadValue{"MinAboveMax", SCENE "goals:\n  - surface: floor\n    max_lux: 100\n    min_lux: 150\n",
                 "goals[0].max_lux = 100", "must be >= min_lux (150)", 5},
        BadValue{"AverageAboveMax", SCENE "goals:\n  - surface: floor\n    average_lux: 500\n    max_lux: 400\n",
                 "goals[0].max_lux = 400", "must be >= average_lux (500)"},
        BadValue{"MinAboveMaxOfAnEarlierEntry",
                 SCENE "goals:\n  - {surface: floor, max_lux: 100}\n  - {surface: floor, min_lux: 150}\n",
                 "goals[1].min_lux = 150", "must be <= max_lux (100) of goal 'floor'"},
        BadValue{"GoalMetricTwice",
                 SCENE "goals:\n  - {name: desks, surface: [desk_1, desk_2], average_lux: 500}\n"
                       "  - name: desks\n    surface: desk_1\n    average_lux: 300\n",
                 "goals[1].average_lux = 300", "goal 'desks' already has average_lux"},
        BadValue{"DefaultNamedGoalMetricTwice",
                 SCENE "goals:\n  - {surface: floor, min_lux: 1}\n  - {surface: [floor], min_lux: 2}\n",
                 "goals[1].min_lux = 2", "goal 'floor' already has min_lux"},
        // constraints
        BadValue{"MaxLuminairesZero", SCENE "constraints:\n  max_luminaires: 0\n", "constraints.max_luminaires = 0",
                 "must be between 1 and"},
        BadValue{"MaxLuminairesFraction", SCENE "constraints:\n  max_luminaires: 2.5\n",
                 "constraints.max_luminaires = 2.5", "must be a whole number"},
        BadValue{"MaxLuminairesBelowCount",
                 SEARCH "  count: [3, 6]\nconstraints:\n  max_luminaires: 2\n  min_distance_m: 1\n",
                 "constraints.max_luminaires = 2", "below the least luminaires.count (3)", 8},
        BadValue{"MaxLuminairesBelowArray",
                 SEARCH "  layout: array\n  array: {rows: 2, columns: 3}\nconstraints:\n  max_luminaires: 5\n",
                 "constraints.max_luminaires = 5", "below the array's rows x columns (6)"},
        BadValue{"MinDistanceNegative", SCENE "constraints:\n  min_distance_m: -1\n", "constraints.min_distance_m = -1",
                 "must be >= 0"},
        // objective
        BadValue{"ObjectiveOther", SCENE "objective: max_light\n", "objective = max_light",
                 "must be min_power or closest_to_target"},
        BadValue{"ObjectiveMap", SCENE "objective: {kind: min_power}\n", "objective", "must be a string"},
        BadValue{"ClosestToTargetWithoutAverage",
                 SCENE "goals:\n  - {surface: floor, min_lux: 100, uniformity: 0.5}\nobjective: closest_to_target\n"
                       "solver:\n  seed: 1\n",
                 "objective = closest_to_target", "needs at least one goal with average_lux", 5},
        BadValue{"ClosestToTargetWithoutGoals", SCENE "objective: closest_to_target\n",
                 "objective = closest_to_target", "needs at least one goal with average_lux"},
        // optimizer
        BadValue{"GlobalAlgorithmOther", SCENE "optimizer:\n  global_algorithm: GN_MLSL\n",
                 "optimizer.global_algorithm = GN_MLSL", "must be one of GN_CRS2_LM, GN_ISRES"},
        BadValue{"LocalAlgorithmGradient", SCENE "optimizer:\n  local_algorithm: LD_LBFGS\n",
                 "optimizer.local_algorithm = LD_LBFGS", "must be one of LN_SBPLX, LN_COBYLA"},
        BadValue{"BothAlgorithmsNone",
                 SCENE "optimizer:\n  global_algorithm: none\n  local_algorithm: none\n  seed: 3\n",
                 "optimizer.local_algorithm = none", "cannot both be none", 5},
        BadValue{"BothAlgorithmsNoneLocalFirst",
                 SCENE "optimizer:\n  local_algorithm: none\n  global_algorithm: none\n",
                 "optimizer.local_algorithm = none", "cannot both be none", 4},
        BadValue{"MaxEvaluationsZero", SCENE "optimizer:\n  max_evaluations: 0\n", "optimizer.max_evaluations = 0",
                 "must be between 1 and 100000000"},
        BadValue{"LocalMaxEvaluationsTooMany", SCENE "optimizer:\n  local_max_evaluations: 200000000\n",
                 "optimizer.local_max_evaluations = 200000000", "must be between 1 and 100000000"},
        BadValue{"MaxSecondsZero", SCENE "optimizer:\n  max_seconds: 0\n", "optimizer.max_seconds = 0", "must be > 0"},
        BadValue{"OptimizerSeedNegative", SCENE "optimizer:\n  seed: -1\n", "optimizer.seed = -1",
                 "must be between 0 and"},
        // verification
        BadValue{"VerificationMethodOther", SCENE "verification:\n  method: approximate\n",
                 "verification.method = approximate", "must be auto, exact, sample or none"},
        BadValue{"VerificationRaysZero", SCENE "verification:\n  rays_per_patch: 0\n",
                 "verification.rays_per_patch = 0", "must be between 1 and"},
        BadValue{"MaxExactPatchesZero", SCENE "verification:\n  max_exact_patches: 0\n",
                 "verification.max_exact_patches = 0", "must be between 1 and"},
        BadValue{"VerificationFractionZero", SCENE "verification:\n  sample_fraction: 0\n",
                 "verification.sample_fraction = 0", "must be in (0, 1]"},
        BadValue{"VerificationFractionAboveOne", SCENE "verification:\n  sample_fraction: 1.5\n",
                 "verification.sample_fraction = 1.5", "must be in (0, 1]"},
        // output
        BadValue{"OutputDirectoryEmpty", SCENE "output:\n  directory: ''\n", "output.directory", "must not be empty"},
        BadValue{"OutputDirectoryList", SCENE "output:\n  directory: [a]\n", "output.directory", "must be a string"},
        BadValue{"FormatsEmpty", SCENE "output:\n  formats: []\n", "output.formats",
                 "must list at least one of json, csv, svg, ply"},
        BadValue{"FormatsNotAList", SCENE "output:\n  formats: json\n", "output.formats = json", "must be a list"},
        BadValue{"FormatOther", SCENE "output:\n  formats: [json, docx]\n", "output.formats[1] = docx",
                 "must be one of json, csv, svg, ply, grid_csv, isolux_svg, isolux_png, plan_png, pdf"},
        BadValue{"GridFormatWithoutGrids", SCENE "output:\n  formats: [json, isolux_png]\n", "output.formats[1] = isolux_png",
                 "needs calculation grids (the job has no grids section)"},
        BadValue{"FormatTwice", SCENE "output:\n  formats:\n    - json\n    - csv\n    - json\n",
                 "output.formats[2] = json", "is listed twice"},
        BadValue{"PlanCutHeightZero", SCENE "output:\n  plan_cut_height_m: 0\n", "output.plan_cut_height_m = 0",
                 "must be > 0"},
        BadValue{"PlanCutHeightTooHigh", SCENE "output:\n  plan_cut_height_m: 5000\n",
                 "output.plan_cut_height_m = 5000", "must be at most 1000 m"},
        BadValue{"PlanCutHeightText", SCENE "output:\n  plan_cut_height_m: high\n", "output.plan_cut_height_m = high",
                 "must be a number"},
        // sweep: checked by applying each value as `ilp sweep` will
        BadValue{"SweepWithoutGoals", SCENE "sweep:\n  key: goals.desks.average_lux\n  values: [300]\n",
                 "sweep: needs goals", "goal parameter", 3, 1},  // at the sweep key itself
        BadValue{"SweepWithoutKey", GOALS "sweep:\n  values: [300]\n", "sweep.key", "required key is missing", 6},
        BadValue{"SweepWithoutValues", GOALS "sweep:\n  key: goals.desks.average_lux\n", "sweep.values",
                 "required key is missing", 6},
        BadValue{"SweepValuesEmpty", GOALS "sweep:\n  key: goals.desks.average_lux\n  values: []\n", "sweep.values",
                 "must list at least one number"},
        BadValue{"SweepValuesNotAList", GOALS "sweep:\n  key: goals.desks.average_lux\n  values: 300\n",
                 "sweep.values = 300", "must be a list"},
        BadValue{"SweepUnknownGoal", GOALS "sweep:\n  key: goals.desk.average_lux\n  values: [300, 500]\n",
                 "sweep.key = goals.desk.average_lux",
                 "no goal parameter goals.desk.average_lux; the job has goals.desks.average_lux, "
                 "goals.desks.uniformity",
                 6},
        BadValue{"SweepMetricTheGoalLacks", GOALS "sweep:\n  key: goals.desks.min_lux\n  values: [300]\n",
                 "sweep.key = goals.desks.min_lux", "no goal parameter goals.desks.min_lux", 6},
        BadValue{"SweepKeyNotAGoal", GOALS "sweep:\n  key: solver.seed\n  values: [1]\n", "sweep.key = solver.seed",
                 "no goal parameter solver.seed", 6},
        BadValue{"SweepUniformityAboveOne",
                 GOALS "sweep:\n  key: goals.desks.uniformity\n  values:\n    - 0.5\n    - 1.5\n    - 0.7\n",
                 "sweep.values[1] = 1.5", "must be in (0, 1]", 9},
        BadValue{"SweepAverageNegative", GOALS "sweep:\n  key: goals.desks.average_lux\n  values: [300, -1]\n",
                 "sweep.values[1] = -1", "must be > 0"},
        BadValue{"SweepValueNotANumber", GOALS "sweep:\n  key: goals.desks.average_lux\n  values: [300, lots]\n",
                 "sweep.values[1] = lots", "must be a number"},
        BadValue{"SweepMinAboveMax",
                 SCENE "goals:\n  - {surface: floor, min_lux: 100, max_lux: 800}\n"
                       "sweep:\n  key: goals.floor.min_lux\n  values: [200, 900]\n",
                 "sweep.values[1] = 900", "must be <= max_lux (800)"}),
    [](const ::testing::TestParamInfo<BadValue>& info) { return std::string(info.param.name); });

#undef GOALS
#undef SEARCH
#undef SCENE

// ---- luminaires.placed with a product: the product's type at its rotation and output.

TEST(JobConfig, PlacedProductsResolveTheirTypeRotationAndOutput) {
  TempDir dir;
  const std::string iku = std::string(ILP_SOURCE_DIR) + "/data/photometry/erco_iku_downlight.ldt";
  const std::string yaml =
      dir.write("job.yaml", "scene:\n  mesh: room.obj\n"
                            "luminaires:\n"
                            "  size_m: 0.3\n"
                            "  products:\n"
                            "    - {name: iku, photometry: " + iku + ", dimming: [0.5, 1]}\n"
                            "    - {name: panel, model: square_lambertian, size_m: 0.6, flux_lm: 3600, power_w: 30}\n"
                            "  placed:\n"
                            "    - {name: A, product: iku, position_m: [1, 1, 2], rotation_deg: 30, output: 0.75}\n"
                            "    - {name: B, product: iku, position_m: [2, 1, 2], flux_lm: 400}\n"
                            "    - {name: C, product: iku, position_m: [3, 1, 2]}\n"
                            "    - {name: D, product: panel, position_m: [1, 2, 2], rotation_deg: -45}\n"
                            "    - {name: E, position_m: [2, 2, 2], flux_lm: 1000}\n");
  const ilp::JobConfig job = ilp::load_job_config(yaml);
  EXPECT_FALSE(job.search.has_value()) << "products need no mounting surface";
  ASSERT_EQ(job.products.size(), 2u);
  ASSERT_EQ(job.luminaires.size(), 5u);
  const ilp::LuminaireSetting &a = job.luminaires[0], &b = job.luminaires[1], &c = job.luminaires[2];
  const ilp::LuminaireSetting &d = job.luminaires[3], &e = job.luminaires[4];
  constexpr double kIkuLm = 611.8;  // integrated from the file (docs/photometry.md)
  EXPECT_EQ(a.product, "iku");
  EXPECT_EQ(a.type.shape, ilp::OutlineShape::disc);
  EXPECT_NEAR(a.type.length_m, 0.076, 1e-9);
  EXPECT_FALSE(a.type.lambertian());
  EXPECT_EQ(a.rotation_deg, 30.0);
  EXPECT_NEAR(a.flux_lm, 0.75 * kIkuLm, 0.1);
  EXPECT_EQ(b.flux_lm, 400.0) << "flux_lm within the dimming range, as given";
  EXPECT_NEAR(c.flux_lm, kIkuLm, 0.1) << "full output by default";
  EXPECT_EQ(c.rotation_deg, 0.0);
  EXPECT_EQ(a.type.distribution, c.type.distribution) << "the product's file is read once for all its luminaires";
  EXPECT_EQ(d.product, "panel");
  EXPECT_TRUE(d.type.lambertian());
  EXPECT_EQ(d.type.length_m, 0.6) << "the panel product's own size, not luminaires.size_m";
  EXPECT_EQ(d.rotation_deg, -45.0);
  EXPECT_EQ(d.flux_lm, 3600.0);
  EXPECT_EQ(e.product, "") << "no product: the plain panel";
  EXPECT_TRUE(e.type.lambertian());
  EXPECT_EQ(e.type.length_m, 0.3);
  EXPECT_EQ(e.type.key(), ilp::LuminaireType::square_lambertian(0.3).key());
  EXPECT_EQ(e.flux_lm, 1000.0);
}

class ConfigPlacedBadValue : public ::testing::TestWithParam<BadValue> {};

TEST_P(ConfigPlacedBadValue, NamesFileLineAndKey) {
  const BadValue& p = GetParam();
  const std::string text = p.section;
  const int bad_line = p.line ? p.line : static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  expect_config_error(text, bad_line, {p.key, p.rule}, p.col);
}

#define SCENE "scene:\n  mesh: room.obj\n"
// lines 3-6: a panel product dimmable to half, a fixed photometric one (611.8 lm)
#define PRODUCTS                                                                                            \
  SCENE "luminaires:\n  products:\n"                                                                        \
        "    - {name: panel, model: square_lambertian, size_m: 0.6, flux_lm: 3600, power_w: 30, dimming: [0.5, 1]}\n" \
        "    - {name: iku, photometry: " ILP_SOURCE_DIR "/data/photometry/erco_iku_downlight.ldt}\n"
#define PLACED PRODUCTS "  placed:\n"

INSTANTIATE_TEST_SUITE_P(
    ConfigPlaced, ConfigPlacedBadValue,
    ::testing::Values(
        BadValue{"UnknownProduct", PLACED "    - {product: downlight, position_m: [1, 1, 2]}\n",
                 "luminaires.placed[0].product = downlight", "unknown product (luminaires.products has panel, iku)"},
        BadValue{"ProductWithoutProducts", SCENE "luminaires:\n  placed:\n    - {product: iku, position_m: [1, 1, 2]}\n",
                 "luminaires.placed[0].product = iku", "unknown product: luminaires.products lists none"},
        BadValue{"FluxAndOutput", PLACED "    - {product: panel, position_m: [1, 1, 2], flux_lm: 3000, output: 0.8}\n",
                 "luminaires.placed[0].output = 0.8", "not with flux_lm"},
        BadValue{"OutputAboveRange", PLACED "    - {product: panel, position_m: [1, 1, 2], output: 1.2}\n",
                 "luminaires.placed[0].output = 1.2", "must be within product 'panel''s dimming range [0.5, 1]"},
        BadValue{"OutputBelowRange",
                 PLACED "    - {product: panel, position_m: [1, 1, 2]}\n    - {product: panel, position_m: [2, 1, 2], output: 0.3}\n",
                 "luminaires.placed[1].output = 0.3", "must be within product 'panel''s dimming range [0.5, 1]"},
        BadValue{"OutputOfAFixedPackage", PLACED "    - {product: iku, position_m: [1, 1, 2], output: 0.9}\n",
                 "luminaires.placed[0].output = 0.9", "must be within product 'iku''s dimming range [1, 1]"},
        BadValue{"OutputNotANumber", PLACED "    - {product: panel, position_m: [1, 1, 2], output: full}\n",
                 "luminaires.placed[0].output = full", "must be a number"},
        BadValue{"FluxBelowRange", PLACED "    - {product: panel, position_m: [1, 1, 2], flux_lm: 1000}\n",
                 "luminaires.placed[0].flux_lm = 1000",
                 "must be within product 'panel''s output, 1800 to 3600 lm (dimming [0.5, 1] x rated 3600 lm)"},
        BadValue{"FluxAboveAFilesRating", PLACED "    - {product: iku, position_m: [1, 1, 2], flux_lm: 700}\n",
                 "luminaires.placed[0].flux_lm = 700", "must be product 'iku''s fixed output, 611.796 lm (no dimming range"},
        BadValue{"OutputWithoutProduct", PLACED "    - {position_m: [1, 1, 2], flux_lm: 100, output: 0.5}\n",
                 "luminaires.placed[0].output = 0.5", "needs product:"},
        BadValue{"PanelWithoutFlux", PLACED "    - {position_m: [1, 1, 2], rotation_deg: 10}\n",
                 "luminaires.placed[0].flux_lm", "required key is missing"},
        BadValue{"RotationOutOfRange", PLACED "    - {product: panel, position_m: [1, 1, 2], rotation_deg: 400}\n",
                 "luminaires.placed[0].rotation_deg = 400", "must be in [-360, 360] degrees"},
        BadValue{"FullOutputOutsideTheRange",
                 SCENE "luminaires:\n  products:\n"
                       "    - {name: low, model: square_lambertian, flux_lm: 3600, power_w: 30, dimming: [0.2, 0.8]}\n"
                       "  placed:\n    - {product: low, position_m: [1, 1, 2]}\n",
                 "luminaires.placed[0].product = low", "full output (1, the default) is outside the product's dimming range [0.2, 0.8]"},
        BadValue{"TypoPlacedKey", PLACED "    - {product: panel, position_m: [1, 1, 2], rotation: 30}\n",
                 "'luminaires.placed[0].rotation'", "unknown key"}),
    [](const ::testing::TestParamInfo<BadValue>& info) { return std::string(info.param.name); });

#undef PLACED
#undef PRODUCTS
#undef SCENE

// set_goal_parameter: what `ilp sweep` and `--set` use.

ilp::JobConfig goal_job(const TempDir& dir) {
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "goals:\n"
                                     "  - {name: desks, surface: [desk_1, desk_2], average_lux: 500, uniformity: 0.6}\n"
                                     "  - {surface: floor, min_lux: 150, max_lux: 800}\n");
  return ilp::load_job_config(yaml);
}

std::vector<double> targets(const ilp::JobConfig& job) {
  std::vector<double> out;
  for (const ilp::GoalSetting& g : job.goals) out.push_back(g.target);
  return out;
}

TEST(ConfigGoalParameter, SetsTheNamedTarget) {
  TempDir dir;
  ilp::JobConfig job = goal_job(dir);
  ASSERT_EQ(targets(job), (std::vector<double>{500, 0.6, 150, 800}));
  ilp::set_goal_parameter(job, "goals.desks.average_lux", 750);
  EXPECT_EQ(targets(job), (std::vector<double>{750, 0.6, 150, 800}));
  ilp::set_goal_parameter(job, "goals.desks.uniformity", 1.0);
  ilp::set_goal_parameter(job, "goals.floor.min_lux", 0.0);
  ilp::set_goal_parameter(job, "goals.floor.max_lux", 150.0);
  EXPECT_EQ(targets(job), (std::vector<double>{750, 1.0, 0, 150}));
  EXPECT_EQ(job.goals[0].loc.line, 4);  // the rest of the setting is untouched
  EXPECT_EQ(job.goals[0].metric, ilp::GoalMetric::average);
}

TEST(ConfigGoalParameter, GoalNamesMayHoldDots) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"
                                     "goals:\n  - {surface: desk.top, average_lux: 300}\n");
  ilp::JobConfig job = ilp::load_job_config(yaml);
  ilp::set_goal_parameter(job, "goals.desk.top.average_lux", 400);
  EXPECT_DOUBLE_EQ(job.goals[0].target, 400.0);
}

TEST(ConfigGoalParameter, UnknownKeyListsTheJobsParameters) {
  TempDir dir;
  ilp::JobConfig job = goal_job(dir);
  const std::string available =
      "the job has goals.desks.average_lux, goals.desks.uniformity, goals.floor.min_lux, goals.floor.max_lux";
  for (const std::string key : {"goals.desk.average_lux", "goals.desks.min_lux", "goals.desks.lux", "desks.average_lux",
                                "goals.desks", "goals..average_lux", "goals.desks.average_lux.x", ""}) {
    SCOPED_TRACE(key);
    const std::string msg = error_of<ilp::ConfigError>([&] { ilp::set_goal_parameter(job, key, 600); });
    expect_message(msg, "--set " + key + ": ", {"no goal parameter " + key + "; " + available});
  }
  EXPECT_EQ(targets(job), (std::vector<double>{500, 0.6, 150, 800}));
}

TEST(ConfigGoalParameter, JobWithoutGoals) {
  ilp::JobConfig job;
  const std::string msg =
      error_of<ilp::ConfigError>([&] { ilp::set_goal_parameter(job, "goals.desks.average_lux", 600); });
  expect_message(msg, "--set goals.desks.average_lux: ", {"the job has no goals"});
}

TEST(ConfigGoalParameter, BadValueBreaksTheFilesRule) {
  TempDir dir;
  ilp::JobConfig job = goal_job(dir);
  struct Case {
    const char* key;
    double value;
    const char* start;
    const char* rule;
  };
  const Case cases[] = {
      {"goals.desks.average_lux", -5, "--set goals.desks.average_lux = -5: ", "must be > 0"},
      {"goals.desks.average_lux", 0, "--set goals.desks.average_lux = 0: ", "must be > 0"},
      {"goals.desks.uniformity", 1.5, "--set goals.desks.uniformity = 1.5: ", "must be in (0, 1]"},
      {"goals.floor.min_lux", -0.5, "--set goals.floor.min_lux = -0.5: ", "must be >= 0"},
      {"goals.floor.max_lux", 0, "--set goals.floor.max_lux = 0: ", "must be > 0"},
      {"goals.floor.min_lux", 900, "--set goals.floor.min_lux = 900: ", "must be <= max_lux (800) of goal 'floor'"},
      {"goals.floor.max_lux", 100, "--set goals.floor.max_lux = 100: ", "must be >= min_lux (150) of goal 'floor'"},
      {"goals.desks.average_lux", std::numeric_limits<double>::quiet_NaN(), "--set goals.desks.average_lux = nan: ",
       "must be a finite number"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.start);
    const std::string msg = error_of<ilp::ConfigError>([&] { ilp::set_goal_parameter(job, c.key, c.value); });
    expect_message(msg, c.start, {c.rule});
  }
  EXPECT_EQ(targets(job), (std::vector<double>{500, 0.6, 150, 800}));  // nothing set
}

TEST(ConfigGoalParameter, MetricNames) {
  EXPECT_EQ(ilp::to_string(ilp::GoalMetric::average), "average");
  EXPECT_EQ(ilp::to_string(ilp::GoalMetric::minimum), "minimum");
  EXPECT_EQ(ilp::to_string(ilp::GoalMetric::maximum), "maximum");
  EXPECT_EQ(ilp::to_string(ilp::GoalMetric::uniformity), "uniformity");
}

// Surface names of the inverse problem are checked against the mesh by
// load_job_scene, at the config's line.

std::string office_job(const std::string& luminaires, const std::string& goals) {
  return std::string("scene:\n  mesh: ") + ILP_SOURCE_DIR + "/data/office.obj\n" + luminaires + goals;
}

TEST(ConfigInverseScene, OfficeNamesLoad) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", office_job("luminaires:\n  mounting_surface: ceiling\n"
                                                            "  flux_lm: [500, 6000]\n",
                                                            "goals:\n"
                                                            "  - {surface: [desk_1, desk_2], average_lux: 500}\n"
                                                            "  - {surface: floor, min_lux: 100}\n"));
  ilp::JobScene loaded;
  ASSERT_NO_THROW(loaded = ilp::load_job_scene(scene_spec(ilp::load_job_config(yaml))));
  EXPECT_GE(loaded.scene.find_surface("desk_2"), 0);
}

TEST(ConfigInverseScene, GoalSurfaceMissingFromTheMesh) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", office_job("luminaires:\n  mounting_surface: ceiling\n"
                                                            "  flux_lm: [500, 6000]\n",
                                                            "goals:\n"                                       // 6
                                                            "  - {surface: floor, min_lux: 100}\n"          // 7
                                                            "  - name: desks\n"                             // 8
                                                            "    surface: [desk_1, desk_3]\n"               // 9
                                                            "    average_lux: 500\n"));                     // 10
  expect_error_at(scene_error<ilp::ConfigError>(yaml), yaml, 9,
                  {"goals.desks.surface", "unknown surface 'desk_3'", "desk_1, desk_1_frame, desk_2"});
}

TEST(ConfigInverseScene, MountingSurfaceMissingFromTheMesh) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml", office_job("luminaires:\n"                                 // 3
                                                            "  flux_lm: [500, 6000]\n"                      // 4
                                                            "  mounting_surface: roof\n"                    // 5
                                                            "  count: 2\n",                                 // 6
                                                            "goals:\n  - {surface: floor, min_lux: 100}\n"));
  expect_error_at(scene_error<ilp::ConfigError>(yaml), yaml, 5,
                  {"luminaires.mounting_surface", "unknown surface 'roof'", "ceiling"});
}

TEST(ConfigInverseScene, PlacedLuminaireIsNoGoalSurface) {
  TempDir dir;
  const std::string yaml = dir.write(
      "job.yaml", office_job("luminaires:\n  placed:\n    - {name: L1, position_m: [1.5, 1.0, 2.95], flux_lm: 3400}\n",
                             "goals:\n  - {surface: L1, average_lux: 100}\n"));  // line 7
  expect_error_at(scene_error<ilp::ConfigError>(yaml), yaml, 7, {"goals.L1.surface", "unknown surface 'L1'"});
}

// ---------------------------------------------------------------------------------
// Defects in the mesh, found by load_job_scene

TEST(JobSceneErrors, MeshWithNoFaces) {
  TempDir dir;
  dir.write("empty.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\n");
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  default_reflectance: 0.5\n"
                                     "  mesh: empty.obj\n");
  expect_error_at(scene_error<ilp::SceneError>(yaml), yaml, 3, {"scene.mesh", dir.file("empty.obj"), "no faces"});
}

TEST(JobSceneErrors, NanVertexInObj) {
  TempDir dir;
  const std::string obj = dir.write("nan.obj",
                                    "# a triangle with a bad vertex\n"
                                    "v 0 0 0\n"
                                    "v 0 nan 0\n"
                                    "v 1 1 0\n"
                                    "f 1 2 3\n");
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: nan.obj\n"
                                     "  default_reflectance: 0.5\n");
  expect_error_at(scene_error<ilp::SceneError>(yaml), yaml, 2, {obj + ":3:", "'nan'", "not a finite number"});
}

TEST(JobSceneErrors, AllFacesDegenerate) {
  TempDir dir;
  dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: flat.obj\n"
                                     "  default_reflectance: 0.5\n");
  const std::string msg = scene_error<ilp::SceneError>(yaml);
  EXPECT_TRUE(Contains(msg, dir.file("flat.obj")));
  EXPECT_TRUE(Contains(msg, "no usable faces"));
}

// ---------------------------------------------------------------------------------
// Where reflectances come from: config, else MTL Kd, else default_reflectance

// floor uses material "white" (Kd on line 4 of room.mtl), wall uses "paint" (Kd 0.25).
void write_room_with_mtl(const TempDir& dir, const std::string& white_kd) {
  dir.write("room.obj",
            "mtllib room.mtl\n"
            "v 0 0 0\n"
            "v 1 0 0\n"
            "v 1 1 0\n"
            "v 0 1 0\n"
            "v 0 0 1\n"
            "v 1 0 1\n"
            "g floor\n"
            "usemtl white\n"
            "f 1 2 3 4\n"
            "g wall\n"
            "usemtl paint\n"
            "f 1 5 6 2\n");
  dir.write("room.mtl",
            "# materials\n"
            "newmtl white\n"
            "Ns 10\n"
            "Kd " + white_kd + "\n"
            "\n"
            "newmtl paint\n"
            "Kd 0.25 0.25 0.25\n");
}

TEST(JobSceneErrors, MtlKdOneWithoutOverride) {
  TempDir dir;
  write_room_with_mtl(dir, "1.0 1.0 1.0");
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: room.obj\n");
  expect_message(scene_error<ilp::SceneError>(yaml), dir.file("room.mtl") + ":4:",
                 {"'white'", "'floor'", "outside [0, 1)", "scene.reflectance", yaml});
}

TEST(JobSceneErrors, MtlKdNegativeWithoutOverride) {
  TempDir dir;
  write_room_with_mtl(dir, "0.5 -0.1 0.5");
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: room.obj\n");
  expect_message(scene_error<ilp::SceneError>(yaml), dir.file("room.mtl") + ":4:", {"'white'"});
}

TEST(JobSceneErrors, EveryBadMtlKdIsListedAtOnce) {
  TempDir dir;
  write_room_with_mtl(dir, "1.0 1.0 1.0");
  dir.write("room.mtl",
            "newmtl white\n"
            "Kd 1 1 1\n"
            "newmtl paint\n"
            "Kd 0.5 1.2 0.5\n");
  const std::string yaml = dir.write("job.yaml", "scene:\n  mesh: room.obj\n");
  expect_message(scene_error<ilp::SceneError>(yaml), dir.file("room.mtl") + ":2:",
                 {"2 material(s)", "'white' = 1 (line 2, surface 'floor')",
                  "'paint' = [0.5, 1.2, 0.5] (line 4, surface 'wall')"});
}

TEST(JobScene, ConfigOverridesBadMtlKd) {
  TempDir dir;
  write_room_with_mtl(dir, "1.0 1.0 1.0");
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: room.obj\n"
                                     "  reflectance:\n"
                                     "    floor: 0.3\n");
  expect_room_reflectance(yaml, Eigen::Vector3d::Constant(0.3), Eigen::Vector3d::Constant(0.25), 1);  // wall: the MTL
}

TEST(JobScene, MtlKdUsedWhenConfigIsSilent) {
  TempDir dir;
  write_room_with_mtl(dir, "0.1 0.2 0.3");
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: room.obj\n"
                                     "  default_reflectance: 0.9\n");  // not used: every material has a Kd
  expect_room_reflectance(yaml, Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d::Constant(0.25), 3);
}

TEST(JobSceneErrors, SurfaceWithoutReflectance) {
  expect_room_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  reflectance:\n"
      "    floor: 0.2\n",
      2, {"surface 'wall' has no reflectance", "scene.default_reflectance"});
}

TEST(JobScene, DefaultReflectanceFillsTheRest) {
  TempDir dir;
  dir.write("room.obj", kRoomObj);
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n"
                                     "  mesh: room.obj\n"
                                     "  reflectance:\n"
                                     "    floor: 0.2\n"
                                     "  default_reflectance: [0.35, 0.4, 0.45]\n");
  expect_room_reflectance(yaml, Eigen::Vector3d::Constant(0.2), Eigen::Vector3d(0.35, 0.4, 0.45), 3);
}

// ---------------------------------------------------------------------------------
// yaml-cpp accepts a repeated key and lookups see only the first; a repeated key is
// as much a mistake as a misspelt one, so the loader refuses it.

TEST(JobConfigErrors, DuplicateKeyIsAnError) {
  expect_config_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  mesh: other.obj\n",
      3, {"scene.mesh"});
}

TEST(JobConfigErrors, DuplicateReflectanceIsAnError) {
  expect_config_error(
      "scene:\n"
      "  mesh: room.obj\n"
      "  reflectance:\n"
      "    floor: 0.2\n"
      "    floor: 0.7\n",
      5, {"scene.reflectance.floor"});
}

}  // namespace

// ---------------------------------------------------------------------------------
// Calculation grids, presets and the maintenance factor

TEST(JobConfigGrids, GridGoalsPresetsAndMaintenanceFactor) {
  TempDir dir;
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n"                                         // 1-2
                                     "grids:\n"                                                           // 3
                                     "  - name: work\n    over_surface: floor\n    height_m: 0.75\n"      // 4-6
                                     "  - name: strip\n    rectangle_m: [[1, 1], [0, 3]]\n    border_m: 0\n"  // 7-9
                                     "    spacing_m: 0.25\n    max_points: 50\n"                          // 10-11
                                     "  - name: board\n    vertical: {from_m: [0, 1], to_m: [0, 3], bottom_m: 1, top_m: 2, facing: right}\n"
                                     "maintenance_factor: 0.8\n"                                          // 14
                                     "goals:\n"                                                           // 15
                                     "  - {grid: work, preset: office_writing, uniformity: 0.7}\n"        // 16
                                     "  - {name: b, grid: board, preset: board, min_lux: 100}\n");        // 17
  ilp::JobConfig job = ilp::load_job_config(yaml);
  ASSERT_EQ(job.grids.size(), 3u);
  EXPECT_EQ(job.grids[0].over_surface, "floor");
  EXPECT_DOUBLE_EQ(job.grids[0].height_m, 0.75);
  EXPECT_DOUBLE_EQ(job.grids[0].border_m, 0.5);
  EXPECT_FALSE(job.grids[0].spacing_m.has_value());
  EXPECT_EQ(job.grids[0].max_points, 20000);
  ASSERT_EQ(job.grids[1].polygon_m.size(), 4u);
  EXPECT_EQ(job.grids[1].polygon_m[0], Eigen::Vector2d(0, 1));
  EXPECT_EQ(job.grids[1].polygon_m[2], Eigen::Vector2d(1, 3));
  EXPECT_EQ(*job.grids[1].spacing_m, 0.25);
  EXPECT_EQ(job.grids[1].max_points, 50);
  EXPECT_EQ(job.grids[2].kind, ilp::GridKind::vertical);
  EXPECT_FALSE(job.grids[2].facing_left);
  EXPECT_DOUBLE_EQ(job.grids[2].border_m, 0.0);
  EXPECT_DOUBLE_EQ(job.maintenance_factor, 0.8);
  // office_writing: Em, U0 (overridden), UGR_L 19, Ez,m 150 with Ez U0 0.10; board: Em,
  // the explicit min_lux, U0, UGR_L 19 (no Ez: on a vertical grid the row gives none).
  ASSERT_EQ(job.goals.size(), 9u);
  EXPECT_EQ(job.goals[2].metric, ilp::GoalMetric::ugr);
  EXPECT_DOUBLE_EQ(job.goals[2].target, 19.0);
  EXPECT_EQ(job.goals[3].metric, ilp::GoalMetric::cylindrical);
  EXPECT_DOUBLE_EQ(job.goals[3].target, 150.0);
  EXPECT_EQ(job.goals[4].metric, ilp::GoalMetric::cylindrical_uniformity);
  EXPECT_DOUBLE_EQ(job.goals[4].target, 0.10);
  job.goals.erase(job.goals.begin() + 2, job.goals.begin() + 5);
  job.goals.pop_back();
  EXPECT_EQ(job.goals[0].name, "work");
  EXPECT_EQ(job.goals[0].grid, "work");
  EXPECT_TRUE(job.goals[0].surfaces.empty());
  EXPECT_EQ(job.goals[0].metric, ilp::GoalMetric::average);
  EXPECT_DOUBLE_EQ(job.goals[0].target, 500.0);  // the preset's Em
  EXPECT_EQ(job.goals[1].metric, ilp::GoalMetric::uniformity);
  EXPECT_DOUBLE_EQ(job.goals[1].target, 0.7);  // the explicit key overrides the preset's 0.60
  EXPECT_EQ(job.goals[2].name, "b");
  EXPECT_DOUBLE_EQ(job.goals[2].target, 500.0);
  EXPECT_EQ(job.goals[3].metric, ilp::GoalMetric::minimum);
  EXPECT_DOUBLE_EQ(job.goals[4].target, 0.70);
  // Initial = maintained / MF for lux, the ratio unchanged.
  EXPECT_DOUBLE_EQ(ilp::initial_target(job.goals[0].metric, job.goals[0].target, job.maintenance_factor), 625.0);
  EXPECT_DOUBLE_EQ(ilp::initial_target(job.goals[1].metric, job.goals[1].target, job.maintenance_factor), 0.7);
  // A sweep point edits the plan's goal lines, checked as the file is.
  ilp::JobConfig inverse = job;  // the plan is an inverse job's: somewhere to mount
  inverse.search = ilp::LuminaireSearch{};
  inverse.search->mounting_surface = "ceiling";
  const ilp::JobPlan plan = ilp::plan_job(inverse);
  ilp::JobGoals point = plan.goals;
  ilp::set_goal_target(point, "goals.work.average_lux", 750);
  EXPECT_DOUBLE_EQ(point.lines[0].target, 750.0);
  EXPECT_DOUBLE_EQ(ilp::search_at(plan.variants.front(), point).goals[0].target, 937.5);
  EXPECT_THROW(ilp::set_goal_target(point, "goals.nowhere.average_lux", 750), ilp::ConfigError);
  EXPECT_THROW(ilp::set_goal_target(point, "goals.work.uniformity", 1.5), ilp::ConfigError);
  ilp::JobConfig sweep = job;
  ilp::set_goal_parameter(sweep, "goals.work.average_lux", 750);
  EXPECT_DOUBLE_EQ(sweep.goals[0].target, 750.0);
  // Every preset is a row of EN 12464-1 with its Em and U0.
  bool office = false;
  for (const ilp::GoalPreset& p : ilp::goal_presets()) {
    EXPECT_GT(p.average_lux, 0.0);
    EXPECT_GT(p.uniformity, 0.0);
    office = office || (std::string(p.key) == "office_writing" && p.average_lux == 500.0 && p.uniformity == 0.6);
  }
  EXPECT_TRUE(office);
}

// A preset on a task area with walls and ceiling, every goal of its row; Ra of the products.
TEST(JobConfigGrids, PresetTurnsIntoEveryGoalOfItsRowAndChecksRa) {
  TempDir dir;
  const std::string head =
      "scene:\n  mesh: room.obj\n"                                                                 // 1-2
      "luminaires:\n  products:\n"                                                                // 3-4
      "    - {name: panel, model: square_lambertian, size_m: 0.6, flux_lm: 3600, power_w: 30, ra: 80}\n"  // 5
      "    - {name: other, model: square_lambertian, size_m: 0.6, flux_lm: 3600, power_w: 30";    // 6
  const std::string tail =
      "}\ngrids:\n  - {name: work, over_surface: floor}\n"                                           // 6-8
      "goals:\n  - {grid: work, preset: office_writing, em: modified, walls: walls, ceiling: [ceiling]}\n";  // 9-10
  const ilp::JobConfig job = ilp::load_job_config(dir.write("job.yaml", head + ", ra: 90" + tail));
  std::vector<std::pair<std::string, ilp::GoalMetric>> got;
  for (const ilp::GoalSetting& g : job.goals) got.emplace_back(g.name, g.metric);
  using M = ilp::GoalMetric;
  const std::vector<std::pair<std::string, M>> expected = {
      {"work", M::average}, {"work", M::uniformity}, {"work", M::ugr}, {"work", M::cylindrical},
      {"work", M::cylindrical_uniformity}, {"walls", M::average}, {"walls", M::uniformity},
      {"ceiling", M::average}, {"ceiling", M::uniformity}};
  EXPECT_EQ(got, expected);
  const double targets[] = {1000, 0.60, 19, 150, 0.10, 150, 0.10, 100, 0.10};
  for (std::size_t k = 0; k < job.goals.size() && k < 9; ++k) EXPECT_DOUBLE_EQ(job.goals[k].target, targets[k]) << k;
  EXPECT_EQ(job.goals[5].surfaces, std::vector<std::string>{"walls"});
  EXPECT_EQ(job.goals[5].loc.line, 10);
  // A product without Ra, or below the row's 80: an error at the product, naming the key.
  for (const auto& [ra, where, rule] :
       {std::tuple<std::string, std::string, std::string>{"", ":6:7: luminaires.products[1].ra", "missing for product 'other'"},
        {", ra: 70", ":6:92: luminaires.products[1].ra = 70", "below what the preset office_writing"}}) {
    SCOPED_TRACE(ra);
    try {
      ilp::load_job_config(dir.write("job.yaml", head + ra + tail));
      ADD_FAILURE() << "no error";
    } catch (const ilp::ConfigError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(where), std::string::npos) << msg;
      EXPECT_NE(msg.find(rule), std::string::npos) << msg;
      EXPECT_NE(msg.find("Ra >= 80"), std::string::npos) << msg;
    }
  }
}

TEST(JobConfigGrids, BadGridsNameFileLineAndKey) {
  TempDir dir;
  struct Case {
    std::string body, where, rule;
  };
  const std::string head = "scene:\n  mesh: room.obj\n";  // lines 1-2
  const Case cases[] = {
      {"grids:\n  - name: g\n    polygon_m: [[0, 0], [4, 3], [4, 0], [0, 3]]\n", ":5:16: grids[0].polygon_m",
       "the polygon is not simple"},
      {"grids:\n  - name: g\n    over_surface: floor\n    rectangle_m: [[0, 0], [1, 1]]\n", ":4:5: grids[0]",
       "needs exactly one of over_surface, rectangle_m, polygon_m, vertical"},
      {"grids:\n  - name: g\n    rectangle_m: [[0, 0], [0, 1]]\n", ":5:18: grids[0].rectangle_m",
       "the corners must differ"},
      {"grids:\n  - name: g\n    over_surface: floor\n    border_m: -1\n", ":6:15: grids[0].border_m = -1", "must be >= 0"},
      {"grids:\n  - name: g\n    over_surface: floor\n    spacing_m: 0\n", ":6:16: grids[0].spacing_m = 0", "must be > 0"},
      {"grids:\n  - name: g\n    over_surface: floor\n  - name: g\n    over_surface: floor\n", ":6:11: grids[1].name = g",
       "already defined"},
      {"goals:\n  - {grid: work, average_lux: 300}\n", ":4:12: goals[0].grid = work", "no grids are defined"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: h, average_lux: 300}\n",
       ":6:12: goals[0].grid = h", "no grid of this name"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, surface: floor, average_lux: 300}\n",
       ":6:12: goals[0].grid = g", "not both"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, preset: office}\n",
       ":6:23: goals[0].preset = office", "unknown preset; close EN 12464-1 rows: office_"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, preset: ofice_writting}\n",
       ":6:23: goals[0].preset = ofice_writting", "close EN 12464-1 rows: office_writing"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, preset: zzz}\n",
       ":6:23: goals[0].preset = zzz", "unknown preset (EN 12464-1 rows: office_filing, office_writing"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, average_lux: 300, ugr_max: 9.5}\n",
       ":6:42: goals[0].ugr_max = 9.5", "must be in [10, 30]"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, average_lux: 300, ugr_max: 31}\n",
       ":6:42: goals[0].ugr_max = 31", "must be in [10, 30]"},
      {"goals:\n  - {surface: floor, cylindrical_lux: 150}\n", ":4:39: goals[0].cylindrical_lux = 150",
       "put the goal on a grid"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, average_lux: 300, observers: "
       "[{position_m: [1, 1], view_direction: [0, 0]}]}\n",
       "goals[0].observers[0].view_direction", "must not be [0, 0]"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, average_lux: 300, observers: "
       "[{position_m: [1, 1], view_direction: [1, 0]}]}\n",
       ":6:44: goals[0].observers", "applies to ugr_max only"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, preset: toilets, em: modified}\n",
       ":6:36: goals[0].em = modified", "gives no modified Em"},
      {"grids:\n  - {name: g, over_surface: floor}\ngoals:\n  - {grid: g, average_lux: 300, walls: walls}\n",
       ":6:40: goals[0].walls = walls", "needs a preset"},
      {"maintenance_factor: 1.2\n", ":3:21: maintenance_factor = 1.2", "must be in [0.1, 1]"},
      {"maintenance_factor: 1e-300\n", ":3:21: maintenance_factor = 1e-300", "must be in [0.1, 1]"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.body);
    const std::string yaml = dir.write("job.yaml", head + c.body);
    try {
      ilp::load_job_config(yaml);
      ADD_FAILURE() << "no error";
    } catch (const ilp::ConfigError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(c.where), std::string::npos) << msg;
      EXPECT_NE(msg.find(c.rule), std::string::npos) << msg;
    }
  }
}

// ---------------------------------------------------------------------------------
// The immediate surrounding area (EN 12464-1:2021) and the power-density cap

TEST(JobConfigSurrounding, TheStandardsTableRelatesTheSurroundingToTheTask) {
  const std::pair<double, double> rows[] = {{1500, 500}, {1000, 500}, {750, 500}, {500, 300}, {400, 200},
                                            {300, 200},  {200, 150},  {150, 150}, {100, 100}, {50, 50}};
  for (const auto& [task, surrounding] : rows) EXPECT_DOUBLE_EQ(ilp::surrounding_average_lux(task), surrounding) << task;
}

// A preset on a task area drawn as a rectangle turns into the band's lines too: its grid
// (the task's outline grown by 0.5 m less the outline, at the task's height) and its
// goal (Em one step down, U0 0.40); `surrounding: false` leaves them out; a preset on a
// grid over the floor (the whole room as task area) adds none.
TEST(JobConfigSurrounding, APresetOnATaskAreaTurnsIntoTheSurroundingLines) {
  TempDir dir;
  const std::string head =
      "scene:\n  mesh: room.obj\n"                                                          // 1-2
      "grids:\n  - {name: desk, rectangle_m: [[1, 1], [2.6, 1.8]], height_m: 0.75, border_m: 0}\n"  // 3-4
      "  - {name: floor_plane, over_surface: floor}\n"                                      // 5
      "goals:\n";                                                                          // 6
  const ilp::JobConfig job = ilp::load_job_config(dir.write("job.yaml", head + "  - {grid: desk, preset: office_writing}\n"));
  ASSERT_EQ(job.grids.size(), 3u);
  const ilp::CalcGridSetting& band = job.grids[2];
  EXPECT_EQ(band.name, "desk_surrounding");
  EXPECT_DOUBLE_EQ(band.band_width_m, 0.5);
  EXPECT_EQ(band.polygon_m, job.grids[0].polygon_m) << "the band is laid around the task's outline";
  EXPECT_DOUBLE_EQ(band.height_m, 0.75);
  EXPECT_DOUBLE_EQ(band.border_m, 0.0);
  EXPECT_EQ(band.loc.line, 7);
  std::vector<std::tuple<std::string, ilp::GoalMetric, double>> surrounding;
  for (const ilp::GoalSetting& g : job.goals)
    if (g.grid == "desk_surrounding") surrounding.emplace_back(g.name, g.metric, g.target);
  using M = ilp::GoalMetric;
  const std::vector<std::tuple<std::string, M, double>> expected{{"desk_surrounding", M::average, 300.0},
                                                                  {"desk_surrounding", M::uniformity, 0.40}};
  EXPECT_EQ(surrounding, expected);
  // The modified Em (1000 lx) gives 500 lx around it.
  const ilp::JobConfig modified =
      ilp::load_job_config(dir.write("job.yaml", head + "  - {grid: desk, preset: office_writing, em: modified}\n"));
  EXPECT_DOUBLE_EQ(modified.goals[modified.goals.size() - 2].target, 500.0);
  // Turned off, or on the whole floor: no band.
  for (const char* entry : {"  - {grid: desk, preset: office_writing, surrounding: false}\n",
                            "  - {grid: floor_plane, preset: office_writing}\n",
                            "  - {grid: desk, preset: corridor}\n"}) {
    const ilp::JobConfig none = ilp::load_job_config(dir.write("job.yaml", head + entry));
    EXPECT_EQ(none.grids.size(), 2u) << entry;
    for (const ilp::GoalSetting& g : none.goals) EXPECT_EQ(g.name.find("_surrounding"), std::string::npos) << entry;
  }
  // Given explicitly: its width and targets; without a preset, from the task's average_lux.
  const ilp::JobConfig given = ilp::load_job_config(dir.write(
      "job.yaml", head + "  - {grid: desk, average_lux: 750, surrounding: {width_m: 0.8, uniformity: 0.5}}\n"));
  ASSERT_EQ(given.grids.size(), 3u);
  EXPECT_DOUBLE_EQ(given.grids[2].band_width_m, 0.8);
  EXPECT_EQ(given.grids[2].band_loc.line, 7);
  ASSERT_EQ(given.goals.size(), 3u);
  EXPECT_DOUBLE_EQ(given.goals[1].target, 500.0);
  EXPECT_DOUBLE_EQ(given.goals[2].target, 0.5);
  const ilp::JobConfig own = ilp::load_job_config(
      dir.write("job.yaml", head + "  - {grid: desk, preset: office_writing, surrounding: {average_lux: 400}}\n"));
  EXPECT_DOUBLE_EQ(own.goals[own.goals.size() - 2].target, 400.0);
}

TEST(JobConfigSurrounding, BadSurroundingsAndPowerCapsNameFileLineAndKey) {
  const std::string head =
      "scene:\n  mesh: room.obj\n"                                                   // 1-2
      "grids:\n  - {name: desk, rectangle_m: [[1, 1], [2.6, 1.8]], border_m: 0}\n"   // 3-4
      "  - {name: g, over_surface: floor}\n"                                         // 5
      "goals:\n";                                                                   // 6
  expect_config_error(head + "  - {grid: desk, average_lux: 500, surrounding: {width_m: 0}}\n", 7,
                      {"goals[0].surrounding.width_m = 0", "must be > 0"});
  expect_config_error(head + "  - {grid: desk, average_lux: 500, surrounding: {width_m: -0.5}}\n", 7,
                      {"goals[0].surrounding.width_m = -0.5", "must be > 0"});
  expect_config_error(head + "  - {grid: desk, average_lux: 500, surrounding: {widht_m: 0.5}}\n", 7,
                      {"widht_m"});
  expect_config_error(head + "  - {grid: desk, average_lux: 500, surrounding: {uniformity: 1.5}}\n", 7,
                      {"goals[0].surrounding.uniformity = 1.5", "must be in (0, 1]"});
  expect_config_error(head + "  - {grid: desk, average_lux: 500, surrounding: maybe}\n", 7,
                      {"goals[0].surrounding = maybe", "must be true, false or a map"});
  expect_config_error(head + "  - {grid: g, average_lux: 500, surrounding: true}\n", 7,
                      {"goals[0].surrounding", "drawn as rectangle_m or polygon_m"});
  expect_config_error(head + "  - {surface: floor, average_lux: 500, surrounding: true}\n", 7,
                      {"goals[0].surrounding", "applies to a goal on a grid"});
  expect_config_error(head + "  - {grid: desk, min_lux: 300, surrounding: true}\n", 7,
                      {"goals[0].surrounding", "needs average_lux"});
  expect_config_error(head + "  - {grid: desk, average_lux: 500}\nconstraints:\n  max_power_density_w_per_m2: 0\n", 9,
                      {"constraints.max_power_density_w_per_m2 = 0", "must be > 0"}, 31);
  expect_config_error(head + "  - {grid: desk, average_lux: 500}\nconstraints:\n  max_power_density_w_per_m2: -3\n", 9,
                      {"constraints.max_power_density_w_per_m2 = -3", "must be > 0"});
  TempDir dir;
  const ilp::JobConfig job = ilp::load_job_config(
      dir.write("job.yaml", head + "  - {grid: desk, average_lux: 500}\nconstraints:\n  max_power_density_w_per_m2: 8.5\n"));
  ASSERT_TRUE(job.constraints.max_power_density_w_per_m2.has_value());
  EXPECT_DOUBLE_EQ(*job.constraints.max_power_density_w_per_m2, 8.5);
  EXPECT_EQ(job.constraints.max_power_density_loc.line, 9);
}
