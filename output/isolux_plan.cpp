#include "output/isolux_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "output/atomic_file.h"
#include "output/png_render.h"
#include "output/svg_plan_parts.h"
#include "output/svg_text.h"

namespace ilp {
namespace {

using svg::cat;
using svg::char_count;
using svg::fixed;
using svg::px;
using svg::significant;
using svg::text_element;
using svg::xml_escape;
using svg::xy;
using Box = Eigen::AlignedBox2d;
using V2 = Eigen::Vector2d;

// ---- layout constants (px) ------------------------------------------------------

constexpr double kMaxPlanWidth_px = 700.0;
constexpr double kMaxPlanHeight_px = 640.0;
constexpr double kLeft_px = 64.0;             // y label and tick labels
constexpr double kGap_px = 32.0;              // plan to legend
constexpr double kLegendColumn_px = 230.0;    // legend, including the right margin
constexpr double kBottom_px = 72.0;           // tick labels, x label, scale bar
constexpr double kCharWidth_em = 0.62;        // DejaVu Sans digits are 0.636 em, most letters narrower
constexpr double kContourFont_px = 11.0;
constexpr double kValueFont_px = 10.0;
constexpr double kLuminaireFont_px = 11.0;
constexpr double kMarker_px = 6.0;            // half the size of the min and max markers
constexpr double kValueGap_px = 44.0;         // least distance between neighbouring point values
constexpr double kContourLabelEvery_px = 260.0;
constexpr double kCandidateStep_px = 8.0;     // how far along a line label spots are tried
constexpr double kFillOpacity = 0.6;          // the fill stays light enough for dark lines and text
constexpr double kMaxExtent_m = 1e5;           // a plan wider than 100 km is an input error
constexpr double kPadding_fraction = 0.03;    // the frame's margin around what is drawn
constexpr std::string_view kGradientId = "ilp-isolux-lux";
constexpr std::string_view kClipId = "ilp-isolux-room";
constexpr std::array<double, 8> kLevelFractions = {0.5, 0.6, 0.7, 0.8, 1.0, 1.2, 1.5, 2.0};

double text_width_px(std::string_view text, double font_px) {
  return static_cast<double>(char_count(text)) * kCharWidth_em * font_px;
}

// A box of the text's size (plus `pad` each side) centred on c.
Box text_box(const V2& c, std::string_view text, double font_px, double pad) {
  const V2 half(0.5 * text_width_px(text, font_px) + pad, 0.5 * font_px + pad);
  return Box(c - half, c + half);
}

bool overlaps(const Box& a, const Box& b) { return !a.intersection(b).isEmpty(); }

// True if the segment a-b passes through (or touches) the box (Liang-Barsky clipping).
bool segment_hits_box(const V2& a, const V2& b, const Box& box) {
  double t0 = 0.0, t1 = 1.0;
  const V2 d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    for (int side = 0; side < 2; ++side) {
      const double p = side == 0 ? -d[axis] : d[axis];
      const double q = side == 0 ? a[axis] - box.min()[axis] : box.max()[axis] - a[axis];
      if (p == 0.0) {
        if (q < 0.0) return false;
      } else {
        const double t = q / p;
        if (p < 0.0) t0 = std::max(t0, t); else t1 = std::min(t1, t);
        if (t0 > t1) return false;
      }
    }
  }
  return true;
}

// 2 significant digits.
double two_digits(double v) {
  const double unit = std::pow(10.0, std::floor(std::log10(v)) - 1.0);
  return std::round(v / unit) * unit;
}

// "512" lx; below 10 lx one decimal.
std::string lux_text(double v) { return fixed(v, std::abs(v) < 9.95 ? 1 : 0); }

// ---- checks ---------------------------------------------------------------------

void check(const IsoluxGridView& v) {
  const auto fail = [&](const std::string& what) {
    throw std::invalid_argument(cat("isolux plan '", v.name, "': ", what));
  };
  if (v.nx < 0 || v.ny < 0) fail("negative grid size");
  if (v.maintained_lux.size() != static_cast<std::size_t>(v.nx) * static_cast<std::size_t>(v.ny))
    fail(cat(std::to_string(v.maintained_lux.size()), " values for ", std::to_string(v.nx), " x ",
             std::to_string(v.ny), " points"));
  if (!v.origin_m.allFinite() || !v.spacing_m.allFinite() || !(v.spacing_m.x() > 0.0) || !(v.spacing_m.y() > 0.0))
    fail("the origin must be finite and the spacing finite and > 0");
  if (!std::isnan(v.target_lux) && !(v.target_lux > 0.0 && std::isfinite(v.target_lux)))
    fail(cat("target_lux = ", significant(v.target_lux), ": must be > 0 (or NaN for none)"));
  if (!(v.maintenance_factor > 0.0) || v.maintenance_factor > 1.0)
    fail(cat("maintenance_factor = ", fixed(v.maintenance_factor, 4), ": must be in (0, 1]"));
  for (const auto& polygon : v.room_outline_m)
    for (const V2& p : polygon)
      if (!p.allFinite()) fail("a room outline point is not finite");
  for (const IsoluxLuminaire& l : v.luminaires)
    if (!l.centre_m.allFinite() || !std::isfinite(l.length_m) || !std::isfinite(l.width_m) || l.length_m < 0.0 ||
        l.width_m < 0.0 || !std::isfinite(l.rotation_deg))
      fail(cat("luminaire '", l.id, "' has a non-finite position, size or rotation, or a negative size"));
}

// ---- geometry -------------------------------------------------------------------

// A luminaire's outline in metres: the rectangle's corners counter-clockwise, or 48
// points round the disc.
std::vector<V2> luminaire_outline_m(const IsoluxLuminaire& l) {
  std::vector<V2> out;
  if (l.round) {
    constexpr int kSides = 48;
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * std::numbers::pi * k / kSides;
      out.push_back(l.centre_m + 0.5 * l.length_m * V2(std::cos(a), std::sin(a)));
    }
    return out;
  }
  const double a = l.rotation_deg * std::numbers::pi / 180.0;
  const V2 u(std::cos(a), std::sin(a)), w(-std::sin(a), std::cos(a));
  const V2 hu = 0.5 * l.length_m * u, hw = 0.5 * l.width_m * w;
  return {l.centre_m - hu - hw, l.centre_m + hu - hw, l.centre_m + hu + hw, l.centre_m - hu + hw};
}

