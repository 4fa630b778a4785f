#include "core/scene/contact_cuts.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace ilp {
namespace {

using V = Eigen::Vector3d;

// A vertex within this share of a patch's longest edge of a cutting line lies on it:
// no sliver thinner than that is made.
constexpr double kSnapRel = 1e-6;
// A segment shorter than this share of the patch's longest edge does not cut it: the
// outline of a thin chair leg or table foot (a few centimetres, drawn with many short
// sides) would cut a floor patch into dozens of pieces to account for a few per cent
// of its area (the classroom: 37 % more patches with them, 4 % without).
constexpr double kMinCutRel = 0.1;

V unit_normal(const Triangle3& t) { return (t[1] - t[0]).cross(t[2] - t[0]).normalized(); }

// Clips the segment [p, q] to triangle t (p and q in its plane): the part inside, with
// its ends, or false when less than `min_length` of it is inside.
bool clip_to_triangle(const Triangle3& t, const V& n, V& p, V& q, double min_length) {
  double t0 = 0.0, t1 = 1.0;
  const V d = q - p;
  for (int k = 0; k < 3; ++k) {
    const V inward = n.cross(t[(k + 1) % 3] - t[k]);  // in the plane, pointing into t (counter-clockwise)
    const double at_p = inward.dot(p - t[k]), rate = inward.dot(d);
    if (rate == 0.0) {
      if (at_p < 0.0) return false;
      continue;
    }
    const double cross = -at_p / rate;
    if (rate > 0.0) t0 = std::max(t0, cross);
    else t1 = std::min(t1, cross);
    if (t0 >= t1) return false;
  }
  const V a = p + t0 * d, b = p + t1 * d;
  if ((b - a).norm() <= min_length) return false;
  p = a;
  q = b;
  return true;
}

// Both ends within `tolerance` of the same edge line of t: the segment runs along t's
// boundary (a mesh neighbour's shared edge) and cuts nothing.
bool along_an_edge(const Triangle3& t, const V& n, const V& p, const V& q, double tolerance) {
  for (int k = 0; k < 3; ++k) {
    const V inward = n.cross(t[(k + 1) % 3] - t[k]).normalized();
    if (std::abs(inward.dot(p - t[k])) <= tolerance && std::abs(inward.dot(q - t[k])) <= tolerance) return true;
  }
  return false;
}

// Where triangle s meets the plane (n, through `origin`): its edges lying in the plane
// (all of them when s lies in it) or the segment where it crosses the plane.
void meeting_segments(const Triangle3& s, const V& n, const V& origin, double tolerance, std::vector<ContactSegment>& out) {
  std::array<double, 3> d{};
  for (int k = 0; k < 3; ++k) d[k] = n.dot(s[k] - origin);
  auto on = [&](int k) { return std::abs(d[k]) <= tolerance; };
  auto projected = [&](int k) -> V { return s[k] - d[k] * n; };
  // Wholly in front, or nowhere in front (behind, or touching from behind: it covers
  // nothing the face's front side shows).
  if ((d[0] > tolerance && d[1] > tolerance && d[2] > tolerance) || (d[0] <= tolerance && d[1] <= tolerance && d[2] <= tolerance && !(on(0) && on(1) && on(2))))
    return;
  if (on(0) && on(1) && on(2)) {  // in the plane: its outline
    for (int k = 0; k < 3; ++k) out.push_back({projected(k), projected((k + 1) % 3)});
    return;
  }
  // Points of s in the plane: its vertices on it and its edges' crossings.
  std::array<V, 4> points;
  int count = 0;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    if (on(k)) points[count++] = projected(k);
    if (!on(k) && !on(l) && (d[k] > 0.0) != (d[l] > 0.0)) {
      const V x = s[k] + (s[l] - s[k]) * (d[k] / (d[k] - d[l]));
      points[count++] = x - n.dot(x - origin) * n;
    }
  }
  if (count < 2) return;
  // Collinear: the two farthest apart.
  int best_i = 0, best_j = 1;
  double best = -1.0;
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j)
      if (const double len = (points[i] - points[j]).squaredNorm(); len > best) best = len, best_i = i, best_j = j;
  out.push_back({points[best_i], points[best_j]});
}

