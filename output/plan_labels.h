// Label placement for plans: each label is tried at candidate spots around what it
// names (right, left, above, below, then the corners, then the same rings farther
// out), and takes the first spot inside the drawing that overlaps no other label and
// no obstacle (every named thing's box among them). A label away from its thing gets
// a leader line. Deterministic: labels are placed in the order given.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace ilp {

struct LabelRequest {
  Eigen::AlignedBox2d anchor_px;                          // what the label names (px, y down)
  Eigen::Vector2d size_px = Eigen::Vector2d::Zero();      // the label's box, margin included
};

struct PlacedLabel {
  bool placed = false;
  Eigen::AlignedBox2d box_px;   // where it went (empty when not placed)
  bool leader = false;          // beyond the first ring: draw a line to the anchor
};

struct LabelPlacementOptions {
  double gap_px = 2.0;      // the first ring's distance from the anchor
  double ring_step_px = 7.0;
  int rings = 14;           // the farthest ring: gap + (rings - 1) x step
};

// One PlacedLabel per request. A placed label lies inside bounds_px and overlaps no
// obstacle, no request's anchor and no other placed label (boxes touching at an edge
// count as overlapping, so placed boxes are disjoint with room between them). A label
// for which no candidate fits is not placed.
std::vector<PlacedLabel> place_labels(const std::vector<LabelRequest>& requests,
                                      const std::vector<Eigen::AlignedBox2d>& obstacles_px,
                                      const Eigen::AlignedBox2d& bounds_px, const LabelPlacementOptions& options = {});

// True when the boxes share any point (their edges included).
bool boxes_overlap(const Eigen::AlignedBox2d& a, const Eigen::AlignedBox2d& b);

}  // namespace ilp
