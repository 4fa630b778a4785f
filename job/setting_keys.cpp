#include "job/setting_keys.h"

namespace ilp {

std::string setting_key(Setting s, std::string_view of) {
  const std::string name(of);
  switch (s) {
    case Setting::patch_edge: return "scene.max_patch_edge_m";
    case Setting::surfaces_from: return "scene.surfaces_from";
    case Setting::regions: return "scene.regions";
    case Setting::two_sided: return "scene.two_sided";
    case Setting::exclude_surfaces: return "scene.exclude_surfaces";
    case Setting::sample_size: return "solver.sample_size";
    case Setting::sample_fraction: return "solver.sample_fraction";
    case Setting::target_error: return "solver.target_error";
    case Setting::max_sample_size: return "solver.max_sample_size";
    case Setting::pilot_fraction: return "solver.pilot_fraction";
    case Setting::error_samples: return "solver.error_samples";
    case Setting::mounting_surface: return "luminaires.mounting_surface";
    case Setting::floor_surface: return "luminaires.floor_surface";
    case Setting::zone: return "luminaires.zone";
    case Setting::candidate_spacing: return "luminaires.candidate_spacing_m";
    case Setting::mount_offset: return "luminaires.mount_offset_m";
    case Setting::suspended_height: return "luminaires.suspended.height_m";
    case Setting::wall_height: return "luminaires.on_wall.height_m";
    case Setting::wall_facing: return "luminaires.on_wall.facing";
    case Setting::wall_surface: return "luminaires.on_wall.surface";
    case Setting::count: return "luminaires.count";
    case Setting::layout: return "luminaires.layout";
    case Setting::array: return "luminaires.array";
    case Setting::array_offset: return "luminaires.array.offset_m";
    case Setting::array_spacing: return "luminaires.array.spacing_m";
    case Setting::max_luminaires: return "constraints.max_luminaires";
    case Setting::min_distance: return "constraints.min_distance_m";
    case Setting::max_evaluations: return "optimizer.max_evaluations";
    case Setting::verification_rays: return "verification.rays_per_patch";
    case Setting::verification_method: return "verification.method";
    case Setting::verification_sample_fraction: return "verification.sample_fraction";
    case Setting::output_formats: return "output.formats";
    case Setting::grid: return name.empty() ? "grids[]" : "grids." + name;
    case Setting::grid_over_surface: return setting_key(Setting::grid, of) + ".over_surface";
    case Setting::grid_height: return setting_key(Setting::grid, of) + ".height_m";
    case Setting::grid_border: return setting_key(Setting::grid, of) + ".border_m";
    case Setting::grid_spacing: return setting_key(Setting::grid, of) + ".spacing_m";
    case Setting::grid_max_points: return setting_key(Setting::grid, of) + ".max_points";
    case Setting::goal_ugr_max: return "goals." + name + ".ugr_max";
    case Setting::goal_observers: return "goals." + name + ".observers";
    case Setting::goal_cylindrical_lux: return "goals." + name + ".cylindrical_lux";
  }
  return "an unknown setting";
}

void name_settings_by_key() { register_setting_names(&setting_key); }

}  // namespace ilp