// Where point k (= j nx + i) lies, in metres.
V2 point_m(const IsoluxGridView& v, int k) {
  const int i = k % v.nx, j = k / v.nx;
  return v.origin_m + V2(i * v.spacing_m.x(), j * v.spacing_m.y());
}

Box cells_box_m(const IsoluxGridView& v) {
  Box box;
  if (v.nx == 0 || v.ny == 0) return box;
  box.extend(V2(v.origin_m - 0.5 * v.spacing_m));
  box.extend(V2(v.origin_m + V2((v.nx - 0.5) * v.spacing_m.x(), (v.ny - 0.5) * v.spacing_m.y())));
  return box;
}

svg::PlanFrame make_frame(const IsoluxGridView& v, double top_px) {
  Box extent = cells_box_m(v);
  for (const auto& polygon : v.room_outline_m)
    for (const V2& p : polygon) extent.extend(p);
  for (const IsoluxLuminaire& l : v.luminaires)
    for (const V2& p : luminaire_outline_m(l)) extent.extend(p);
  if (extent.isEmpty()) extent = Box(V2::Zero(), V2::Ones());
  if (!extent.sizes().allFinite() || extent.sizes().maxCoeff() > kMaxExtent_m)
    throw std::invalid_argument(cat("isolux plan '", v.name, "': the grid, room and luminaires span more than ",
                                    fixed(kMaxExtent_m, 0), " m"));
  const double pad = std::max(1e-3, kPadding_fraction * extent.sizes().maxCoeff());
  extent.min() -= V2::Constant(pad);
  extent.max() += V2::Constant(pad);
  svg::PlanFrame f;
  f.extent_m = extent;
  f.scale_px_per_m = std::min(kMaxPlanWidth_px / extent.sizes().x(), kMaxPlanHeight_px / extent.sizes().y());
  f.left_px = kLeft_px;
  f.top_px = top_px;
  return f;
}

// The plan's frame and the legend's bar, shared by the layout and the drawing.
struct PlanGeometry {
  svg::PlanFrame frame;
  double top_px = 0.0, bar_px = 0.0, width_px = 0.0, height_px = 0.0;
};

PlanGeometry plan_geometry(const IsoluxGridView& v) {
  PlanGeometry g;
  g.top_px = v.title.empty() ? 44.0 : 64.0;
  g.frame = make_frame(v, g.top_px);
  g.bar_px = std::clamp(g.frame.height_px() - 220.0, 160.0, 320.0);
  g.width_px = g.frame.left_px + g.frame.width_px() + kGap_px + kLegendColumn_px;
  constexpr double kLegendBelowBar_px = 24.0 + 9 * 16.0 + 60.0;  // rows of text, then the north arrow
  g.height_px = g.top_px + std::max(g.frame.height_px(), 40.0 + g.bar_px + kLegendBelowBar_px) + kBottom_px;
  return g;
}

Box frame_box_px(const svg::PlanFrame& f) {
  return Box(V2(f.left_px, f.top_px), V2(f.left_px + f.width_px(), f.top_px + f.height_px()));
}

// ---- labels ---------------------------------------------------------------------

