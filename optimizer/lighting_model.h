// What the layout search evaluates: the illuminance at the goal patches as a linear
// function of candidate luminaire fluxes, from one sample-based operator whose light
// sources are the job's fixed sources (placed luminaires, emitting surfaces) and one
// candidate luminaire per grid position on the mounting surface.
//
// Candidates are virtual: they are added to the scene after its BVH is built, so
// they neither block light nor shade one another; each real luminaire is later
// placed alone (the verification measures the difference).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/glare/ugr.h"
#include "core/grid/calc_grid.h"
#include "core/base/error.h"
#include "core/light/luminaire.h"
#include "core/operator/sample_size.h"
#include "core/base/progress.h"
#include "core/transport/ray_caster.h"
#include "core/operator/sample_operator.h"
#include "core/scene/scene.h"
#include "optimizer/candidate_grid.h"
#include "optimizer/goal_spec.h"

namespace ilp {

// A surface is the room's floor, unless the job names one, when its patches facing up lie
// within this of the scene's lowest point: a grid over a table top is a task area, not
// the floor (heights above the floor, the power density's area).
inline constexpr double kFloorLevelTolerance_m = 0.2;

class KeyWriter;  // core/base/key_hash.h

// Wall mounting: the mounting surface is a wall; luminaires hang on its faces that face
// `facing` (into the room: +x, -x, +y or -y), their openings' centres height_m above
// the floor, each turned so that its C0 points along `facing` (so a tilt aims it into
// the room; the rotation is added to that).
struct WallMountSpec {
  Eigen::Vector2d facing = Eigen::Vector2d::UnitX();
  double height_m = 2.5;
  FileLoc height_loc, facing_loc;
};

// The operator cache's key: every field but the FileLocs.
void hash_fields(KeyWriter& k, const WallMountSpec& w);

// The wall's facing as a rotation about z, degrees (+x: 0, +y: 90, -x: 180, -y: -90).
double wall_facing_deg(const Eigen::Vector2d& facing);

// Where the candidates go: one luminaire type at one rotation on a mounting surface.
// The locations point a refusal (a surface that holds no luminaire) at the job's key.
struct CandidateSpec {
  std::string mounting_surface;
  LuminaireType type = LuminaireType::square_lambertian(0.6);
  double rotation_deg = 0.0;
  double tilt_deg = 0.0;           // aim (core/light/luminaire.h)
  double spacing_m = 0.5;          // at most this between candidates
  double wall_distance_m = 0.0;    // an outline keeps at least this from the surface's edges
  double ceiling_module_m = 0.0;   // > 0: centres at a ceiling module's cell centres
  double mount_offset_m = 0.02;    // the emitting face this far below the surface
  // The mounting zone, where centres may lie: this rectangle (lower and upper x, y
  // corners, m) when given, else the goals' outline in plan widened by
  // zone_margin_m, else (neither) the whole mounting surface.
  std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> zone_m;
  std::optional<double> zone_margin_m = 0.5;
  // Suspended: the emitting faces this far above the floor, on a plane over the zone
  // (no mounting surface). The floor: floor_surface's patches facing up, or when it
  // is empty the first grid's surface if it lies at the scene's lowest level (within
  // kFloorLevelTolerance_m); heights are reported above it.
  std::optional<double> suspended_height_m;
  std::optional<WallMountSpec> wall;  // mounting_surface is a wall: luminaires on it at a height
  std::string floor_surface;
  FileLoc mounting_loc, spacing_loc, offset_loc, zone_loc, suspended_loc, floor_loc;
};

// The operator cache's key (core/base/key_hash.h; defined in model_spec_hash.cpp):
// every field but the FileLocs.
void hash_fields(KeyWriter& k, const CandidateSpec& c);

// An observer a job places for glare: where (x, y in the scene frame), the eye this far
// above the floor, looking along `view` (horizontal, need not be unit length).
struct ObserverSpec {
  Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();
  double eye_height_m = kSeatedEyeHeightM;
  Eigen::Vector2d view = Eigen::Vector2d::UnitX();
  FileLoc loc = {};  // for an observer outside the room or inside a solid
};

// The operator cache's key: every field but the FileLoc.
void hash_fields(KeyWriter& k, const ObserverSpec& o);

// Vertical receivers per point of a cylindrical area (their mean is Ez), at azimuths
// 360 / kCylinderPlanes apart, turned per point by a low-discrepancy offset so that the
// quadrature's error (at most -5.2 % / +2.6 % for one point source) averages out over a grid.
inline constexpr int kCylinderPlanes = 8;

// One named goal area to lay (optimizer/goal_spec.h, AreaKind): the patches of some
// surfaces (those facing as asked) or the points of one calculation grid; a grid's
// points at eye height as cylinders; or observers' eyes.
struct GoalAreaSpec {
  std::string name;
  std::vector<std::string> surfaces;
  GoalFacing facing = GoalFacing::any;
  int grid = -1;  // into ModelSpec::grids, or -1 for surfaces
  AreaKind kind = AreaKind::illuminance;
  // cylindrical: the grid's points this far above the floor; glare without observers:
  // the eye height of the standard's observers (1.2 m seated, 1.6 m standing).
  double eye_height_m = kSeatedEyeHeightM;
  // glare: the observers; empty: the standard's, at the middle of each wall of the
  // floor's plan box, kDefaultObserverWallOffsetM into the room, looking across it.
  std::vector<ObserverSpec> observers = {};
  FileLoc loc = {};  // the goal's, for an area that cannot be laid (no floor)
};
inline constexpr double kDefaultObserverWallOffsetM = 0.5;

// The operator cache's key: every field.
void hash_fields(KeyWriter& k, const GoalAreaSpec& a);

// Everything the lighting model is built from, besides the job's scene.
struct ModelSpec {
  CandidateSpec candidates;
  std::vector<GoalAreaSpec> areas;      // in the job's goal order, each name once
  std::vector<CalcGridSetting> grids;   // every grid of the job (named by goals or only reported)
  SampleOperatorOptions operator_options;  // sample_size chosen by sample_size
  SampleSizeRule sample_size;
  // The candidates' reflected light at every n-th node of their grid, blended between
  // (optimizer/candidate_grid.h, candidate_reflected_blend); 1: at every candidate.
  int reflected_stride = 2;
  double probe_flux_lm = 0.0;           // each candidate's flux when a target error chooses k (the range's top)
  int threads = 0;                      // for the grids' inside-solid test; 0: every core
};

// The operator cache's key: every field but threads (the same model for any thread
// count), probe_flux_lm only when sample_size.target_error is set (only then does the
// probe choose k). With the job's scene inputs (hash_scene_inputs, job/job_scene.h),
// what lighting_model_key digests.
void hash_fields(KeyWriter& k, const ModelSpec& m);

// The rows one named goal is measured over: the patches of its surfaces (weighted by
// area), or the points of its calculation grid (equal weights: each stands for one cell).
struct GoalArea {
  std::string name;
  AreaKind kind = AreaKind::illuminance;
  // cylindrical: each point's kCylinderPlanes vertical rows, then its row facing up;
  // area_weights 1 / (planes x points) on the vertical rows and 0 on the up rows, so
  // their dot product with the lux is Ez,m. glare: one eye row per observer.
  std::vector<int> observers;      // glare: into LightingModel::observers, one per row
  std::vector<std::string> surfaces;
  int grid = -1;                   // into LightingModel::grids, or -1 for surfaces
  std::vector<Eigen::Index> rows;  // goal rows: LightingModel::goal_patches, then goal_points
  Eigen::VectorXd area_weights;    // A_i / sum A (1 / #points on a grid), per row: the average is their dot product
  double area_m2 = 0.0;
};

struct LightingModel {
  Scene scene;  // the job's scene plus the candidates (virtual: not in the caster's BVH)
  CandidateGrid grid;
  Eigen::AlignedBox2d zone_m;  // the mounting zone (x, y) the candidates lie in; regular layouts are centred on it
  std::optional<double> floor_z_m;  // the finished floor's height (CandidateSpec::floor_surface), when known
  std::string floor_surface;        // its surface
  std::vector<int> goal_patches;                 // ascending, each once: goal rows 0 ... #patches - 1
  std::vector<ReceiverPoint> goal_points;        // the grids' points, grid after grid: the goal rows after the patches
  std::vector<CalcGrid> grids;                   // every grid of the job (named by goals or only reported), in job.grids order
  std::vector<Eigen::Index> grid_first_row;      // per grid: its first goal row
  std::vector<GoalArea> areas;                   // one per goal name and area kind, in the job's order
  // Glare: every glare area's observers (eyes at their height, horizontal lines of
  // sight), each with its eye's goal row, and per observer and candidate the glare term
  // L^2 omega / p^2 per lm^2 (core/glare/ugr.h), so a luminaire of flux phi blended from
  // candidates adds phi^2 x the blend of their terms; the fixed luminaires' terms at
  // their flux. The indirect illuminance at the eye row (T minus D) gives Lb = E_ind / pi.
  std::vector<UgrObserver> observers;
  std::vector<Eigen::Index> observer_rows;
  Eigen::MatrixXd candidate_glare_per_lm2;       // observers x candidates
  Eigen::VectorXd fixed_glare;                   // per observer
  // Goal rows: T's rows, patches then points (fixed_lux and the candidate columns have this many).
  Eigen::Index goal_rows() const { return static_cast<Eigen::Index>(goal_patches.size() + goal_points.size()); }
  Eigen::VectorXd fixed_lux;                     // from the fixed sources at their flux
  Eigen::VectorXd fixed_direct_lux;
  double fixed_flux_lm = 0.0;                    // placed luminaires (emitting surfaces are not counted)
  Eigen::MatrixXd candidate_lux_per_lm;          // goal patches x candidates: T's candidate columns
  Eigen::MatrixXd candidate_direct_lux_per_lm;
  int sample_size = 0;                           // k (0: direct light only)
  SampleOperatorStats stats;
  std::vector<std::string> log;                  // the operator's log and the grid's
  double build_seconds = 0.0;
};

// Index of the GoalArea with this name and kind, or -1.
int find_goal_area(const LightingModel& model, const std::string& name, AreaKind kind = AreaKind::illuminance);

// The cheap part of the model: the candidate grid, the scene with the candidates,
// the goal patches, the grids' points and the areas, fixed_flux_lm. Throws ConfigError
// pointing at the config for a mounting surface that cannot hold luminaires or a grid
// that cannot be laid (core/grid/calc_grid.h). `caster` (the job scene's) finds grid points
// inside solids; without it a temporary one is built when the spec has grids.
// `before_grids`, when given, is called after the candidates and goal patches are
// placed and before any grid is laid (every grid point costs rays), with the model so
// far (no grids, no areas) and each grid's size (calc_grid_size): it may throw to
// refuse a job whose grids it cannot afford.
using BeforeGrids = std::function<void(const LightingModel& partial, const std::vector<CalcGridSize>& grids)>;
LightingModel lighting_model_geometry(const Scene& job_scene, const ModelSpec& spec, const RayCaster* caster = nullptr,
                                      const BeforeGrids& before_grids = {});

// The expensive part, on a model from lighting_model_geometry: builds the operator
// and fills fixed_lux, the candidate columns, sample_size, stats, build_seconds and
// the log. `caster` is the job scene's (the candidates are not in it).
void compute_lighting_operator(LightingModel& model, const Scene& job_scene, const RayCaster& caster,
                               const ModelSpec& spec, const ProgressCallback& progress = {});

}  // namespace ilp
