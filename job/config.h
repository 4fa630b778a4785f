// The job configuration (YAML), parsed and checked before any work starts. Every
// value keeps the file location it came from, so later checks (a surface name the
// mesh lacks) can point at it. Unknown keys are errors: a typo must not silently
// fall back to a default. The schema is documented in docs/config.md.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/grid/calc_grid.h"
#include "core/transport/direct_light.h"
#include "core/base/error.h"
#include "core/transport/form_factors.h"
#include "core/scene/mesh.h"
#include "core/operator/patch_sample.h"
#include "core/exact/radiosity.h"
#include "core/operator/sample_operator.h"
#include "core/operator/sample_size.h"
#include "core/scene/scene.h"
#include "core/scene/surface_split.h"
#include "optimizer/goal_spec.h"
#include "optimizer/lighting_model.h"
#include "optimizer/scenario_spec.h"
#include "output/output_formats.h"
#include "optimizer/search_spec.h"
#include "job/scene_spec.h"
#include "job/verification_spec.h"

namespace ilp {

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
  int max_size_for_target = 4000;  // solver.max_sample_size: the largest k target_error or sample_fraction gives
  FileLoc max_size_loc;
  int reflected_stride = 2;        // the candidates' reflected light at every n-th candidate (ModelSpec)
  // solver.hit_block_patches: the patches the rows hit are taken in blocks of this many
  // (SampleOperatorOptions::hit_block_patches): what a split build spreads over ranks.
  int hit_block_patches = 1 << 14;

  // The sample-size part, as the operator's stage takes it (core/operator/sample_size.h).
  SampleSizeRule rule() const;
  int size_for(std::size_t population) const;  // rule().size_for
};

// ---- The inverse problem (`ilp run`, `ilp sweep`): where luminaires may go, what the
// goal surfaces must receive, and how to search. docs/config.md gives the schema, docs/user-guide.md a walk through it.

// luminaires.products: a luminaire one can buy. Photometric (an IES LM-63 or EULUMDAT
// file) or the square Lambertian test panel; lumens and watts from the file unless
// given; a fixed lumen package unless a dimming range is given.
struct ProductSetting {
  std::string name;
  FileLoc loc;
  std::string photometry_path;         // resolved against the config's folder; empty: square_lambertian
  FileLoc photometry_loc;
  double size_m = 0.6;                 // square_lambertian only: the panel's side
  std::optional<double> flux_lm;       // rated output; default: the file's luminaire flux
  std::optional<double> power_w;       // electric power at the rated output; default: the file's input watts
  FileLoc power_loc;
  double dim_min = 1.0, dim_max = 1.0; // dimming: [min, max] as fractions of the rated output
  std::optional<double> maintenance_factor;
  std::vector<double> rotations_deg;   // empty: 0 for rotationally symmetric distributions, else 0 and 90
  std::optional<double> mount_offset_m;  // its opening this far below the mounting surface (a pendant's
  FileLoc mount_offset_loc;              // suspension); default: luminaires.mount_offset_m
  double tilt_deg = 0.0;                 // aim: [0, 90] about its C90-C270 axis, nadir toward C0 (a wall washer, a spot)
  std::optional<double> length_axis_c_deg;  // which C-plane (0 or 90) its opening's length runs along; default: from the file
  FileLoc length_axis_loc;
  std::optional<double> ra;                 // colour rendering index Ra (data sheet), checked against a preset's
  FileLoc ra_loc;
};