struct Placer {
  Box frame_px;
  std::vector<Box> obstacles_px;                   // luminaire outlines
  std::vector<IsoluxLabel>* labels = nullptr;

  bool fits(const Box& b) const {
    if (!frame_px.contains(b)) return false;
    for (const Box& o : obstacles_px)
      if (overlaps(o, b)) return false;
    for (const IsoluxLabel& l : *labels)
      if (overlaps(l.box_px, b)) return false;
    return true;
  }
};

void place_luminaire_labels(const IsoluxGridView& v, Placer& placer,
                            const std::vector<Box>& outlines_px) {
  for (std::size_t k = 0; k < v.luminaires.size(); ++k) {
    const std::string& id = v.luminaires[k].id;
    if (id.empty()) continue;
    const Box& o = outlines_px[k];
    const double w = text_width_px(id, kLuminaireFont_px) + 4.0, h = kLuminaireFont_px + 4.0;
    const V2 c = o.center();
    // Right, left, above, below the outline, 3 px off.
    const std::array<V2, 4> centres = {V2(o.max().x() + 3.0 + 0.5 * w, c.y()), V2(o.min().x() - 3.0 - 0.5 * w, c.y()),
                                       V2(c.x(), o.min().y() - 3.0 - 0.5 * h), V2(c.x(), o.max().y() + 3.0 + 0.5 * h)};
    for (const V2& centre : centres) {
      const Box b = text_box(centre, id, kLuminaireFont_px, 2.0);
      if (placer.fits(b)) {
        placer.labels->push_back({IsoluxLabel::Kind::luminaire, id, b});
        break;
      }
    }
  }
}

// A polyline in px with its cumulative arc length.
struct PxLine {
  std::vector<V2> points;
  std::vector<double> at;  // arc length at each point
  double level = 0.0;
  Box bounds;
};

PxLine to_px(const ContourLine& line, const svg::PlanFrame& f) {
  PxLine out;
  out.level = line.level;
  for (const V2& p : line.points_m) out.points.push_back(f.to_px(p));
  if (line.closed && !out.points.empty()) out.points.push_back(out.points.front());
  double s = 0.0;
  for (std::size_t k = 0; k < out.points.size(); ++k) {
    if (k > 0) s += (out.points[k] - out.points[k - 1]).norm();
    out.at.push_back(s);
    out.bounds.extend(out.points[k]);
  }
  return out;
}

V2 point_at(const PxLine& l, double s) {
  const auto it = std::lower_bound(l.at.begin(), l.at.end(), s);
  if (it == l.at.begin()) return l.points.front();
  if (it == l.at.end()) return l.points.back();
  const std::size_t k = static_cast<std::size_t>(it - l.at.begin());
  const double span = l.at[k] - l.at[k - 1];
  const double t = span > 0.0 ? (s - l.at[k - 1]) / span : 0.0;
  return l.points[k - 1] + t * (l.points[k] - l.points[k - 1]);
}

bool crosses_other_line(const Box& b, const std::vector<PxLine>& lines, std::size_t own) {
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (k == own || !overlaps(lines[k].bounds, b)) continue;
    const auto& p = lines[k].points;
    for (std::size_t i = 1; i < p.size(); ++i)
      if (segment_hits_box(p[i - 1], p[i], b)) return true;
  }
  return false;
}

// A line's own other parts (it may curl back) must not cross its label either: only
// the stretch within `reach` of the label's spot s may (reach 0: none may).
bool crosses_own_line_elsewhere(const Box& b, const PxLine& l, double s, double reach) {
  for (std::size_t i = 1; i < l.points.size(); ++i) {
    if (reach > 0.0 && l.at[i] >= s - reach && l.at[i - 1] <= s + reach) continue;
    if (segment_hits_box(l.points[i - 1], l.points[i], b)) return true;
  }
  return false;
}

// A label next to a short line (e.g. a corner's arc): boxes touching the line's middle
// from eight directions, the first that fits and that no line crosses.
void place_beside(const PxLine& l, std::size_t own, const std::vector<PxLine>& lines, const std::string& text,
                  Placer& placer) {
  constexpr double kLeast_px = 12.0;  // a shorter line is a speck: no label
  const double length = l.at.empty() ? 0.0 : l.at.back();
  if (length < kLeast_px) return;
  const V2 at = point_at(l, 0.5 * length);
  const Box probe = text_box(at, text, kContourFont_px, 3.0);
  const V2 half = 0.5 * probe.sizes() + V2::Constant(2.0);
  for (const V2& dir : {V2(1, 0), V2(-1, 0), V2(0, -1), V2(0, 1), V2(1, -1), V2(-1, -1), V2(1, 1), V2(-1, 1)}) {
    const Box b = text_box(at + dir.cwiseProduct(half), text, kContourFont_px, 3.0);
    if (!placer.fits(b) || crosses_other_line(b, lines, own) || crosses_own_line_elsewhere(b, l, -1.0, 0.0)) continue;
    placer.labels->push_back({IsoluxLabel::Kind::contour, text, b, false});
    return;
  }
}

