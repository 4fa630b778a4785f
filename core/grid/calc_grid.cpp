#include "core/grid/calc_grid.h"

#include "core/base/setting.h"
#include <algorithm>
#include <array>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/base/key_hash.h"

namespace ilp {
namespace {

std::string metres(double v) {
  std::ostringstream os;
  os << std::setprecision(4) << v << " m";
  return os.str();
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Proper or touching intersection of closed segments ab and cd.
bool segments_meet(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double scale = std::max({(b - a).norm(), (d - c).norm(), 1e-300});
  const double eps = 1e-12 * scale * scale;
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a);
  const double d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
  auto on = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {  // r on pq, collinear
    return std::min(p.x(), q.x()) - 1e-12 * scale <= r.x() && r.x() <= std::max(p.x(), q.x()) + 1e-12 * scale &&
           std::min(p.y(), q.y()) - 1e-12 * scale <= r.y() && r.y() <= std::max(p.y(), q.y()) + 1e-12 * scale;
  };
  if (((d1 > eps && d2 < -eps) || (d1 < -eps && d2 > eps)) && ((d3 > eps && d4 < -eps) || (d3 < -eps && d4 > eps)))
    return true;
  return (std::abs(d1) <= eps && on(a, b, c)) || (std::abs(d2) <= eps && on(a, b, d)) ||
         (std::abs(d3) <= eps && on(c, d, a)) || (std::abs(d4) <= eps && on(c, d, b));
}

// Crossing-number test of a point against a polygon.
bool inside_polygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  bool inside = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

bool inside_triangle(const std::array<Eigen::Vector2d, 3>& t, const Eigen::Vector2d& p) {
  const double d1 = cross2(t[1] - t[0], p - t[0]), d2 = cross2(t[2] - t[1], p - t[1]), d3 = cross2(t[0] - t[2], p - t[2]);
  const bool negative = d1 < 0 || d2 < 0 || d3 < 0, positive = d1 > 0 || d2 > 0 || d3 > 0;
  return !(negative && positive);
}

// The area a horizontal grid covers: a polygon, or the union of a surface's patches facing up.
// A band's polygon has a hole (its task area).
struct Outline {
  std::vector<Eigen::Vector2d> polygon;
  std::vector<Eigen::Vector2d> hole;
  std::vector<std::array<Eigen::Vector2d, 3>> triangles;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = Eigen::Vector2d::Constant(-INFINITY);
  bool contains(const Eigen::Vector2d& p) const {
    if (!polygon.empty()) return inside_polygon(polygon, p) && (hole.empty() || !inside_polygon(hole, p));
    return std::any_of(triangles.begin(), triangles.end(), [&](const auto& t) { return inside_triangle(t, p); });
  }
  void extend(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

// Inside the outline and at least `band` from its edge (checked in 8 directions).
bool inside_less_band(const Outline& outline, const Eigen::Vector2d& p, double band) {
  if (!outline.contains(p)) return false;
  if (band <= 0.0) return true;
  for (int k = 0; k < 8; ++k) {
    const double a = k * 0.25 * 3.14159265358979323846;
    if (!outline.contains(p + band * Eigen::Vector2d(std::cos(a), std::sin(a)))) return false;
  }
  return true;
}

// The part of a polygon inside the box (Sutherland-Hodgman, one side of the box at a time).
std::vector<Eigen::Vector2d> clip_to_box(std::vector<Eigen::Vector2d> poly, const Eigen::Vector2d& lo,
                                         const Eigen::Vector2d& hi) {
  for (int side = 0; side < 4 && !poly.empty(); ++side) {
    const int axis = side % 2;
    const bool low = side < 2;
    const double bound = low ? lo[axis] : hi[axis];
    auto inside = [&](const Eigen::Vector2d& p) { return low ? p[axis] >= bound : p[axis] <= bound; };
    std::vector<Eigen::Vector2d> out;
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const Eigen::Vector2d& a = poly[i];
      const Eigen::Vector2d& b = poly[(i + 1) % poly.size()];
      if (inside(a)) out.push_back(a);
      if (inside(a) != inside(b)) out.push_back(a + (b - a) * ((bound - a[axis]) / (b[axis] - a[axis])));
    }
    poly = std::move(out);
  }
  return poly;
}

}  // namespace

std::vector<Eigen::Vector2d> grow_polygon(const std::vector<Eigen::Vector2d>& poly, double width_m) {
  const std::size_t n = poly.size();
  double area2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) area2 += cross2(poly[i], poly[(i + 1) % n]);
  const double side = area2 >= 0.0 ? 1.0 : -1.0;  // counter-clockwise: the outward normal is the edge turned -90 degrees
  auto outward = [&](std::size_t i) {
    const Eigen::Vector2d d = (poly[(i + 1) % n] - poly[i]).normalized();
    return Eigen::Vector2d(side * d.y(), -side * d.x());
  };
  std::vector<Eigen::Vector2d> out;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d n1 = outward((i + n - 1) % n), n2 = outward(i);
    // The mitre: the point width_m from both moved edges, (n1 + n2) / (1 + n1.n2) x width.
    const double c = 1.0 + n1.dot(n2);
    out.push_back(poly[i] + width_m * (c > 1e-9 ? Eigen::Vector2d((n1 + n2) / c) : n1));
  }
  return out;
}

