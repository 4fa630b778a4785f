#include "optimizer/candidate_grid.h"

#include "core/base/setting.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace ilp {
namespace {

// A patch counts as facing down when its normal is within about 8 degrees of -z: real
// models carry ceilings a few degrees off level (Sponza's arcades).
constexpr double kFacingDownCos = 0.99;
constexpr double kMaxGridNodes = 4e6;  // nodes of the candidate grid (each candidate is a column of T)

// Height of the mounting surface above (x, y): the patch whose top-view triangle
// holds the point, if any.
// The height of the highest of `patches` over xy: a shell surface faces down both at its
// ceiling and under its floor slab, and a luminaire hangs from the ceiling.
std::optional<double> surface_height(const Scene& scene, const std::vector<int>& patches, const Eigen::Vector2d& xy) {
  constexpr double kInsideTolerance = 1e-9;
  std::optional<double> highest;
  for (int index : patches) {
    const Patch& p = scene.patches[static_cast<std::size_t>(index)];
    const Eigen::Vector2d a = p.vertices_m[0].head<2>(), b = p.vertices_m[1].head<2>(), c = p.vertices_m[2].head<2>();
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (std::abs(area2) <= 0.0) continue;
    const double l1 = ((b - xy).x() * (c - xy).y() - (b - xy).y() * (c - xy).x()) / area2;
    const double l2 = ((c - xy).x() * (a - xy).y() - (c - xy).y() * (a - xy).x()) / area2;
    const double l3 = 1.0 - l1 - l2;
    if (l1 >= -kInsideTolerance && l2 >= -kInsideTolerance && l3 >= -kInsideTolerance) {
      const double z = l1 * p.vertices_m[0].z() + l2 * p.vertices_m[1].z() + l3 * p.vertices_m[2].z();
      highest = std::max(highest.value_or(z), z);
    }
  }
  return highest;
}

}  // namespace

void CandidateGrid::lay_nodes(const Eigen::AlignedBox2d& box, const CandidateGridOptions& options, const std::string& name) {
  surface_box_ = box;
  const Eigen::Vector2d half = options.half_footprint_m.array() + options.wall_distance_m;
  lower_ = box.min() + half;
  upper_ = box.max() - half;
  if (!options.zone_m.isEmpty()) {
    lower_ = lower_.cwiseMax(options.zone_m.min());
    upper_ = upper_.cwiseMin(options.zone_m.max());
    if ((upper_.array() < lower_.array()).any())
      throw std::invalid_argument((std::ostringstream() << "mounting surface '" << name << "': the mounting zone x ["
                                                        << options.zone_m.min().x() << ", " << options.zone_m.max().x()
                                                        << "] y [" << options.zone_m.min().y() << ", "
                                                        << options.zone_m.max().y() << "] m holds no luminaire position")
                                      .str());
  }
  if (options.module_m > 0.0) {
    // The module's cell centres, counted from the surface's lower corner.
    for (int axis = 0; axis < 2; ++axis) {
      const double first = box.min()[axis] + 0.5 * options.module_m;
      lower_[axis] = first + std::ceil((lower_[axis] - first) / options.module_m - 1e-9) * options.module_m;
      upper_[axis] = first + std::floor((upper_[axis] - first) / options.module_m + 1e-9) * options.module_m;
    }
  }
  if ((upper_.array() < lower_.array()).any())
    throw std::invalid_argument("mounting surface '" + name + "' is smaller than one luminaire");
  const Eigen::Vector2d extent = upper_ - lower_;
  // The node count in double before any int: a tiny spacing would overflow it.
  const double spacing = options.module_m > 0.0 ? options.module_m : options.spacing_m;
  const double nx = std::max(1.0, std::ceil(extent.x() / spacing - 1e-9)),
               ny = std::max(1.0, std::ceil(extent.y() / spacing - 1e-9));
  if (!((nx + 1) * (ny + 1) <= kMaxGridNodes))
    throw std::length_error((std::ostringstream() << spacing << " m over the " << extent.x() << " x "
                                                  << extent.y() << " m of mounting surface '" << name << "' makes "
                                                  << (nx + 1) * (ny + 1) << " grid nodes, more than "
                                                  << kMaxGridNodes << "; use a larger spacing")
                                .str());
  nx_ = static_cast<int>(nx);
  ny_ = static_cast<int>(ny);
  step_ = Eigen::Vector2d(extent.x() / nx_, extent.y() / ny_);
  if (options.module_m > 0.0 && extent.minCoeff() <= 0.0)
    step_ = Eigen::Vector2d::Constant(options.module_m);  // a single row or column of modules
}

