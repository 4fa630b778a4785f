#include "core/base/setting.h"

#include <atomic>

namespace ilp {
namespace {

std::atomic<SettingNamer> g_namer{nullptr};

// The description of a setting where no reading layer named it.
std::string described(Setting s, std::string_view of) {
  const std::string own = of.empty() ? std::string() : " of '" + std::string(of) + "'";
  switch (s) {
    case Setting::patch_edge: return "the longest patch edge";
    case Setting::surfaces_from: return "the rule that splits surfaces";
    case Setting::regions: return "the named regions";
    case Setting::two_sided: return "the two-sided surfaces";
    case Setting::exclude_surfaces: return "the surfaces left out";
    case Setting::sample_size: return "the sample size";
    case Setting::sample_fraction: return "the sample fraction";
    case Setting::target_error: return "the target error";
    case Setting::max_sample_size: return "the largest sample size";
    case Setting::pilot_fraction: return "the pilot samples' fraction";
    case Setting::error_samples: return "the number of pilot samples";
    case Setting::mounting_surface: return "the mounting surface";
    case Setting::floor_surface: return "the floor surface";
    case Setting::zone: return "the luminaires' zone";
    case Setting::candidate_spacing: return "the candidate spacing";
    case Setting::mount_offset: return "the mounting offset";
    case Setting::suspended_height: return "the suspension height";
    case Setting::wall_height: return "the wall mounting height";
    case Setting::wall_facing: return "the wall's facing";
    case Setting::wall_surface: return "the wall surface";
    case Setting::count: return "the luminaire count";
    case Setting::layout: return "the layout";
    case Setting::array: return "the array";
    case Setting::array_offset: return "the array's offset";
    case Setting::array_spacing: return "the array's spacing";
    case Setting::max_luminaires: return "the most luminaires";
    case Setting::min_distance: return "the least distance between luminaires";
    case Setting::max_evaluations: return "the most evaluations";
    case Setting::verification_rays: return "the verification's rays per patch";
    case Setting::verification_method: return "the verification method";
    case Setting::verification_sample_fraction: return "the verification's sample fraction";
    case Setting::output_formats: return "the output formats";
    case Setting::grid: return "the grid" + own;
    case Setting::grid_over_surface: return "the surface under the grid" + own;
    case Setting::grid_height: return "the height of the grid" + own;
    case Setting::grid_border: return "the border of the grid" + own;
    case Setting::grid_spacing: return "the spacing of the grid" + own;
    case Setting::grid_max_points: return "the most points of the grid" + own;
    case Setting::goal_ugr_max: return "the UGR limit" + own;
    case Setting::goal_observers: return "the observers" + own;
    case Setting::goal_cylindrical_lux: return "the cylindrical illuminance" + own;
  }
  return "a setting";
}

}  // namespace

std::string setting_name(Setting s, std::string_view of) {
  const SettingNamer namer = g_namer.load(std::memory_order_acquire);
  return namer ? namer(s, of) : described(s, of);
}

SettingNamer register_setting_names(SettingNamer namer) { return g_namer.exchange(namer, std::memory_order_acq_rel); }

}  // namespace ilp