// A point inside a solid object sees the backs of its faces: the first hit is a back
// face in at least 4 of the 6 axis directions.
bool inside_solid(const RayCaster& caster, const Eigen::Vector3d& p) {
  static const std::array<Eigen::Vector3d, 6> kDirections{Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(),
                                                          Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitY(),
                                                          Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};
  int back = 0;
  for (const Eigen::Vector3d& d : kDirections) {
    const RayHit hit = caster.first_hit(p, d);
    if (hit.patch >= 0 && !hit.front) ++back;
  }
  return back >= 4;
}

double en12464_grid_spacing_m(double longer_side_m) {
  if (!(longer_side_m > 0.0)) return 0.0;
  return std::min(10.0, 0.2 * std::pow(5.0, std::log10(longer_side_m)));
}

Eigen::Vector2i grid_cell_counts(double side_u_m, double side_v_m, double spacing_m) {
  auto count = [&](double side) { return static_cast<int>(std::max(1.0, std::min(1e9, std::round(side / spacing_m)))); };
  Eigen::Vector2i n(count(side_u_m), count(side_v_m));
  while (side_u_m / n.x() > 2.0 * side_v_m / n.y()) ++n.x();
  while (side_v_m / n.y() > 2.0 * side_u_m / n.x()) ++n.y();
  return n;
}

bool polygon_is_simple(const std::vector<Eigen::Vector2d>& poly) {
  const std::size_t n = poly.size();
  if (n < 3) return false;
  double area = 0.0;
  for (std::size_t i = 0; i < n; ++i) area += cross2(poly[i], poly[(i + 1) % n]);
  if (!(std::abs(area) > 0.0)) return false;
  for (std::size_t i = 0; i < n; ++i) {
    if ((poly[i] - poly[(i + 1) % n]).norm() == 0.0) return false;
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      const Eigen::Vector2d &a = poly[i], &b = poly[(i + 1) % n], &c = poly[j], &d = poly[(j + 1) % n];
      if (!adjacent) {
        if (segments_meet(a, b, c, d)) return false;
      } else {
        // Adjacent edges share one vertex; they must not fold back over each other.
        const Eigen::Vector2d shared = j == i + 1 ? b : a;
        const Eigen::Vector2d p = j == i + 1 ? a : b, q = j == i + 1 ? d : c;
        const Eigen::Vector2d e1 = p - shared, e2 = q - shared;
        if (std::abs(cross2(e1, e2)) <= 1e-12 * e1.norm() * e2.norm() && e1.dot(e2) > 0.0) return false;
      }
    }
  }
  return true;
}

