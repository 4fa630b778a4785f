// The operator cache's key from the stage inputs, beyond core (tests/core/key_hash_test.cpp):
// the lighting model's spec (CandidateSpec, GoalAreaSpec, ModelSpec) and the job's
// scene inputs (hash_scene_inputs and the schema's scene settings). Each struct has one
// case per field, as many as field_count finds: a field added without a case, or with
// a case but not hashed, fails here.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/base/key_hash.h"
#include "job/config.h"
#include "job/plan.h"
#include "job/job_scene.h"
#include "optimizer/lighting_model.h"
#include "tests/key_coverage.h"
#include "tests/optimizer/optimizer_test_scenes.h"

namespace ilp {
namespace {

using test::expect_key_covers_fields;
using test::FieldCase;
using test::left_out;
using test::room_obj;
using test::TempDir;

const FileLoc kAt{"job.yaml", 7, 3};

// ---- The lighting model's spec.

TEST(CacheKey, CandidateSpecCoversEveryField) {
  CandidateSpec c;
  c.mounting_surface = "ceiling";
  expect_key_covers_fields<CandidateSpec>("CandidateSpec", c, {
      {"mounting_surface", [](CandidateSpec& s) { s.mounting_surface = "soffit"; }},
      {"type", [](CandidateSpec& s) { s.type = LuminaireType::square_lambertian(0.3); }},
      {"rotation_deg", [](CandidateSpec& s) { s.rotation_deg = 90.0; }},
      {"tilt_deg", [](CandidateSpec& s) { s.tilt_deg = 30.0; }},
      {"spacing_m", [](CandidateSpec& s) { s.spacing_m = 0.4; }},
      {"wall_distance_m", [](CandidateSpec& s) { s.wall_distance_m = 0.3; }},
      {"ceiling_module_m", [](CandidateSpec& s) { s.ceiling_module_m = 0.6; }},
      {"mount_offset_m", [](CandidateSpec& s) { s.mount_offset_m = 0.05; }},
      left_out<CandidateSpec>("mounting_loc", [](CandidateSpec& s) { s.mounting_loc = kAt; }),
      left_out<CandidateSpec>("spacing_loc", [](CandidateSpec& s) { s.spacing_loc = kAt; }),
      left_out<CandidateSpec>("offset_loc", [](CandidateSpec& s) { s.offset_loc = kAt; }),
      {"zone_m", [](CandidateSpec& s) { s.zone_m = std::make_pair(Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1)); }},
      {"zone_margin_m", [](CandidateSpec& s) { s.zone_margin_m = 1.0; }},
      {"suspended_height_m", [](CandidateSpec& s) { s.suspended_height_m = 3.0; }},
      {"wall", [](CandidateSpec& s) { s.wall = WallMountSpec{}; }},
      {"floor_surface", [](CandidateSpec& s) { s.floor_surface = "floor"; }},
      left_out<CandidateSpec>("zone_loc", [](CandidateSpec& s) { s.zone_loc = kAt; }),
      left_out<CandidateSpec>("suspended_loc", [](CandidateSpec& s) { s.suspended_loc = kAt; }),
      left_out<CandidateSpec>("floor_loc", [](CandidateSpec& s) { s.floor_loc = kAt; }),
  });
}

TEST(CacheKey, WallMountSpecCoversEveryField) {
  expect_key_covers_fields<WallMountSpec>("WallMountSpec", WallMountSpec{}, {
      {"facing", [](WallMountSpec& w) { w.facing = Eigen::Vector2d(0, -1); }},
      {"height_m", [](WallMountSpec& w) { w.height_m = 2.6; }},
      left_out<WallMountSpec>("height_loc", [](WallMountSpec& w) { w.height_loc = kAt; }),
      left_out<WallMountSpec>("facing_loc", [](WallMountSpec& w) { w.facing_loc = kAt; }),
  });
}

TEST(CacheKey, GoalAreaSpecCoversEveryField) {
  expect_key_covers_fields<GoalAreaSpec>("GoalAreaSpec", {"desks", {"desk"}, GoalFacing::any, -1}, {
      {"name", [](GoalAreaSpec& a) { a.name = "tables"; }},
      {"surfaces", [](GoalAreaSpec& a) { a.surfaces.push_back("table"); }},
      {"facing", [](GoalAreaSpec& a) { a.facing = GoalFacing::up; }},
      {"grid", [](GoalAreaSpec& a) { a.grid = 0; }},
      {"kind", [](GoalAreaSpec& a) { a.kind = AreaKind::glare; }},
      {"eye_height_m", [](GoalAreaSpec& a) { a.eye_height_m = 1.6; }},
      {"observers", [](GoalAreaSpec& a) { a.observers.push_back(ObserverSpec{}); }},
      left_out<GoalAreaSpec>("loc", [](GoalAreaSpec& a) { a.loc = kAt; }),
  });
}

TEST(CacheKey, ObserverSpecCoversEveryField) {
  expect_key_covers_fields<ObserverSpec>("ObserverSpec", ObserverSpec{}, {
      {"xy_m", [](ObserverSpec& o) { o.xy_m.x() = 1.0; }},
      {"eye_height_m", [](ObserverSpec& o) { o.eye_height_m = 1.6; }},
      {"view", [](ObserverSpec& o) { o.view = Eigen::Vector2d(0, 1); }},
      left_out<ObserverSpec>("loc", [](ObserverSpec& o) { o.loc = kAt; }),
  });
}

ModelSpec model_spec_with_target_error() {
  ModelSpec m;
  m.candidates.mounting_surface = "ceiling";
  m.areas = {{"desks", {"desk"}, GoalFacing::any, -1}};
  CalcGridSetting grid;
  grid.name = "plane";
  grid.over_surface = "floor";
  m.grids = {grid};
  m.sample_size.target_error = 0.05;  // so that the probe flux counts
  m.probe_flux_lm = 4000.0;
  return m;
}

TEST(CacheKey, ModelSpecCoversEveryField) {
  expect_key_covers_fields<ModelSpec>("ModelSpec", model_spec_with_target_error(), {
      {"candidates", [](ModelSpec& m) { m.candidates.spacing_m = 0.4; }},
      {"areas", [](ModelSpec& m) { m.areas[0].surfaces = {"floor"}; }},
      {"grids", [](ModelSpec& m) { m.grids[0].height_m = 0.75; }},
      {"operator_options", [](ModelSpec& m) { m.operator_options.form_factors.rays_per_patch = 64; }},
      {"sample_size", [](ModelSpec& m) { m.sample_size.fraction = 0.2; }},
      {"reflected_stride", [](ModelSpec& m) { m.reflected_stride = 1; }},
      {"probe_flux_lm", [](ModelSpec& m) { m.probe_flux_lm = 5000.0; }},
      left_out<ModelSpec>("threads", [](ModelSpec& m) { m.threads = 1; }),
  });
}

TEST(CacheKey, ProbeFluxCountsOnlyWithATargetError) {
  ModelSpec m = model_spec_with_target_error();
  m.sample_size.target_error.reset();
  ModelSpec other = m;
  other.probe_flux_lm = 5000.0;
  EXPECT_EQ(key_text_of(other), key_text_of(m)) << "k does not depend on the probe flux without a target error";
}

TEST(CacheKey, ThreadsAndProgressNeverCount) {
  const ModelSpec m = model_spec_with_target_error();
  ModelSpec other = m;
  other.threads = 1;
  other.operator_options.form_factors.threads = 1;
  other.operator_options.direct_light.threads = 1;
  other.operator_options.hit_direct_light.threads = 1;
  other.operator_options.direct_light.progress = [](std::string_view, std::size_t, std::size_t) {};
  other.operator_options.direct_light.progress_label = "elsewhere";
  EXPECT_EQ(key_text_of(other), key_text_of(m));
}

// ---- The schema's scene settings.

TEST(CacheKey, SceneSettingsCoverEveryField) {
  expect_key_covers_fields<ReflectanceSetting>("ReflectanceSetting", {"walls", Eigen::Vector3d::Constant(0.5), {}}, {
      {"surface", [](ReflectanceSetting& r) { r.surface = "floor"; }},
      {"rgb", [](ReflectanceSetting& r) { r.rgb.z() = 0.4; }},
      left_out<ReflectanceSetting>("loc", [](ReflectanceSetting& r) { r.loc = kAt; }),
  });
  FloorSetting floor;
  floor.name = "slab";
  floor.hi = Eigen::Vector2d(4, 4);
  expect_key_covers_fields<FloorSetting>("FloorSetting", floor, {
      {"name", [](FloorSetting& f) { f.name = "ground"; }},
      {"lo", [](FloorSetting& f) { f.lo.y() = -1.0; }},
      {"hi", [](FloorSetting& f) { f.hi.x() = 5.0; }},
      {"z_m", [](FloorSetting& f) { f.z_m = -0.1; }},
      {"rgb", [](FloorSetting& f) { f.rgb.x() = 0.2; }},
      left_out<FloorSetting>("loc", [](FloorSetting& f) { f.loc = kAt; }),
  });
  expect_key_covers_fields<EmitterSetting>("EmitterSetting", {"window", 100.0, {}}, {
      {"surface", [](EmitterSetting& e) { e.surface = "skylight"; }},
      {"exitance_lm_per_m2", [](EmitterSetting& e) { e.exitance_lm_per_m2 = 150.0; }},
      left_out<EmitterSetting>("loc", [](EmitterSetting& e) { e.loc = kAt; }),
  });
  LuminaireSetting placed;
  placed.name = "old";
  placed.position_m = Eigen::Vector3d(1, 1, 2.4);
  placed.flux_lm = 2000.0;
  expect_key_covers_fields<LuminaireSetting>("LuminaireSetting", placed, {
      {"name", [](LuminaireSetting& l) { l.name = "older"; }},
      {"position_m", [](LuminaireSetting& l) { l.position_m.z() = 2.3; }},
      {"flux_lm", [](LuminaireSetting& l) { l.flux_lm = 3000.0; }},
      left_out<LuminaireSetting>("loc", [](LuminaireSetting& l) { l.loc = kAt; }),
      // The product's name says nothing its type does not: the type is what lights the scene.
      left_out<LuminaireSetting>("product", [](LuminaireSetting& l) { l.product = "spot"; }),
      {"type", [](LuminaireSetting& l) { l.type = LuminaireType::square_lambertian(0.3); }},
      {"rotation_deg", [](LuminaireSetting& l) { l.rotation_deg = 30.0; }},
  });
}

// ---- The job's scene inputs: every JobConfig field is a scene input (it changes
// hash_scene_inputs) or not (the solver, goals, grids and search reach the operator
// through plan_job's ModelSpec; the rest never change the scene).

std::string scene_key(const JobConfig& job) {
  KeyWriter k;
  hash_scene_inputs(k, scene_spec(job));
  return k.text();
}

TEST(CacheKey, SceneInputsCoverEveryJobConfigField) {
  TempDir dir;
  JobConfig job;
  job.path = dir.file("job.yaml");
  job.mesh_path = dir.write("room.obj", room_obj({{"mat", {1.3, 1.7}}}));
  job.default_reflectance = Eigen::Vector3d::Constant(0.5);
  job.search = LuminaireSearch{};
  job.search->mounting_surface = "ceiling";
  job.goals = {GoalSetting{}};
  job.goals[0].name = "mat";
  job.goals[0].surfaces = {"mat"};
  job.goals[0].target = 200.0;
  const std::string other_mesh = dir.write("other.obj", room_obj({{"mat", {2.0, 2.0}}}));
  auto not_scene = [](std::string field, std::function<void(JobConfig&)> change) {
    return left_out<JobConfig>(std::move(field), std::move(change));
  };
  expect_key_covers_fields<JobConfig>("JobConfig", job, {
      not_scene("path", [&](JobConfig& j) { j.path = dir.file("elsewhere.yaml"); }),
      {"mesh_path", [&](JobConfig& j) { j.mesh_path = other_mesh; }},
      not_scene("mesh_loc", [](JobConfig& j) { j.mesh_loc = kAt; }),
      {"mesh_read", [](JobConfig& j) { j.mesh_read.surface_naming = SurfaceNaming::material; }},
      {"scene", [](JobConfig& j) { j.scene.max_patch_edge_m = 0.3; }},
      {"surface_split", [](JobConfig& j) { j.surface_split.connected = true; }},
      not_scene("max_patch_edge_loc", [](JobConfig& j) { j.max_patch_edge_loc = kAt; }),
      // Set or not: a set up_axis or scale_to_m overrides what an imported model states.
      {"up_axis_loc", [](JobConfig& j) { j.up_axis_loc = kAt; }},
      {"scale_to_m_loc", [](JobConfig& j) { j.scale_to_m_loc = kAt; }},
      {"reflectance", [](JobConfig& j) { j.reflectance.push_back({"walls", Eigen::Vector3d::Constant(0.3), {}}); }},
      {"default_reflectance", [](JobConfig& j) { j.default_reflectance.reset(); }},
      {"emitting_surfaces", [](JobConfig& j) { j.emitting_surfaces.push_back({"ceiling", 50.0, {}}); }},
      {"add_floors", [](JobConfig& j) {
         j.add_floors.push_back({"extra", Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), 0.0, Eigen::Vector3d::Constant(0.3), {}});
       }},
      {"exclude_surfaces", [](JobConfig& j) { j.exclude_surfaces.push_back("walls"); }},
      not_scene("exclude_surface_locs", [](JobConfig& j) { j.exclude_surface_locs.push_back(kAt); }),
      {"two_sided_surfaces", [](JobConfig& j) { j.two_sided_surfaces.push_back("walls"); }},
      not_scene("two_sided_locs", [](JobConfig& j) { j.two_sided_locs.push_back(kAt); }),
      {"two_sided_all", [](JobConfig& j) { j.two_sided_all = true; }},
      {"luminaire_size_m", [](JobConfig& j) { j.luminaire_size_m = 0.3; }},
      {"luminaires", [](JobConfig& j) { j.luminaires.emplace_back();
         j.luminaires.back().name = "old";
         j.luminaires.back().position_m = Eigen::Vector3d(0.5, 0.5, 2.4);
         j.luminaires.back().flux_lm = 2000.0; }},
      not_scene("form_factors", [](JobConfig& j) { j.form_factors.rays_per_patch = 64; }),
      not_scene("direct_light", [](JobConfig& j) { j.direct_light.shadow_rays = 2; }),
      not_scene("radiosity", [](JobConfig& j) { j.radiosity.max_iterations = 10; }),
      not_scene("method", [](JobConfig& j) { j.method = SolveMethod::exact; }),
      not_scene("sample", [](JobConfig& j) { j.sample.fraction = 0.3; }),
      not_scene("report_surfaces", [](JobConfig& j) { j.report_surfaces.push_back("floor"); }),
      not_scene("report_surface_locs", [](JobConfig& j) { j.report_surface_locs.push_back(kAt); }),
      not_scene("search", [](JobConfig& j) { j.search->candidate_spacing_m = 0.4; }),
      not_scene("groups", [](JobConfig& j) { j.groups.push_back({"A", {}, {}, *j.search}); }),
      not_scene("goals", [](JobConfig& j) { j.goals[0].surfaces = {"floor"}; }),
      not_scene("grids", [](JobConfig& j) { j.grids.push_back(CalcGridSetting{}); }),
      not_scene("maintenance_factor", [](JobConfig& j) { j.maintenance_factor = 0.8; }),
      not_scene("maintenance_loc", [](JobConfig& j) { j.maintenance_loc = kAt; }),
      not_scene("constraints", [](JobConfig& j) { j.constraints.min_distance_m = 1.0; }),
      not_scene("objective", [](JobConfig& j) { j.objective = Objective::closest_to_target; }),
      not_scene("optimizer", [](JobConfig& j) { j.optimizer.seed = 99; }),
      not_scene("verification", [](JobConfig& j) { j.verification.rays_per_patch = 64; }),
      not_scene("output", [](JobConfig& j) { j.output.directory = "elsewhere"; }),
      not_scene("energy", [](JobConfig& j) { j.energy.occupancy_factor = 0.5; }),
      not_scene("sweep", [](JobConfig& j) { j.sweep = SweepSetting{"goals.mat.average_lux", {300, 500}, {}}; }),
      // Other lighting states are judged on the layout found, after the operator.
      not_scene("scenarios", [](JobConfig& j) { j.scenarios.push_back(ScenarioSpec{}); }),
      // products reach the scene only through the placed luminaires' resolved types.
      not_scene("products", [](JobConfig& j) { j.products.push_back(ProductSetting{}); }),
      {"ignore_material_kd", [](JobConfig& j) { j.ignore_material_kd = true; }},
      // A room's part of the model: two rooms of one model must not share an operator.
      {"keep_surfaces", [](JobConfig& j) { j.keep_surfaces.push_back({"mat", "rooms[0].surfaces[0]", kAt}); }},
      // Each room runs as a job of its own (its keep_surfaces above); the list is no scene input.
      not_scene("rooms", [](JobConfig& j) { j.rooms.emplace_back(); }),
  }, scene_key);
}

TEST(CacheKey, SceneInputsReadTheMeshFilesNotTheirPath) {
  TempDir dir;
  JobConfig job;
  const std::string obj = room_obj({{"mat", {1.3, 1.7}}});
  job.mesh_path = dir.write("room.obj", obj);
  const std::string key = scene_key(job);
  JobConfig moved = job;
  moved.mesh_path = dir.write("copy.obj", obj);
  EXPECT_EQ(scene_key(moved), key) << "the same bytes under another name";
  dir.write("room.obj", obj + "# a comment\n");
  EXPECT_NE(scene_key(job), key) << "other bytes under the same name";
  JobConfig missing = job;
  missing.mesh_path = dir.file("none.obj");
  EXPECT_NE(scene_key(missing), key) << "no file: a marker, not an error";
}

TEST(CacheKey, SceneInputsReadAGltfsBufferFiles) {
  TempDir dir;
  JobConfig job;
  dir.write("room.bin", "0123");
  job.mesh_path = dir.write("room.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"uri" : "room.bin", "byteLength": 4}]})");
  const std::string key = scene_key(job);
  dir.write("room.bin", "4567");
  EXPECT_NE(scene_key(job), key) << "the buffer's bytes are the geometry";
}

}  // namespace
}  // namespace ilp