CandidateGrid::CandidateGrid(const Scene& scene, int mounting_surface, const CandidateGridOptions& options) {
  if (mounting_surface < 0 || mounting_surface >= static_cast<int>(scene.surfaces.size()))
    throw std::invalid_argument("mounting surface: no surface with index " + std::to_string(mounting_surface));
  const std::string& name = scene.surfaces[static_cast<std::size_t>(mounting_surface)].name;
  if (!(options.spacing_m > 0.0) || !(options.half_footprint_m.minCoeff() > 0.0) || !(options.mount_offset_m > 0.0) ||
      !(options.wall_distance_m >= 0.0) || !(options.module_m >= 0.0))
    throw std::invalid_argument("mounting surface '" + name + "': spacing, luminaire size and offset must be > 0");
  Eigen::AlignedBox2d box;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (p.surface != mounting_surface) continue;
    if (p.normal.z() > -kFacingDownCos) {
      ++ignored_patches_;
      continue;
    }
    mounting_patches_.push_back(static_cast<int>(i));
    mounting_area_m2_ += p.area_m2;
    for (const auto& v : p.vertices_m) box.extend(v.head<2>());
  }
  if (mounting_patches_.empty())
    throw std::invalid_argument("mounting surface '" + name +
                                "' has no patch facing down: luminaires hang under a horizontal ceiling");

  lay_nodes(box, options, name);
  const Eigen::Vector2d half = options.half_footprint_m.array() + options.wall_distance_m;

  // A candidate exists where the centre and the four corners of the footprint (just
  // inside, with the wall distance) all lie over the surface.
  candidate_of_node_.assign(static_cast<std::size_t>((nx_ + 1) * (ny_ + 1)), -1);
  const Eigen::Vector2d corner = 0.999 * half;
  std::optional<double> under_floor_z;  // the first surface height a luminaire would hang under the floor from
  const double lowest_z = scene.bounds_m.min().z();
  auto hangs_under_floor = [&](double z) { return lowest_z < z && z - options.mount_offset_m <= lowest_z; };
  for (int j = 0; j <= ny_; ++j)
    for (int i = 0; i <= nx_; ++i) {
      const Eigen::Vector2d xy = lower_ + Eigen::Vector2d(i * step_.x(), j * step_.y());
      const std::optional<double> z = surface_height(scene, mounting_patches_, xy);
      if (!z) continue;
      // Where the surface is only a slab's underside (a hole in a shell's ceiling), the
      // luminaire would hang under the floor: no position there, nor a footprint reaching it.
      if (hangs_under_floor(*z)) {
        if (!under_floor_z) under_floor_z = *z;
        continue;
      }
      bool fits = true;
      for (const Eigen::Vector2d& d : {Eigen::Vector2d(-corner.x(), -corner.y()), Eigen::Vector2d(corner.x(), -corner.y()),
                                      Eigen::Vector2d(-corner.x(), corner.y()), Eigen::Vector2d(corner.x(), corner.y())}) {
        const std::optional<double> at = surface_height(scene, mounting_patches_, xy + d);
        fits = fits && at.has_value() && !hangs_under_floor(*at);
      }
      if (!fits) continue;
      candidate_of_node_[static_cast<std::size_t>(j * (nx_ + 1) + i)] = static_cast<int>(positions_.size());
      positions_.emplace_back(xy.x(), xy.y(), *z - options.mount_offset_m);
    }
  if (positions_.empty() && under_floor_z)
    throw std::out_of_range((std::ostringstream() << options.mount_offset_m << " m below mounting surface '" << name
                                                  << "' (at z = " << *under_floor_z << " m) is at or below the "
                                                  << "scene's lowest point (z = " << scene.bounds_m.min().z()
                                                  << " m): luminaires would hang under the floor")
                                .str());
  if (positions_.empty())
    throw std::invalid_argument("mounting surface '" + name + "': no position where a whole " +
                                (std::ostringstream() << 2.0 * options.half_footprint_m.x() << " x "
                                                      << 2.0 * options.half_footprint_m.y()).str() +
                                " m luminaire fits" +
                                (options.wall_distance_m > 0.0 ? " with the wall distance" : ""));
}

