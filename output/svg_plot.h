// A small, dependency-free SVG line-chart writer for results such as "error (%)
// against build time (s)": a few series of points on linear or base-10 logarithmic
// axes, written as one standalone SVG document.
#pragma once

#include <string>
#include <vector>

namespace ilp {

// One line of the chart: points joined in the given order, each with a marker.
// A series without points is listed in the legend only.
struct PlotSeries {
  std::string label;         // legend text (plain text; escaped on output)
  std::vector<double> x, y;  // same size
};

struct PlotAxes {
  std::string title, x_label, y_label;  // plain text; empty: left out
  bool x_log = false, y_log = false;    // base-10 logarithmic axes
};

// Returns a complete standalone SVG document (800 x 480 px): frame, grid and ticks
// at "nice" values (1-2-5 steps on linear axes; decades, with 2 and 5 labelled too
// where they fit, on log axes), tick labels, axis labels, title, one colour and
// marker shape per series, and a legend right of the plot (labels longer than 32
// characters are shortened there, in full in its tooltip). The axes cover every
// point with a small margin; a single value is given a range around it. Throws
// std::invalid_argument for x and y of different sizes, non-finite values, or
// values <= 0 on a log axis.
std::string render_svg_plot(const PlotAxes& axes, const std::vector<PlotSeries>& series);

}  // namespace ilp
