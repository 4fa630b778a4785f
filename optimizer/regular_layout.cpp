#include "optimizer/regular_layout.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace ilp {
namespace {

constexpr int kMaxBays = 10000;
// A zone narrower than this along an axis is a line (wall-mounted luminaires): one
// row or column across it.
constexpr double kLineM = 1e-6;
// What one search may enumerate: arrangements, and their members in all (memory).
constexpr std::size_t kMaxArrangements = 100000;
constexpr std::size_t kMaxMembers = 20000000;

// Adds an arrangement, refusing ranges too wide to enumerate.
void add(std::vector<Arrangement>& out, Arrangement a, std::size_t& members) {
  members += a.xy_m.size();
  out.push_back(std::move(a));
  if (out.size() > kMaxArrangements || members > kMaxMembers)
    throw std::length_error("the layout's ranges (rows, columns, per_row, edge_ratio, count) make more than " +
                            std::to_string(kMaxArrangements) + " arrangements or " + std::to_string(kMaxMembers) +
                            " luminaires in all: narrow them");
}

std::string text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// The spacing even_positions uses: the outer luminaires edge_ratio x spacing from the ends.
double even_spacing(double length, int n, double edge_ratio) { return length / (n - 1 + 2.0 * edge_ratio); }

// Whole modules between neighbours and the first centre on a module cell centre, the
// row kept as near its centre as the module allows.
void snap_to_module(std::vector<double>& positions, double module_m, double origin_m) {
  if (!(module_m > 0.0) || positions.empty()) return;
  const std::size_t n = positions.size();
  const double spacing = n > 1 ? (positions.back() - positions.front()) / static_cast<double>(n - 1) : 0.0;
  const double step = n > 1 ? std::max(1.0, std::round(spacing / module_m)) * module_m : 0.0;
  const double centre = 0.5 * (positions.front() + positions.back());
  const double first = centre - 0.5 * static_cast<double>(n - 1) * step;
  const double snapped = origin_m + std::round((first - origin_m) / module_m) * module_m;
  for (std::size_t i = 0; i < n; ++i) positions[i] = snapped + static_cast<double>(i) * step;
}

double spacing_of(const std::vector<double>& p) {
  return p.size() > 1 ? (p.back() - p.front()) / static_cast<double>(p.size() - 1) : 0.0;
}

// The grid of every x with every y, rows (y) outer.
Arrangement grid_of(std::string label, const std::vector<double>& xs, const std::vector<double>& ys) {
  Arrangement a;
  a.label = std::move(label);
  for (double y : ys)
    for (double x : xs) a.xy_m.emplace_back(x, y);
  a.spacing_m = Eigen::Vector2d(spacing_of(xs), spacing_of(ys));
  return a;
}

// The edge ratios tried: the largest, then down in steps of 0.05 to the smallest.
std::vector<double> edge_ratios(const RegularLayoutParams& p) {
  std::vector<double> out{p.edge_ratio_max};
  constexpr double kStep = 0.05;
  for (double r = p.edge_ratio_max - kStep; r > p.edge_ratio_min + 1e-9; r -= kStep) out.push_back(r);
  if (p.edge_ratio_min < p.edge_ratio_max) out.push_back(p.edge_ratio_min);
  return out;
}

std::string edges_label(const RegularLayoutParams& p, double rx, double ry) {
  if (p.edge_ratio_min == p.edge_ratio_max) return {};
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << ", edges " << rx << " / " << ry << " of a spacing";
  return out.str();
}

bool count_allowed(const LayoutSpec& layout, long n) { return n >= layout.count_min && n <= layout.count_max; }

void add_fields(const LayoutSpec& layout, const ArrangementFrame& frame, std::vector<Arrangement>& out,
                std::size_t& members) {
  const RegularLayoutParams& p = layout.regular;
  const Eigen::Vector2d lo = frame.zone_m.min(), hi = frame.zone_m.max(), size = hi - lo;
  const std::vector<double> ratios = edge_ratios(p);
  // A zone that is a line (luminaires on a wall) holds one row or column across it.
  const bool line_x = size.x() <= kLineM, line_y = size.y() <= kLineM;
  for (int r = p.rows.min; r <= p.rows.max; ++r)
    for (int c = p.columns.min; c <= p.columns.max; ++c) {
      if (!count_allowed(layout, static_cast<long>(r) * c)) continue;
      if ((line_x && c > 1) || (line_y && r > 1)) continue;
      // Square-ish cells at the preferred edges: the spacings along x and y within the ratio allowed.
      const double sx = even_spacing(size.x(), c, p.edge_ratio_max), sy = even_spacing(size.y(), r, p.edge_ratio_max);
      if (!line_x && !line_y && std::max(sx, sy) > p.max_spacing_ratio * std::min(sx, sy)) continue;
      for (double rx : c > 1 ? ratios : std::vector<double>{0.5})
        for (double ry : r > 1 ? ratios : std::vector<double>{0.5}) {
          std::vector<double> xs = even_positions(lo.x(), hi.x(), c, rx);
          std::vector<double> ys = even_positions(lo.y(), hi.y(), r, ry);
          snap_to_module(xs, frame.module_m, frame.module_origin_m.x());
          snap_to_module(ys, frame.module_m, frame.module_origin_m.y());
          add(out, grid_of(std::to_string(c) + " x " + std::to_string(r) + " field" + edges_label(p, rx, ry), xs, ys),
              members);
        }
    }
}

// Rows run along the luminaires' length (the longer side of their outline as placed).
void add_rows(const LayoutSpec& layout, const ArrangementFrame& frame, std::vector<Arrangement>& out,
              std::size_t& members) {
  const RegularLayoutParams& p = layout.regular;
  const Eigen::Vector2d lo = frame.zone_m.min(), hi = frame.zone_m.max();
  // Along the luminaires' length; on a zone that is a line (a wall), along the line.
  int along = frame.luminaire_extent_m.x() >= frame.luminaire_extent_m.y() ? 0 : 1;
  if (hi[along] - lo[along] <= kLineM && hi[1 - along] - lo[1 - along] > kLineM) along = 1 - along;
  const int across = 1 - along;
  const bool line = hi[across] - lo[across] <= kLineM;
  const double unit_m = frame.luminaire_extent_m[along];
  const std::vector<double> ratios = edge_ratios(p);
  for (int r = p.rows.min; r <= p.rows.max; ++r)
    for (int n = p.columns.min; n <= p.columns.max; ++n) {
      if (!count_allowed(layout, static_cast<long>(r) * n) || (line && r > 1)) continue;
      for (double r_along : p.continuous || n == 1 ? std::vector<double>{0.5} : ratios)
        for (double r_across : r > 1 ? ratios : std::vector<double>{0.5}) {
          std::vector<double> in_row;
          if (p.continuous) {
            const double centre = 0.5 * (lo[along] + hi[along]);
            for (int i = 0; i < n; ++i) in_row.push_back(centre + (i - 0.5 * (n - 1)) * unit_m);
          } else {
            in_row = even_positions(lo[along], hi[along], n, r_along);
            snap_to_module(in_row, frame.module_m, frame.module_origin_m[along]);
          }
          std::vector<double> rows_at = even_positions(lo[across], hi[across], r, r_across);
          snap_to_module(rows_at, frame.module_m, frame.module_origin_m[across]);
          const std::string label = std::to_string(r) + (r == 1 ? " row of " : " rows of ") + std::to_string(n) +
                                    (p.continuous ? " end to end" : "") + (along == 0 ? " along x" : " along y") +
                                    (along == 0 ? edges_label(p, r_along, r_across) : edges_label(p, r_across, r_along));
          add(out, along == 0 ? grid_of(label, in_row, rows_at) : grid_of(label, rows_at, in_row), members);
        }
    }
}

// n luminaires in a bay: a near-square sub-field, its longer side along the bay's.
Eigen::Vector2i bay_split(int n, const Eigen::Vector2d& module_m) {
  int short_side = 1;
  for (int d = 1; d * d <= n; ++d)
    if (n % d == 0) short_side = d;
  const int long_side = n / short_side;
  return module_m.x() >= module_m.y() ? Eigen::Vector2i(long_side, short_side) : Eigen::Vector2i(short_side, long_side);
}

void add_bays(const LayoutSpec& layout, const ArrangementFrame& frame, std::vector<Arrangement>& out,
              std::size_t& members) {
  const RegularLayoutParams& p = layout.regular;
  const Eigen::Vector2d m = p.bay_module_m, o = p.bay_origin_m;
  if (!(m.minCoeff() > 0.0)) throw std::invalid_argument("bays: the module must be > 0 along x and y");
  // Bays whose centre o + (i + 0.5) m lies in the zone.
  Eigen::Vector2i first, last;
  for (int axis = 0; axis < 2; ++axis) {
    first[axis] = static_cast<int>(std::ceil((frame.zone_m.min()[axis] - o[axis]) / m[axis] - 0.5 - 1e-9));
    last[axis] = static_cast<int>(std::floor((frame.zone_m.max()[axis] - o[axis]) / m[axis] - 0.5 + 1e-9));
  }
  const long bays = static_cast<long>(std::max(0, last.x() - first.x() + 1)) * std::max(0, last.y() - first.y() + 1);
  if (bays == 0) return;
  if (bays > kMaxBays) throw std::invalid_argument("bays: more than " + std::to_string(kMaxBays) + " bays in the zone");
  for (int n = p.per_bay.min; n <= p.per_bay.max; ++n) {
    if (!count_allowed(layout, bays * n)) continue;
    const Eigen::Vector2i split = bay_split(n, m);
    std::vector<double> xs, ys;
    for (int i = first.x(); i <= last.x(); ++i)
      for (double x : even_positions(o.x() + i * m.x(), o.x() + (i + 1) * m.x(), split.x(), 0.5)) xs.push_back(x);
    for (int j = first.y(); j <= last.y(); ++j)
      for (double y : even_positions(o.y() + j * m.y(), o.y() + (j + 1) * m.y(), split.y(), 0.5)) ys.push_back(y);
    Arrangement a = grid_of(std::to_string(n) + " per bay, " + std::to_string(bays) + " bays of " + text(m.x()) + " x " +
                                text(m.y()) + " m",
                            xs, ys);
    a.spacing_m = Eigen::Vector2d(m.x() / split.x(), m.y() / split.y());
    add(out, std::move(a), members);
  }
}

}  // namespace

std::vector<double> even_positions(double lo, double hi, int n, double edge_ratio) {
  std::vector<double> out;
  const double s = even_spacing(hi - lo, n, edge_ratio);
  for (int i = 0; i < n; ++i) out.push_back(lo + (edge_ratio + i) * s);
  return out;
}

std::vector<Arrangement> regular_arrangements(const LayoutSpec& layout, const ArrangementFrame& frame) {
  if (frame.zone_m.isEmpty()) throw std::invalid_argument("regular layout: the mounting zone is empty");
  std::vector<Arrangement> out;
  std::size_t members = 0;
  switch (layout.family) {
    case LayoutFamily::field: add_fields(layout, frame, out, members); break;
    case LayoutFamily::rows: add_rows(layout, frame, out, members); break;
    case LayoutFamily::bays: add_bays(layout, frame, out, members); break;
    default: throw std::invalid_argument("regular_arrangements: not a field, rows or bays layout");
  }
  std::ranges::stable_sort(out, {}, [](const Arrangement& a) { return a.xy_m.size(); });
  return out;
}

}  // namespace ilp
