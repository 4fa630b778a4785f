#include "output/svg_plan_parts.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>

#include "output/colour_map.h"
#include "output/svg_text.h"

namespace ilp::svg {
namespace {

constexpr double kTick_px = 5.0;

}  // namespace

std::string fixed(double v, int decimals) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::fixed,
                                    std::clamp(decimals, 0, 12));
  std::string s(buffer.data(), result.ptr);
  if (s.find('.') != std::string::npos) {
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.') s.pop_back();
  }
  return s == "-0" ? "0" : s;
}

std::string px(double v) { return fixed(v, 2); }

std::string xy(double x, double y) { return cat(px(x), ',', px(y)); }

std::string significant(double v) {
  if (v == 0.0 || !std::isfinite(v)) return fixed(v, 0);
  return fixed(v, std::min(3, 2 - static_cast<int>(std::floor(std::log10(std::abs(v))))));
}

std::string exact(double v, double resolution) {
  for (int decimals = 0;; ++decimals) {
    const double rounded = std::round(v * std::pow(10.0, decimals)) / std::pow(10.0, decimals);
    if (decimals == 12 || std::abs(rounded - v) <= 1e-6 * resolution) return fixed(v, decimals);
  }
}

double nice_step(double v) {
  const double decade = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= v * (1.0 - 1e-9)) return m * decade;
  return 10.0 * decade;
}

std::string text_element(double x, double y, std::string_view anchor, const std::string& text,
                         std::string_view extra) {
  return cat("<text x=\"", px(x), "\" y=\"", px(y), "\" text-anchor=\"", anchor, '"', extra, '>', xml_escape(text),
             "</text>\n");
}

std::string plan_axes(const PlanFrame& f, std::string_view x_label, std::string_view y_label) {
  std::string marks, labels;
  const double right_px = f.left_px + f.width_px(), bottom_px = f.top_px + f.height_px();
  for (int axis = 0; axis < 2; ++axis) {
    const double lo = f.extent_m.min()[axis], hi = f.extent_m.max()[axis];
    const double step = nice_step((axis == 0 ? 56.0 : 44.0) / f.scale_px_per_m);
    for (double k = std::ceil(lo / step - 1e-9); k <= std::floor(hi / step + 1e-9); ++k) {
      const double v = k * step;
      const std::string label = exact(v, step);
      if (axis == 0) {
        const double x = f.x_px(v);
        marks += cat('M', xy(x, bottom_px), 'v', px(kTick_px));
        labels += text_element(x, bottom_px + kTick_px + 13.0, "middle", label);
      } else {
        const double y = f.y_px(v);
        marks += cat('M', xy(f.left_px, y), 'h', px(-kTick_px));
        labels += text_element(f.left_px - kTick_px - 3.0, y + 4.0, "end", label);
      }
    }
  }
  std::string svg;
  if (!marks.empty()) svg += cat("<path d=\"", marks, "\" stroke=\"#333333\" fill=\"none\"/>\n");
  svg += labels;
  svg += text_element(0.5 * (f.left_px + right_px), bottom_px + 38.0, "middle", std::string(x_label));
  const double cy = 0.5 * (f.top_px + bottom_px);
  svg += text_element(16.0, cy, "middle", std::string(y_label), cat(" transform=\"rotate(-90 16 ", px(cy), ")\""));
  return svg;
}

std::string plan_scale_bar(const PlanFrame& f) {
  const double length_m = nice_step(64.0 / f.scale_px_per_m);
  const double y = f.top_px + f.height_px() + 50.0, length_px = length_m * f.scale_px_per_m;
  return cat("<rect x=\"", px(f.left_px), "\" y=\"", px(y), "\" width=\"", px(length_px),
             "\" height=\"5\" fill=\"#222222\"/>\n",
             text_element(f.left_px + length_px + 6.0, y + 6.0, "start", cat(exact(length_m, length_m), " m")));
}

std::string colour_map_gradient(std::string_view id) {
  std::string svg = cat("<linearGradient id=\"", id, "\" x1=\"0\" y1=\"1\" x2=\"0\" y2=\"0\">\n");
  for (int k = 0; k <= 60; ++k)
    svg += cat("<stop offset=\"", fixed(k / 60.0, 4), "\" stop-color=\"", svg_colour(colour_map(k / 60.0)), "\"/>\n");
  return svg + "</linearGradient>\n";
}

}  // namespace ilp::svg
