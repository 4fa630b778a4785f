#include "output/contours.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace ilp {
namespace {

// Edges of the lattice, numbered so that each is shared by the squares on its two
// sides: the horizontal edge from node (i, j) to (i + 1, j) is 2 (j nx + i), the
// vertical edge from (i, j) to (i, j + 1) is 2 (j nx + i) + 1.
using EdgeId = std::int64_t;

struct Segment {
  std::array<EdgeId, 2> edges;
  std::array<Eigen::Vector2d, 2> points_m;
};

void check(const LatticeField& f, double level) {
  if (f.nx < 0 || f.ny < 0)
    throw std::invalid_argument("contour_lines: negative lattice size " + std::to_string(f.nx) + " x " +
                                std::to_string(f.ny));
  if (f.values.size() != static_cast<std::size_t>(f.nx) * static_cast<std::size_t>(f.ny))
    throw std::invalid_argument("contour_lines: " + std::to_string(f.values.size()) + " values for a " +
                                std::to_string(f.nx) + " x " + std::to_string(f.ny) + " lattice");
  if (!(f.spacing_m.x() > 0.0) || !(f.spacing_m.y() > 0.0) || !f.spacing_m.allFinite() || !f.origin_m.allFinite())
    throw std::invalid_argument("contour_lines: the spacing must be finite and > 0 and the origin finite");
  if (!std::isfinite(level)) throw std::invalid_argument("contour_lines: the level must be finite");
}

// The segments of every square, in row-major square order.
std::vector<Segment> square_segments(const LatticeField& f, double level) {
  std::vector<Segment> segments;
  const auto value = [&](int i, int j) { return f.values[static_cast<std::size_t>(j) * f.nx + i]; };
  for (int j = 0; j + 1 < f.ny; ++j) {
    for (int i = 0; i + 1 < f.nx; ++i) {
      // Corners counter-clockwise from the lower left: 0 (i, j), 1 (i+1, j), 2 (i+1, j+1), 3 (i, j+1).
      const std::array<double, 4> v = {value(i, j), value(i + 1, j), value(i + 1, j + 1), value(i, j + 1)};
      if (std::isnan(v[0]) || std::isnan(v[1]) || std::isnan(v[2]) || std::isnan(v[3])) continue;
      const std::array<Eigen::Vector2d, 4> p = {f.node_m(i, j), f.node_m(i + 1, j), f.node_m(i + 1, j + 1),
                                                f.node_m(i, j + 1)};
      const EdgeId base = 2 * (static_cast<EdgeId>(j) * f.nx + i);
      // Side k joins corner k to corner k+1: bottom, right, top, left.
      const std::array<EdgeId, 4> edge = {base, base + 2 * 1 + 1, base + 2 * static_cast<EdgeId>(f.nx), base + 1};
      int mask = 0;
      for (int k = 0; k < 4; ++k)
        if (v[k] >= level) mask |= 1 << k;
      if (mask == 0 || mask == 15) continue;
      const auto crossing = [&](int side) {
        const int a = side, b = (side + 1) % 4;
        const double t = (level - v[a]) / (v[b] - v[a]);  // v[a], v[b] on different sides: no division by 0
        return Eigen::Vector2d(p[a] + t * (p[b] - p[a]));
      };
      const auto add = [&](int s0, int s1) { segments.push_back({{edge[s0], edge[s1]}, {crossing(s0), crossing(s1)}}); };
      const bool centre_above = 0.25 * (v[0] + v[1] + v[2] + v[3]) >= level;
      switch (mask) {
        case 1: case 14: add(3, 0); break;
        case 2: case 13: add(0, 1); break;
        case 3: case 12: add(3, 1); break;
        case 4: case 11: add(1, 2); break;
        case 6: case 9: add(0, 2); break;
        case 7: case 8: add(2, 3); break;
        case 5:  // corners 0 and 2 above
          if (centre_above) { add(0, 1); add(2, 3); } else { add(3, 0); add(1, 2); }
          break;
        case 10:  // corners 1 and 3 above
          if (centre_above) { add(3, 0); add(1, 2); } else { add(0, 1); add(2, 3); }
          break;
        default: break;
      }
    }
  }
  return segments;
}

}  // namespace

std::vector<ContourLine> contour_lines(const LatticeField& field, double level) {
  check(field, level);
  const std::vector<Segment> segments = square_segments(field, level);
  // Each edge point belongs to at most two segments (the squares either side).
  std::unordered_map<EdgeId, std::array<int, 2>> at_edge;
  at_edge.reserve(2 * segments.size());
  for (int s = 0; s < static_cast<int>(segments.size()); ++s)
    for (EdgeId e : segments[s].edges) {
      auto [it, inserted] = at_edge.try_emplace(e, std::array<int, 2>{s, -1});
      if (!inserted) it->second[1] = s;
    }
  const auto other = [&](EdgeId e, int s) {
    const std::array<int, 2>& pair = at_edge.at(e);
    return pair[0] == s ? pair[1] : pair[0];
  };

  std::vector<bool> used(segments.size(), false);
  std::vector<ContourLine> lines;
  for (int start = 0; start < static_cast<int>(segments.size()); ++start) {
    if (used[start]) continue;
    used[start] = true;
    // Walk backwards from the start segment's first edge to the line's beginning (or
    // all the way round), then forwards from there.
    int s = start, side = 0;  // leave segment s through its edge `side`
    bool closed = false;
    for (;;) {
      const int next = other(segments[s].edges[side], s);
      if (next < 0) break;
      if (next == start) { closed = true; break; }
      if (used[next]) break;  // not reached: an edge point joins two segments at most
      used[next] = true;
      side = segments[next].edges[0] == segments[s].edges[side] ? 1 : 0;
      s = next;
    }
    // s is the line's first segment, leaving it through `side` leads backwards (or,
    // when closed, s is start's predecessor chain end). Walk forwards from s.
    ContourLine line;
    line.level = level;
    line.closed = closed;
    int entry_side = closed ? 1 : side;  // the edge by which the walk enters s
    if (closed) { s = start; entry_side = 0; }
    const int first = s;
    for (;;) {
      const int exit_side = 1 - entry_side;
      line.points_m.push_back(segments[s].points_m[entry_side]);
      const EdgeId exit_edge = segments[s].edges[exit_side];
      const int next = other(exit_edge, s);
      if (next < 0 || next == first) {
        if (!closed) line.points_m.push_back(segments[s].points_m[exit_side]);
        break;
      }
      used[next] = true;
      entry_side = segments[next].edges[0] == exit_edge ? 0 : 1;
      s = next;
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

}  // namespace ilp