// luminaires: the luminaires the search places (present when mounting_surface is given).
struct LuminaireSearch {
  std::string model = "square_lambertian";  // the only model: a square Lambertian panel facing down
  double flux_min_lm = 0.0;                 // flux_lm: [min, max]; 0 <= min < max
  double flux_max_lm = 0.0;
  FileLoc flux_loc;
  double efficacy_lm_per_w = 100.0;         // > 0; electric power = flux / efficacy
  std::string mounting_surface;             // a surface of the scene facing down (a ceiling)
  FileLoc mounting_loc;
  double mount_offset_m = 0.02;             // the emitting face hangs this far below the mounting surface, > 0
  FileLoc offset_loc;  // where mount_offset_m was set (if it was)
  double candidate_spacing_m = 0.5;         // grid of precomputed positions; T is interpolated between them
  FileLoc spacing_loc;
  int count_min = 1;                        // count: N or [min, max]: how many luminaires (free layout)
  int count_max = 1;
  FileLoc count_loc;
  double wall_distance_m = 0.0;             // a luminaire's outline keeps at least this from the mounting surface's edges
  double ceiling_module_m = 0.0;            // > 0: centres snap to the module's cell centres (a 0.6 m grid ceiling)
  LayoutFamily layout = LayoutFamily::free;
  // layout: array. rows x columns; spacing and offset (the first luminaire's centre,
  // from the mounting surface's lower x, y corner) fixed when given, else searched.
  int array_rows = 0;
  int array_columns = 0;
  std::optional<Eigen::Vector2d> array_spacing_m;
  std::optional<Eigen::Vector2d> array_offset_m;
  // layout: field, rows or bays (the blocks field:, rows:, bays:).
  RegularLayoutParams regular;
  FileLoc layout_loc;
  // output: equal (default: every luminaire of the layout at one output, dimmed
  // together) or individual (free layouts of the plain panel: each its own flux).
  bool individual_output = false;
  // zone: where luminaire centres may lie: a rectangle [[x0, y0], [x1, y1]] (scene
  // frame, m), else the goals' outline in plan widened by margin_m.
  std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> zone_m;
  double zone_margin_m = 0.5;
  bool zone_set = false;  // the job has a zone block
  FileLoc zone_loc;
  // suspended: {height_m}: instead of mounting_surface, luminaires hang on a plane this
  // far above the floor over the zone (pendants, high-bays).
  std::optional<double> suspended_height_m;
  FileLoc suspended_loc;
  // on_wall: {surface, height_m, facing}: instead of mounting_surface (which then holds
  // the wall's surface name), luminaires on a wall's faces facing into the room that way,
  // at a height above the floor, their C0 into the room (a tilt aims them).
  std::optional<WallMountSpec> on_wall;
  // floor_surface: the finished floor heights are given and reported above (default:
  // the first grid's over_surface).
  std::string floor_surface;
  FileLoc floor_loc;
};

// luminaires.groups: one of several luminaire groups searched together (issue 19, item
// 5; docs/config.md): its name, the products it chooses from and its own search settings
// (mounting, layout family, zone, output), read by the single group's reader.
struct LuminaireGroup {
  std::string name;
  FileLoc loc;
  std::vector<std::string> products;  // names in luminaires.products
  LuminaireSearch search;
};

// One line of goals: a metric over the union of some surfaces. A goals entry with
// several metrics (average_lux and uniformity) becomes several GoalSettings with the
// same name.

struct GoalSetting {
  std::string name;                   // `name:`, else the surfaces joined with '+' (or the grid's name)
  std::vector<std::string> surfaces;  // surface: NAME or [NAME, ...]; empty for a grid goal
  std::string grid;                   // grid: NAME, a calculation grid of `grids` (instead of surface)
  FileLoc surfaces_loc;
  GoalFacing facing = GoalFacing::any;  // facing: any, up or down
  GoalMetric metric = GoalMetric::average;
  double target = 0.0;                // lux, or the U0 ratio: a maintained value (see maintenance_factor)
  FileLoc loc;                        // of the metric's key (or the preset's)
  // eye_height_m: cylindrical metrics' points and the standard's observers this far above
  // the floor (default 1.2 m, seated); observers: ugr_max's (default: the standard's four).
  std::optional<double> eye_height_m;
  std::vector<ObserverSpec> observers;
};

// EN 12464-1:2021 rows (docs/config.md gives the sources): `preset: office_writing` on a
// task area gives the row's Em (required, or modified with `em: modified`) as average_lux,
// U0 as uniformity, UGR_L as ugr_max, Ez,m as cylindrical_lux (with Ez U0 >= 0.10) and,
// on the surfaces the entry names as `walls` and `ceiling`, their Em and U0 >= 0.10; on a
// task area drawn as a rectangle or polygon, for rows with one, the immediate surrounding
// area (`surrounding: false` leaves it out). Products must state Ra (`ra`) at least the row's. 0: the row gives no value.
struct GoalPreset {
  const char* key;         // office_writing, ...
  const char* standard;    // the row as the standard names it
  const char* building;    // offices, education, health care, retail, industry, circulation, places of worship
  double average_lux;      // Em required
  double modified_lux;     // Em modified (0: none known)
  double uniformity;       // U0
  double ugr_max;          // UGR_L (0: none)
  double ra;               // Ra (0: none)
  double cylindrical_lux;  // Ez,m (0: none)
  double wall_lux;         // Em,wall (the general 50 lx when the row gives none)
  double ceiling_lux;      // Em,ceiling (the general 30 lx when the row gives none)
  bool surrounding;        // a task area with an immediate surrounding area (not a whole room: corridor, store, ...)
};
std::span<const GoalPreset> goal_presets();
inline constexpr double kRoomSurfaceUniformity = 0.10;  // EN 12464-1:2021: walls, ceiling and Ez