void place_contour_labels(const std::vector<PxLine>& lines, double reference_lux, Placer& placer) {
  // The target's lines first, then outwards from it.
  std::vector<std::size_t> order(lines.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::abs(std::log(lines[a].level / reference_lux)) < std::abs(std::log(lines[b].level / reference_lux));
  });
  for (std::size_t k : order) {
    const PxLine& l = lines[k];
    const std::string text = lux_text(l.level);
    const double w = text_width_px(text, kContourFont_px) + 6.0;
    const double length = l.at.empty() ? 0.0 : l.at.back();
    if (length < 2.0 * w) {  // too short to carry its number: beside it, if at all
      place_beside(l, k, lines, text, placer);
      continue;
    }
    const int wanted = std::max(1, static_cast<int>(std::floor(length / kContourLabelEvery_px)));
    const double stretch = length / wanted;
    for (int n = 0; n < wanted; ++n) {
      // Try spots outwards from the middle of the n-th stretch, keeping clear of its ends.
      const double mid = (n + 0.5) * stretch, room = 0.5 * stretch - 0.5 * w;
      for (double off = 0.0; off <= room; off += kCandidateStep_px) {
        bool placed = false;
        for (double s : {mid + off, mid - off}) {
          const Box b = text_box(point_at(l, s), text, kContourFont_px, 3.0);
          if (!placer.fits(b) || crosses_other_line(b, lines, k) || crosses_own_line_elsewhere(b, l, s, w)) continue;
          placer.labels->push_back({IsoluxLabel::Kind::contour, text, b});
          placed = true;
          break;
        }
        if (placed) break;
      }
    }
  }
}

// The first index of an every-`step` subset of 0 .. n-1 centred in the range.
int centred_start(int n, int step) { return n > 0 ? ((n - 1) % step) / 2 : 0; }

void place_value_labels(const IsoluxGridView& v, const svg::PlanFrame& f, IsoluxLayout& layout, Placer& placer) {
  // Capped at the grid's size (one value at most along that axis), which also keeps the
  // conversion to int in range for a spacing that is tiny on the plan.
  const auto step = [&](double spacing_m, int n) {
    const double wanted = std::ceil(kValueGap_px / (spacing_m * f.scale_px_per_m) - 1e-9);
    return static_cast<int>(std::clamp(wanted, 1.0, static_cast<double>(std::max(n, 1))));
  };
  layout.value_step_x = step(v.spacing_m.x(), v.nx);
  layout.value_step_y = step(v.spacing_m.y(), v.ny);
  for (int j = centred_start(v.ny, layout.value_step_y); j < v.ny; j += layout.value_step_y)
    for (int i = centred_start(v.nx, layout.value_step_x); i < v.nx; i += layout.value_step_x) {
      const double lux = v.maintained_lux[static_cast<std::size_t>(j) * v.nx + i];
      if (!std::isfinite(lux)) continue;
      const V2 at = f.to_px(V2(v.origin_m + V2(i * v.spacing_m.x(), j * v.spacing_m.y())));
      const std::string text = lux_text(lux);
      const Box b = text_box(at, text, kValueFont_px, 1.5);
      if (placer.fits(b)) placer.labels->push_back({IsoluxLabel::Kind::value, text, b});
    }
}

// ---- drawing ----------------------------------------------------------------------

std::string polygon_path(const std::vector<V2>& points_m, const svg::PlanFrame& f) {
  std::string d;
  for (const V2& p : points_m) d += cat(d.empty() ? "M" : "L", xy(f.x_px(p.x()), f.y_px(p.y())));
  return d.empty() ? d : d + "Z";
}

std::string room_path(const IsoluxGridView& v, const svg::PlanFrame& f) {
  std::string d;
  for (const auto& polygon : v.room_outline_m)
    if (polygon.size() >= 3) d += polygon_path(polygon, f);
  return d;
}

std::string cells(const IsoluxGridView& v, const svg::PlanFrame& f, const ColourScale& scale, bool clip) {
  std::string svg = cat("<g class=\"cells\" opacity=\"", fixed(kFillOpacity, 2), "\"", clip ? cat(" clip-path=\"url(#", kClipId, ")\"") : "",
                        " stroke-width=\"0.6\">\n");
  const double w = v.spacing_m.x() * f.scale_px_per_m, h = v.spacing_m.y() * f.scale_px_per_m;
  for (int j = 0; j < v.ny; ++j)
    for (int i = 0; i < v.nx; ++i) {
      const double lux = v.maintained_lux[static_cast<std::size_t>(j) * v.nx + i];
      if (!std::isfinite(lux)) continue;
      const std::string colour = svg_colour(colour_map(scale.fraction(lux)));
      const V2 c = f.to_px(V2(v.origin_m + V2(i * v.spacing_m.x(), j * v.spacing_m.y())));
      svg += cat("<rect x=\"", px(c.x() - 0.5 * w), "\" y=\"", px(c.y() - 0.5 * h), "\" width=\"", px(w),
                 "\" height=\"", px(h), "\" fill=\"", colour, "\" stroke=\"", colour, "\"/>\n");
    }
  return svg + "</g>\n";
}

