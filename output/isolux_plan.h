// The isolux plan of one calculation grid, as a designer hands it on: the grid's
// maintained illuminance as a colour fill on a scale tied to the goal's target,
// labelled isolines at fractions of the target, the values at a readable subset of
// the points, the room outline and the luminaires at their real size, axes in metres,
// a scale bar and a legend. SVG (pure) and PNG (through output/png_render.h).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <vector>

#include "output/colour_map.h"
#include "output/contours.h"
#include "output/plan_architecture.h"

namespace ilp {

// A luminaire as seen from above (or, for a vertical grid, projected on the grid's plane).
struct IsoluxLuminaire {
  std::string id;                                       // label on the plan (plain text)
  std::string product;                                  // in the tooltip; may be empty
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();   // in the plan's coordinates
  double length_m = 0.0, width_m = 0.0;                 // along its own x and y (>= 0); round: diameter = length_m
  double rotation_deg = 0.0;                            // its x axis from the plan's +x, counter-clockwise
  bool round = false;                                   // a disc rather than a rectangle
};

// One calculation grid for the plan. The points are the nodes of a regular lattice
// (the grid's cell centres): point (i, j), 0 <= i < nx, 0 <= j < ny, sits at
// origin_m + (i * spacing_m.x(), j * spacing_m.y()) and each stands for the cell of
// spacing_m around it.
struct IsoluxGridView {
  std::string name;                                    // the grid's name: the plan's heading
  std::string title;                                   // second line, e.g. "work plane 0.80 m: Em 512 lx, U0 0.64"
  int nx = 0, ny = 0;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // point (0, 0)
  Eigen::Vector2d spacing_m = Eigen::Vector2d::Ones(); // both > 0
  // nx * ny maintained values in lx (initial x maintenance_factor), row-major
  // (index j * nx + i); NaN where there is no point (inside a solid, outside the outline).
  std::vector<double> maintained_lux;
  std::vector<std::vector<Eigen::Vector2d>> room_outline_m;  // polygons (e.g. the floor's outline); may be empty
  std::vector<IsoluxLuminaire> luminaires;
  // The goal's maintained target Em (> 0): the colour scale runs 0 .. 2 x target and the
  // isolines sit at fractions of it. NaN: the grid has no target; the plan then takes
  // the grid's own average (of the finite values) and says so.
  double target_lux = std::numeric_limits<double>::quiet_NaN();
  double maintenance_factor = 1.0;  // in (0, 1]: stated in the legend
  std::string x_label = "x (m)", y_label = "y (m)";  // axis names (e.g. "along the wall (m)")
  // Direction of north as degrees clockwise from the plan's +y; NaN: no north arrow.
  double north_deg = std::numeric_limits<double>::quiet_NaN();
  // A horizontal grid's architecture in its plan coordinates (output/plan_architecture.h),
  // drawn over the cells and under the isolines, clipped to the plan; cut_height_m 0: none.
  PlanArchitecture architecture = {};
};

// The isoline levels for a reference (target) illuminance: 0.5, 0.6, 0.7, 0.8, 1, 1.2,
// 1.5 and 2 x reference, each but the reference itself rounded to 2 significant digits
// (500 lx: 250 300 350 400 500 600 750 1000). Throws std::invalid_argument unless
// reference_lux is finite and > 0.
std::vector<double> isolux_levels(double reference_lux);

// A label the plan writes, with the box it occupies (px, y down).
struct IsoluxLabel {
  enum class Kind { contour, value, luminaire };
  Kind kind = Kind::value;
  std::string text;
  Eigen::AlignedBox2d box_px;  // text plus its margin; no two labels' boxes intersect
  bool on_line = true;         // an isoline's label: centred on its line, or (false) beside a short one
};

// What the plan draws, computed before any SVG is written (and what the tests check).
struct IsoluxLayout {
  double width_px = 0.0, height_px = 0.0;     // the whole document
  Eigen::AlignedBox2d plan_px;                // the plan's frame in the document
  double scale_px_per_m = 1.0;                // the plan's scale, both axes
  double reference_lux = 0.0;                 // target_lux, or the grid's average without a target
  bool reference_is_target = true;
  ColourScale scale;                          // 0 .. 2 x reference_lux: never the hot spot
  std::vector<double> levels_lux;             // isolux_levels(reference_lux)
  std::vector<ContourLine> lines;             // every level's isolines, in metres
  std::vector<IsoluxLabel> labels;            // luminaire ids, then isoline values, then point values
  int value_step_x = 1, value_step_y = 1;     // values are printed at every n-th point (before collisions)
  double min_lux = 0.0, max_lux = 0.0;        // over the finite values (NaN when none)
  int min_point = -1, max_point = -1;         // index (j * nx + i) of the first min / max; -1 when none
  int points = 0;                             // finite values
};

// Lays the plan out: x right, y up, one scale on both axes (the plan about 700 px wide
// or at most 640 px high), the legend right of it. Isoline labels are placed on their
// lines (about one per 260 px of line, at least one per line where one fits), each on a
// spot where no other isoline crosses its box (a line too short to carry its number
// gets it beside its middle, where no line crosses it); point values at every n-th point with n
// chosen so that neighbouring values are at least 44 px apart; a label that would
// overlap one already placed (luminaire ids first, then isolines, then point values),
// a luminaire outline or the plan's edge is left out. Throws std::invalid_argument for
// maintained_lux not of nx * ny entries, a spacing not > 0, a target neither NaN nor
// > 0, a maintenance factor outside (0, 1], a non-finite coordinate or luminaire size, or
// a drawing (grid, room and luminaires) more than 100 km across.
IsoluxLayout isolux_plan_layout(const IsoluxGridView& view);

// The plan as one standalone SVG document (deterministic, locale-independent):
//  - the room outline's polygons filled light grey and framed, under everything;
//  - each point's cell filled by colour_map over 0 .. 2 x target (values above in the
//    top colour, as the legend says); no point: the grey shows through;
//  - the isolines (the target's line thicker), each labelled with its lux value;
//  - the architecture (furniture outlines thin, the section's material filled and its
//    lines thick) over the cells;
//  - point values, luminaire outlines (rotated rectangles, discs) with their ids;
//  - the minimum's point marked with an open triangle pointing down, the maximum's
//    with a filled one pointing up (no label covers them);
//  - axes in metres, a scale bar, an optional north arrow, and a legend "maintained
//    illuminance (lx)" with the maintenance factor, the target, the levels, and the
//    grid's min and max.
// Throws as isolux_plan_layout.
std::string isolux_plan_svg(const IsoluxGridView& view);

// Writes isolux_plan_svg(view) to path_svg and its rendering (2 px per SVG px) to
// path_png, each atomically (output/atomic_file.h); an empty path is skipped. Throws
// IlpError naming the file when a write or the rendering fails.
void write_isolux_plan(const std::string& path_svg, const std::string& path_png, const IsoluxGridView& view);

}  // namespace ilp
