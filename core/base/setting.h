// The job settings a message of core/ or optimizer/ points the user at, named by what
// they set. Below job/, a message names one with setting_name(); the layer that reads
// the job file registers how its file spells each (job/setting_keys.h: the YAML key), so
// core/ and optimizer/ never spell the schema. Unregistered (the libraries used without
// job/), a setting is named by its description.
#pragma once

#include <string>
#include <string_view>

namespace ilp {

enum class Setting {
  // the scene
  patch_edge, surfaces_from, regions, two_sided, exclude_surfaces,
  // the sample-based operator
  sample_size, sample_fraction, target_error, max_sample_size, pilot_fraction, error_samples,
  // where luminaires go and how many
  mounting_surface, floor_surface, zone, candidate_spacing, mount_offset, suspended_height, wall_height,
  wall_facing, wall_surface, count, layout, array, array_offset, array_spacing, max_luminaires, min_distance,
  // the search, the verification, the outputs
  max_evaluations, verification_rays, verification_method, verification_sample_fraction, output_formats,
  // a calculation grid (`of`: its name; empty: every grid)
  grid, grid_over_surface, grid_height, grid_border, grid_spacing, grid_max_points,
  // a goal (`of`: its name)
  goal_ugr_max, goal_observers, goal_cylindrical_lux,
};

// What a message calls setting `s` (of the grid or goal named `of`, for theirs).
std::string setting_name(Setting s, std::string_view of = {});

// How the reading layer names settings; registered once, before any work (later
// registrations replace it: the same function every time). Returns the namer it
// replaced (nullptr: none, the descriptions).
using SettingNamer = std::string (*)(Setting s, std::string_view of);
SettingNamer register_setting_names(SettingNamer namer);

}  // namespace ilp