CandidateGrid::CandidateGrid(const Eigen::AlignedBox2d& plane_m, double z_m, const CandidateGridOptions& options) {
  const std::string name = "the suspension plane";
  if (plane_m.isEmpty() || !(plane_m.sizes().minCoeff() > 0.0) || !std::isfinite(z_m))
    throw std::invalid_argument("suspended luminaires: the zone must be a rectangle of non-zero area");
  if (!(options.spacing_m > 0.0) || !(options.half_footprint_m.minCoeff() > 0.0) || !(options.wall_distance_m >= 0.0) ||
      !(options.module_m >= 0.0))
    throw std::invalid_argument("suspended luminaires: spacing and luminaire size must be > 0");
  mounting_area_m2_ = plane_m.volume();
  lay_nodes(plane_m, options, name);
  candidate_of_node_.assign(static_cast<std::size_t>((nx_ + 1) * (ny_ + 1)), -1);
  for (int j = 0; j <= ny_; ++j)
    for (int i = 0; i <= nx_; ++i) {
      const Eigen::Vector2d xy = lower_ + Eigen::Vector2d(i * step_.x(), j * step_.y());
      candidate_of_node_[static_cast<std::size_t>(j * (nx_ + 1) + i)] = static_cast<int>(positions_.size());
      positions_.emplace_back(xy.x(), xy.y(), z_m);
    }
}

namespace {

// Whether (t, z) lies on one of the patches seen along the wall's normal (t: the
// coordinate along the wall, axis `t` of the scene).
bool on_wall_patches(const Scene& scene, const std::vector<int>& patches, int t, const Eigen::Vector2d& tz) {
  constexpr double kInsideTolerance = 1e-9;
  for (int index : patches) {
    const Patch& p = scene.patches[static_cast<std::size_t>(index)];
    const Eigen::Vector2d a(p.vertices_m[0][t], p.vertices_m[0].z()), b(p.vertices_m[1][t], p.vertices_m[1].z()),
        c(p.vertices_m[2][t], p.vertices_m[2].z());
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (std::abs(area2) <= 0.0) continue;
    const double l1 = ((b - tz).x() * (c - tz).y() - (b - tz).y() * (c - tz).x()) / area2;
    const double l2 = ((c - tz).x() * (a - tz).y() - (c - tz).y() * (a - tz).x()) / area2;
    if (l1 >= -kInsideTolerance && l2 >= -kInsideTolerance && 1.0 - l1 - l2 >= -kInsideTolerance) return true;
  }
  return false;
}

}  // namespace

