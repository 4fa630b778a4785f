// The installation plan of the inverse-lighting result (plan.svg), as one standalone SVG
// document an installer can set out from: the architecture cut at a height (walls,
// columns, partitions filled or drawn thick; furniture below the cut as outlines from
// above), the goal surfaces and calculation grids coloured by illuminance, the
// luminaires at their real outline (turned, tilted ones with their aim) labelled L1,
// L2, ... where no label covers another or an outline, dimension chains (walls to the
// outer rows, spacings between rows) in m with 2 decimals, a colour legend, a
// luminaire schedule with heights above the floor, and a title block with a scale bar
// and the axes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "output/plan_architecture.h"
#include "output/plan_dimensions.h"

namespace ilp {

struct PlanLuminaire {
  std::string id;                                        // label (plain text; escaped on output)
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // centre; z is not drawn
  double size_m = 0.0;                                   // side of the square (when outline_m is empty)
  double flux_lm = 0.0;
  // The opening's real outline in the plane, scene frame (a rotated rectangle, a disc's
  // polygon, a tilted one's projection); empty: a square of size_m.
  std::vector<Eigen::Vector2d> outline_m;
  std::string product;                                   // shown in the tooltip when given
  double rotation_deg = 0.0;  // about the vertical: the luminaire's C0 from +x, counter-clockwise
  double tilt_deg = 0.0;      // aim: the nadir turned toward C0 by this; > 0 draws an arrow
  double above_floor_m = std::numeric_limits<double>::quiet_NaN();  // the schedule's height; NaN: unknown
};

// A calculation grid's values on the plan: each point's cell coloured on the plan's scale.
struct PlanGrid {
  std::string name;
  std::vector<Eigen::Vector2d> points_m;               // the points, in plan
  Eigen::Vector2d cell_m = Eigen::Vector2d::Zero();    // the cell each stands for (> 0 to draw cells)
  std::vector<double> lux;                             // one per point, on goal_lux's basis
  std::string see;                                     // the file with its values, e.g. "isolux_work_plane.png"
};

struct PlanView {
  std::string title;                  // e.g. "office: optimal layout, total 152 W" (plain text)
  std::vector<int> goal_patches;      // patches coloured by illuminance (goal surfaces)
  Eigen::VectorXd goal_lux;           // one value per goal patch; NaN: drawn grey
  std::vector<int> outline_patches;   // patches whose top view shows the room (e.g. the floor); empty: every patch
  std::vector<PlanLuminaire> luminaires;
  std::vector<PlanGrid> grids = {};
  PlanArchitecture architecture = {};  // cut_height_m 0: no architecture drawn
  // Values drawn are goal_lux (and grid lux) x this, in (0, 1]; below 1 the legend says
  // "maintained".
  double maintenance_factor = 1.0;
  bool dimensions = true;             // dimension chains of the luminaire centres
  std::vector<std::string> title_block = {};  // first line bold: job; then products with count, layout, ...
};

// What the plan draws, laid out before any SVG is written (what the tests check).
struct PlanLayout {
  double width_px = 0.0, height_px = 0.0;
  Eigen::AlignedBox2d plan_px;                 // the plan's frame
  double scale_px_per_m = 1.0;
  std::vector<Eigen::AlignedBox2d> outline_px; // per luminaire: its drawn outline's box
  std::vector<Eigen::AlignedBox2d> label_px;   // per luminaire: its label's box (empty: not placed)
  std::vector<bool> leader;                    // per luminaire: the label has a leader line
  DimensionChain along_x, along_y;             // empty stops: no chain
  std::vector<std::string> along_x_text, along_y_text;  // the lengths as written ("2.00")
};

// Lays the plan out: x right, y up, metres at one scale on both axes (the plan at most
// 620 px wide and 640 px high), the x chain above the plan, the y chain right of it, the
// legend, schedule and title block in a column on the right. Dimension chains are drawn
// when `dimensions` is set and there are luminaires; walls are architecture.walls, else
// the outline's frame. Throws std::invalid_argument when goal_lux and goal_patches
// differ in size, a patch index is out of range, a luminaire has a non-finite position,
// size or flux or a negative size, a grid has not one value per point, or the
// maintenance factor is outside (0, 1].
PlanLayout plan_svg_layout(const Scene& scene, const PlanView& view);

// The plan as SVG (deterministic, locale-independent numbers). Throws as plan_svg_layout.
std::string render_plan_svg(const Scene& scene, const PlanView& view);

// Metres with exactly 2 decimals ("2.00", "0.75"): how dimensions are written.
std::string metres_2(double v);

}  // namespace ilp