namespace {

// A grid's lattice before its points are tested (no rays): the outline, the plane's
// normal, the cells. Throws the setting's ConfigErrors that need no ray.
struct GridLattice {
  CalcGrid grid;  // name, kind, axes, origin, spacing, cells
  Outline outline;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

GridLattice lay_lattice(const Scene& scene, const CalcGridSetting& s) {
  GridLattice lattice;
  CalcGrid& grid = lattice.grid;
  Outline& outline = lattice.outline;
  Eigen::Vector3d& normal = lattice.normal;
  grid.name = s.name;
  grid.kind = s.kind;
  const Eigen::AlignedBox3d& bounds = scene.bounds_m;
  const double tolerance = 1e-6 * (1.0 + bounds.diagonal().norm());
  const std::string label = setting_name(Setting::grid, s.name);
  double lu = 0.0, lv = 0.0;
  if (s.kind == GridKind::horizontal) {
    double z = s.height_m;
    if (!s.over_surface.empty()) {
      const int surface = scene.find_surface(s.over_surface);
      if (surface < 0)
        throw ConfigError(located(s.shape_loc, setting_name(Setting::grid_over_surface, s.name) + ": unknown surface '" + s.over_surface + "'"));
      double area = 0.0, weighted_z = 0.0;
      for (const Patch& p : scene.patches) {
        if (p.surface != surface || p.normal.z() < 0.9) continue;
        outline.triangles.push_back({p.vertices_m[0].head<2>(), p.vertices_m[1].head<2>(), p.vertices_m[2].head<2>()});
        for (const auto& v : p.vertices_m) outline.extend(v.head<2>());
        area += p.area_m2;
        weighted_z += p.area_m2 * p.centroid_m.z();
      }
      if (!(area > 0.0))
        throw ConfigError(located(s.shape_loc, setting_name(Setting::grid_over_surface, s.name) + ": '" + s.over_surface +
                                                   "' has no patch facing up to lay a work plane over"));
      z += weighted_z / area;
    } else if (s.band_width_m > 0.0) {
      // The band: the task outline grown, less the outline, clipped to the room. The
      // lattice spans the grown outline before clipping, so that its cells keep their
      // alignment with the task outline.
      const Eigen::Vector2d room = bounds.sizes().head<2>();
      if (s.band_width_m > room.maxCoeff())
        throw ConfigError(located(s.band_loc, label + ": a surrounding band " + metres(s.band_width_m) +
                                                  " wide is wider than the room (" + metres(room.x()) + " x " +
                                                  metres(room.y()) + ")"));
      const std::vector<Eigen::Vector2d> grown = grow_polygon(s.polygon_m, s.band_width_m);
      for (const auto& p : grown) outline.extend(p);
      outline.polygon = clip_to_box(grown, bounds.min().head<2>(), bounds.max().head<2>());
      outline.hole = s.polygon_m;
      if (outline.polygon.size() < 3)
        throw ConfigError(located(s.band_loc, label + ": the surrounding band lies outside the scene"));
    } else {
      outline.polygon = s.polygon_m;
      for (const auto& p : s.polygon_m) outline.extend(p);
      if ((outline.lo.array() < bounds.min().head<2>().array() - tolerance).any() ||
          (outline.hi.array() > bounds.max().head<2>().array() + tolerance).any())
        throw ConfigError(located(s.shape_loc, label + ": the grid reaches outside the scene (x " +
                                                   metres(bounds.min().x()) + " to " + metres(bounds.max().x()) +
                                                   ", y " + metres(bounds.min().y()) + " to " + metres(bounds.max().y()) + ")"));
    }
    if (!(z > bounds.min().z() + tolerance && z < bounds.max().z() - tolerance))
      throw ConfigError(located(s.height_loc, setting_name(Setting::grid_height, s.name) + ": the plane at z = " + metres(z) +
                                                  " is outside the scene (z " + metres(bounds.min().z()) + " to " +
                                                  metres(bounds.max().z()) + ")"));
    lu = outline.hi.x() - outline.lo.x() - 2.0 * s.border_m;
    lv = outline.hi.y() - outline.lo.y() - 2.0 * s.border_m;
    grid.origin_m = Eigen::Vector3d(outline.lo.x() + s.border_m, outline.lo.y() + s.border_m, z);
    grid.u_axis = Eigen::Vector3d::UnitX();
    grid.v_axis = Eigen::Vector3d::UnitY();
  } else {
    const Eigen::Vector2d along = s.to_m - s.from_m;
    const double length = along.norm();
    if (!(length > 0.0)) throw ConfigError(located(s.shape_loc, label + ": from_m and to_m are the same point"));
    for (const Eigen::Vector2d& p : {s.from_m, s.to_m})
      if ((p.array() < bounds.min().head<2>().array() - tolerance).any() ||
          (p.array() > bounds.max().head<2>().array() + tolerance).any())
        throw ConfigError(located(s.shape_loc, label + ": the segment reaches outside the scene"));
    if (s.bottom_m < bounds.min().z() - tolerance || s.top_m > bounds.max().z() + tolerance || !(s.top_m > s.bottom_m))
      throw ConfigError(located(s.height_loc, label + ": bottom_m to top_m must lie within the scene's heights (z " +
                                                  metres(bounds.min().z()) + " to " + metres(bounds.max().z()) +
                                                  ") with top above bottom"));
    const Eigen::Vector2d u = along / length;
    normal = s.facing_left ? Eigen::Vector3d(-u.y(), u.x(), 0.0) : Eigen::Vector3d(u.y(), -u.x(), 0.0);
    grid.u_axis = Eigen::Vector3d(u.x(), u.y(), 0.0);
    grid.v_axis = Eigen::Vector3d::UnitZ();
    lu = length - 2.0 * s.border_m;
    lv = s.top_m - s.bottom_m - 2.0 * s.border_m;
    grid.origin_m = Eigen::Vector3d(s.from_m.x(), s.from_m.y(), s.bottom_m) + s.border_m * (grid.u_axis + grid.v_axis);
  }
  if (!(lu > 0.0 && lv > 0.0))
    throw ConfigError(located(s.border_loc, setting_name(Setting::grid_border, s.name) + ": a band of " + metres(s.border_m) +
                                                " leaves nothing of the grid's area (the band is wider than the room)"));
  grid.spacing_m = s.spacing_m ? *s.spacing_m : en12464_grid_spacing_m(std::max(lu, lv));
  Eigen::Vector2i n = grid_cell_counts(lu, lv, grid.spacing_m);
  double band_cell_m = 0.0;
  if (s.band_width_m > 0.0) {  // square cells, a whole number of them across the band
    band_cell_m = s.band_width_m / std::ceil(s.band_width_m / grid.spacing_m - 1e-9);
    n = Eigen::Vector2i(static_cast<int>(std::ceil(lu / band_cell_m - 1e-9)),
                        static_cast<int>(std::ceil(lv / band_cell_m - 1e-9)));
  }
  const double cells = static_cast<double>(n.x()) * static_cast<double>(n.y());
  if (cells > s.max_points)
    throw ConfigError(located(s.spacing_m ? s.spacing_loc : s.loc,
                              label + ": a spacing of " + metres(grid.spacing_m) + " over " + metres(lu) + " x " +
                                  metres(lv) + " makes " + std::to_string(static_cast<long long>(cells)) +
                                  " points, more than max_points (" + std::to_string(s.max_points) + ")"));
  grid.cells_u = n.x();
  grid.cells_v = n.y();
  grid.cell_u_m = band_cell_m > 0.0 ? band_cell_m : lu / n.x();
  grid.cell_v_m = band_cell_m > 0.0 ? band_cell_m : lv / n.y();
  return lattice;
}

}  // namespace

CalcGridSize calc_grid_size(const Scene& scene, const CalcGridSetting& setting) {
  const GridLattice lattice = lay_lattice(scene, setting);
  return {static_cast<std::size_t>(lattice.grid.cells_u) * static_cast<std::size_t>(lattice.grid.cells_v),
          lattice.outline.triangles.size() + lattice.outline.polygon.size()};
}

CalcGrid make_calc_grid(const Scene& scene, const RayCaster& caster, const CalcGridSetting& s) {
  GridLattice lattice = lay_lattice(scene, s);
  CalcGrid& grid = lattice.grid;
  const Outline& outline = lattice.outline;
  const Eigen::Vector3d normal = lattice.normal;
  const Eigen::Vector2i n(grid.cells_u, grid.cells_v);
  const std::string label = setting_name(Setting::grid, s.name);
  std::size_t no_floor = 0;
  for (int j = 0; j < n.y(); ++j)
    for (int i = 0; i < n.x(); ++i) {
      const Eigen::Vector3d p =
          grid.origin_m + (i + 0.5) * grid.cell_u_m * grid.u_axis + (j + 0.5) * grid.cell_v_m * grid.v_axis;
      if (s.kind == GridKind::horizontal && !inside_less_band(outline, p.head<2>(), s.border_m)) {
        ++grid.outside_outline;
        continue;
      }
      const bool band = s.band_width_m > 0.0;
      if (band && caster.first_hit(p, -Eigen::Vector3d::UnitZ()).patch < 0 &&
          caster.first_hit(p + Eigen::Vector3d(0.37e-3, 0.61e-3, 0.0), -Eigen::Vector3d::UnitZ()).patch < 0) {
        ++grid.outside_room;  // a band is clipped to the room: no floor under it, no point
        continue;
      }
      if (inside_solid(caster, p + normal * caster.ray_offset_m())) {
        ++grid.inside_solid;
        continue;
      }
      // A ray straight down can slip through an edge between two floor triangles
      // (points on a regular grid often lie on one): no floor only if a second ray,
      // from a point 1 mm aside, misses too.
      if (s.kind == GridKind::horizontal && caster.first_hit(p, -Eigen::Vector3d::UnitZ()).patch < 0 &&
          caster.first_hit(p + Eigen::Vector3d(0.37e-3, 0.61e-3, 0.0), -Eigen::Vector3d::UnitZ()).patch < 0)
        ++no_floor;
      grid.points.push_back({p, normal});
      grid.cell_of_point.emplace_back(i, j);
    }
  if (no_floor > 0)
    throw ConfigError(located(s.loc, label + ": " + std::to_string(no_floor) + " of " +
                                         std::to_string(grid.points.size()) +
                                         " points have no floor under them (the grid lies outside the room)"));
  if (grid.points.empty())
    throw ConfigError(located(s.band_width_m > 0.0 ? s.band_loc : s.loc,
                              label + ": no point is left (" + std::to_string(grid.outside_outline) +
                                  " outside the outline less its band, " + std::to_string(grid.inside_solid) +
                                  " inside solid objects, " + std::to_string(grid.outside_room) + " outside the room)"));
  grid.area_m2 = static_cast<double>(grid.points.size()) * grid.cell_u_m * grid.cell_v_m;
  grid.border_m = s.border_m;
  grid.outline_polygon_m = std::move(lattice.outline.polygon);
  grid.outline_hole_m = std::move(lattice.outline.hole);
  grid.outline_triangles_m = std::move(lattice.outline.triangles);
  return std::move(grid);
}

static_assert(field_count<CalcGridSetting>() == 21, "CalcGridSetting changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const CalcGridSetting& s) {
  k.field("name", s.name).field("kind", s.kind).field("over_surface", s.over_surface).field("polygon_m", s.polygon_m);
  k.field("height_m", s.height_m).field("from_m", s.from_m).field("to_m", s.to_m).field("bottom_m", s.bottom_m);
  k.field("top_m", s.top_m).field("facing_left", s.facing_left).field("border_m", s.border_m);
  k.field("spacing_m", s.spacing_m).field("band_width_m", s.band_width_m);
  // Not max_points (it refuses a grid, never changes one), nor loc, shape_loc,
  // height_loc, border_loc, spacing_loc, max_points_loc, band_loc (where the values were written).
}

}  // namespace ilp