CandidateGrid::CandidateGrid(const Scene& scene, int wall_surface, const Eigen::Vector2d& facing, double z_m,
                             const CandidateGridOptions& options) {
  if (wall_surface < 0 || wall_surface >= static_cast<int>(scene.surfaces.size()))
    throw std::invalid_argument("wall: no surface with index " + std::to_string(wall_surface));
  const std::string& name = scene.surfaces[static_cast<std::size_t>(wall_surface)].name;
  const int a = std::abs(facing.x()) > 0.5 ? 0 : 1, t = 1 - a;  // across the wall, along it
  const double sign = facing[a] > 0.0 ? 1.0 : -1.0;
  const std::string facing_text = std::string(sign > 0.0 ? "+" : "-") + (a == 0 ? "x" : "y");
  if (!(std::abs(std::abs(facing[a]) - 1.0) < 1e-9 && facing[t] == 0.0) || !std::isfinite(z_m))
    throw std::invalid_argument("wall '" + name + "': facing must be +x, -x, +y or -y and the height finite");
  if (!(options.spacing_m > 0.0) || !(options.half_footprint_m.minCoeff() >= 0.0) || !(options.mount_offset_m > 0.0) ||
      !(options.wall_distance_m >= 0.0))
    throw std::invalid_argument("wall '" + name + "': spacing and offset must be > 0");
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  normal[a] = sign;
  double plane_sum = 0.0, lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
  double t_min = lowest, t_max = -lowest;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (p.surface != wall_surface) continue;
    if (p.normal.dot(normal) < kFacingDownCos) {
      ++ignored_patches_;
      continue;
    }
    mounting_patches_.push_back(static_cast<int>(i));
    mounting_area_m2_ += p.area_m2;
    plane_sum += p.area_m2 * p.centroid_m[a];
    for (const auto& v : p.vertices_m) {
      t_min = std::min(t_min, v[t]);
      t_max = std::max(t_max, v[t]);
      lowest = std::min(lowest, v.z());
      highest = std::max(highest, v.z());
    }
  }
  if (mounting_patches_.empty())
    throw std::invalid_argument("wall '" + name + "' has no patch facing " + facing_text +
                                " (a vertical face whose normal points into the room that way)");
  const double plane = plane_sum / mounting_area_m2_;
  constexpr double kPlaneToleranceM = 0.05;  // one wall: its faces within this of their mean plane
  for (int index : mounting_patches_) {
    const double d = scene.patches[static_cast<std::size_t>(index)].centroid_m[a] - plane;
    if (std::abs(d) > kPlaneToleranceM)
      throw std::invalid_argument((std::ostringstream() << "wall '" << name << "': its faces facing " << facing_text
                                                        << " lie in more than one plane (" << (a == 0 ? "x" : "y")
                                                        << " = " << plane << " and " << plane + d
                                                        << " m): name one wall (" << setting_name(Setting::regions) << ", or "
                                                        << setting_name(Setting::surfaces_from) << ": connected)").str());
  }
  if (!(z_m > lowest && z_m < highest))
    throw std::out_of_range((std::ostringstream() << "at z = " << z_m << " m, outside wall '" << name << "' (z from "
                                                  << lowest << " to " << highest << " m)").str());
  const Eigen::Vector2d half = options.half_footprint_m;
  double lo = t_min + half[t] + options.wall_distance_m, hi = t_max - half[t] - options.wall_distance_m;
  if (!options.zone_m.isEmpty()) {
    lo = std::max(lo, options.zone_m.min()[t]);
    hi = std::min(hi, options.zone_m.max()[t]);
    if (hi < lo)
      throw std::invalid_argument((std::ostringstream() << "wall '" << name << "': the mounting zone "
                                                        << (t == 0 ? "x" : "y") << " [" << options.zone_m.min()[t]
                                                        << ", " << options.zone_m.max()[t]
                                                        << "] m holds no luminaire position along it").str());
  }
  if (hi < lo) throw std::invalid_argument("wall '" + name + "' is shorter than one luminaire");
  const double across = plane + sign * (options.mount_offset_m + half[a]);
  const double n = std::max(1.0, std::ceil((hi - lo) / options.spacing_m - 1e-9));
  if (!(n + 1 <= kMaxGridNodes)) throw std::length_error("wall '" + name + "': too many candidates; use a larger spacing");
  const int along_nodes = static_cast<int>(n);
  lower_[a] = upper_[a] = across;
  lower_[t] = lo;
  upper_[t] = hi;
  step_[a] = 0.0;
  step_[t] = (hi - lo) / along_nodes;
  surface_box_ = Eigen::AlignedBox2d(lower_, upper_);
  surface_box_.min()[t] = t_min;
  surface_box_.max()[t] = t_max;
  // One line of nodes along the wall, doubled across it (the blend needs a cell): both
  // copies of a node hold the same candidate.
  nx_ = a == 0 ? 1 : along_nodes;
  ny_ = a == 0 ? along_nodes : 1;
  candidate_of_node_.assign(static_cast<std::size_t>((nx_ + 1) * (ny_ + 1)), -1);
  for (int k = 0; k <= along_nodes; ++k) {
    const double at = lo + k * step_[t];
    bool fits = true;
    for (const double d : {0.0, -0.999 * half[t], 0.999 * half[t]})
      fits = fits && on_wall_patches(scene, mounting_patches_, t, Eigen::Vector2d(at + d, z_m));
    if (!fits) continue;
    const int c = static_cast<int>(positions_.size());
    Eigen::Vector3d position(0.0, 0.0, z_m);
    position[a] = across;
    position[t] = at;
    positions_.push_back(position);
    for (int side = 0; side <= 1; ++side) {
      const int i = a == 0 ? side : k, j = a == 0 ? k : side;
      candidate_of_node_[static_cast<std::size_t>(j * (nx_ + 1) + i)] = c;
    }
  }
  if (positions_.empty())
    throw std::invalid_argument((std::ostringstream() << "wall '" << name << "': no position at z = " << z_m
                                                      << " m where a whole luminaire fits on its faces facing "
                                                      << facing_text).str());
}

