#include "output/svg_plot.h"


#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "output/svg_text.h"

namespace ilp {
namespace {

constexpr double kWidth_px = 800.0;
constexpr double kHeight_px = 480.0;
constexpr double kFont_px = 12.0;
constexpr double kCharWidth_px = 7.0;  // a generous estimate of one sans-serif glyph at 12 px
constexpr double kTick_px = 5.0;
constexpr double kMinorTick_px = 3.0;
constexpr double kMarker_px = 4.0;  // marker "radius"
constexpr double kLegendRow_px = 20.0;
constexpr std::size_t kLegendChars = 32;

// Okabe-Ito colours (distinguishable with colour-vision deficiencies) without the
// yellow, which is too pale on white, plus gray. Shapes cycle with a different
// period (7), so colour and shape together stay unique for 56 series.
constexpr std::array<std::string_view, 8> kColours = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                      "#E69F00", "#56B4E9", "#000000", "#7F7F7F"};
enum class Marker { circle, square, triangle_up, diamond, triangle_down, cross, plus };
constexpr int kMarkerCount = 7;

// ---- text ---------------------------------------------------------------------

using svg::cat;
using svg::char_count;
using svg::xml_escape;

double text_width_px(std::string_view text) { return static_cast<double>(char_count(text)) * kCharWidth_px; }

// The first `max_chars` characters of `text`, the last one an ellipsis if it was cut.
std::string shortened(const std::string& text, std::size_t max_chars) {
  if (char_count(text) <= max_chars) return text;
  std::size_t chars = 0, end = 0;
  for (; end < text.size(); ++end) {
    if ((static_cast<unsigned char>(text[end]) & 0xC0) != 0x80 && chars++ == max_chars - 1) break;
  }
  return text.substr(0, end) + "\u2026";
}

// ---- numbers (std::to_chars: independent of the C++ and C locales) -------------

std::string to_text(double v, std::chars_format format, int precision) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, format, precision);
  std::string s(buffer.data(), result.ptr);
  // "2.5e+06" -> "2.5e6", "1e-05" -> "1e-5"
  const std::size_t e = s.find('e');
  if (e != std::string::npos) {
    std::string exponent = s.substr(e + 1);
    const bool negative = exponent[0] == '-';
    exponent.erase(0, exponent.find_first_not_of("+-0"));
    s = s.substr(0, e + 1) + (negative ? "-" : "") + (exponent.empty() ? "0" : exponent);
  }
  return s;
}