// The architecture clipped to the plan's frame: furniture thin, the section's material
// (loops with it inside, and their holes) filled, every section line thick.
std::string architecture_svg(const PlanArchitecture& a, const svg::PlanFrame& f) {
  if (a.cut_height_m <= 0.0) return {};
  const Box frame = frame_box_px(f);
  std::string svg = cat("<clipPath id=\"ilp-isolux-frame\"><rect x=\"", px(frame.min().x()), "\" y=\"", px(frame.min().y()),
                        "\" width=\"", px(frame.sizes().x()), "\" height=\"", px(frame.sizes().y()),
                        "\"/></clipPath>\n<g class=\"architecture\" clip-path=\"url(#ilp-isolux-frame)\">\n");
  std::string furniture, material, lines;
  for (const Ring2& ring : a.furniture) furniture += polygon_path(ring, f);
  for (const SectionLine& l : a.section) {
    std::string d = polygon_path(l.points_m, f);
    if (!l.closed && !d.empty()) d.pop_back();  // an open line: no Z
    lines += d;
    if (section_material(l, a.section)) material += polygon_path(l.points_m, f);
  }
  if (!furniture.empty())
    svg += cat("<path class=\"furniture\" d=\"", furniture, "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1\"/>\n");
  if (!material.empty()) svg += cat("<path class=\"section-fill\" d=\"", material, "\" fill=\"#595959\"/>\n");
  if (!lines.empty())
    svg += cat("<path class=\"section\" d=\"", lines, "\" fill=\"none\" stroke=\"#111111\" stroke-width=\"2\"/>\n");
  return svg + "</g>\n";
}

std::string isolines(const std::vector<PxLine>& lines, double reference_lux) {
  std::string svg = "<g fill=\"none\" stroke=\"#1a1a1a\" stroke-linejoin=\"round\" stroke-linecap=\"round\">\n";
  for (const PxLine& l : lines) {
    std::string d;
    for (const V2& p : l.points) d += cat(d.empty() ? "M" : "L", xy(p.x(), p.y()));
    const bool target = std::abs(l.level - reference_lux) <= 1e-9 * reference_lux;
    svg += cat("<path d=\"", d, "\" stroke-width=\"", target ? "2.2" : "1.1", "\"><title>", lux_text(l.level),
               " lx</title></path>\n");
  }
  return svg + "</g>\n";
}

std::string labels_svg(const std::vector<IsoluxLabel>& labels) {
  std::string contour = "<g class=\"contour-labels\" font-size=\"11\" fill=\"#111111\">\n";
  std::string value =
      "<g class=\"value-labels\" font-size=\"10\" fill=\"#111111\" stroke=\"white\" stroke-width=\"2.5\" "
      "stroke-linejoin=\"round\" paint-order=\"stroke\">\n";
  std::string luminaire =
      "<g class=\"luminaire-labels\" font-size=\"11\" font-weight=\"bold\" fill=\"#111111\" stroke=\"white\" "
      "stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\">\n";
  for (const IsoluxLabel& l : labels) {
    const V2 c = l.box_px.center();
    // The baseline sits about 0.35 em below the centre for digits.
    switch (l.kind) {
      case IsoluxLabel::Kind::contour:
        contour += cat("<rect x=\"", px(l.box_px.min().x()), "\" y=\"", px(l.box_px.min().y()), "\" width=\"",
                       px(l.box_px.sizes().x()), "\" height=\"", px(l.box_px.sizes().y()),
                       "\" rx=\"3\" fill=\"white\" fill-opacity=\"0.92\"/>\n",
                       text_element(c.x(), c.y() + 0.36 * kContourFont_px, "middle", l.text));
        break;
      case IsoluxLabel::Kind::value:
        value += text_element(c.x(), c.y() + 0.36 * kValueFont_px, "middle", l.text);
        break;
      case IsoluxLabel::Kind::luminaire:
        luminaire += text_element(c.x(), c.y() + 0.36 * kLuminaireFont_px, "middle", l.text);
        break;
    }
  }
  return cat(contour, "</g>\n", value, "</g>\n", luminaire, "</g>\n");
}