// The immediate surrounding area (EN 12464-1:2021, 5.3.3): a band at least 0.5 m wide
// around the task area, U0 >= 0.40, its Em one step of the illuminance scale below the
// task's: task >= 750 lx -> 500, 500 -> 300, 300 -> 200, 200 -> 150, <= 150 -> the task's
// own (a task Em between rows takes the row at or below it). docs/config.md gives the sources.
inline constexpr double kSurroundingWidthM = 0.5;
inline constexpr double kSurroundingUniformity = 0.40;
double surrounding_average_lux(double task_average_lux);
// The band's grid and goal are named after the task's: "<grid>_surrounding", "<goal>_surrounding".
inline constexpr const char* kSurroundingSuffix = "_surrounding";

struct SearchConstraints {
  std::optional<int> max_luminaires;    // caps luminaires.count (free) or rows x columns (array: error if more)
  FileLoc max_luminaires_loc;
  double min_distance_m = 0.0;          // between luminaire centres, >= 0
  // max_power_density_w_per_m2: the layout's electric power over the power density's
  // area (JobOutcome::floor_area_m2: the floor, or a grid's own area, named) at most
  // this; > 0. The search takes it as a cap on the total power, cap x that area.
  std::optional<double> max_power_density_w_per_m2;
  FileLoc max_power_density_loc;
};

struct OutputSettings {
  std::string directory;  // as written in the file (relative to the working directory); empty: "results/<config stem>"
  // formats: the keys of output/output_formats.h listed (default: those written by
  // default); the grid formats write one file per job (grid.csv) or per grid
  // (isolux_<grid>.svg, .png) and nothing for a job without grids (listing one there is
  // an error).
  std::vector<std::string> formats = default_output_formats();
  bool wants(std::string_view key) const { return std::find(formats.begin(), formats.end(), key) != formats.end(); }
  // plan_cut_height_m: the plan's section plane over the floor (> 0); 0: the first
  // horizontal grid's height, else 0.8 m (EN 12464-1's work plane).
  double plan_cut_height_m = 0.0;
};

// energy: the operating profile behind the annual energy and LENI (EN 15193-1,
// core/energy/leni.h). Without the section: an office's hours, no controls.
struct EnergySettings {
  std::string building_type = "office";      // a row of building_types(): its t_D, t_N by default
  std::optional<double> hours_day;           // t_D, h per year; default: the building type's
  std::optional<double> hours_night;         // t_N, h per year; default: the building type's
  double occupancy_factor = 1.0;             // F_O in (0, 1]
  double daylight_factor = 1.0;              // F_D in [0, 1]
  bool constant_illuminance = false;         // F_C = (1 + MF) / 2 when true, else 1
  double parasitic_kwh_per_m2 = 6.0;         // emergency lighting + controls standby, kWh/(m²·a)
  bool given = false;                        // the job has an energy section
  FileLoc loc;
};

// sweep: run the job once per value of one goal parameter, e.g.
// key "goals.desks.average_lux" with values [300, 500, 750].
struct SweepSetting {
  std::string key;
  std::vector<double> values;
  FileLoc loc;
};

struct RoomSetting;


