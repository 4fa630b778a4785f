// What the scene stage reads of a job (load_job_scene, job/job_scene.h): the mesh and the
// frame it is read in, its surfaces' reflectances, what is left out, doubled or added,
// the job's own sources, and the surfaces it checks the mesh has (reported, lit, searched).
// plan_job translates the job file into it (job/plan.h); the scene stage and the operator
// cache's key read nothing else of the job.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/light/luminaire.h"
#include "core/scene/mesh.h"
#include "core/scene/scene.h"
#include "core/scene/surface_split.h"

namespace ilp {

struct ReflectanceSetting {
  std::string surface;
  Eigen::Vector3d rgb;  // each channel in [0, 1); equal channels when given as one number
  FileLoc loc;
};

// scene.add_floor: a horizontal rectangle added to the mesh as its own surface, facing
// up (a real floor where a model has only a ground plane around it, or none).
struct FloorSetting {
  std::string name;
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero();  // x, y corners, scene frame (m)
  double z_m = 0.0;
  Eigen::Vector3d rgb = Eigen::Vector3d::Constant(0.3);
  FileLoc loc;
};

struct EmitterSetting {
  std::string surface;
  double exitance_lm_per_m2 = 0.0;
  FileLoc loc;
};

// luminaires.placed: a fixed luminaire, as the scene adds it (add_luminaire): its type,
// where it is and its output. Without a product, the square Lambertian panel of
// luminaires.size_m; with one, the product's type as the config loader resolved it
// (job/products.h: its photometric file read there, once per product).
struct LuminaireSetting {
  std::string name;
  Eigen::Vector3d position_m;  // centre of the emitting face, scene frame (z up, m)
  double flux_lm = 0.0;
  FileLoc loc;
  std::string product;         // a product of luminaires.products; empty: the plain panel
  LuminaireType type = LuminaireType::square_lambertian(0.6);
  double rotation_deg = 0.0;   // about +z, counter-clockwise seen from above
};

// The part of a model one room of a building job sees (rooms[].surfaces): the surfaces
// it names, each a name or a prefix ending in '*'; every other surface of the mesh is
// left out of the room's scene, as scene.exclude_surfaces would. Empty: the whole model.
struct SurfacePattern {
  std::string pattern;  // "office_1_floor", or "office_1_*" (every name starting "office_1_")
  std::string key;      // where it was written: rooms[2].surfaces[0]
  FileLoc loc;
};

// The search's surfaces the mesh must have: luminaires.mounting_surface (unless the
// luminaires hang on a suspension plane) and luminaires.floor_surface (if named).
struct SearchSurfaces {
  std::string mounting_surface;
  FileLoc mounting_loc;
  bool suspended = false;
  std::string floor_surface;  // empty: none named
  FileLoc floor_loc;
};

// A goal's surfaces (goals.NAME.surface), which must keep a patch.
struct GoalSurfaces {
  std::string name;
  std::vector<std::string> surfaces;
  FileLoc loc;
};

struct SceneSpec {
  std::string path;  // the job file, for messages
  // The mesh, resolved against the job's folder, and how it is read.
  std::string mesh_path;
  FileLoc mesh_loc;
  MeshReadOptions mesh_read;
  SceneOptions scene;
  SurfaceSplitOptions surface_split;  // surfaces_from: connected, weld_tolerance_m, regions
  FileLoc max_patch_edge_loc;         // where max_patch_edge_m was set (if it was)
  // Set (a file location), they override what an imported model states of its frame.
  FileLoc up_axis_loc;
  FileLoc scale_to_m_loc;
  std::vector<ReflectanceSetting> reflectance;  // in file order: a later one wins
  std::optional<Eigen::Vector3d> default_reflectance;
  std::vector<EmitterSetting> emitting_surfaces;
  std::vector<FloorSetting> add_floors;
  std::vector<std::string> exclude_surfaces;
  std::vector<FileLoc> exclude_surface_locs;
  std::vector<std::string> two_sided_surfaces;  // back faces reflect too (doubled back to back)
  std::vector<FileLoc> two_sided_locs;
  bool two_sided_all = false;
  double luminaire_size_m = 0.6;            // the plain panel's side
  std::vector<LuminaireSetting> luminaires;  // placed
  // Every triangle takes default_reflectance, whatever its MTL Kd (`ilp inspect MESH`).
  bool ignore_material_kd = false;
  // A room of a building job: only these surfaces (and its coupled rooms'). Empty: all.
  std::vector<SurfacePattern> keep_surfaces;
  // Checked, never changing the scene: report.surfaces, the goals' surfaces, the search's.
  std::vector<std::string> report_surfaces;
  std::vector<FileLoc> report_surface_locs;
  std::vector<GoalSurfaces> goals;
  std::optional<SearchSurfaces> search;  // an inverse job's (group 0's for a job of groups)
};

}  // namespace ilp