std::string luminaires_svg(const IsoluxGridView& v, const svg::PlanFrame& f) {
  std::string svg = "<g fill=\"white\" stroke=\"#111111\" stroke-width=\"1.3\">\n";
  for (const IsoluxLuminaire& l : v.luminaires) {
    std::string tip = l.id;
    if (!l.product.empty()) tip += cat(" (", l.product, ")");
    tip += cat(": ", l.round ? cat("disc ", significant(l.length_m), " m") : cat(significant(l.length_m), " x ",
               significant(l.width_m), " m at ", significant(l.rotation_deg), " deg"),
               ", centre (", significant(l.centre_m.x()), ", ", significant(l.centre_m.y()), ") m");
    const std::string title = cat("<title>", xml_escape(tip), "</title>");
    const double min_px = 3.0;  // a point source still shows
    if (l.round || l.length_m * f.scale_px_per_m < min_px) {
      const double r = std::max(0.5 * l.length_m * f.scale_px_per_m, min_px);
      svg += cat("<circle cx=\"", px(f.x_px(l.centre_m.x())), "\" cy=\"", px(f.y_px(l.centre_m.y())), "\" r=\"", px(r),
                 "\">", title, "</circle>\n");
    } else {
      svg += cat("<path d=\"", polygon_path(luminaire_outline_m(l), f), "\">", title, "</path>\n");
    }
  }
  return svg + "</g>\n";
}

// Triangles at the minimum's point (open, pointing down) and the maximum's (filled, up).
std::string extreme_markers(const IsoluxGridView& v, const IsoluxLayout& layout, const svg::PlanFrame& f) {
  std::string svg;
  const double m = kMarker_px;
  if (layout.min_point >= 0) {
    const V2 c = f.to_px(point_m(v, layout.min_point));
    svg += cat("<path class=\"min-marker\" d=\"M", xy(c.x() - m, c.y() - 0.6 * m), 'L', xy(c.x() + m, c.y() - 0.6 * m), 'L',
               xy(c.x(), c.y() + m), "Z\" fill=\"white\" stroke=\"#111111\" stroke-width=\"1.5\"><title>min ",
               lux_text(layout.min_lux), " lx</title></path>\n");
  }
  if (layout.max_point >= 0) {
    const V2 c = f.to_px(point_m(v, layout.max_point));
    svg += cat("<path class=\"max-marker\" d=\"M", xy(c.x() - m, c.y() + 0.6 * m), 'L', xy(c.x() + m, c.y() + 0.6 * m), 'L',
               xy(c.x(), c.y() - m), "Z\" fill=\"#111111\" stroke=\"white\" stroke-width=\"1.5\"><title>max ",
               lux_text(layout.max_lux), " lx</title></path>\n");
  }
  return svg;
}

std::string north_arrow(double north_deg, double cx, double cy) {
  return cat("<g transform=\"rotate(", fixed(north_deg, 3), ' ', xy(cx, cy), ")\">\n<path d=\"M", xy(cx, cy - 18.0),
             "L", xy(cx + 7.0, cy + 10.0), "L", xy(cx, cy + 5.0), "L", xy(cx - 7.0, cy + 10.0),
             "Z\" fill=\"#222222\"/>\n", text_element(cx, cy - 22.0, "middle", "N", " font-weight=\"bold\""), "</g>\n");
}

// "every point", "every 2nd point", "every 3rd point", "every 4th point", ...
std::string every(int n) {
  if (n == 1) return "every point";
  const int tens = n % 100 / 10, units = n % 10;
  const char* suffix = tens == 1 ? "th" : units == 1 ? "st" : units == 2 ? "nd" : units == 3 ? "rd" : "th";
  return cat("every ", std::to_string(n), suffix, " point");
}

