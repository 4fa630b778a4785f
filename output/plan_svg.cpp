#include "output/plan_svg.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "output/colour_map.h"
#include "output/svg_plan_parts.h"
#include "output/svg_text.h"

namespace ilp {
namespace {

constexpr double kFont_px = 12.0;
constexpr double kLabelCharWidth_px = 6.5;  // a generous estimate of one sans-serif glyph at 11 px
constexpr double kLeft_px = 64.0;           // y label and tick labels
constexpr double kGap_px = 30.0;            // plan to legend
constexpr double kLegendColumn_px = 140.0;  // legend, including the right margin
constexpr double kMaxPlanWidth_px = 900.0 - kLeft_px - kGap_px - kLegendColumn_px;
constexpr double kMaxPlanHeight_px = 720.0;
constexpr double kBottom_px = 72.0;  // tick labels, x label, scale bar
constexpr double kTick_px = 5.0;
constexpr double kMinLuminaire_px = 4.0;
constexpr std::string_view kGradientId = "ilp-plan-lux";

// ---- text ---------------------------------------------------------------------

using svg::cat;
using svg::char_count;
using svg::exact;
using svg::fixed;
using svg::px;
using svg::significant;
using svg::text_element;
using svg::xml_escape;
using svg::xy;

double label_width_px(std::string_view text) { return static_cast<double>(char_count(text)) * kLabelCharWidth_px; }

// ---- geometry ------------------------------------------------------------------

using Frame = svg::PlanFrame;

void extend(Eigen::AlignedBox2d& box, const Patch& p) {
  for (const Eigen::Vector3d& v : p.vertices_m) box.extend(v.head<2>());
}

// A box with neither side (nearly) zero: a single point or a line still gets a plan.
Eigen::AlignedBox2d padded(Eigen::AlignedBox2d box) {
  if (box.isEmpty()) return Eigen::AlignedBox2d(Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones());
  const double least = std::max(1e-3, 0.02 * box.sizes().maxCoeff());
  for (int axis = 0; axis < 2; ++axis) {
    const double missing = least - box.sizes()[axis];
    if (missing <= 0.0) continue;
    box.min()[axis] -= 0.5 * missing;
    box.max()[axis] += 0.5 * missing;
  }
  return box;
}

void check(const Scene& scene, const PlanView& view) {
  if (static_cast<std::size_t>(view.goal_lux.size()) != view.goal_patches.size())
    throw std::invalid_argument(cat("render_plan_svg: ", std::to_string(view.goal_patches.size()), " goal patches but ",
                                    std::to_string(view.goal_lux.size()), " lux values"));
  const auto check_indices = [&](const std::vector<int>& patches, const char* what) {
    for (int p : patches)
      if (p < 0 || static_cast<std::size_t>(p) >= scene.patches.size())
        throw std::invalid_argument(cat("render_plan_svg: ", what, " patch ", std::to_string(p),
                                        " is not in the scene (", std::to_string(scene.patches.size()),
                                        " patches)"));
  };
  check_indices(view.goal_patches, "goal");
  check_indices(view.outline_patches, "outline");
  for (const PlanLuminaire& l : view.luminaires)
    if (!l.position_m.allFinite() || !std::isfinite(l.size_m) || l.size_m < 0.0 || !std::isfinite(l.flux_lm))
      throw std::invalid_argument(
          cat("render_plan_svg: luminaire '", l.id, "' has a non-finite position, size or flux, or a negative size"));
}

// The colour bar with ticks at quarters of the scale, then the goal's min and max.
std::string legend(const ColourScale& scale, const Eigen::VectorXd& lux, double x, double top, double bar_px) {
  constexpr double kBar_px = 18.0;
  std::string svg = text_element(x, top + 10.0, "start", "illuminance (lx)");
  const double bar_top = top + 22.0, bar_bottom = bar_top + bar_px;
  svg += cat("<rect x=\"", px(x), "\" y=\"", px(bar_top), "\" width=\"", px(kBar_px), "\" height=\"", px(bar_px),
             "\" fill=\"url(#", kGradientId, ")\" stroke=\"#333333\"/>\n");
  std::string marks, labels;
  const double range = scale.max_lux - scale.min_lux;
  for (int k = 0; k <= 4; ++k) {
    const double y = bar_bottom - 0.25 * k * bar_px;
    marks += cat('M', xy(x + kBar_px, y), 'h', px(kTick_px));
    labels += text_element(x + kBar_px + kTick_px + 3.0, y + 4.0, "start",
                           exact(scale.min_lux + 0.25 * k * range, range > 0.0 ? range : 1.0));
  }
  svg += cat("<path d=\"", marks, "\" stroke=\"#333333\"/>\n", labels);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (Eigen::Index i = 0; i < lux.size(); ++i) {
    if (!std::isfinite(lux[i])) continue;
    lo = std::min(lo, lux[i]);
    hi = std::max(hi, lux[i]);
  }
  if (lo <= hi) {
    svg += text_element(x, bar_bottom + 22.0, "start", cat("max ", significant(hi), " lx"));
    svg += text_element(x, bar_bottom + 38.0, "start", cat("min ", significant(lo), " lx"));
  }
  return svg;
}

// The luminaire's outline in the plane: its real one, or a square of size_m.
std::vector<Eigen::Vector2d> plan_outline_m(const PlanLuminaire& l) {
  if (!l.outline_m.empty()) return l.outline_m;
  const Eigen::Vector2d c = l.position_m.head<2>();
  const double h = 0.5 * l.size_m;
  return {c + Eigen::Vector2d(-h, -h), c + Eigen::Vector2d(h, -h), c + Eigen::Vector2d(h, h), c + Eigen::Vector2d(-h, h)};
}

// Outline, a cross through it and labels of one luminaire (a tiny one is drawn at
// least kMinLuminaire_px across); labels go left of it when they would leave the plan
// on the right.
std::string luminaire(const Frame& f, const PlanLuminaire& l) {
  const double cx = f.x_px(l.position_m.x()), cy = f.y_px(l.position_m.y());
  std::vector<Eigen::Vector2d> outline_px;
  double x0 = cx, x1 = cx, y0 = cy, y1 = cy;
  for (const Eigen::Vector2d& v : plan_outline_m(l)) {
    outline_px.emplace_back(f.x_px(v.x()), f.y_px(v.y()));
    x0 = std::min(x0, outline_px.back().x());
    x1 = std::max(x1, outline_px.back().x());
    y0 = std::min(y0, outline_px.back().y());
    y1 = std::max(y1, outline_px.back().y());
  }
  const double grow = std::max(1.0, kMinLuminaire_px / std::max(1e-9, std::max(x1 - x0, y1 - y0)));
  std::string d;
  for (std::size_t k = 0; k < outline_px.size(); ++k) {
    const Eigen::Vector2d q = Eigen::Vector2d(cx, cy) + grow * (outline_px[k] - Eigen::Vector2d(cx, cy));
    d += cat(k == 0 ? "M" : "L", xy(q.x(), q.y()));
  }
  x0 = cx - grow * (cx - x0);
  x1 = cx + grow * (x1 - cx);
  y0 = cy - grow * (cy - y0);
  y1 = cy + grow * (y1 - cy);
  // The cross along the outline's first two edges' directions (the luminaire's axes).
  const Eigen::Vector2d a = 0.5 * grow * (outline_px[1] - outline_px[0]), b = 0.5 * grow * (outline_px.back() - outline_px[0]);
  if (outline_px.size() == 4)
    d += cat("Z M", xy(cx - a.x() - b.x(), cy - a.y() - b.y()), 'L', xy(cx + a.x() + b.x(), cy + a.y() + b.y()), 'M',
             xy(cx + a.x() - b.x(), cy + a.y() - b.y()), 'L', xy(cx - a.x() + b.x(), cy - a.y() + b.y()));
  else
    d += cat("Z M", xy(x0, cy), 'L', xy(x1, cy), 'M', xy(cx, y0), 'L', xy(cx, y1));
  const std::string flux = cat(significant(l.flux_lm), " lm");
  const double label_px = std::max(label_width_px(l.id), label_width_px(flux));
  const bool left = x1 + 4.0 + label_px > f.left_px + f.width_px() && x0 - 4.0 - label_px >= f.left_px;
  const double label_x = left ? x0 - 4.0 : x1 + 4.0;
  const std::string_view anchor = left ? "end" : "start";
  const Eigen::Vector3d& p = l.position_m;
  constexpr std::string_view kHalo = " fill=\"#111111\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\"";
  return cat("<g>\n<title>",
             xml_escape(cat(l.id, ": ", flux, ", ", l.product.empty() ? cat(significant(l.size_m), " m square") : l.product,
                            " at (", significant(p.x()), ", ", significant(p.y()), ", ", significant(p.z()), ") m")),
             "</title>\n",
             // A dark line on a white halo, and dark text on a white halo: legible on
             // every colour of the map.
             "<path d=\"", d, "\" fill=\"none\" stroke=\"white\" stroke-width=\"3.5\"/>\n", "<path d=\"", d,
             "\" fill=\"none\" stroke=\"#111111\" stroke-width=\"1.25\"/>\n",
             text_element(label_x, cy - 2.0, anchor, l.id, kHalo), text_element(label_x, cy + 11.0, anchor, flux, kHalo),
             "</g>\n");
}

}  // namespace

std::string render_plan_svg(const Scene& scene, const PlanView& view) {
  check(scene, view);
  const std::vector<int>& outline = view.outline_patches.empty() ? scene.all_patches() : view.outline_patches;

  // What the plan spans: the outline's frame, the goal patches and the luminaires.
  Eigen::AlignedBox2d frame_m;
  for (int p : outline) extend(frame_m, scene.patches[p]);
  Eigen::AlignedBox2d extent_m = frame_m;
  for (int p : view.goal_patches) extend(extent_m, scene.patches[p]);
  for (const PlanLuminaire& l : view.luminaires) {
    for (const Eigen::Vector2d& v : plan_outline_m(l)) extent_m.extend(v);
  }

  Frame f;
  f.extent_m = padded(extent_m);
  f.scale_px_per_m =
      std::min(kMaxPlanWidth_px / f.extent_m.sizes().x(), kMaxPlanHeight_px / f.extent_m.sizes().y());
  f.left_px = kLeft_px;
  f.top_px = view.title.empty() ? 24.0 : 52.0;
  const double legend_x = f.left_px + f.width_px() + kGap_px;
  const double bar_px = std::clamp(f.height_px() - 66.0, 160.0, 300.0);
  const double width_px = legend_x + kLegendColumn_px;
  const double height_px = f.top_px + std::max(f.height_px(), 22.0 + bar_px + 44.0) + kBottom_px;

  std::string svg = cat("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", px(width_px), "\" height=\"",
                        px(height_px), "\" viewBox=\"0 0 ", px(width_px), ' ', px(height_px),
                        "\" font-family=\"sans-serif\" font-size=\"", px(kFont_px), "\">\n");
  svg += cat("<defs>\n", svg::colour_map_gradient(kGradientId), "</defs>\n");
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!view.title.empty())
    svg += text_element(16.0, 30.0, "start", view.title, " font-size=\"15\" font-weight=\"bold\"");