namespace {

// Catmull-Rom weights of the four nodes around a point at fraction t of its cell.
std::array<double, 4> catmull_rom(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {0.5 * (-t3 + 2 * t2 - t), 0.5 * (3 * t3 - 5 * t2 + 2), 0.5 * (-3 * t3 + 4 * t2 + t), 0.5 * (t3 - t2)};
}

}  // namespace

GridPoint CandidateGrid::locate(const Eigen::Vector2d& xy_m) const {
  const Eigen::Vector2d xy = xy_m.allFinite() ? xy_m.cwiseMax(lower_).cwiseMin(upper_) : lower_;  // NaN: no int cast of it
  const Eigen::Vector2d cell = ((xy - lower_).array() / step_.array().max(1e-300)).matrix();
  const int i = std::clamp(static_cast<int>(std::floor(cell.x())), 0, nx_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor(cell.y())), 0, ny_ - 1);
  const double u = std::clamp(cell.x() - i, 0.0, 1.0), v = std::clamp(cell.y() - j, 0.0, 1.0);
  GridPoint out;
  auto finish = [&](int used) {
    out.position_m.setZero();
    for (int k = 0; k < used; ++k)
      if (out.candidates[k] >= 0) out.position_m += out.weights[k] * positions_[static_cast<std::size_t>(out.candidates[k])];
    out.position_m.head<2>() = xy;  // the blend's z; x, y as asked
    return out;
  };
  // Catmull-Rom: 4 x 4 nodes, indices clamped at the edges (the weights of a clamped
  // node add up, so the blend still reproduces constants).
  {
    const std::array<double, 4> wx = catmull_rom(u), wy = catmull_rom(v);
    bool complete = true;
    int used = 0;
    for (int b = 0; b < 4 && complete; ++b)
      for (int a = 0; a < 4 && complete; ++a) {
        const int c = node(std::clamp(i - 1 + a, 0, nx_), std::clamp(j - 1 + b, 0, ny_));
        const double w = wx[a] * wy[b];
        if (w == 0.0) continue;
        if (c < 0) {
          complete = false;
          break;
        }
        int slot = 0;
        while (slot < used && out.candidates[slot] != c) ++slot;
        if (slot == used) out.candidates[used++] = c;
        out.weights[slot] += w;
      }
    if (complete) return finish(used);
    out = GridPoint();
  }
  const std::array<int, 4> corners{node(i, j), node(i + 1, j), node(i, j + 1), node(i + 1, j + 1)};
  const std::array<double, 4> weights{(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
  bool complete = true;
  for (int k = 0; k < 4; ++k) complete = complete && (corners[k] >= 0 || weights[k] == 0.0);
  if (complete) {
    for (int k = 0; k < 4; ++k) {
      if (weights[k] == 0.0) continue;
      out.candidates[k] = corners[k];
      out.weights[k] = weights[k];
    }
    return finish(4);
  }
  // Off the surface (or over a hole): the nearest candidate.
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < positions_.size(); ++c) {
    const double d = (positions_[c].head<2>() - xy_m).squaredNorm();
    if (d < best) {
      best = d;
      out.candidates[0] = static_cast<int>(c);
    }
  }
  out.weights[0] = 1.0;
  out.position_m = positions_[static_cast<std::size_t>(out.candidates[0])];
  return out;
}

double CandidateGrid::mount_distance_m(const Eigen::Vector2d& xy_m) const {
  if (!xy_m.allFinite()) return std::numeric_limits<double>::infinity();
  // The nearest point of the centres' extent, then whether a whole cell holds it.
  const Eigen::Vector2d inside = xy_m.cwiseMax(lower_).cwiseMin(upper_);
  const Eigen::Vector2d cell = ((inside - lower_).array() / step_.array().max(1e-300)).matrix();
  const int i = std::clamp(static_cast<int>(std::floor(cell.x())), 0, nx_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor(cell.y())), 0, ny_ - 1);
  if (node(i, j) >= 0 && node(i + 1, j) >= 0 && node(i, j + 1) >= 0 && node(i + 1, j + 1) >= 0)
    return (inside - xy_m).norm();
  return (nearest_candidate_m(xy_m) - xy_m).norm();
}