// A coordinate in px: two decimals, trailing zeros dropped.
std::string px(double v) {
  std::string s = to_text(v, std::chars_format::fixed, 2);
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

// ---- axes ----------------------------------------------------------------------

struct Tick {
  double value = 0.0;  // data units
  std::string label;   // empty: an unlabelled minor tick
};

struct Axis {
  bool log = false;
  double lo = 0.0, hi = 1.0;        // axis units: the value, or log10 of it on a log axis
  double px_lo = 0.0, px_hi = 1.0;  // screen position of lo and hi
  bool horizontal = true;
  std::vector<Tick> ticks;  // ascending values

  double units(double value) const { return log ? std::log10(value) : value; }
  double to_px(double value) const { return px_lo + (units(value) - lo) / (hi - lo) * (px_hi - px_lo); }
  double length_px() const { return std::abs(px_hi - px_lo); }
  bool contains(double value) const {
    const double u = units(value), slack = 1e-9 * (hi - lo);
    return u >= lo - slack && u <= hi + slack;
  }
};

// The data range on one axis, in axis units, with a 4 % margin each side so that
// markers clear the frame. Equal values (to rounding) get a range around them; no
// values give [0, 1] (linear) or [1, 10] (log).
void set_range(Axis& axis, const std::vector<double>& values) {
  if (values.empty()) {
    axis.lo = 0.0;
    axis.hi = 1.0;
    return;
  }
  const auto [min_it, max_it] = std::minmax_element(values.begin(), values.end());
  double lo = axis.units(*min_it), hi = axis.units(*max_it);
  if (*max_it - *min_it <= 1e-9 * std::max(std::abs(*min_it), std::abs(*max_it))) {
    const double mid = 0.5 * (lo + hi);
    const double half = axis.log ? 0.5 : (mid == 0.0 ? 1.0 : 0.1 * std::abs(mid));  // log: half a decade
    lo = mid - half;
    hi = mid + half;
  }
  const double margin = 0.04 * (hi - lo);
  axis.lo = lo - margin;
  axis.hi = hi + margin;
  if (!std::isfinite(axis.lo) || !std::isfinite(axis.hi) || !(axis.hi > axis.lo))
    throw std::invalid_argument("render_svg_plot: the values span too large a range to plot");
}

// True if consecutive labels keep clear of each other along the axis.
bool labels_fit(const Axis& axis, const std::vector<Tick>& ticks) {
  const double gap_px = axis.horizontal ? 18.0 : 16.0;
  bool have_previous = false;
  double previous_px = 0.0, previous_extent_px = 0.0;
  for (const Tick& t : ticks) {
    if (t.label.empty()) continue;
    const double at_px = axis.to_px(t.value);
    const double extent_px = axis.horizontal ? text_width_px(t.label) : kFont_px;
    if (have_previous && std::abs(at_px - previous_px) < 0.5 * (extent_px + previous_extent_px) + gap_px) return false;
    have_previous = true;
    previous_px = at_px;
    previous_extent_px = extent_px;
  }
  return true;
}

std::size_t labelled(const std::vector<Tick>& ticks) {
  return static_cast<std::size_t>(
      std::count_if(ticks.begin(), ticks.end(), [](const Tick& t) { return !t.label.empty(); }));
}

// Multiples of `step` in [a, b], labelled with the decimals the step needs
// (scientific notation for very large or small magnitudes).
std::vector<Tick> multiples(double a, double b, double step) {
  const double k0 = std::ceil(a / step - 1e-9), k1 = std::floor(b / step + 1e-9);
  const int exponent = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  const double largest = std::max(std::abs(k0 * step), std::abs(k1 * step));
  const bool scientific = largest >= 1e6 || (largest > 0.0 && largest < 1e-3);
  const int digits = scientific ? std::clamp(static_cast<int>(std::floor(std::log10(largest))) - exponent, 0, 15) : 0;
  std::vector<Tick> ticks;
  for (double k = k0; k <= k1; ++k) {
    const double v = k == 0.0 ? 0.0 : k * step;  // no "-0"
    const std::string label = !scientific ? to_text(v, std::chars_format::fixed, std::max(0, -exponent))
                              : v == 0.0  ? std::string("0")
                                          : to_text(v, std::chars_format::scientific, digits);
    ticks.push_back({v, label});
  }
  return ticks;
}

// Labelled ticks at the smallest 1-2-5 step whose labels fit, between values a < b.
std::vector<Tick> linear_ticks(const Axis& axis, double a, double b) {
  double magnitude = std::pow(10.0, std::floor(std::log10(b - a)) - 2.0);  // at most ~1000 ticks to start
  for (int decade = 0; decade < 8; ++decade, magnitude *= 10.0) {
    for (double m : {1.0, 2.0, 5.0}) {
      if ((b - a) / (m * magnitude) > 2000.0) continue;  // only if rounding made the start too fine
      std::vector<Tick> ticks = multiples(a, b, m * magnitude);
      if (ticks.size() <= 1 || labels_fit(axis, ticks)) return ticks;
    }
  }
  return {};
}

// Ticks m x 10^k in the axis range for the given mantissas m, labelled when
// `label_it(m, k)` says so.
template <class LabelIt>
std::vector<Tick> log_multiples(const Axis& axis, std::initializer_list<int> mantissas, LabelIt label_it) {
  // One notation on the axis: "1e-6 ... 1e0 ... 1e6" rather than "1e-6 ... 1 ... 1e6".
  const bool scientific = axis.lo < -4.0 || axis.hi >= 6.0;
  std::vector<Tick> ticks;
  for (int k = static_cast<int>(std::floor(axis.lo)); k <= static_cast<int>(std::ceil(axis.hi)); ++k) {
    for (int m : mantissas) {
      const double v = m * std::pow(10.0, k);
      if (!axis.contains(v)) continue;
      std::string label;
      if (label_it(m, k))
        label = scientific ? to_text(v, std::chars_format::scientific, 0) : to_text(v, std::chars_format::general, 6);
      ticks.push_back({v, label});
    }
  }
  return ticks;
}

// Log axis: decades (every 2nd, 5th, ... decade when they crowd), with 2 and 5
// labelled too where they fit. Ranges of about a decade or less get every mantissa
// 1..9, or failing that 1-2-5 steps as on a linear axis, when that labels more.
// Unlabelled minor ticks at 2..9 x 10^k when a decade is long enough to show them.
std::vector<Tick> log_ticks(const Axis& axis) {
  const auto every = [](int, int) { return true; };
  std::vector<Tick> ticks = log_multiples(axis, {1, 2, 5}, every);
  if (!labels_fit(axis, ticks)) {
    for (int stride : {1, 2, 5, 10, 20, 50, 100, 200, 500}) {
      ticks = log_multiples(axis, {1}, [stride](int, int k) { return k % stride == 0; });
      if (labelled(ticks) <= 1 || labels_fit(axis, ticks)) break;
    }
  }
  if (labelled(ticks) < 3) {
    std::vector<Tick> all = log_multiples(axis, {1, 2, 3, 4, 5, 6, 7, 8, 9}, every);
    if (labelled(all) > labelled(ticks) && labels_fit(axis, all)) ticks = std::move(all);
  }
  if (labelled(ticks) < 3) {
    std::vector<Tick> linear = linear_ticks(axis, std::pow(10.0, axis.lo), std::pow(10.0, axis.hi));
    if (labelled(linear) > labelled(ticks)) return linear;
  }
  const double decade_px = axis.length_px() / (axis.hi - axis.lo);
  const auto unlabelled = [](int, int) { return false; };
  std::vector<Tick> minor;
  if (decade_px >= 30.0)
    minor = log_multiples(axis, {1, 2, 3, 4, 5, 6, 7, 8, 9}, unlabelled);
  else if (decade_px >= 4.0)
    minor = log_multiples(axis, {1}, unlabelled);
  for (const Tick& t : minor) {
    const bool taken = std::any_of(ticks.begin(), ticks.end(),
                                   [&](const Tick& u) { return std::abs(u.value - t.value) <= 1e-9 * t.value; });
    if (!taken) ticks.push_back(t);
  }
  std::sort(ticks.begin(), ticks.end(), [](const Tick& p, const Tick& q) { return p.value < q.value; });
  return ticks;
}

void set_ticks(Axis& axis) { axis.ticks = axis.log ? log_ticks(axis) : linear_ticks(axis, axis.lo, axis.hi); }

// ---- drawing -------------------------------------------------------------------

// "x,y" in px.
std::string xy(double x, double y) { return cat(px(x), ',', px(y)); }

std::string text_element(double x, double y, std::string_view anchor, const std::string& text,
                         std::string_view extra = "") {
  return cat("<text x=\"", px(x), "\" y=\"", px(y), "\" text-anchor=\"", anchor, '"', extra, '>', xml_escape(text),
             "</text>\n");
}

std::string marker_element(Marker shape, double x, double y, std::string_view colour) {
  const double r = kMarker_px;
  const auto polygon = [&](std::initializer_list<std::pair<double, double>> corners) {
    std::string points;
    for (const auto& [dx, dy] : corners) points += cat(points.empty() ? "" : " ", xy(x + dx, y + dy));
    return cat("<polygon points=\"", points, "\" fill=\"", colour, "\"/>\n");
  };
  const auto strokes = [&](const std::string& d) {
    return cat("<path d=\"", d, "\" stroke=\"", colour, "\" stroke-width=\"2\" fill=\"none\"/>\n");
  };
  switch (shape) {
    case Marker::circle:
      return cat("<circle cx=\"", px(x), "\" cy=\"", px(y), "\" r=\"", px(r), "\" fill=\"", colour, "\"/>\n");
    case Marker::square:
      return polygon({{-r, -r}, {r, -r}, {r, r}, {-r, r}});
    case Marker::triangle_up:
      return polygon({{0, -1.2 * r}, {1.1 * r, 0.8 * r}, {-1.1 * r, 0.8 * r}});
    case Marker::diamond:
      return polygon({{0, -1.3 * r}, {1.3 * r, 0}, {0, 1.3 * r}, {-1.3 * r, 0}});
    case Marker::triangle_down:
      return polygon({{0, 1.2 * r}, {1.1 * r, -0.8 * r}, {-1.1 * r, -0.8 * r}});
    case Marker::cross:
      return strokes(cat('M', xy(x - r, y - r), 'L', xy(x + r, y + r), 'M', xy(x - r, y + r), 'L', xy(x + r, y - r)));
    case Marker::plus:
      return strokes(
          cat('M', xy(x - 1.2 * r, y), 'L', xy(x + 1.2 * r, y), 'M', xy(x, y - 1.2 * r), 'L', xy(x, y + 1.2 * r)));
  }
  return {};
}

void check(const PlotAxes& axes, const std::vector<PlotSeries>& series) {
  for (std::size_t i = 0; i < series.size(); ++i) {
    const PlotSeries& s = series[i];
    const std::string name = cat("render_svg_plot: series ", std::to_string(i), " ('", s.label, "')");
    if (s.x.size() != s.y.size())
      throw std::invalid_argument(
          cat(name, ": ", std::to_string(s.x.size()), " x values but ", std::to_string(s.y.size()), " y values"));
    for (std::size_t j = 0; j < s.x.size(); ++j) {
      if (!std::isfinite(s.x[j]) || !std::isfinite(s.y[j]))
        throw std::invalid_argument(cat(name, ": point ", std::to_string(j), " is not finite"));
      if ((axes.x_log && s.x[j] <= 0.0) || (axes.y_log && s.y[j] <= 0.0))
        throw std::invalid_argument(cat(name, ": point ", std::to_string(j), " is not > 0 on a logarithmic axis"));
    }
  }
}

}  // namespace