std::string legend(const IsoluxGridView& v, const IsoluxLayout& layout, double x, double top, double bar_px) {
  constexpr double kBar_px = 18.0, kTick_px = 5.0, kRow_px = 16.0;
  std::string svg = text_element(x, top + 10.0, "start", "maintained illuminance (lx)", " font-weight=\"bold\"");
  svg += text_element(x, top + 10.0 + kRow_px, "start",
                      v.maintenance_factor == 1.0 ? std::string("= initial (maintenance factor 1)")
                                                  : cat("= initial x maintenance factor ", fixed(v.maintenance_factor, 2)));
  const double bar_top = top + 40.0, bar_bottom = bar_top + bar_px;
  svg += cat("<rect x=\"", px(x), "\" y=\"", px(bar_top), "\" width=\"", px(kBar_px), "\" height=\"", px(bar_px),
             "\" fill=\"white\"/>\n<rect x=\"", px(x), "\" y=\"", px(bar_top), "\" width=\"", px(kBar_px), "\" height=\"",
             px(bar_px), "\" fill=\"url(#", kGradientId, ")\" opacity=\"", fixed(kFillOpacity, 2), "\"/>\n<rect x=\"", px(x),
             "\" y=\"", px(bar_top), "\" width=\"", px(kBar_px), "\" height=\"", px(bar_px),
             "\" fill=\"none\" stroke=\"#333333\"/>\n");
  const bool above = layout.max_lux > layout.scale.max_lux;
  std::string marks, labels;
  for (int k = 0; k <= 4; ++k) {
    const double lux = 0.25 * k * layout.scale.max_lux, y = bar_bottom - 0.25 * k * bar_px;
    marks += cat('M', xy(x + kBar_px, y), 'h', px(kTick_px));
    std::string text = lux_text(lux);
    if (k == 2) text += layout.reference_is_target ? "  target" : "  Em (no target)";
    if (k == 4 && above) text = cat("\u2265 ", text);
    labels += text_element(x + kBar_px + kTick_px + 3.0, y + 4.0, "start", text);
  }
  svg += cat("<path d=\"", marks, "\" stroke=\"#333333\"/>\n", labels);
  // The isoline levels as marks across the bar, the target's thicker (as its line).
  for (double level : layout.levels_lux) {
    if (level > layout.scale.max_lux) continue;
    const double ly = bar_bottom - layout.scale.fraction(level) * bar_px;
    const bool target = std::abs(level - layout.reference_lux) <= 1e-9 * layout.reference_lux;
    svg += cat("<path d=\"M", xy(x - 4.0, ly), 'h', px(kBar_px + 4.0), "\" stroke=\"#1a1a1a\" stroke-width=\"",
               target ? "2.2" : "1.1", "\"/>\n");
  }
  double y = bar_bottom + 24.0;
  const auto row = [&](const std::string& text, std::string_view extra = "") {
    svg += text_element(x, y, "start", text, extra);
    y += kRow_px;
  };
  row(layout.reference_is_target ? cat("target Em ", lux_text(layout.reference_lux), " lx")
                                 : cat("no target: scale on Em ", lux_text(layout.reference_lux), " lx"));
  if (layout.points > 0)
    row(cat("\u25bd min ", lux_text(layout.min_lux), " lx, \u25b2 max ", lux_text(layout.max_lux), " lx"));
  if (above) row(cat("above ", lux_text(layout.scale.max_lux), " lx: top colour"));
  row("isolines (lx):");
  // Four levels a row, so that four-digit levels stay inside the column.
  for (std::size_t first = 0; first < layout.levels_lux.size(); first += 4) {
    std::string levels;
    for (std::size_t k = first; k < std::min(first + 4, layout.levels_lux.size()); ++k)
      levels += cat(levels.empty() ? "" : " ", lux_text(layout.levels_lux[k]));
    row(levels);
  }
  row(cat(std::to_string(layout.points), " points, values at"));
  row(layout.value_step_x == layout.value_step_y
          ? every(layout.value_step_x)
          : cat("every ", std::to_string(layout.value_step_x), " / ", std::to_string(layout.value_step_y),
                " points (x / y)"));
  row("grey: no point (band, solid)");
  return svg;
}

}  // namespace

std::vector<double> isolux_levels(double reference_lux) {
  if (!(reference_lux > 0.0) || !std::isfinite(reference_lux))
    throw std::invalid_argument(cat("isolux_levels: reference ", significant(reference_lux), " lx must be > 0"));
  std::vector<double> levels;
  for (double fraction : kLevelFractions) {
    const double level = fraction == 1.0 ? reference_lux : two_digits(fraction * reference_lux);
    if (levels.empty() || level > levels.back()) levels.push_back(level);
  }
  return levels;
}

