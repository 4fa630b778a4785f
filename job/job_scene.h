// From a job configuration to a ready scene: loads the mesh, resolves every
// triangle's reflectance (config by surface name, else the MTL Kd, else the
// config's default), builds patches, sets emitting surfaces and adds luminaires.
// Names in the config that the mesh lacks are ConfigErrors pointing at the config.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace ilp {

// job/config.h: the scene stage reads the job's scene keys.
struct JobConfig;
struct ReflectanceSetting;
struct FloorSetting;
struct EmitterSetting;
struct LuminaireSetting;
class KeyWriter;

class KeyWriter;  // core/base/key_hash.h

struct JobScene {
  Scene scene;
  std::vector<std::string> log;  // what was done to the input, for the run log
  // The frame the mesh was read in: the job's up_axis and scale_to_m, or what an
  // imported file states where the job sets neither.
  SceneOptions frame = {};
};

// `mesh_out`, when given, receives the mesh the scene was made from (file units, after
// surface splitting, exclusions and two-sided doubling), for `ilp inspect`. A model read
// through assimp is limited to job.mesh_read.import_limits, its memory by default to the
// machine's available memory (memory_budget_bytes).
JobScene load_job_scene(const JobConfig& job, TriangleMesh* mesh_out = nullptr);

// The search's surfaces (luminaires.mounting_surface, unless suspended, and
// luminaires.floor_surface) are surfaces of the scene's mesh: a located ConfigError naming
// the surfaces there if not. load_job_scene checks them for its own job; a job of groups
// reads its scene once and checks each group's.
void require_search_surfaces(const JobConfig& job, const Scene& scene);

// The operator cache's key (core/base/key_hash.h): everything load_job_scene's scene
// depends on. The mesh file by its bytes (and, for OBJ, each mtllib's name and bytes;
// a missing or unreadable file gives a marker, never an error), its format and, for
// PLY/OFF, its stem (the surface's name), not its path; then mesh_read, scene,
// surface_split, reflectance, default_reflectance, emitting_surfaces, add_floors,
// exclude_surfaces, two_sided_surfaces, two_sided_all, luminaire_size_m, luminaires and
// ignore_material_kd. Every other JobConfig field is either no scene input (the solver,
// goals, grids and search reach the operator through plan_job's ModelSpec, hashed on
// their own) or never changes the scene (file locations, checks, the memory budget).
void hash_scene_inputs(KeyWriter& k, const JobConfig& job);

// The schema's scene settings in the key: every field but loc. (Here rather than next
// to their definitions in job/config.h; LuminaireSetting's keeps its fields in one place
// for when placed luminaires carry a product.)
void hash_fields(KeyWriter& k, const ReflectanceSetting& r);
void hash_fields(KeyWriter& k, const FloorSetting& f);
void hash_fields(KeyWriter& k, const EmitterSetting& e);
void hash_fields(KeyWriter& k, const LuminaireSetting& l);

}  // namespace ilp