std::string render_svg_plot(const PlotAxes& axes, const std::vector<PlotSeries>& series) {
  check(axes, series);
  std::vector<double> xs, ys;
  for (const PlotSeries& s : series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  Axis x_axis, y_axis;
  x_axis.log = axes.x_log;
  y_axis.log = axes.y_log;
  y_axis.horizontal = false;
  set_range(x_axis, xs);
  set_range(y_axis, ys);

  // Layout: the plot's height is fixed by the title and x labels; its width follows
  // from the y tick labels (known once the y ticks are) and the legend.
  const double top_px = axes.title.empty() ? 20.0 : 44.0;
  const double bottom_px = kHeight_px - (axes.x_label.empty() ? 34.0 : 56.0);
  y_axis.px_lo = bottom_px;
  y_axis.px_hi = top_px;
  set_ticks(y_axis);
  double y_labels_px = 0.0;
  for (const Tick& t : y_axis.ticks) y_labels_px = std::max(y_labels_px, text_width_px(t.label));
  const double left_px = (axes.y_label.empty() ? 12.0 : 34.0) + y_labels_px + kTick_px + 6.0;
  std::vector<std::string> legend_labels;
  double legend_text_px = 0.0;
  for (const PlotSeries& s : series) {
    legend_labels.push_back(shortened(s.label, kLegendChars));
    legend_text_px = std::max(legend_text_px, text_width_px(legend_labels.back()));
  }
  const double legend_width_px = series.empty() ? 0.0 : 46.0 + legend_text_px + 10.0;
  const double legend_left_px = kWidth_px - 10.0 - legend_width_px;
  const double right_px = series.empty() ? kWidth_px - 20.0 : legend_left_px - 16.0;
  x_axis.px_lo = left_px;
  x_axis.px_hi = right_px;
  set_ticks(x_axis);

  std::string svg = cat("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", px(kWidth_px), "\" height=\"",
                        px(kHeight_px), "\" viewBox=\"0 0 ", px(kWidth_px), ' ', px(kHeight_px),
                        "\" font-family=\"sans-serif\" font-size=\"", px(kFont_px), "\">\n");
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";

  // Grid at labelled ticks, then the frame, tick marks and labels outside it.
  std::string grid, marks, labels;
  for (const Tick& t : x_axis.ticks) {
    const double at_px = x_axis.to_px(t.value);
    marks += cat('M', xy(at_px, bottom_px), 'v', px(t.label.empty() ? kMinorTick_px : kTick_px));
    if (t.label.empty()) continue;
    grid += cat('M', xy(at_px, top_px), 'V', px(bottom_px));
    labels += text_element(at_px, bottom_px + kTick_px + 13.0, "middle", t.label);
  }
  for (const Tick& t : y_axis.ticks) {
    const double at_px = y_axis.to_px(t.value);
    marks += cat('M', xy(left_px, at_px), 'h', px(-(t.label.empty() ? kMinorTick_px : kTick_px)));
    if (t.label.empty()) continue;
    grid += cat('M', xy(left_px, at_px), 'H', px(right_px));
    labels += text_element(left_px - kTick_px - 3.0, at_px + 4.0, "end", t.label);
  }
  if (!grid.empty()) svg += cat("<path d=\"", grid, "\" stroke=\"#e0e0e0\" stroke-width=\"1\"/>\n");
  svg += cat("<rect x=\"", px(left_px), "\" y=\"", px(top_px), "\" width=\"", px(right_px - left_px), "\" height=\"",
             px(bottom_px - top_px), "\" fill=\"none\" stroke=\"black\"/>\n");
  if (!marks.empty()) svg += cat("<path d=\"", marks, "\" stroke=\"black\"/>\n");
  svg += labels;

  if (!axes.title.empty())
    svg +=
        text_element(0.5 * (left_px + right_px), 26.0, "middle", axes.title, " font-size=\"15\" font-weight=\"bold\"");
  if (!axes.x_label.empty()) svg += text_element(0.5 * (left_px + right_px), kHeight_px - 14.0, "middle", axes.x_label);
  if (!axes.y_label.empty()) {
    const double cy = 0.5 * (top_px + bottom_px);
    svg += text_element(18.0, cy, "middle", axes.y_label, cat(" transform=\"rotate(-90 18 ", px(cy), ")\""));
  }

  // Series: a line through the points in order, then the markers on top.
  for (std::size_t i = 0; i < series.size(); ++i) {
    const PlotSeries& s = series[i];
    if (s.x.empty()) continue;
    const std::string_view colour = kColours[i % kColours.size()];
    const auto shape = static_cast<Marker>(i % kMarkerCount);
    svg += "<g>\n";
    if (s.x.size() > 1) {
      std::string points;
      for (std::size_t j = 0; j < s.x.size(); ++j)
        points += cat(j ? " " : "", xy(x_axis.to_px(s.x[j]), y_axis.to_px(s.y[j])));
      svg += cat("<polyline points=\"", points, "\" fill=\"none\" stroke=\"", colour, "\" stroke-width=\"1.5\"/>\n");
    }
    for (std::size_t j = 0; j < s.x.size(); ++j)
      svg += marker_element(shape, x_axis.to_px(s.x[j]), y_axis.to_px(s.y[j]), colour);
    svg += "</g>\n";
  }

  // Legend: one row per series (also those without points), full label as tooltip.
  if (!series.empty()) {
    svg +=
        cat("<rect x=\"", px(legend_left_px), "\" y=\"", px(top_px), "\" width=\"", px(legend_width_px), "\" height=\"",
            px(8.0 + kLegendRow_px * static_cast<double>(series.size())), "\" fill=\"white\" stroke=\"#999999\"/>\n");
    for (std::size_t i = 0; i < series.size(); ++i) {
      const std::string_view colour = kColours[i % kColours.size()];
      const double cy = top_px + 4.0 + kLegendRow_px * (static_cast<double>(i) + 0.5);
      svg += cat("<g>\n<title>", xml_escape(series[i].label), "</title>\n");
      svg +=
          cat("<path d=\"M", xy(legend_left_px + 10.0, cy), "h28\" stroke=\"", colour, "\" stroke-width=\"1.5\"/>\n");
      svg += marker_element(static_cast<Marker>(i % kMarkerCount), legend_left_px + 24.0, cy, colour);
      svg += text_element(legend_left_px + 46.0, cy + 4.0, "start", legend_labels[i]);
      svg += "</g>\n";
    }
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace ilp
