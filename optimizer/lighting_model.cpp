#include "optimizer/lighting_model.h"

#include "core/base/setting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "core/base/error.h"
#include "optimizer/area_points.h"

namespace ilp {

double wall_facing_deg(const Eigen::Vector2d& facing) {
  return std::atan2(facing.y(), facing.x()) * 180.0 / std::numbers::pi;
}

int find_goal_area(const LightingModel& model, const std::string& name, AreaKind kind) {
  for (std::size_t a = 0; a < model.areas.size(); ++a)
    if (model.areas[a].name == name && model.areas[a].kind == kind) return static_cast<int>(a);
  return -1;
}

namespace {

CandidateGridOptions grid_options(const CandidateSpec& search, const Eigen::AlignedBox2d& zone) {
  return {.spacing_m = search.spacing_m,
          .half_footprint_m = search.type.half_footprint_m(search.rotation_deg, search.tilt_deg),
          .wall_distance_m = search.wall_distance_m,
          .module_m = search.ceiling_module_m,
          .mount_offset_m = search.mount_offset_m,
          .zone_m = zone};
}

// What to set where a height is measured from a floor the job does not name.
std::string floor_hint() {
  return setting_name(Setting::floor_surface) + " (or set " + setting_name(Setting::grid_over_surface) + " to the floor)";
}

// Suspended luminaires: a plane over the zone at the height above the floor, below
// the scene's top.
CandidateGrid suspension_grid(const Scene& scene, const CandidateSpec& search, const Eigen::AlignedBox2d& zone,
                              std::optional<double> floor_z_m) {
  const std::string key = setting_name(Setting::suspended_height);
  if (!floor_z_m)
    throw ConfigError(located(search.suspended_loc, key + ": no floor to measure from: name " + floor_hint()));
  if (zone.isEmpty())
    throw ConfigError(located(search.suspended_loc,
                              key + ": no zone to hang over: give " + setting_name(Setting::zone) + " or goals"));
  const double z = *floor_z_m + *search.suspended_height_m;
  if (!(z < scene.bounds_m.max().z()))
    throw ConfigError(located(search.suspended_loc, (std::ostringstream() << key << " = " << *search.suspended_height_m
                                                      << ": at z = " << z << " m, at or above the top of the scene (z = "
                                                      << scene.bounds_m.max().z() << " m, the ceiling)").str()));
  try {
    return CandidateGrid(zone, z, grid_options(search, Eigen::AlignedBox2d()));
  } catch (const std::exception& e) {
    throw ConfigError(located(search.suspended_loc, key + ": " + e.what()));
  }
}

// Wall-mounted luminaires: a line along the wall's faces facing into the room, at the
// height above the floor, below the top of the scene.
CandidateGrid wall_grid(const Scene& scene, int surface, const CandidateSpec& search, const Eigen::AlignedBox2d& zone,
                        std::optional<double> floor_z_m) {
  const WallMountSpec& wall = *search.wall;
  const std::string key = setting_name(Setting::wall_height);
  if (!floor_z_m)
    throw ConfigError(located(wall.height_loc, key + ": no floor to measure from: name " + floor_hint()));
  const double z = *floor_z_m + wall.height_m;
  if (!(z < scene.bounds_m.max().z()))
    throw ConfigError(located(wall.height_loc, (std::ostringstream() << key << " = " << wall.height_m << ": at z = " << z
                                                 << " m, at or above the top of the scene (z = "
                                                 << scene.bounds_m.max().z() << " m, the ceiling)").str()));
  try {
    return CandidateGrid(scene, surface, wall.facing, z, grid_options(search, zone));
  } catch (const std::out_of_range& e) {
    throw ConfigError(located(wall.height_loc, key + " = " + (std::ostringstream() << wall.height_m).str() + ": " + e.what()));
  } catch (const std::invalid_argument& e) {
    if (search.zone_m && std::string_view(e.what()).find("zone") != std::string_view::npos)
      throw ConfigError(located(search.zone_loc, setting_name(Setting::zone) + ": " + e.what()));
    if (std::string_view(e.what()).find("facing must be") != std::string_view::npos)
      throw ConfigError(located(wall.facing_loc, setting_name(Setting::wall_facing) + ": " + e.what()));
    throw ConfigError(located(search.mounting_loc, setting_name(Setting::wall_surface) + ": " + e.what()));
  } catch (const std::length_error& e) {
    const FileLoc& at = search.spacing_loc.file.empty() ? search.mounting_loc : search.spacing_loc;
    throw ConfigError(located(at, setting_name(Setting::candidate_spacing) + ": " + e.what()));
  }
}

CandidateGrid make_grid(const Scene& scene, const CandidateSpec& search, const Eigen::AlignedBox2d& zone,
                        std::optional<double> floor_z_m) {
  if (search.suspended_height_m) return suspension_grid(scene, search, zone, floor_z_m);
  if (search.wall) {
    const int surface = scene.find_surface(search.mounting_surface);
    if (surface < 0)
      throw ConfigError(located(search.mounting_loc, setting_name(Setting::wall_surface) + ": unknown surface '" +
                                                         search.mounting_surface + "'"));
    return wall_grid(scene, surface, search, zone, floor_z_m);
  }
  const int surface = scene.find_surface(search.mounting_surface);
  if (surface < 0)
    throw ConfigError(located(search.mounting_loc, setting_name(Setting::mounting_surface) + ": unknown surface '" +
                                                       search.mounting_surface + "'"));
  try {
    return CandidateGrid(scene, surface, grid_options(search, zone));
  } catch (const std::invalid_argument& e) {
    if (search.zone_m && std::string_view(e.what()).find("zone") != std::string_view::npos)
      throw ConfigError(located(search.zone_loc, setting_name(Setting::zone) + ": " + e.what()));
    throw ConfigError(located(search.mounting_loc, setting_name(Setting::mounting_surface) + ": " + e.what()));
  } catch (const std::length_error& e) {
    const FileLoc& at = search.spacing_loc.file.empty() ? search.mounting_loc : search.spacing_loc;
    throw ConfigError(located(at, setting_name(Setting::candidate_spacing) + ": " + e.what()));
  } catch (const std::out_of_range& e) {
    const FileLoc& at = search.offset_loc.file.empty() ? search.mounting_loc : search.offset_loc;
    throw ConfigError(located(at, setting_name(Setting::mount_offset) + ": " + e.what()));
  }
}

// The finished floor: the named surface (or the first grid's over_surface when its
// patches facing up lie at the scene's lowest level: a grid over a table top is a task
// area, not the floor), the area-weighted height of its patches facing up.
std::optional<double> floor_height_m(const Scene& scene, const ModelSpec& spec, std::string& surface_name) {
  surface_name = spec.candidates.floor_surface;
  const bool named = !surface_name.empty();
  if (!named)
    for (const CalcGridSetting& g : spec.grids)
      if (!g.over_surface.empty()) {
        surface_name = g.over_surface;
        break;
      }
  const int surface = surface_name.empty() ? -1 : scene.find_surface(surface_name);
  if (surface < 0) {
    if (!spec.candidates.floor_surface.empty())
      throw ConfigError(located(spec.candidates.floor_loc, setting_name(Setting::floor_surface) + ": unknown surface '" + surface_name + "'"));
    surface_name.clear();
    return std::nullopt;
  }
  double area = 0.0, z = 0.0;
  for (const Patch& p : scene.patches)
    if (p.surface == surface && p.normal.z() > 0.9) {
      area += p.area_m2;
      z += p.area_m2 * p.centroid_m.z();
    }
  if (!(area > 0.0)) {
    if (!spec.candidates.floor_surface.empty())
      throw ConfigError(located(spec.candidates.floor_loc,
                                setting_name(Setting::floor_surface) + ": '" + surface_name + "' has no patch facing up"));
    surface_name.clear();
    return std::nullopt;
  }
  if (!named && z / area > scene.bounds_m.min().z() + kFloorLevelTolerance_m) {
    surface_name.clear();
    return std::nullopt;
  }
  return z / area;
}

}  // namespace

namespace {

// The fixed sources' flux that counts as placed luminaires (emitting surfaces do not),
// then one virtual candidate per grid position, after the job scene's sources.
void add_candidates(LightingModel& model, const Scene& job_scene, const CandidateSpec& spec) {
  const std::vector<LightSource> fixed = scene_light_sources(job_scene);
  const Eigen::VectorXd fixed_flux = source_flux_lm(job_scene, fixed);
  for (std::size_t l = 0; l < fixed.size(); ++l)
    if (job_scene.surfaces[static_cast<std::size_t>(fixed[l].surface)].is_luminaire())
      model.fixed_flux_lm += fixed_flux[static_cast<Eigen::Index>(l)];
  for (std::size_t c = 0; c < model.grid.size(); ++c) {
    const int surface = add_luminaire(model.scene, std::string("candidate ").append(std::to_string(c + 1)), spec.type,
                                      {model.grid.positions_m()[c], spec.rotation_deg, spec.tilt_deg}, 0.0);
    model.scene.surfaces[static_cast<std::size_t>(surface)].is_virtual = true;
  }
}

// Every grid of the spec, in its order, with a log line each.
void lay_grids(LightingModel& model, const Scene& job_scene, const ModelSpec& spec, const RayCaster* caster) {
  if (spec.grids.empty()) return;
  std::unique_ptr<RayCaster> own;
  if (!caster) {
    own = std::make_unique<RayCaster>(job_scene, spec.threads);
    caster = own.get();
  }
  for (const CalcGridSetting& setting : spec.grids) {
    model.grids.push_back(make_calc_grid(job_scene, *caster, setting));
    const CalcGrid& grid = model.grids.back();
    std::ostringstream line;
    line << std::fixed << std::setprecision(3) << "grid '" << grid.name << "': " << grid.points.size() << " points ("
         << grid.cells_u << " x " << grid.cells_v << " cells of " << grid.cell_u_m << " x " << grid.cell_v_m
         << " m, spacing " << grid.spacing_m << " m" << (setting.spacing_m ? "" : " from EN 12464-1") << "), "
         << grid.inside_solid << " inside solid objects dropped, " << grid.outside_outline
         << " outside the outline less its band";
    model.log.push_back(line.str());
  }
}

// The patches of an area's surfaces that face as asked (none for a grid area).
std::vector<int> area_patches(const Scene& job_scene, const GoalAreaSpec& area) {
  if (area.grid >= 0 || area.kind != AreaKind::illuminance) return {};
  std::vector<int> patches = job_scene.patches_of(area.surfaces);
  if (area.facing != GoalFacing::any) {
    constexpr double kVerticalCos = 0.9;  // within about 25 degrees of straight up or down
    std::erase_if(patches, [&](int p) {
      const double z = job_scene.patches[static_cast<std::size_t>(p)].normal.z();
      return area.facing == GoalFacing::up ? z < kVerticalCos : z > -kVerticalCos;
    });
  }
  return patches;
}

// A grid area's rows (its points, equal weights) or a surface area's (its patches'
// rows, weighted by area).
GoalArea make_area(const LightingModel& model, const Scene& job_scene, const GoalAreaSpec& spec,
                   const std::vector<int>& patches) {
  GoalArea area;
  area.name = spec.name;
  area.surfaces = spec.surfaces;
  area.grid = spec.grid;
  area.kind = spec.kind;
  if (spec.kind != AreaKind::illuminance) return area;  // rows laid by lay_area_points
  if (area.grid >= 0) {
    const CalcGrid& grid = model.grids[static_cast<std::size_t>(area.grid)];
    const Eigen::Index first = model.grid_first_row[static_cast<std::size_t>(area.grid)];
    for (std::size_t q = 0; q < grid.points.size(); ++q) area.rows.push_back(first + static_cast<Eigen::Index>(q));
    area.area_weights = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(grid.points.size()),
                                                  1.0 / static_cast<double>(grid.points.size()));
    area.area_m2 = grid.area_m2;
    return area;
  }
  area.area_weights.resize(static_cast<Eigen::Index>(patches.size()));
  for (int p : patches) {
    const auto row = std::lower_bound(model.goal_patches.begin(), model.goal_patches.end(), p) - model.goal_patches.begin();
    area.area_weights[static_cast<Eigen::Index>(area.rows.size())] = job_scene.patches[static_cast<std::size_t>(p)].area_m2;
    area.rows.push_back(row);
    area.area_m2 += job_scene.patches[static_cast<std::size_t>(p)].area_m2;
  }
  if (!(area.area_m2 > 0.0))
    throw std::invalid_argument("goal '" + area.name + "' has no area (no patch of its surfaces faces as asked)");
  area.area_weights /= area.area_m2;
  return area;
}

// The goals' outline in plan (x, y): grid points with their cells, goal patches with
// their vertices.
Eigen::AlignedBox2d goals_outline_m(const LightingModel& model, const Scene& job_scene) {
  Eigen::AlignedBox2d box;
  for (int p : model.goal_patches)
    for (const Eigen::Vector3d& v : job_scene.patches[static_cast<std::size_t>(p)].vertices_m) box.extend(v.head<2>());
  for (const CalcGrid& grid : model.grids) {
    const Eigen::Vector3d du = 0.5 * grid.cell_u_m * grid.u_axis, dv = 0.5 * grid.cell_v_m * grid.v_axis;
    for (const ReceiverPoint& q : grid.points)
      for (const double su : {-1.0, 1.0})
        for (const double sv : {-1.0, 1.0}) box.extend((q.position_m + su * du + sv * dv).head<2>());
  }
  return box;
}

// The mounting zone: the spec's rectangle, or the goals' outline widened by the margin.
Eigen::AlignedBox2d mounting_zone_m(const LightingModel& model, const Scene& job_scene, const CandidateSpec& spec) {
  if (spec.zone_m) return Eigen::AlignedBox2d(spec.zone_m->first, spec.zone_m->second);
  if (!spec.zone_margin_m) return {};
  Eigen::AlignedBox2d box = goals_outline_m(model, job_scene);
  if (box.isEmpty()) return box;
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(*spec.zone_margin_m);
  return Eigen::AlignedBox2d(box.min() - margin, box.max() + margin);
}

void log_candidates(LightingModel& model, const CandidateSpec& spec) {
  std::ostringstream grid;
  std::ostringstream where;
  if (spec.suspended_height_m)
    where << "a plane " << *spec.suspended_height_m << " m above the floor '" << model.floor_surface << "'";
  else if (spec.wall)
    where << "wall '" << spec.mounting_surface << "' (facing " << (spec.wall->facing.sum() > 0.0 ? "+" : "-")
          << (std::abs(spec.wall->facing.x()) > 0.5 ? "x" : "y") << ") " << spec.wall->height_m
          << " m above the floor '" << model.floor_surface << "'";
  else
    where << "'" << spec.mounting_surface << "'";
  grid << std::fixed << std::setprecision(3) << "candidates: " << model.grid.size() << " positions on "
       << where.str() << " (" << model.grid.nodes_x() << " x " << model.grid.nodes_y() << " grid, "
       << model.grid.spacing_m().x() << " x " << model.grid.spacing_m().y() << " m apart, centres in x ["
       << model.grid.lower_m().x() << ", " << model.grid.upper_m().x() << "] y [" << model.grid.lower_m().y() << ", "
       << model.grid.upper_m().y() << "] m, faces at z = " << model.grid.positions_m().front().z() << " m)";
  model.log.push_back(grid.str());
  if (!model.zone_m.isEmpty()) {
    std::ostringstream zone;
    zone << std::fixed << std::setprecision(3) << "mounting zone: x [" << model.zone_m.min().x() << ", "
         << model.zone_m.max().x() << "] y [" << model.zone_m.min().y() << ", " << model.zone_m.max().y() << "] m ("
         << (spec.zone_m ? setting_name(Setting::zone) : "the goals' outline + " + std::to_string(*spec.zone_margin_m).substr(0, 4) + " m") << ")";
    model.log.push_back(zone.str());
  }
  if (model.grid.ignored_patches() > 0)
    model.log.push_back("candidates: " + std::to_string(model.grid.ignored_patches()) + " patches of '" +
                        spec.mounting_surface + (spec.wall ? "' do not face the way given and hold no luminaire"
                                                                   : "' do not face down and hold no luminaire"));
}

// The rows of the cylindrical and glare areas, after every grid's points: a grid's
// points at eye height as cylinders, observers' eyes (model.observers, observer_rows).
void lay_area_points(LightingModel& model, const Scene& job_scene, const ModelSpec& spec, const RayCaster* caster) {
  std::unique_ptr<RayCaster> own;
  for (std::size_t a = 0; a < spec.areas.size(); ++a) {
    const GoalAreaSpec& s = spec.areas[a];
    GoalArea& area = model.areas[a];
    const auto first = static_cast<Eigen::Index>(model.goal_patches.size() + model.goal_points.size());
    if (s.kind == AreaKind::cylindrical) {
      if (!model.floor_z_m)
        throw ConfigError(located(s.loc, setting_name(Setting::goal_cylindrical_lux, s.name) +
                                         ": no floor to measure the eye height from: name " + floor_hint()));
      const CalcGrid& grid = model.grids.at(static_cast<std::size_t>(s.grid));
      const std::vector<ReceiverPoint> points = cylinder_receivers(grid, *model.floor_z_m + s.eye_height_m);
      model.goal_points.insert(model.goal_points.end(), points.begin(), points.end());
      const auto n = static_cast<double>(grid.points.size());
      area.area_weights.resize(static_cast<Eigen::Index>(points.size()));
      for (std::size_t r = 0; r < points.size(); ++r) {
        area.rows.push_back(first + static_cast<Eigen::Index>(r));
        const bool up = r % (kCylinderPlanes + 1) == kCylinderPlanes;
        area.area_weights[static_cast<Eigen::Index>(r)] = up ? 0.0 : 1.0 / (kCylinderPlanes * n);
      }
      area.area_m2 = grid.area_m2;
    } else if (s.kind == AreaKind::glare) {
      if (!caster) {
        own = std::make_unique<RayCaster>(job_scene, spec.threads);
        caster = own.get();
      }
      for (const UgrObserver& o : area_observers(job_scene, *caster, s, model.floor_z_m, model.floor_surface)) {
        area.observers.push_back(static_cast<int>(model.observers.size()));
        area.rows.push_back(static_cast<Eigen::Index>(model.goal_patches.size() + model.goal_points.size()));
        model.observers.push_back(o);
        model.observer_rows.push_back(area.rows.back());
        model.goal_points.push_back(eye_receiver(o));
      }
      area.area_weights = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(area.rows.size()),
                                                    1.0 / static_cast<double>(area.rows.size()));
    }
  }
}

}  // namespace