// A uniform grid over the triangles' bounds, each cell listing the triangles whose
// (tolerance-widened) bounds overlap it: about one cell per triangle.
class TriangleGrid {
 public:
  explicit TriangleGrid(const std::vector<Eigen::AlignedBox3d>& boxes) {
    Eigen::AlignedBox3d all;
    for (const auto& b : boxes) all.extend(b);
    origin_ = all.min();
    const V size = all.diagonal().cwiseMax(1e-9);
    const double n = std::max(1.0, static_cast<double>(boxes.size()));
    double cell = std::cbrt(size.prod() / n);
    for (;;) {  // a flat scene makes the cube root small: widen until the cells number about n
      for (int a = 0; a < 3; ++a) dims_[a] = static_cast<int>(std::max(1.0, std::ceil(size[a] / cell)));
      if (static_cast<double>(dims_[0]) * dims_[1] * dims_[2] <= 2.0 * n + 8.0) break;
      cell *= 1.25;
    }
    cell_ = size.cwiseQuotient(V(dims_[0], dims_[1], dims_[2]));
    cells_.resize(static_cast<std::size_t>(dims_[0]) * static_cast<std::size_t>(dims_[1]) * static_cast<std::size_t>(dims_[2]));
    for (std::size_t t = 0; t < boxes.size(); ++t)
      for_cells(boxes[t], [&](std::size_t c) { cells_[c].push_back(static_cast<int>(t)); });
  }
  // Calls f(list of triangles) for every cell `box` overlaps.
  template <class F>
  void visit(const Eigen::AlignedBox3d& box, const F& f) const {
    for_cells(box, [&](std::size_t c) { f(cells_[c]); });
  }

 private:
  template <class F>
  void for_cells(const Eigen::AlignedBox3d& box, const F& f) const {
    std::array<int, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::clamp(static_cast<int>(std::floor((box.min()[a] - origin_[a]) / cell_[a])), 0, dims_[a] - 1);
      hi[a] = std::clamp(static_cast<int>(std::floor((box.max()[a] - origin_[a]) / cell_[a])), 0, dims_[a] - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          f((static_cast<std::size_t>(z) * static_cast<std::size_t>(dims_[1]) + static_cast<std::size_t>(y)) *
                static_cast<std::size_t>(dims_[0]) +
            static_cast<std::size_t>(x));
  }

  V origin_ = V::Zero(), cell_ = V::Ones();
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<std::vector<int>> cells_;
};

// Twice the area of a planar polygon (its vector area's length).
double doubled_area(const std::vector<V>& polygon) {
  V sum = V::Zero();
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k) sum += (polygon[k] - polygon[0]).cross(polygon[k + 1] - polygon[0]);
  return sum.norm();
}

// Splits a convex polygon by the line through `p` with in-plane normal m into the parts
// on either side (a vertex within `snap` of the line belongs to both).
void split(const std::vector<V>& polygon, const V& p, const V& m, double snap, std::vector<V>& front, std::vector<V>& back) {
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const V& a = polygon[k];
    const V& b = polygon[(k + 1) % n];
    double da = m.dot(a - p), db = m.dot(b - p);
    if (std::abs(da) <= snap) da = 0.0;
    if (std::abs(db) <= snap) db = 0.0;
    if (da >= 0.0) front.push_back(a);
    if (da <= 0.0) back.push_back(a);
    if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0)) {
      const V x = a + (b - a) * (da / (da - db));
      front.push_back(x);
      back.push_back(x);
    }
  }
}

}  // namespace

