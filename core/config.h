// The job configuration (YAML), parsed and checked before any work starts. Every
// value keeps the file location it came from, so later checks (a surface name the
// mesh lacks) can point at it. Unknown keys are errors: a typo must not silently
// fall back to a default. The schema is documented in docs/config.md.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/direct_light.h"
#include "core/error.h"
#include "core/form_factors.h"
#include "core/mesh.h"
#include "core/radiosity.h"
#include "core/scene.h"

namespace ilp {

struct ReflectanceSetting {
  std::string surface;
  Eigen::Vector3d rgb;  // each channel in [0, 1); equal channels when given as one number
  FileLoc loc;
};

struct EmitterSetting {
  std::string surface;
  double exitance_lm_per_m2 = 0.0;
  FileLoc loc;
};

struct LuminaireSetting {
  std::string name;
  Eigen::Vector3d position_m;  // centre of the emitting face, scene frame (z up, m)
  double flux_lm = 0.0;
  FileLoc loc;
};

struct JobConfig {
  std::string path;                     // the YAML file
  // scene
  std::string mesh_path;                // resolved against the config's folder
  FileLoc mesh_loc;
  MeshReadOptions mesh_read;
  SceneOptions scene;
  FileLoc max_patch_edge_loc;           // where max_patch_edge_m was set (if it was)
  std::vector<ReflectanceSetting> reflectance;
  std::optional<Eigen::Vector3d> default_reflectance;
  std::vector<EmitterSetting> emitting_surfaces;
  // luminaires
  double luminaire_size_m = 0.6;
  std::vector<LuminaireSetting> luminaires;
  // solver
  FormFactorOptions form_factors;
  DirectLightOptions direct_light;
  RadiosityOptions radiosity;
  // report
  std::vector<std::string> report_surfaces;  // empty: every surface
  std::vector<FileLoc> report_surface_locs;
};

// Reads and validates a job file. Throws ConfigError "file:line:col: key = value: rule".
JobConfig load_job_config(const std::string& path);

}  // namespace ilp
