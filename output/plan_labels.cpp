#include "output/plan_labels.h"

#include <array>

namespace ilp {
namespace {

using Box = Eigen::AlignedBox2d;
using V2 = Eigen::Vector2d;

// The label's box at ring distance d from the anchor in direction (sx, sy), each -1, 0
// or 1: beside the anchor's side (0 along that axis: centred on the anchor).
Box candidate(const Box& anchor, const V2& size, int sx, int sy, double d) {
  V2 centre = anchor.center();
  const V2 half = 0.5 * size;
  if (sx != 0) centre.x() = sx > 0 ? anchor.max().x() + d + half.x() : anchor.min().x() - d - half.x();
  if (sy != 0) centre.y() = sy > 0 ? anchor.max().y() + d + half.y() : anchor.min().y() - d - half.y();
  return Box(centre - half, centre + half);
}

}  // namespace

bool boxes_overlap(const Box& a, const Box& b) {
  return !a.isEmpty() && !b.isEmpty() && a.min().x() <= b.max().x() && b.min().x() <= a.max().x() &&
         a.min().y() <= b.max().y() && b.min().y() <= a.max().y();
}

std::vector<PlacedLabel> place_labels(const std::vector<LabelRequest>& requests, const std::vector<Box>& obstacles_px,
                                      const Box& bounds_px, const LabelPlacementOptions& options) {
  // Right, left, above, below (y down), then the four corners.
  constexpr std::array<std::array<int, 2>, 8> kDirections = {
      {{1, 0}, {-1, 0}, {0, -1}, {0, 1}, {1, -1}, {-1, -1}, {1, 1}, {-1, 1}}};
  std::vector<Box> taken = obstacles_px;
  for (const LabelRequest& r : requests) taken.push_back(r.anchor_px);
  std::vector<PlacedLabel> out(requests.size());
  for (std::size_t k = 0; k < requests.size(); ++k) {
    const LabelRequest& r = requests[k];
    for (int ring = 0; ring < options.rings && !out[k].placed; ++ring) {
      const double d = options.gap_px + ring * options.ring_step_px;
      for (const auto& [sx, sy] : kDirections) {
        const Box b = candidate(r.anchor_px, r.size_px, sx, sy, d);
        if (!bounds_px.contains(b)) continue;
        bool free = true;
        for (const Box& t : taken)
          if (boxes_overlap(t, b)) {
            free = false;
            break;
          }
        if (!free) continue;
        out[k] = {true, b, ring > 0};
        taken.push_back(b);
        break;
      }
    }
  }
  return out;
}

}  // namespace ilp
