#include "output/grid_report.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

#include "output/plan_architecture.h"

namespace ilp {
namespace {

using V2 = Eigen::Vector2d;

// The segment from_m .. to_m of a vertical grid starts here (z left at 0).
Eigen::Vector3d vertical_start_m(const CalcGrid& g) { return g.origin_m - g.border_m * (g.u_axis + g.v_axis); }

void check_light(const CalcGrid& grid, const GridLight& light) {
  const auto n = static_cast<Eigen::Index>(grid.points.size());
  if (light.total_initial_lux.size() != n || light.direct_initial_lux.size() != n)
    throw std::invalid_argument("grid '" + grid.name + "': need one value per point");
  if (!(light.maintenance_factor > 0.0 && light.maintenance_factor <= 1.0))
    throw std::invalid_argument("grid '" + grid.name + "': the maintenance factor must be in (0, 1]");
}

std::string fixed(double v, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

// "z = 0.80 m: Em 512 lx, Emin 301 lx, U0 0.59 (maintained, verified, exact)".
std::string view_title(const CalcGrid& grid, const GridLight& light) {
  const Eigen::VectorXd m = light.total_initial_lux * light.maintenance_factor;
  const double em = m.size() ? m.mean() : 0.0, emin = m.size() ? m.minCoeff() : 0.0;
  std::string where = grid.kind == GridKind::horizontal
                          ? "horizontal at z = " + fixed(grid.points.empty() ? 0.0 : grid.points.front().position_m.z(), 2) + " m"
                          : "vertical plane";
  return where + ": Em " + fixed(em, 0) + " lx, Emin " + fixed(emin, 0) + " lx, U0 " +
         fixed(em > 0.0 ? emin / em : 0.0, 2) + " (maintained" + (light.basis.empty() ? "" : ", " + light.basis) + ")";
}

}  // namespace

Eigen::Vector2d grid_plan_position_m(const CalcGrid& grid, const Eigen::Vector3d& p) {
  if (grid.kind == GridKind::horizontal) return p.head<2>();
  const Eigen::Vector3d start = vertical_start_m(grid);
  return V2((p - start).head<2>().dot(grid.u_axis.head<2>()), p.z());
}

std::vector<std::vector<Eigen::Vector2d>> grid_room_outline_m(const CalcGrid& grid) {
  if (grid.kind == GridKind::vertical) {
    const double length = 2.0 * grid.border_m + grid.cells_u * grid.cell_u_m;
    const double bottom = grid.origin_m.z() - grid.border_m;
    const double top = bottom + 2.0 * grid.border_m + grid.cells_v * grid.cell_v_m;
    return {{V2(0.0, bottom), V2(length, bottom), V2(length, top), V2(0.0, top)}};
  }
  if (!grid.outline_hole_m.empty()) return {grid.outline_polygon_m, grid.outline_hole_m};  // a band and its task area
  if (!grid.outline_polygon_m.empty()) return {grid.outline_polygon_m};
  return union_outline(grid.outline_triangles_m, kOutlineRasterCells);
}

std::vector<IsoluxLuminaire> isolux_luminaires(const CalcGrid& grid, const std::vector<DrawnLuminaire>& luminaires) {
  constexpr double kMinThickness_m = 0.02;
  std::vector<IsoluxLuminaire> out;
  for (const DrawnLuminaire& l : luminaires) {
    IsoluxLuminaire d;
    d.id = l.id;
    d.product = l.product;
    if (grid.kind == GridKind::horizontal && l.at.tilt_deg != 0.0) {
      // A tilted outline projected on the plan, as its box in the luminaire's turned axes.
      const Eigen::Rotation2Dd turn(l.at.rotation_deg * std::numbers::pi / 180.0);
      Eigen::AlignedBox2d box;
      for (const Eigen::Vector3d& v : luminaire_outline_m(l.type, l.at))
        box.extend(turn.inverse() * (v - l.at.position_m).head<2>());
      d.centre_m = l.at.position_m.head<2>() + turn * box.center();
      d.length_m = box.sizes().x();
      d.width_m = std::max(kMinThickness_m, box.sizes().y());
      d.rotation_deg = l.at.rotation_deg;
    } else if (grid.kind == GridKind::horizontal) {
      d.centre_m = l.at.position_m.head<2>();
      d.length_m = l.type.length_m;
      d.width_m = l.type.width_m;
      d.rotation_deg = l.at.rotation_deg;
      d.round = l.type.shape == OutlineShape::disc;
    } else {
      Eigen::AlignedBox2d box;
      for (const Eigen::Vector3d& v : luminaire_outline_m(l.type, l.at)) box.extend(grid_plan_position_m(grid, v));
      d.centre_m = box.center();
      d.length_m = box.sizes().x();
      d.width_m = std::max(kMinThickness_m, box.sizes().y());
    }
    out.push_back(std::move(d));
  }
  return out;
}

IsoluxGridView isolux_grid_view(const CalcGrid& grid, const GridLight& light,
                                const std::vector<DrawnLuminaire>& luminaires) {
  check_light(grid, light);
  IsoluxGridView v;
  v.name = grid.name;
  v.title = view_title(grid, light);
  v.nx = grid.cells_u;
  v.ny = grid.cells_v;
  const Eigen::Vector3d first = grid.origin_m + 0.5 * grid.cell_u_m * grid.u_axis + 0.5 * grid.cell_v_m * grid.v_axis;
  v.origin_m = grid_plan_position_m(grid, first);
  v.spacing_m = V2(grid.cell_u_m, grid.cell_v_m);
  v.maintained_lux.assign(static_cast<std::size_t>(v.nx) * static_cast<std::size_t>(v.ny),
                          std::numeric_limits<double>::quiet_NaN());
  for (std::size_t q = 0; q < grid.points.size(); ++q) {
    const Eigen::Vector2i c = grid.cell_of_point[q];
    v.maintained_lux[static_cast<std::size_t>(c.y()) * v.nx + c.x()] =
        light.total_initial_lux[static_cast<Eigen::Index>(q)] * light.maintenance_factor;
  }
  v.room_outline_m = grid_room_outline_m(grid);
  v.luminaires = isolux_luminaires(grid, luminaires);
  v.target_lux = light.target_lux;
  v.maintenance_factor = light.maintenance_factor;
  if (grid.kind == GridKind::vertical) {
    v.x_label = "along the plane (m)";
    v.y_label = "height z (m)";
  }
  return v;
}

GridCsvGrid grid_csv_grid(const CalcGrid& grid, const GridLight& light) {
  check_light(grid, light);
  GridCsvGrid out{grid.name, light.maintenance_factor, {}};
  for (std::size_t q = 0; q < grid.points.size(); ++q) {
    const auto k = static_cast<Eigen::Index>(q);
    out.points.push_back({grid.points[q].position_m, light.direct_initial_lux[k], light.total_initial_lux[k]});
  }
  return out;
}

std::vector<std::string> isolux_file_stems(const std::vector<std::string>& grid_names) {
  std::vector<std::string> out;
  std::set<std::string> taken;
  for (const std::string& name : grid_names) {
    std::string safe;
    for (const char c : name) {
      const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
      safe += keep ? c : '_';
    }
    std::string stem = "isolux_" + safe;
    for (int n = 2; taken.count(stem); ++n) stem = "isolux_" + safe + "_" + std::to_string(n);
    taken.insert(stem);
    out.push_back(stem);
  }
  return out;
}

}  // namespace ilp
