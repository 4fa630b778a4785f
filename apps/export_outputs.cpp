// The export formats of `ilp run`, each staged into the run's OutputSet.
#include "apps/export_outputs.h"
#include "job/config.h"

namespace ilp::cli {
namespace {

RadianceNames names_for(const JobConfig& job) {
  std::vector<std::string> products, grids;
  for (const ProductSetting& p : job.products) products.push_back(p.name);
  for (const CalcGridSetting& g : job.grids) grids.push_back(g.name);
  return radiance_names(products, grids);
}

}  // namespace

std::vector<std::string> radiance_output_names(const JobConfig& job) { return names_for(job).all(); }

void stage_radiance(OutputSet& set, const ExportInputs& in, const JobConfig& job) {
  write_radiance_scene(*in.scene, in.luminaires, in.grids, names_for(job),
                       [&](const std::string& name, const std::function<void(std::ostream&)>& write) { set.write(name, write); });
}

void stage_gltf(OutputSet& set, const ExportInputs& in) {
  write_illuminance_gltf(set.staging_path(kGltfName), *in.scene, in.lux_per_patch, in.scale, in.luminaires);
  set.staged(kGltfName);
}

void stage_dxf(OutputSet& set, const ExportInputs& in) {
  set.write(kDxfName, [&](std::ostream& out) { write_dxf_plan(out, *in.scene, in.luminaires, in.floor_z_m, kPlanCutHeightM); });
}

void stage_schedule(OutputSet& set, const ExportInputs& in) {
  set.write(kScheduleName, [&](std::ostream& out) { write_schedule_csv(out, in.luminaires); });
}

}  // namespace ilp::cli
