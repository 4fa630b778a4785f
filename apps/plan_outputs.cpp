#include "apps/plan_outputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

#include "output/png_render.h"
#include "job/config.h"

namespace ilp::cli {
namespace {

constexpr double kDefaultCut_m = 0.8;         // EN 12464-1's work plane
constexpr double kWallCutBelowLuminaires_m = 0.1;

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

PlanLuminaire plan_luminaire(const std::string& id, const std::string& product, const LuminaireType& type,
                             const LuminairePlacement& at, double flux_lm, double floor_z_m) {
  PlanLuminaire l;
  l.id = id;
  l.product = product;
  l.position_m = at.position_m;
  l.size_m = type.length_m;
  l.flux_lm = flux_lm;
  for (const Eigen::Vector3d& v : luminaire_outline_m(type, at)) l.outline_m.push_back(v.head<2>());
  l.rotation_deg = at.rotation_deg;
  l.tilt_deg = at.tilt_deg;
  l.above_floor_m = at.position_m.z() - floor_z_m;
  return l;
}

// The layout found (L1, L2, ...), then the luminaires placed in the config.
std::vector<PlanLuminaire> plan_luminaires(const PlanInputs& in, double floor_z_m) {
  std::vector<PlanLuminaire> out;
  for (std::size_t j = 0; j < in.outcome.luminaires.size(); ++j) {
    const SearchLuminaire& s = outcome_plan(in.prepared, in.outcome, j).search.luminaire;
    out.push_back(plan_luminaire(outcome_luminaire_name(in.outcome, j), s.product, s.type,
                                 {in.outcome.luminaires[j].position_m, s.rotation_deg, s.tilt_deg},
                                 in.outcome.luminaires[j].flux_lm, floor_z_m));
  }
  const Scene& scene = in.prepared.loaded.scene;
  for (const SceneLuminaire& l : scene.luminaires)
    out.push_back(plan_luminaire(scene.surfaces[static_cast<std::size_t>(l.surface)].name, l.type.name, l.type,
                                 l.placement, l.flux_lm, floor_z_m));
  return out;
}

// Job, products with count, layout, power, basis.
std::vector<std::string> title_block(const PlanInputs& in) {
  const ResultRecord& r = in.record;
  std::vector<std::string> lines{std::filesystem::path(in.job.path).stem().string()};
  for (const BillLine& b : r.bill_of_materials)
    lines.push_back(std::to_string(b.count) + " x " + b.product + ", " + fixed(b.unit_power_w, 1) + " W at " +
                    fixed(100.0 * b.output_fraction, 0) + " %");
  if (!r.arrangement.empty()) {
    std::string spacing;
    if (r.spacing_x_m > 0.0 && r.spacing_y_m > 0.0)
      spacing = ", spacing " + metres_2(r.spacing_x_m) + " x " + metres_2(r.spacing_y_m) + " m";
    else if (r.spacing_x_m > 0.0 || r.spacing_y_m > 0.0)
      spacing = ", spacing " + metres_2(std::max(r.spacing_x_m, r.spacing_y_m)) + " m";
    lines.push_back(r.arrangement + spacing);
  } else if (!r.layout_family.empty()) {
    lines.push_back("layout: " + r.layout_family);
  }
  if (r.no_layout.empty())
    lines.push_back("total " + fixed(r.power_w, 1) + " W, " + fixed(r.power_density_w_per_m2, 2) + " W/m², " +
                    (r.verification != "none" ? "verified (" + r.verification + ")" : "predicted"));
  return lines;
}

}  // namespace

double plan_floor_z_m(const Scene& scene, const std::optional<double>& floor_z_m) {
  if (floor_z_m) return *floor_z_m;
  return scene.bounds_m.isEmpty() ? 0.0 : scene.bounds_m.min().z();
}

double plan_cut_height_m(const JobConfig& job, const std::vector<CalcGrid>& grids, double floor_z_m) {
  if (job.output.plan_cut_height_m > 0.0) return job.output.plan_cut_height_m;
  for (const CalcGrid& g : grids)
    if (g.kind == GridKind::horizontal && !g.points.empty()) {
      const double h = g.points.front().position_m.z() - floor_z_m;
      if (h > 0.0) return h;
    }
  return kDefaultCut_m;
}

PlanArchitecture job_architecture(const JobConfig& job, const Scene& scene, const std::vector<CalcGrid>& grids,
                                  double floor_z_m, double lowest_luminaire_z_m) {
  ArchitectureOptions o;
  o.floor_z_m = floor_z_m;
  o.cut_height_m = plan_cut_height_m(job, grids, floor_z_m);
  const double wall_cut = lowest_luminaire_z_m - floor_z_m - kWallCutBelowLuminaires_m;
  if (std::isfinite(wall_cut) && wall_cut > o.cut_height_m) o.wall_cut_height_m = wall_cut;
  return plan_architecture(scene, o);
}

PlanArchitecture run_architecture(const PreparedJob& prepared, const JobConfig& job,
                                  const std::vector<DrawnLuminaire>& luminaires) {
  const Scene& scene = prepared.loaded.scene;
  double lowest = std::numeric_limits<double>::quiet_NaN();
  for (const DrawnLuminaire& l : luminaires)
    if (!(l.at.position_m.z() >= lowest)) lowest = l.at.position_m.z();
  return job_architecture(job, scene, prepared.model.grids, plan_floor_z_m(scene, prepared.model.floor_z_m), lowest);
}

PlanView run_plan_view(const PlanInputs& in) {
  const Scene& scene = in.prepared.loaded.scene;
  const double floor_z = plan_floor_z_m(scene, in.prepared.model.floor_z_m);
  PlanView view;
  view.outline_patches = in.prepared.model.grid.mounting_patches();
  view.maintenance_factor = in.outcome.maintenance_factor;
  view.title_block = title_block(in);
  const std::string stem = std::filesystem::path(in.job.path).stem().string();
  if (!in.record.no_layout.empty()) {  // the room and the reason, no light to show
    view.title = stem + ": no layout (" + in.record.no_layout + ")";
    view.architecture =
        job_architecture(in.job, scene, in.prepared.model.grids, floor_z, std::numeric_limits<double>::quiet_NaN());
    return view;
  }
  std::ostringstream title;
  title << std::fixed << std::setprecision(1) << stem << ": " << in.outcome.luminaires.size() << " luminaires, "
        << in.outcome.power_w << " W, " << (in.outcome.verification.method != "none" ? "verified" : "predicted")
        << " maintained illuminance";
  view.title = title.str();
  view.goal_patches = in.prepared.model.goal_patches;
  view.goal_lux = in.goal_lux;
  view.luminaires = plan_luminaires(in, floor_z);
  double lowest = std::numeric_limits<double>::quiet_NaN();
  for (const PlanLuminaire& l : view.luminaires)
    if (!(l.position_m.z() >= lowest)) lowest = l.position_m.z();
  view.architecture = job_architecture(in.job, scene, in.prepared.model.grids, floor_z, lowest);
  for (std::size_t g = 0; g < in.grids.size(); ++g) {
    const CalcGrid& grid = *in.grids[g].grid;
    if (grid.kind != GridKind::horizontal) continue;
    PlanGrid p;
    p.name = grid.name;
    p.cell_m = Eigen::Vector2d(grid.cell_u_m, grid.cell_v_m);
    for (std::size_t q = 0; q < grid.points.size(); ++q) {
      p.points_m.push_back(grid.points[q].position_m.head<2>());
      p.lux.push_back(in.grids[g].light.total_initial_lux[static_cast<Eigen::Index>(q)]);
    }
    if (g < in.grid_files.size()) p.see = in.grid_files[g];
    view.grids.push_back(std::move(p));
  }
  return view;
}

void stage_plan(OutputSet& set, const Scene& scene, const PlanView& view, const std::string& name) {
  const std::string svg = render_plan_svg(scene, view);
  if (name.ends_with(".png")) {
    write_png_from_svg(set.staging_path(name), svg, 2.0);
    set.staged(name);
  } else {
    set.write(name, [&](std::ostream& out) { out << svg; });
  }
}

}  // namespace ilp::cli
