// What `ilp run` exports for other tools (output.formats radiance, gltf, dxf,
// schedule): the layout and the job's placed luminaires as output/layout_export.h
// describes them, each format staged into the run's OutputSet.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "job/config.h"
#include "output/atomic_file.h"
#include "output/colour_map.h"
#include "output/layout_export.h"

namespace ilp::cli {

// The exports' inputs: the verified scene (without the layout), every luminaire (the
// layout's, then the job's placed ones), the illuminance per patch and its colour
// scale, the grids' points and the floor's height.
struct ExportInputs {
  const Scene* scene = nullptr;
  std::vector<ExportLuminaire> luminaires;
  Eigen::VectorXd lux_per_patch;
  ColourScale scale;
  std::vector<ExportGrid> grids;
  double floor_z_m = 0.0;
};

// The plan's cut: 1.0 m above the floor, where an architect's plan cuts walls.
inline constexpr double kPlanCutHeightM = 1.0;

// Every file each format can write for the job (for OutputSet's owned list).
std::vector<std::string> radiance_output_names(const JobConfig& job);
inline constexpr const char* kGltfName = "scene.glb";
inline constexpr const char* kDxfName = "plan.dxf";
inline constexpr const char* kScheduleName = "schedule.csv";

void stage_radiance(OutputSet& set, const ExportInputs& in, const JobConfig& job);
void stage_gltf(OutputSet& set, const ExportInputs& in);
void stage_dxf(OutputSet& set, const ExportInputs& in);
void stage_schedule(OutputSet& set, const ExportInputs& in);

}  // namespace ilp::cli
