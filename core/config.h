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
#include "core/patch_sample.h"
#include "core/radiosity.h"
#include "core/sample_operator.h"
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

// How `ilp solve` computes illuminance: through the sample-based operator, or the
// exact reference (every form-factor row, Gauss-Seidel).
enum class SolveMethod { sample, exact };

// The sample-based operator's settings (solver section).
struct SampleSettings {
  std::optional<int> size;         // k; when absent, fraction of the reflecting patches
  double fraction = 0.05;
  FileLoc size_loc;                // where size or fraction was set
  SampleStrategy strategy = SampleStrategy::stratified;
  std::uint64_t seed = 1;          // which patches are drawn
  IndirectMethod indirect = IndirectMethod::exact_second_bounce;
  std::optional<double> target_error;  // choose k so the predicted RMS relative error is at most this
  FileLoc target_error_loc;
  int error_samples = 4;           // eta pilot samples behind the prediction
  double pilot_fraction = 0.02;    // their size, of the reflecting patches

  // k for a population of reflecting patches (at least 1).
  int size_for(std::size_t population) const;
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
  SolveMethod method = SolveMethod::sample;
  SampleSettings sample;
  // report
  std::vector<std::string> report_surfaces;  // empty: every surface
  std::vector<FileLoc> report_surface_locs;
};

// Reads and validates a job file. Throws ConfigError "file:line:col: key = value: rule".
JobConfig load_job_config(const std::string& path);

}  // namespace ilp