Eigen::Vector2d CandidateGrid::nearest_candidate_m(const Eigen::Vector2d& xy_m) const {
  Eigen::Vector2d best = xy_m;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : positions_)
    if (const double d2 = (p.head<2>() - xy_m).squaredNorm(); d2 < best_d2) {
      best_d2 = d2;
      best = p.head<2>();
    }
  return best;
}

namespace {

// The computed nodes around index i of an axis with `last` + 1 nodes, every `stride`-th
// and the last: (lo, hi, weight of hi); lo == hi when i is one of them.
struct AxisSpan {
  int lo = 0, hi = 0;
  double t = 0.0;
};
AxisSpan axis_span(int i, int last, int stride) {
  if (i % stride == 0 || i == last) return {i, i, 0.0};
  const int lo = i - i % stride, hi = std::min(lo + stride, last);
  return {lo, hi, static_cast<double>(i - lo) / (hi - lo)};
}

}  // namespace

ReflectedBlend candidate_reflected_blend(const CandidateGrid& grid, std::size_t fixed_sources, int stride) {
  if (stride < 1) throw std::invalid_argument("candidate_reflected_blend: stride must be >= 1");
  const std::size_t sources = fixed_sources + grid.size();
  if (stride == 1 || grid.size() == 0) return identity_blend(sources);
  const int last_x = grid.nodes_x() - 1, last_y = grid.nodes_y() - 1;
  // Each candidate's blend over candidates (before the computed ones are numbered).
  std::vector<std::vector<std::pair<int, double>>> from(grid.size());
  std::vector<bool> computed(grid.size(), false);
  for (int j = 0; j <= last_y; ++j)
    for (int i = 0; i <= last_x; ++i) {
      const int c = grid.candidate_at_node(i, j);
      if (c < 0) continue;
      const AxisSpan x = axis_span(i, last_x, stride), y = axis_span(j, last_y, stride);
      std::vector<std::pair<int, double>> blend;
      bool complete = true;
      for (const auto& [a, wa] : {std::pair{x.lo, 1.0 - x.t}, std::pair{x.hi, x.t}})
        for (const auto& [b, wb] : {std::pair{y.lo, 1.0 - y.t}, std::pair{y.hi, y.t}}) {
          const double w = wa * wb;
          if (w == 0.0) continue;
          const int n = grid.candidate_at_node(a, b);
          if (n < 0) complete = false;
          blend.emplace_back(n, w);
        }
      const bool own = blend.size() == 1 && blend[0].first == c;
      if (!complete || own) {
        computed[static_cast<std::size_t>(c)] = true;
        blend = {{c, 1.0}};
      }
      from[static_cast<std::size_t>(c)] = std::move(blend);
    }
  // A blended candidate's nodes are computed ones: those with w > 0 lie on the computed
  // lattice, where every candidate is its own blend.
  ReflectedBlend out;
  std::vector<int> index(sources, -1);
  for (std::size_t s = 0; s < sources; ++s)
    if (s < fixed_sources || computed[s - fixed_sources]) {
      index[s] = static_cast<int>(out.computed.size());
      out.computed.push_back(static_cast<int>(s));
    }
  std::vector<Eigen::Triplet<double>> w;
  for (std::size_t s = 0; s < sources; ++s) {
    if (s < fixed_sources) {
      w.emplace_back(index[s], static_cast<int>(s), 1.0);
      continue;
    }
    for (const auto& [c, weight] : from[s - fixed_sources])
      w.emplace_back(index[fixed_sources + static_cast<std::size_t>(c)], static_cast<int>(s), weight);
  }
  out.weights.resize(static_cast<Eigen::Index>(out.computed.size()), static_cast<Eigen::Index>(sources));
  out.weights.setFromTriplets(w.begin(), w.end());
  check_blend(out, sources);
  return out;
}

}  // namespace ilp