LightingModel lighting_model_geometry(const Scene& job_scene, const ModelSpec& spec, const RayCaster* caster,
                                      const BeforeGrids& before_grids) {
  if (spec.areas.empty()) throw std::invalid_argument("the job has no goals");
  for (const GoalAreaSpec& area : spec.areas)
    if (area.grid >= static_cast<int>(spec.grids.size()))
      throw std::invalid_argument("goal '" + area.name + "': no such grid");
  LightingModel model;
  model.scene = job_scene;
  // Goal rows: the areas' patches (ascending, each once), then every grid's points.
  std::vector<std::vector<int>> patches;
  for (const GoalAreaSpec& area : spec.areas) {
    patches.push_back(area_patches(job_scene, area));
    model.goal_patches.insert(model.goal_patches.end(), patches.back().begin(), patches.back().end());
  }
  std::sort(model.goal_patches.begin(), model.goal_patches.end());
  model.goal_patches.erase(std::unique(model.goal_patches.begin(), model.goal_patches.end()), model.goal_patches.end());
  if (before_grids) {
    std::vector<CalcGridSize> sizes;
    for (const CalcGridSetting& setting : spec.grids) sizes.push_back(calc_grid_size(job_scene, setting));
    before_grids(model, sizes);
  }
  lay_grids(model, job_scene, spec, caster);
  for (const CalcGrid& grid : model.grids) {
    model.grid_first_row.push_back(static_cast<Eigen::Index>(model.goal_patches.size() + model.goal_points.size()));
    model.goal_points.insert(model.goal_points.end(), grid.points.begin(), grid.points.end());
  }
  for (std::size_t a = 0; a < spec.areas.size(); ++a) model.areas.push_back(make_area(model, job_scene, spec.areas[a], patches[a]));
  // The candidates where the goals are: patches are added after the goal rows' (the
  // job scene's patches keep their indices).
  model.zone_m = mounting_zone_m(model, job_scene, spec.candidates);
  model.floor_z_m = floor_height_m(job_scene, spec, model.floor_surface);
  lay_area_points(model, job_scene, spec, caster);
  model.grid = make_grid(job_scene, spec.candidates, model.zone_m, model.floor_z_m);
  if (spec.candidates.wall && !model.zone_m.isEmpty()) {
    // On a wall the zone bounds the line along it only: across, it is the line itself.
    const int across = std::abs(spec.candidates.wall->facing.x()) > 0.5 ? 0 : 1;
    model.zone_m.min()[across] = model.zone_m.max()[across] = model.grid.lower_m()[across];
  }
  add_candidates(model, job_scene, spec.candidates);
  compute_glare_terms(model, job_scene, spec.candidates);
  log_candidates(model, spec.candidates);
  return model;
}