struct JobConfig {
  std::string path;                     // the YAML file
  // scene
  std::string mesh_path;                // resolved against the config's folder
  FileLoc mesh_loc;
  MeshReadOptions mesh_read;
  SceneOptions scene;
  SurfaceSplitOptions surface_split;    // surfaces_from: connected, weld_tolerance_m, regions
  FileLoc max_patch_edge_loc;           // where max_patch_edge_m was set (if it was)
  // Where up_axis and scale_to_m were set (if they were): set, they override what an
  // imported model (glTF, IFC, ...) states of its frame; unset, the file's statement holds.
  FileLoc up_axis_loc;
  FileLoc scale_to_m_loc;
  std::vector<ReflectanceSetting> reflectance;
  std::optional<Eigen::Vector3d> default_reflectance;
  std::vector<EmitterSetting> emitting_surfaces;
  std::vector<FloorSetting> add_floors;
  // Surfaces left out of the scene (a ground plane around a room, outdoor objects).
  std::vector<std::string> exclude_surfaces;
  std::vector<FileLoc> exclude_surface_locs;
  // Surfaces that reflect on both sides (patches doubled back to back); all of them
  // with `two_sided: all`. Others are one-sided: light striking a back face is absorbed.
  std::vector<std::string> two_sided_surfaces;
  std::vector<FileLoc> two_sided_locs;
  bool two_sided_all = false;
  // luminaires
  double luminaire_size_m = 0.6;
  std::vector<LuminaireSetting> luminaires;
  // luminaires.products: what placed luminaires may name, and with mounting_surface
  // what the search chooses from (each product at each rotation); empty: the search
  // places the model/flux_lm/efficacy_lm_per_w panel.
  std::vector<ProductSetting> products;
  // solver
  FormFactorOptions form_factors;
  DirectLightOptions direct_light;
  RadiosityOptions radiosity;
  SolveMethod method = SolveMethod::sample;
  SampleSettings sample;
  // report
  std::vector<std::string> report_surfaces;  // empty: every surface
  std::vector<FileLoc> report_surface_locs;
  // the inverse problem
  std::optional<LuminaireSearch> search;  // luminaires.mounting_surface and its companions
  std::vector<LuminaireGroup> groups;     // luminaires.groups (then search is empty)
  std::vector<GoalSetting> goals;
  std::vector<CalcGridSetting> grids;     // calculation grids goals can name
  // scenarios: the layout's other lighting states (optimizer/scenario_spec.h), each
  // judged on the layout found and verified on its verification; targets maintained.
  std::vector<ScenarioSpec> scenarios;
  // Targets are maintained values; the search and the verification work on initial
  // values = target / maintenance_factor (lux metrics; U0 is a ratio and unchanged).
  double maintenance_factor = 1.0;
  FileLoc maintenance_loc;
  SearchConstraints constraints;
  Objective objective = Objective::min_power;
  SearchOptions optimizer;              // optimizer: NLopt names (e.g. GN_CRS2_LM, LN_SBPLX) or "none"; threads set at run time
  VerificationSettings verification;
  OutputSettings output;
  EnergySettings energy;
  std::optional<SweepSetting> sweep;
  // Not from the file: every triangle takes default_reflectance, whatever its MTL Kd
  // (`ilp inspect MESH`, where reflectances do not matter).
  bool ignore_material_kd = false;
  // A room of a building job: only these surfaces of the mesh (with the surfaces of the
  // rooms it is coupled to), every other left out (load_job_scene). Empty: all of them.
  std::vector<SurfacePattern> keep_surfaces;
  // rooms: a building job (docs/building.md): each room a single-room job of its own,
  // its keys read over the building's shared ones. Empty: a single-room job.
  std::vector<RoomSetting> rooms;
};

// One room of a building job (rooms[i]): its name (its output folder rooms/<name>), what
// it is used for, and the single-room job it runs as: the building's shared keys (scene,
// solver, optimizer, verification, output, report; luminaires.products as the catalogue;
// maintenance_factor, energy and objective as defaults) with the room's own keys read
// over them (luminaires, grids, goals, constraints, maintenance_factor, energy,
// objective, surfaces, coupled_with).
struct RoomSetting {
  std::string name;
  std::string use;                       // `use:`, else the first goal preset's key, else ""
  FileLoc loc;                           // the room's entry
  std::vector<std::string> coupled_with;  // rooms whose surfaces join this room's scene
  JobConfig job;
};

// Sets the goal parameter `key` ("goals.NAME.average_lux", ".min_lux", ".max_lux" or
// ".uniformity") to value, checked as the file would be. Throws ConfigError naming
// the key when no goal has that name and metric or the value breaks the rule.
void set_goal_parameter(JobConfig& job, const std::string& key, double value);

// Index of the grid with this name in job.grids, or -1.
int find_grid(const JobConfig& job, const std::string& name);

// The job as group g of job.groups alone: its search, its products, no groups (what
// the single-group stages are given for each group).
JobConfig group_job(const JobConfig& job, std::size_t g);

// Characters a room's name may hold (it names a folder): letters, digits, '_', '-', '.'
// (not "." or "..").
bool valid_room_name(const std::string& name);

// Reads and validates a job file. Throws ConfigError "file:line:col: key = value: rule".
JobConfig load_job_config(const std::string& path);

}  // namespace ilp
