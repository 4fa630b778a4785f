// SVG line charts: a well-formed document, escaped text, tick values on linear and
// log axes, degenerate ranges, and the input checks.
#include "output/svg_plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "tests/output/svg_checks.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::Contains;
using test::WellFormed;


// The contents of every <text> element, as written (still escaped).
std::vector<std::string> texts(const std::string& svg) {
  std::vector<std::string> out;
  for (std::size_t i = svg.find("<text"); i != std::string::npos; i = svg.find("<text", i + 1)) {
    const std::size_t start = svg.find('>', i) + 1;
    out.push_back(svg.substr(start, svg.find("</text>", start) - start));
  }
  return out;
}

bool has_text(const std::string& svg, const std::string& text) {
  const std::vector<std::string> all = texts(svg);
  return std::find(all.begin(), all.end(), text) != all.end();
}

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t i = text.find(part); i != std::string::npos; i = text.find(part, i + 1)) ++n;
  return n;
}

PlotSeries line(std::string label, std::vector<double> x, std::vector<double> y) {
  return {std::move(label), std::move(x), std::move(y)};
}

TEST(SvgPlot, IsAWellFormedStandaloneDocument) {
  const PlotAxes axes{"Error against build time", "build time (s)", "error (%)", true, true};
  const std::string svg = render_svg_plot(
      axes, {line("exact", {0.5, 2, 8, 40}, {12, 6, 3, 1.5}), line("sampled", {0.3, 1, 3}, {20, 9, 4})});
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  std::string trimmed = svg;
  trimmed.erase(trimmed.find_last_not_of(" \n") + 1);
  EXPECT_TRUE(trimmed.ends_with("</svg>"));
  EXPECT_TRUE(Contains(svg, "xmlns=\"http://www.w3.org/2000/svg\"", "svg"));
  EXPECT_EQ(count(svg, "<text"), count(svg, "</text>"));
  EXPECT_TRUE(WellFormed(svg));
  for (const char* text : {"Error against build time", "build time (s)", "error (%)", "exact", "sampled"})
    EXPECT_TRUE(has_text(svg, text)) << text;
  EXPECT_EQ(count(svg, "<polyline"), 2u);
}

TEST(SvgPlot, EscapesEveryText) {
  const PlotAxes axes{"a & b", "x <m>", "\"y\"", false, false};
  const std::string svg = render_svg_plot(axes, {line("fast <&> \"rough\"", {0, 1}, {0, 1})});
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_TRUE(has_text(svg, "fast &lt;&amp;&gt; &quot;rough&quot;"));
  EXPECT_TRUE(has_text(svg, "a &amp; b"));
  EXPECT_TRUE(has_text(svg, "x &lt;m&gt;"));
  EXPECT_TRUE(has_text(svg, "&quot;y&quot;"));
  EXPECT_EQ(svg.find("<&>"), std::string::npos);
}

TEST(SvgPlot, LongLegendLabelIsShortenedButKeptAsTooltip) {
  const std::string label = "a label much longer than the legend has room for, really";
  const std::string svg = render_svg_plot({}, {line(label, {1, 2}, {1, 2})});
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_FALSE(has_text(svg, label));
  EXPECT_TRUE(Contains(svg, "<title>" + label + "</title>", "svg"));
  EXPECT_TRUE(has_text(svg, label.substr(0, 31) + "\u2026"));
}

TEST(SvgPlot, LogAxisTicksAtTheDecadesSpanningTheData) {
  PlotAxes axes;
  axes.x_log = true;
  const std::string svg = render_svg_plot(axes, {line("s", {0.3, 2, 40}, {1000, 1500, 2000})});
  EXPECT_TRUE(has_text(svg, "1"));
  EXPECT_TRUE(has_text(svg, "10"));
  EXPECT_FALSE(has_text(svg, "100"));  // beyond the data
  EXPECT_FALSE(has_text(svg, "0.1"));
  EXPECT_TRUE(has_text(svg, "2"));  // 2 and 5 fit on a 2-decade axis
  EXPECT_TRUE(has_text(svg, "5"));
  EXPECT_FALSE(has_text(svg, "3"));  // but not every mantissa
}

TEST(SvgPlot, WideLogAxisLabelsOnlyPowersOfTen) {
  PlotAxes axes;
  axes.x_log = axes.y_log = true;
  const std::string svg = render_svg_plot(axes, {line("s", {1e-6, 1, 1e6}, {1e-6, 1, 1e6})});
  int ticks = 0;
  for (const std::string& t : texts(svg)) {
    if (t == "s") continue;
    const double v = std::stod(t);
    EXPECT_NEAR(std::log10(v), std::round(std::log10(v)), 1e-12) << t;
    ++ticks;
  }
  EXPECT_GE(ticks, 6);  // at least three per axis
  for (const char* decade : {"1e-6", "1e0", "1e6"}) EXPECT_TRUE(has_text(svg, decade)) << decade;  // one notation
}

