#include "output/plan_architecture.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "output/contours.h"

namespace ilp {
namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

double cross(const V2& a, const V2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Points welded within `weld` of one another: each new point takes the id of the first
// node within weld in its own or a neighbouring hash cell.
class Welder {
 public:
  explicit Welder(double weld) : weld_(weld) {}

  int id(const V2& p) {
    const std::int64_t cx = cell(p.x()), cy = cell(p.y());
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find({cx + dx, cy + dy});
        if (it == cells_.end()) continue;
        for (int n : it->second)
          if ((nodes_[static_cast<std::size_t>(n)] - p).norm() <= weld_) return n;
      }
    nodes_.push_back(p);
    const int n = static_cast<int>(nodes_.size()) - 1;
    cells_[{cx, cy}].push_back(n);
    return n;
  }
  const V2& node(int n) const { return nodes_[static_cast<std::size_t>(n)]; }

 private:
  std::int64_t cell(double v) const { return static_cast<std::int64_t>(std::floor(v / weld_)); }
  double weld_;
  std::vector<V2> nodes_;
  std::map<std::pair<std::int64_t, std::int64_t>, std::vector<int>> cells_;
};

// The segment of one triangle at height z, material on its left; false when it does not cross.
bool cut_triangle(const Triangle3& t, double z, V2& a, V2& b) {
  std::array<bool, 3> above{};
  for (int k = 0; k < 3; ++k) above[k] = t[k].z() >= z;
  if (above[0] == above[1] && above[1] == above[2]) return false;
  std::array<V2, 2> hits;
  int n = 0;
  for (int k = 0; k < 3; ++k) {
    const V3& p = t[k];
    const V3& q = t[(k + 1) % 3];
    if (above[k] == above[(k + 1) % 3]) continue;
    const double s = (z - p.z()) / (q.z() - p.z());
    hits[n++] = (p + s * (q - p)).head<2>();
  }
  const V3 normal = (t[1] - t[0]).cross(t[2] - t[0]);
  const V2 left_dir(-normal.y(), normal.x());  // the direction along which -normal lies on the left
  a = hits[0];
  b = hits[1];
  if ((b - a).dot(left_dir) < 0.0) std::swap(a, b);
  return true;
}

struct Edge {
  int from = 0, to = 0;
};

// Drops points within weld of the line through their neighbours (and repeated points).
std::vector<V2> simplify_collinear(const std::vector<V2>& points, bool closed, double weld) {
  std::vector<V2> out = points;
  bool changed = true;
  while (changed && out.size() > (closed ? 3u : 2u)) {
    changed = false;
    for (std::size_t k = 0; k < out.size() && out.size() > (closed ? 3u : 2u); ++k) {
      if (!closed && (k == 0 || k + 1 == out.size())) continue;
      const V2& prev = out[(k + out.size() - 1) % out.size()];
      const V2& next = out[(k + 1) % out.size()];
      const V2 d = next - prev;
      const double len = d.norm();
      const bool drop = len <= weld ? (out[k] - prev).norm() <= weld
                                    : std::abs(cross(d, out[k] - prev)) / len <= weld &&
                                          (out[k] - prev).dot(d) >= 0.0 && (out[k] - next).dot(-d) >= 0.0;
      if (drop) {
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(k));
        changed = true;
      }
    }
  }
  return out;
}

// The Douglas-Peucker helpers of union_outline.
double segment_distance(const V2& p, const V2& a, const V2& b) {
  const V2 d = b - a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * d)).norm();
}

void simplify(const std::vector<V2>& pts, std::size_t first, std::size_t last, double tolerance, std::vector<V2>& out) {
  double worst = -1.0;
  std::size_t at = first;
  for (std::size_t k = first + 1; k < last; ++k)
    if (const double d = segment_distance(pts[k], pts[first], pts[last]); d > worst) {
      worst = d;
      at = k;
    }
  if (worst > tolerance) {
    simplify(pts, first, at, tolerance, out);
    simplify(pts, at, last, tolerance, out);
  } else {
    out.push_back(pts[last]);
  }
}