std::vector<std::vector<ContactSegment>> contact_segments(const std::vector<Triangle3>& triangles,
                                                          const std::vector<int>& surface, double tolerance_m,
                                                          int threads) {
  if (surface.size() != triangles.size()) throw std::invalid_argument("contact_segments: one surface per triangle");
  std::vector<Eigen::AlignedBox3d> boxes(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (const V& v : triangles[t]) boxes[t].extend(v);
    boxes[t].min().array() -= tolerance_m;
    boxes[t].max().array() += tolerance_m;
  }
  const TriangleGrid grid(boxes);
  std::vector<std::vector<ContactSegment>> out(triangles.size());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 64), [&](const auto& range) {
      std::vector<int> near;
      std::vector<ContactSegment> meeting;
      for (std::size_t t = range.begin(); t != range.end(); ++t) {
        const Triangle3& tri = triangles[t];
        const V n = unit_normal(tri);
        near.clear();
        grid.visit(boxes[t], [&](const std::vector<int>& cell) {
          for (int s : cell)
            if (surface[static_cast<std::size_t>(s)] != surface[t] && boxes[t].intersects(boxes[static_cast<std::size_t>(s)]))
              near.push_back(s);
        });
        std::sort(near.begin(), near.end());
        near.erase(std::unique(near.begin(), near.end()), near.end());
        for (int s : near) {
          meeting.clear();
          meeting_segments(triangles[static_cast<std::size_t>(s)], n, tri[0], tolerance_m, meeting);
          for (ContactSegment seg : meeting)
            if (clip_to_triangle(tri, n, seg.a, seg.b, tolerance_m) && !along_an_edge(tri, n, seg.a, seg.b, tolerance_m))
              out[t].push_back(seg);
        }
      }
    });
  });
  return out;
}

bool cut_along_segments(const Triangle3& patch, const std::vector<ContactSegment>& segments, std::vector<Triangle3>& out) {
  const V n = unit_normal(patch);
  const double longest = std::max({(patch[1] - patch[0]).norm(), (patch[2] - patch[1]).norm(), (patch[0] - patch[2]).norm()});
  const double snap = kSnapRel * longest;
  Eigen::AlignedBox3d bounds;
  for (const V& v : patch) bounds.extend(v);
  bounds.min().array() -= snap;
  bounds.max().array() += snap;
  std::vector<std::vector<V>> pieces{{patch[0], patch[1], patch[2]}};
  std::vector<std::vector<V>> next;
  bool cut = false;
  for (const ContactSegment& seg : segments) {
    if ((seg.b - seg.a).norm() < kMinCutRel * longest) continue;
    Eigen::AlignedBox3d sb;
    sb.extend(seg.a).extend(seg.b);
    if (!bounds.intersects(sb)) continue;
    const V m = n.cross(seg.b - seg.a).normalized();  // the line's normal in the plane
    next.clear();
    for (std::vector<V>& piece : pieces) {
      // Cut only a piece the segment passes through (not one its line merely crosses).
      bool enters = false;
      for (std::size_t k = 1; k + 1 < piece.size() && !enters; ++k) {
        V p = seg.a, q = seg.b;
        enters = clip_to_triangle({piece[0], piece[k], piece[k + 1]}, n, p, q, snap);
      }
      std::vector<V> front, back;
      if (enters) split(piece, seg.a, m, snap, front, back);
      // Both parts must have area: a line along the piece's edge leaves it whole.
      if (front.size() >= 3 && back.size() >= 3 && doubled_area(front) > snap * longest &&
          doubled_area(back) > snap * longest) {
        next.push_back(std::move(front));
        next.push_back(std::move(back));
        cut = true;
      } else {
        next.push_back(std::move(piece));
      }
    }
    pieces.swap(next);
  }
  for (const std::vector<V>& piece : pieces)
    for (std::size_t k = 1; k + 1 < piece.size(); ++k) out.push_back({piece[0], piece[k], piece[k + 1]});
  return cut;
}

}  // namespace ilp
