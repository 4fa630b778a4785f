// Bad input handling of the job file (load_job_config) and of the scene it names
// (load_job_scene): every error must be the right type and say where it is
// (file:line), which key, and what was wrong. Every test writes its own small YAML
// and OBJ files into a fresh temporary folder.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/config.h"
#include "core/job.h"
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
  return error_of<E>([&] { (void)ilp::load_job_scene(job); });
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
  const ilp::JobScene loaded = ilp::load_job_scene(ilp::load_job_config(yaml));
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
    ASSERT_NO_THROW(loaded = ilp::load_job_scene(job));
    EXPECT_GT(loaded.scene.patches.size(), 0u);
    for (const ilp::LuminaireSetting& l : job.luminaires) EXPECT_GE(loaded.scene.find_surface(l.name), 0) << l.name;
    for (const std::string& s : job.report_surfaces) EXPECT_GE(loaded.scene.find_surface(s), 0) << s;
  }
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
                 "must be group, object or material"},
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