// A closed ring simplified: split at the point farthest from the first, each half by Douglas-Peucker.
Ring2 simplify_ring(const Ring2& ring, double tolerance) {
  if (ring.size() < 4) return ring;
  std::size_t far = 0;
  for (std::size_t k = 1; k < ring.size(); ++k)
    if ((ring[k] - ring[0]).squaredNorm() > (ring[far] - ring[0]).squaredNorm()) far = k;
  std::vector<V2> closed = ring;
  closed.push_back(ring[0]);
  std::vector<V2> out{ring[0]};
  simplify(closed, 0, far, tolerance, out);
  simplify(closed, far, closed.size() - 1, tolerance, out);
  out.pop_back();  // the first point again
  return out;
}

// Even-odd point in polygon.
bool inside(const V2& p, const std::vector<V2>& polygon) {
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const V2& a = polygon[i];
    const V2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

bool mesh_patch(const Scene& scene, const Patch& p) {
  const Surface& s = scene.surfaces[static_cast<std::size_t>(p.surface)];
  return !s.is_luminaire() && !s.is_virtual;
}

std::vector<Triangle3> scene_triangles(const Scene& scene) {
  std::vector<Triangle3> out;
  for (const Patch& p : scene.patches)
    if (mesh_patch(scene, p)) out.push_back(p.vertices_m);
  return out;
}

}  // namespace

std::vector<SectionLine> section_cut(const std::vector<Triangle3>& triangles, double cut_z_m, double weld_m) {
  if (!(weld_m > 0.0) || !std::isfinite(weld_m) || !std::isfinite(cut_z_m))
    throw std::invalid_argument("section_cut: the weld distance must be > 0 and the cut height finite");
  Welder welder(weld_m);
  std::vector<Edge> edges;
  for (const Triangle3& t : triangles) {
    V2 a, b;
    if (!cut_triangle(t, cut_z_m, a, b)) continue;
    const Edge e{welder.id(a), welder.id(b)};
    if (e.from != e.to) edges.push_back(e);
  }
  std::map<int, std::vector<std::size_t>> out_of, into;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    out_of[edges[e].from].push_back(e);
    into[edges[e].to].push_back(e);
  }
  std::vector<bool> used(edges.size(), false);
  // An unused edge at node n: in the walk's direction first (forward: leaving n), else
  // against it; `other` is its far node.
  const auto take = [&](int n, bool forward, int& other, std::size_t& edge) {
    const std::vector<std::size_t>& with = forward ? out_of[n] : into[n];
    const std::vector<std::size_t>& against = forward ? into[n] : out_of[n];
    for (const std::vector<std::size_t>* list : {&with, &against})
      for (std::size_t e : *list)
        if (!used[e]) {
          used[e] = true;
          edge = e;
          other = edges[e].from == n ? edges[e].to : edges[e].from;
          return true;
        }
    return false;
  };
  std::vector<SectionLine> lines;
  for (std::size_t start = 0; start < edges.size(); ++start) {
    if (used[start]) continue;
    used[start] = true;
    std::vector<int> chain{edges[start].from, edges[start].to};
    std::vector<std::size_t> chain_edges{start};
    bool closed = false;
    int other = 0;
    std::size_t edge = 0;
    while (!closed && take(chain.back(), true, other, edge)) {
      chain_edges.push_back(edge);
      if (other == chain.front()) closed = true;
      else chain.push_back(other);
    }
    while (!closed && take(chain.front(), false, other, edge)) {
      chain_edges.push_back(edge);
      if (other == chain.back()) closed = true;
      else chain.insert(chain.begin(), other);
    }
    SectionLine line;
    line.closed = closed && chain.size() >= 3;
    for (int n : chain) line.points_m.push_back(welder.node(n));
    if (line.closed) {
      double doubled = 0.0;
      for (std::size_t e : chain_edges) doubled += cross(welder.node(edges[e].from), welder.node(edges[e].to));
      line.signed_area_m2 = 0.5 * doubled;
    }
    line.points_m = simplify_collinear(line.points_m, line.closed, weld_m);
    if (line.closed && line.points_m.size() < 3) line.closed = false, line.signed_area_m2 = 0.0;
    lines.push_back(std::move(line));
  }
  return lines;
}

bool section_material(const SectionLine& line, const std::vector<SectionLine>& section) {
  constexpr double kLeastArea_m2 = 1e-6;
  if (!line.closed || std::abs(line.signed_area_m2) < kLeastArea_m2 || line.points_m.empty()) return false;
  if (line.signed_area_m2 > 0.0) return true;
  for (const SectionLine& outer : section)
    if (outer.closed && outer.signed_area_m2 > kLeastArea_m2 && inside(line.points_m.front(), outer.points_m)) return true;
  return false;
}