void compute_lighting_operator(LightingModel& model, const Scene& job_scene, const RayCaster& caster,
                               const ModelSpec& spec, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<LightSource> fixed = scene_light_sources(job_scene);
  const Eigen::VectorXd fixed_flux = source_flux_lm(job_scene, fixed);
  const std::vector<LightSource> sources = scene_light_sources(model.scene);
  SampleOperatorOptions options = spec.operator_options;
  GoalRows goal_rows =
      compute_goal_rows(model.scene, caster, model.goal_patches, model.goal_points, sources, options, progress);
  // A sample size chosen for a target error is judged on every candidate at the same flux.
  Eigen::VectorXd probe_flux = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(sources.size()));
  probe_flux.head(fixed_flux.size()) = fixed_flux;
  probe_flux.tail(static_cast<Eigen::Index>(model.grid.size())).setConstant(spec.probe_flux_lm);
  const SampleSizeChoice choice = choose_sample_size(spec.sample_size, model.scene, caster, goal_rows, probe_flux, options, progress);
  if (!choice.log.empty()) model.log.push_back(choice.log);
  options.sample_size = choice.sample_size;
  const ReflectedBlend blend = candidate_reflected_blend(model.grid, fixed.size(), spec.reflected_stride);
  const SampleOperator op =
      build_blended_sample_operator(model.scene, caster, std::move(goal_rows), options, blend, progress);

  const Eigen::Index nf = static_cast<Eigen::Index>(fixed.size()), nc = static_cast<Eigen::Index>(model.grid.size());
  model.fixed_lux = op.total_lux_per_lm.leftCols(nf) * fixed_flux;
  model.fixed_direct_lux = op.direct_lux_per_lm.leftCols(nf) * fixed_flux;
  model.candidate_lux_per_lm = op.total_lux_per_lm.rightCols(nc);
  model.candidate_direct_lux_per_lm = op.direct_lux_per_lm.rightCols(nc);
  model.sample_size = op.stats.direct_only ? 0 : static_cast<int>(op.stats.sample_patches);
  model.stats = op.stats;

  model.log.insert(model.log.end(), op.log.begin(), op.log.end());
  model.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace ilp
