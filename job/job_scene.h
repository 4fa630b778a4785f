// From a job's scene spec (job/scene_spec.h) to a ready scene: loads the mesh, resolves
// every triangle's reflectance (the job's by surface name, else the MTL Kd, else the
// job's default), builds patches, sets emitting surfaces and adds luminaires. Names in
// the job that the mesh lacks are ConfigErrors pointing at the job file.
#pragma once

#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "job/scene_spec.h"

namespace ilp {

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
// through assimp is limited to spec.mesh_read.import_limits, its memory by default to the
// machine's available memory (memory_budget_bytes).
JobScene load_job_scene(const SceneSpec& spec, TriangleMesh* mesh_out = nullptr);

// The search's surfaces (luminaires.mounting_surface, unless suspended, and
// luminaires.floor_surface) are surfaces of the scene's mesh (`mesh_path`): a located
// ConfigError naming the surfaces there if not. load_job_scene checks spec.search; a job
// of groups reads its scene once and checks each group's.
void require_search_surfaces(const SearchSurfaces& search, const std::string& mesh_path, const Scene& scene);

// The operator cache's key (core/base/key_hash.h): everything load_job_scene's scene
// depends on. The mesh file by its bytes (and, for OBJ, each mtllib's name and bytes;
// a missing or unreadable file gives a marker, never an error), its format and, for
// PLY/OFF, its stem (the surface's name), not its path; then mesh_read, scene,
// surface_split, reflectance, default_reflectance, emitting_surfaces, add_floors,
// exclude_surfaces, two_sided_surfaces, two_sided_all, luminaire_size_m, luminaires and
// ignore_material_kd. Every other SceneSpec field never changes the scene (file
// locations, the surfaces checked); the job's other keys reach the operator through
// plan_job's ModelSpec, hashed on their own, or not at all.
void hash_scene_inputs(KeyWriter& k, const SceneSpec& spec);

// The scene settings in the key: every field but loc. (Here rather than next to their
// definitions in job/scene_spec.h; LuminaireSetting's keeps its fields in one place for
// when placed luminaires carry a product.)
void hash_fields(KeyWriter& k, const ReflectanceSetting& r);
void hash_fields(KeyWriter& k, const FloorSetting& f);
void hash_fields(KeyWriter& k, const EmitterSetting& e);
void hash_fields(KeyWriter& k, const LuminaireSetting& l);

}  // namespace ilp