std::vector<Ring2> union_outline(const std::vector<Triangle2>& triangles, int cells) {
  Eigen::AlignedBox2d box;
  for (const Triangle2& t : triangles)
    for (const V2& v : t) box.extend(v);
  if (box.isEmpty() || !(box.sizes().maxCoeff() > 0.0)) return {};
  const double cell = box.sizes().maxCoeff() / std::max(cells, 8);
  LatticeField field;
  field.nx = static_cast<int>(std::ceil(box.sizes().x() / cell)) + 3;
  field.ny = static_cast<int>(std::ceil(box.sizes().y() / cell)) + 3;
  field.origin_m = box.min() - V2::Constant(cell);
  field.spacing_m = V2::Constant(cell);
  field.values.assign(static_cast<std::size_t>(field.nx) * static_cast<std::size_t>(field.ny), 0.0);
  const double eps = 1e-9 * cell * cell;
  for (const Triangle2& t : triangles) {
    const double area = cross(t[1] - t[0], t[2] - t[0]);
    if (area == 0.0) continue;
    const double sign = area > 0.0 ? 1.0 : -1.0;
    Eigen::AlignedBox2d tb;
    for (const V2& v : t) tb.extend(v);
    const int i0 = std::max(0, static_cast<int>(std::floor((tb.min().x() - field.origin_m.x()) / cell)));
    const int j0 = std::max(0, static_cast<int>(std::floor((tb.min().y() - field.origin_m.y()) / cell)));
    const int i1 = std::min(field.nx - 1, static_cast<int>(std::ceil((tb.max().x() - field.origin_m.x()) / cell)));
    const int j1 = std::min(field.ny - 1, static_cast<int>(std::ceil((tb.max().y() - field.origin_m.y()) / cell)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const V2 p = field.node_m(i, j);
        bool inside = true;
        for (int e = 0; e < 3 && inside; ++e) inside = sign * cross(t[(e + 1) % 3] - t[e], p - t[e]) >= -eps;
        if (inside) field.values[static_cast<std::size_t>(j) * field.nx + i] = 1.0;
      }
  }
  std::vector<Ring2> out;
  for (const ContourLine& line : contour_lines(field, 0.5))
    out.push_back(line.closed ? simplify_ring(line.points_m, 0.5 * cell) : line.points_m);
  return out;
}

PlanArchitecture plan_architecture(const Scene& scene, const ArchitectureOptions& o) {
  if (!(o.cut_height_m > 0.0) || !std::isfinite(o.cut_height_m) || !std::isfinite(o.floor_z_m) ||
      !(o.weld_m > 0.0) || std::isinf(o.wall_cut_height_m))
    throw std::invalid_argument("plan_architecture: the cut height must be > 0 and the floor and weld finite");
  PlanArchitecture a;
  a.floor_z_m = o.floor_z_m;
  a.cut_height_m = o.cut_height_m;
  const double cut_z = o.floor_z_m + o.cut_height_m;
  const std::vector<Triangle3> triangles = scene_triangles(scene);
  a.section = section_cut(triangles, cut_z, o.weld_m);
  if (std::isfinite(o.wall_cut_height_m)) a.walls = section_cut(triangles, o.floor_z_m + o.wall_cut_height_m, o.weld_m);
  // Per surface, what faces up between the floor and the cut.
  std::map<int, std::vector<Triangle2>> up;
  for (const Patch& p : scene.patches) {
    if (!mesh_patch(scene, p) || p.normal.z() < o.up_normal_min) continue;
    bool between = true;
    for (const V3& v : p.vertices_m) between = between && v.z() > o.floor_z_m + o.furniture_min_m && v.z() < cut_z;
    if (between) up[p.surface].push_back({p.vertices_m[0].head<2>(), p.vertices_m[1].head<2>(), p.vertices_m[2].head<2>()});
  }
  for (const auto& [surface, list] : up)
    for (Ring2& ring : union_outline(list, o.outline_cells))
      if (ring.size() >= 3) a.furniture.push_back(std::move(ring));
  return a;
}

}  // namespace ilp
