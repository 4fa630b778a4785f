#include "optimizer/area_points.h"

#include "core/base/setting.h"
#include <cmath>
#include <iomanip>
#include <numbers>
#include <sstream>

#include "core/base/error.h"
#include "core/grid/calc_grid.h"

namespace ilp {
namespace {

std::string metres(const Eigen::Vector3d& p) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << "(" << p.x() << ", " << p.y() << ", " << p.z() << ") m";
  return out.str();
}

// Why an eye cannot be there ("" when it can): outside the scene's bounds, over no
// floor (a ray straight down escapes), or inside a solid object.
std::string eye_refusal(const Scene& scene, const RayCaster& caster, const Eigen::Vector3d& eye) {
  if (!scene.bounds_m.contains(eye)) return "the eye at " + metres(eye) + " is outside the scene";
  if (caster.first_hit(eye, -Eigen::Vector3d::UnitZ()).patch < 0 &&
      caster.first_hit(eye + Eigen::Vector3d(0.37e-3, 0.61e-3, 0.0), -Eigen::Vector3d::UnitZ()).patch < 0)
    return "the eye at " + metres(eye) + " has no floor under it (outside the room)";
  if (inside_solid(caster, eye)) return "the eye at " + metres(eye) + " is inside a solid object";
  return "";
}

// The plan box of a surface's patches facing up.
Eigen::AlignedBox2d floor_box(const Scene& scene, const std::string& surface) {
  Eigen::AlignedBox2d box;
  const int s = scene.find_surface(surface);
  for (const Patch& p : scene.patches)
    if (p.surface == s && p.normal.z() > 0.9)
      for (const Eigen::Vector3d& v : p.vertices_m) box.extend(v.head<2>());
  return box;
}

}  // namespace

std::vector<ReceiverPoint> cylinder_receivers(const CalcGrid& grid, double z_m) {
  std::vector<ReceiverPoint> out;
  const double step = 2.0 * std::numbers::pi / kCylinderPlanes;
  for (std::size_t q = 0; q < grid.points.size(); ++q) {
    const Eigen::Vector3d p(grid.points[q].position_m.x(), grid.points[q].position_m.y(), z_m);
    // The golden ratio's fractional parts: offsets spread evenly over a plane's step.
    const double offset = step * std::fmod(0.6180339887498949 * static_cast<double>(q), 1.0);
    for (int k = 0; k < kCylinderPlanes; ++k) {
      const double a = offset + k * step;
      out.push_back({p, Eigen::Vector3d(std::cos(a), std::sin(a), 0.0)});
    }
    out.push_back({p, Eigen::Vector3d::UnitZ()});
  }
  return out;
}

ReceiverPoint eye_receiver(const UgrObserver& o) {
  const Eigen::Vector3d view(o.view_direction.x(), o.view_direction.y(), 0.0);
  return {o.position_m, view.normalized()};
}

std::vector<UgrObserver> area_observers(const Scene& scene, const RayCaster& caster, const GoalAreaSpec& area,
                                        std::optional<double> floor_z_m, const std::string& floor_surface) {
  const std::string key = setting_name(Setting::goal_ugr_max, area.name);
  if (!floor_z_m)
    throw ConfigError(located(area.loc, key + ": no floor to put the observers' eyes above: name " +
                                            setting_name(Setting::floor_surface) + " (or set " +
                                            setting_name(Setting::grid_over_surface) + " to the floor)"));
  std::vector<UgrObserver> out;
  if (area.observers.empty()) {
    const Eigen::AlignedBox2d box = floor_box(scene, floor_surface);
    out = default_ugr_observers(box.min(), box.max(), *floor_z_m, area.eye_height_m, kDefaultObserverWallOffsetM);
    for (const UgrObserver& o : out)
      if (const std::string why = eye_refusal(scene, caster, o.position_m); !why.empty())
        throw ConfigError(located(area.loc, key + ": the standard's observer at the middle of a wall of '" +
                                                floor_surface + "': " + why + "; give observers"));
    return out;
  }
  for (std::size_t i = 0; i < area.observers.size(); ++i) {
    const ObserverSpec& s = area.observers[i];
    UgrObserver o{{s.xy_m.x(), s.xy_m.y(), *floor_z_m + s.eye_height_m}, {s.view.x(), s.view.y(), 0.0}};
    if (const std::string why = eye_refusal(scene, caster, o.position_m); !why.empty())
      throw ConfigError(located(s.loc, setting_name(Setting::goal_observers, area.name) + "[" + std::to_string(i) + "]: " + why));
    out.push_back(o);
  }
  return out;
}

void compute_glare_terms(LightingModel& model, const Scene& job_scene, const CandidateSpec& spec) {
  const auto n_obs = static_cast<Eigen::Index>(model.observers.size());
  const auto n_cand = static_cast<Eigen::Index>(model.grid.size());
  model.candidate_glare_per_lm2.setZero(n_obs, n_cand);
  model.fixed_glare.setZero(n_obs);
  for (Eigen::Index o = 0; o < n_obs; ++o) {
    const UgrObserver& eye = model.observers[static_cast<std::size_t>(o)];
    for (Eigen::Index c = 0; c < n_cand; ++c) {
      const LuminairePlacement at{model.grid.positions_m()[static_cast<std::size_t>(c)], spec.rotation_deg, spec.tilt_deg};
      model.candidate_glare_per_lm2(o, c) = glare_term_per_lm2(glare_source(spec.type, at, 1.0), eye);
    }
    for (const SceneLuminaire& l : job_scene.luminaires)
      model.fixed_glare[o] += glare_term(glare_source(l.type, l.placement, l.flux_lm), eye);
  }
}

}  // namespace ilp