IsoluxLayout isolux_plan_layout(const IsoluxGridView& v) {
  check(v);
  IsoluxLayout layout;
  double sum = 0.0;
  layout.min_lux = std::numeric_limits<double>::infinity();
  layout.max_lux = -layout.min_lux;
  for (std::size_t k = 0; k < v.maintained_lux.size(); ++k) {
    const double lux = v.maintained_lux[k];
    if (!std::isfinite(lux)) continue;
    ++layout.points;
    sum += lux;
    if (lux < layout.min_lux) {
      layout.min_lux = lux;
      layout.min_point = static_cast<int>(k);
    }
    if (lux > layout.max_lux) {
      layout.max_lux = lux;
      layout.max_point = static_cast<int>(k);
    }
  }
  if (layout.points == 0) layout.min_lux = layout.max_lux = std::numeric_limits<double>::quiet_NaN();
  layout.reference_is_target = !std::isnan(v.target_lux);
  const double average = layout.points > 0 ? sum / layout.points : 0.0;
  layout.reference_lux = layout.reference_is_target ? v.target_lux : (average > 0.0 ? average : 1.0);
  layout.scale = {0.0, 2.0 * layout.reference_lux};
  layout.levels_lux = isolux_levels(layout.reference_lux);

  LatticeField field{v.nx, v.ny, v.origin_m, v.spacing_m, v.maintained_lux};
  for (double& lux : field.values)
    if (!std::isfinite(lux)) lux = std::numeric_limits<double>::quiet_NaN();  // +-inf: no point either
  for (double level : layout.levels_lux)
    for (ContourLine& line : contour_lines(field, level)) layout.lines.push_back(std::move(line));

  const PlanGeometry g = plan_geometry(v);
  const svg::PlanFrame& f = g.frame;
  layout.width_px = g.width_px;
  layout.height_px = g.height_px;
  layout.plan_px = frame_box_px(f);
  layout.scale_px_per_m = f.scale_px_per_m;

  std::vector<Box> outlines_px;
  for (const IsoluxLuminaire& l : v.luminaires) {
    Box b;
    for (const V2& p : luminaire_outline_m(l)) b.extend(f.to_px(p));
    b.extend(V2(b.center() - V2::Constant(3.0))).extend(V2(b.center() + V2::Constant(3.0)));
    outlines_px.push_back(b);
  }
  std::vector<Box> obstacles_px = outlines_px;
  for (int point : {layout.min_point, layout.max_point})
    if (point >= 0) {
      const V2 c = f.to_px(point_m(v, point));
      obstacles_px.emplace_back(c - V2::Constant(kMarker_px + 1.0), c + V2::Constant(kMarker_px + 1.0));
    }
  Placer placer{frame_box_px(f), obstacles_px, &layout.labels};
  place_luminaire_labels(v, placer, outlines_px);
  std::vector<PxLine> lines;
  for (const ContourLine& line : layout.lines) lines.push_back(to_px(line, f));
  place_contour_labels(lines, layout.reference_lux, placer);
  place_value_labels(v, f, layout, placer);
  return layout;
}

std::string isolux_plan_svg(const IsoluxGridView& v) {
  const IsoluxLayout layout = isolux_plan_layout(v);
  const PlanGeometry g = plan_geometry(v);
  const svg::PlanFrame& f = g.frame;
  const std::string room = room_path(v, f);

  std::string svg = cat("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", px(layout.width_px), "\" height=\"",
                        px(layout.height_px), "\" viewBox=\"0 0 ", px(layout.width_px), ' ', px(layout.height_px),
                        "\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"12\">\n<defs>\n",
                        svg::colour_map_gradient(kGradientId));
  if (!room.empty()) svg += cat("<clipPath id=\"", kClipId, "\"><path d=\"", room, "\" clip-rule=\"evenodd\"/></clipPath>\n");
  svg += "</defs>\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += text_element(kLeft_px, 28.0, "start", v.name.empty() ? std::string("isolux plan") : v.name,
                      " font-size=\"16\" font-weight=\"bold\"");
  if (!v.title.empty()) svg += text_element(kLeft_px, 48.0, "start", v.title, " font-size=\"13\"");

  const Box frame = frame_box_px(f);
  svg += cat("<rect x=\"", px(frame.min().x()), "\" y=\"", px(frame.min().y()), "\" width=\"", px(frame.sizes().x()),
             "\" height=\"", px(frame.sizes().y()), "\" fill=\"none\" stroke=\"#999999\" stroke-width=\"0.8\"/>\n");
  if (!room.empty()) svg += cat("<path d=\"", room, "\" fill=\"#d9d9d9\" fill-rule=\"evenodd\"/>\n");
  svg += cells(v, f, layout.scale, !room.empty());
  svg += architecture_svg(v.architecture, f);
  if (!room.empty())
    svg += cat("<path d=\"", room, "\" fill=\"none\" stroke=\"#222222\" stroke-width=\"2\" stroke-linejoin=\"round\"/>\n");
  std::vector<PxLine> lines;
  for (const ContourLine& line : layout.lines) lines.push_back(to_px(line, f));
  svg += isolines(lines, layout.reference_lux);
  svg += luminaires_svg(v, f);
  svg += extreme_markers(v, layout, f);
  svg += labels_svg(layout.labels);
  svg += svg::plan_axes(f, v.x_label, v.y_label);
  svg += svg::plan_scale_bar(f);
  const double legend_x = f.left_px + f.width_px() + kGap_px;
  svg += legend(v, layout, legend_x, g.top_px, g.bar_px);
  if (std::isfinite(v.north_deg)) svg += north_arrow(v.north_deg, legend_x + 30.0, layout.height_px - kBottom_px - 10.0);
  return svg + "</svg>\n";
}

void write_isolux_plan(const std::string& path_svg, const std::string& path_png, const IsoluxGridView& view) {
  const std::string svg = isolux_plan_svg(view);
  if (!path_svg.empty()) write_file_atomically(path_svg, [&](std::ostream& out) { out << svg; });
  if (!path_png.empty()) write_png_from_svg(path_png, svg, 2.0);
}

}  // namespace ilp
