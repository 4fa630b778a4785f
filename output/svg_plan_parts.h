// Pieces shared by the plan-like SVG writers of this module (plan_svg.cpp,
// isolux_plan.cpp): locale-independent number formatting, the mapping from metres
// to px, text elements, axis ticks in metres, a scale bar and the colour map's
// gradient for legends.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <string_view>

namespace ilp::svg {

// v with `decimals` fixed decimals (0 to 12), trailing zeros dropped, never "-0"
// (std::to_chars: independent of the C++ and C locales).
std::string fixed(double v, int decimals);

// A coordinate in px (2 decimals).
std::string px(double v);

// "x,y" in px.
std::string xy(double x, double y);

// 3 significant digits but whole numbers from 100 up and at most 3 decimals: "1500",
// "437", "62.5", "0.125", "0.001" (so 1.3e-8 lx reads "0").
std::string significant(double v);

// The fewest decimals (up to 12) that give v to within a millionth of `resolution`.
std::string exact(double v, double resolution);

// The smallest of 1, 2, 5 x 10^n that is >= v > 0.
double nice_step(double v);

// A plan's mapping from metres (x right, y up) to SVG px (x right, y down), one
// scale on both axes.
struct PlanFrame {
  Eigen::AlignedBox2d extent_m;
  double scale_px_per_m = 1.0;
  double left_px = 0.0, top_px = 0.0;

  double x_px(double x_m) const { return left_px + (x_m - extent_m.min().x()) * scale_px_per_m; }
  double y_px(double y_m) const { return top_px + (extent_m.max().y() - y_m) * scale_px_per_m; }
  Eigen::Vector2d to_px(const Eigen::Vector2d& p_m) const { return {x_px(p_m.x()), y_px(p_m.y())}; }
  double width_px() const { return extent_m.sizes().x() * scale_px_per_m; }
  double height_px() const { return extent_m.sizes().y() * scale_px_per_m; }
};

// <text> at (x, y) px with the anchor ("start", "middle", "end"), `text` escaped;
// `extra` is inserted verbatim among the attributes (e.g. " font-size=\"15\"").
std::string text_element(double x, double y, std::string_view anchor, const std::string& text,
                         std::string_view extra = "");

// Ticks along the frame's bottom and left edges at a 1-2-5 step in metres that keeps
// labels apart, their labels, and the axis labels centred below and left of the frame
// (the left one turned by -90 degrees at x = 16 px).
std::string plan_axes(const PlanFrame& f, std::string_view x_label = "x (m)", std::string_view y_label = "y (m)");

// A 1-2-5 length of 64 to 160 px drawn 50 px below the frame, labelled "<length> m".
std::string plan_scale_bar(const PlanFrame& f);

// A <linearGradient id="`id`"> running bottom (0) to top (1) through colour_map, with
// stops at every 60th, which include the colour map's knots, so a bar filled with it
// interpolates exactly as colour_map does. Goes inside <defs>.
std::string colour_map_gradient(std::string_view id);

}  // namespace ilp::svg