TEST(SvgPlot, NarrowLogAxisStillHasSeveralLabels) {
  PlotAxes axes;
  axes.x_log = axes.y_log = true;
  // y within a decade: every mantissa; x within a factor 1.3: plain 1-2-5 steps.
  const std::string svg = render_svg_plot(axes, {line("s", {2.0, 2.6}, {2, 8})});
  for (const char* label : {"2", "3", "4", "5", "8"}) EXPECT_TRUE(has_text(svg, label)) << label;
  int x_labels = 0;
  for (const std::string& t : texts(svg)) x_labels += t.rfind("2.", 0) == 0;
  EXPECT_GE(x_labels, 3);  // 2.0, 2.1, ... or 2.00, 2.05, ...
}

TEST(SvgPlot, LinearTicksAtNiceValues) {
  const std::string svg = render_svg_plot({}, {line("s", {0, 0.25, 1}, {0, 0.7, 1})});
  EXPECT_TRUE(has_text(svg, "0.5"));
  EXPECT_TRUE(has_text(svg, "0.0"));
  EXPECT_TRUE(has_text(svg, "1.0"));
  for (const std::string& t : texts(svg)) {
    if (t == "s") continue;
    const double v = std::stod(t) * 10.0;
    EXPECT_NEAR(v, std::round(v), 1e-9) << t;  // multiples of the 0.1 step
    EXPECT_GE(v, -0.5);                        // within the data's range (plus margin)
    EXPECT_LE(v, 10.5);
  }
  const std::string large = render_svg_plot({}, {line("s", {0, 3000}, {-40, 40})});
  EXPECT_TRUE(has_text(large, "1000"));
  EXPECT_TRUE(has_text(large, "-20"));
  EXPECT_TRUE(has_text(large, "0"));
  EXPECT_FALSE(has_text(large, "-0"));
}

TEST(SvgPlot, SinglePointAndEqualValuesGetARange) {
  const std::string one = render_svg_plot({}, {line("one", {5}, {5})});
  EXPECT_TRUE(WellFormed(one));
  EXPECT_TRUE(has_text(one, "5.0"));
  EXPECT_EQ(one.find("nan"), std::string::npos);
  EXPECT_EQ(one.find("inf"), std::string::npos);
  EXPECT_EQ(count(one, "<circle"), 2u);  // the point and its legend marker

  PlotAxes log_axes;
  log_axes.x_log = log_axes.y_log = true;
  const std::string log_one = render_svg_plot(log_axes, {line("one", {5}, {5})});
  EXPECT_TRUE(has_text(log_one, "5"));
  EXPECT_EQ(log_one.find("nan"), std::string::npos);

  const std::string flat = render_svg_plot({}, {line("flat", {1, 2, 3}, {0, 0, 0})});
  EXPECT_TRUE(has_text(flat, "0.0"));
  EXPECT_EQ(flat.find("nan"), std::string::npos);
}

TEST(SvgPlot, SeriesWithoutPointsIsOnlyInTheLegend) {
  const std::string svg = render_svg_plot({}, {line("empty", {}, {}), line("full", {1, 2}, {3, 4})});
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_TRUE(has_text(svg, "empty"));
  EXPECT_EQ(count(svg, "<polyline"), 1u);
  EXPECT_NO_THROW(render_svg_plot({}, {}));
  EXPECT_TRUE(WellFormed(render_svg_plot({}, {line("nothing", {}, {})})));
}

TEST(SvgPlot, SeriesDifferInColourAndMarker) {
  const std::string svg = render_svg_plot({}, {line("a", {1, 2}, {1, 2}), line("b", {1, 2}, {2, 1})});
  const std::size_t first = svg.find("<polyline"), second = svg.find("<polyline", first + 1);
  ASSERT_NE(second, std::string::npos);
  const auto stroke = [&](std::size_t at) {
    const std::size_t s = svg.find("stroke=\"", at) + 8;
    return svg.substr(s, svg.find('"', s) - s);
  };
  EXPECT_NE(stroke(first), stroke(second));
  EXPECT_EQ(count(svg, "<circle"), 3u);  // series a: two points and its legend entry; b uses another shape
}

TEST(SvgPlot, InvalidInputThrows) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(render_svg_plot({}, {line("s", {1, 2}, {1})}), std::invalid_argument);
  EXPECT_THROW(render_svg_plot({}, {line("s", {1, nan}, {1, 2})}), std::invalid_argument);
  EXPECT_THROW(render_svg_plot({}, {line("s", {1, 2}, {1, inf})}), std::invalid_argument);
  PlotAxes log_x;
  log_x.x_log = true;
  EXPECT_THROW(render_svg_plot(log_x, {line("s", {0, 1}, {1, 2})}), std::invalid_argument);
  EXPECT_NO_THROW(render_svg_plot(log_x, {line("s", {0.5, 1}, {-1, 0})}));  // y stays linear
  PlotAxes log_y;
  log_y.y_log = true;
  EXPECT_THROW(render_svg_plot(log_y, {line("s", {1, 2}, {1, -2})}), std::invalid_argument);
  EXPECT_THROW(render_svg_plot({}, {line("s", {-1e308, 1e308}, {1, 2})}), std::invalid_argument);
}

}  // namespace
}  // namespace ilp
