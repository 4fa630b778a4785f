#include "output/plan_dimensions.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ilp {
namespace {

using V2 = Eigen::Vector2d;

// Distance along the unit direction dir from p to the nearest crossing of segment a-b
// (infinity when none ahead; a segment lying along the ray is not a crossing).
double ray_hit(const V2& p, const V2& dir, const V2& a, const V2& b) {
  const V2 e = b - a;
  const double denom = dir.x() * e.y() - dir.y() * e.x();
  if (std::abs(denom) < 1e-15) return std::numeric_limits<double>::infinity();
  const V2 w = a - p;
  const double t = (w.x() * e.y() - w.y() * e.x()) / denom;
  const double s = (w.x() * dir.y() - w.y() * dir.x()) / denom;
  if (t <= 1e-9 || s < 0.0 || s > 1.0) return std::numeric_limits<double>::infinity();
  return t;
}

double nearest_wall(const V2& p, const V2& dir, const std::vector<SectionLine>& walls) {
  double best = std::numeric_limits<double>::infinity();
  for (const SectionLine& l : walls) {
    const std::size_t n = l.points_m.size();
    for (std::size_t k = 0; k + 1 < n + (l.closed ? 1 : 0); ++k)
      best = std::min(best, ray_hit(p, dir, l.points_m[k], l.points_m[(k + 1) % n]));
  }
  return best;
}

}  // namespace

std::vector<double> DimensionChain::lengths_m() const {
  std::vector<double> out;
  for (std::size_t k = 1; k < stops_m.size(); ++k) out.push_back(stops_m[k] - stops_m[k - 1]);
  return out;
}

std::vector<double> distinct_positions(const std::vector<Eigen::Vector2d>& centres_m, int axis, double tolerance_m) {
  std::vector<double> all;
  for (const V2& c : centres_m) all.push_back(c[axis]);
  std::sort(all.begin(), all.end());
  std::vector<double> out;
  for (double v : all)
    if (out.empty() || v - out.back() > tolerance_m) out.push_back(v);
  return out;
}

DimensionChain dimension_chain(const std::vector<Eigen::Vector2d>& centres_m, int axis,
                               const std::vector<SectionLine>& walls, double tolerance_m) {
  DimensionChain chain;
  chain.axis = axis;
  const std::vector<double> rows = distinct_positions(centres_m, axis, tolerance_m);
  if (rows.empty()) return chain;
  V2 dir = V2::Zero();
  dir[axis] = 1.0;
  // The least distance to a wall from the members of the outer row, outward.
  const auto wall = [&](double row, double sign) {
    double best = std::numeric_limits<double>::infinity();
    for (const V2& c : centres_m)
      if (std::abs(c[axis] - row) <= tolerance_m) best = std::min(best, nearest_wall(c, sign * dir, walls));
    return best;
  };
  const double before = wall(rows.front(), -1.0), after = wall(rows.back(), 1.0);
  if (std::isfinite(before)) {
    chain.stops_m.push_back(rows.front() - before);
    chain.wall_first = true;
  }
  chain.stops_m.insert(chain.stops_m.end(), rows.begin(), rows.end());
  if (std::isfinite(after)) {
    chain.stops_m.push_back(rows.back() + after);
    chain.wall_last = true;
  }
  return chain;
}

}  // namespace ilp