  // Room: the outline triangles as one path, each turned the same way round, so that
  // nonzero filling gives their union without anti-aliasing seams between them.
  std::string room;
  for (int p : outline) {
    std::array<Eigen::Vector2d, 3> v;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& q = scene.patches[p].vertices_m[k];
      v[k] = {f.x_px(q.x()), f.y_px(q.y())};
    }
    const double doubled_area = (v[1] - v[0]).x() * (v[2] - v[0]).y() - (v[1] - v[0]).y() * (v[2] - v[0]).x();
    if (std::abs(doubled_area) < 1e-6) continue;  // seen edge-on, e.g. a wall
    if (doubled_area < 0.0) std::swap(v[1], v[2]);
    room += cat('M', xy(v[0].x(), v[0].y()), 'L', xy(v[1].x(), v[1].y()), 'L', xy(v[2].x(), v[2].y()), 'Z');
  }
  if (!room.empty()) svg += cat("<path d=\"", room, "\" fill=\"#e6e6e6\"/>\n");

  // Goal patches, lowest mean height first; the stroke in the fill colour covers the
  // hairline seams anti-aliasing leaves between neighbours.
  const ColourScale scale = colour_scale_for(view.goal_lux);
  std::vector<std::size_t> order(view.goal_patches.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto height = [&](std::size_t i) {
    const auto& v = scene.patches[view.goal_patches[i]].vertices_m;
    return v[0].z() + v[1].z() + v[2].z();
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return height(a) < height(b); });
  svg += "<g stroke-width=\"0.5\" stroke-linejoin=\"round\">\n";
  for (std::size_t i : order) {
    const Patch& patch = scene.patches[view.goal_patches[i]];
    const std::string colour = svg_colour(colour_map(scale.fraction(view.goal_lux[static_cast<Eigen::Index>(i)])));
    std::string points;
    for (const Eigen::Vector3d& q : patch.vertices_m) points += cat(points.empty() ? "" : " ", xy(f.x_px(q.x()), f.y_px(q.y())));
    svg += cat("<polygon points=\"", points, "\" fill=\"", colour, "\" stroke=\"", colour, "\"/>\n");
  }
  svg += "</g>\n";

  if (!frame_m.isEmpty())
    svg += cat("<rect x=\"", px(f.x_px(frame_m.min().x())), "\" y=\"", px(f.y_px(frame_m.max().y())), "\" width=\"",
               px(frame_m.sizes().x() * f.scale_px_per_m), "\" height=\"", px(frame_m.sizes().y() * f.scale_px_per_m),
               "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1.5\"/>\n");
  svg += svg::plan_axes(f);
  svg += svg::plan_scale_bar(f);

  if (!view.luminaires.empty()) {
    svg += "<g font-size=\"11\" stroke-linejoin=\"round\">\n";
    for (const PlanLuminaire& l : view.luminaires) svg += luminaire(f, l);
    svg += "</g>\n";
  }
  svg += legend(scale, view.goal_lux, legend_x, f.top_px, bar_px);
  svg += "</svg>\n";
  return svg;
}

}  // namespace ilp
