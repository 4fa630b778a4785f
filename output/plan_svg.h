// A top view (plan) of a room for the inverse-lighting result, as one standalone SVG
// document: goal surfaces coloured by illuminance, the room outline, the luminaires
// with their flux, a colour legend and a scale bar.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace ilp {

struct PlanLuminaire {
  std::string id;                                        // label (plain text; escaped on output)
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // centre; z is not drawn
  double size_m = 0.0;                                   // side of the square (when outline_m is empty)
  double flux_lm = 0.0;
  // The opening's real outline in the plane, scene frame (a rotated rectangle, a disc's
  // polygon); empty: a square of size_m.
  std::vector<Eigen::Vector2d> outline_m;
  std::string product;                                   // shown in the tooltip when given
};

struct PlanView {
  std::string title;                  // e.g. "office: optimal layout, total 152 W" (plain text)
  std::vector<int> goal_patches;      // patches coloured by illuminance (goal surfaces)
  Eigen::VectorXd goal_lux;           // one value per goal patch; NaN: drawn grey
  std::vector<int> outline_patches;   // patches whose top view shows the room (e.g. the floor); empty: every patch
  std::vector<PlanLuminaire> luminaires;
};

// Returns the plan, x to the right and y up, metres at one scale on both axes, about
// 900 px wide (less for a room deeper than wide; the plan is at most 720 px high):
//  - the outline patches' xy projections filled light grey, framed by their bounding
//    rectangle (or every patch's, when outline_patches is empty), with axis ticks in m;
//  - each goal patch as a polygon filled by colour_map over colour_scale_for(goal_lux),
//    lower patches first so that desks cover the floor beneath them;
//  - each luminaire as its square (at least 4 px) with a cross, labelled with its id
//    and "<flux> lm";
//  - a vertical legend "illuminance (lx)" with 5 ticks and the goal's min and max;
//  - a scale bar of a 1-2-5 length in metres.
// The drawing spans the frame, the goal patches and the luminaires. Output is
// deterministic (numbers with fixed decimals, independent of the locale). Throws
// std::invalid_argument when goal_lux and goal_patches differ in size, a patch index
// is out of range, or a luminaire has a non-finite position, size or flux or a
// negative size.
std::string render_plan_svg(const Scene& scene, const PlanView& view);

}  // namespace ilp
