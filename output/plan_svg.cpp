#include "output/plan_svg.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "output/colour_map.h"
#include "output/plan_labels.h"
#include "output/svg_plan_parts.h"
#include "output/svg_text.h"

namespace ilp {
namespace {

constexpr double kFont_px = 12.0;
constexpr double kSmallFont_px = 11.0;
constexpr double kCharWidth_px = 6.6;       // a generous estimate of one DejaVu Sans glyph at 11-12 px
constexpr double kBoldCharWidth_px = 7.4;   // ... in bold
constexpr double kLeft_px = 64.0;           // y label and tick labels
constexpr double kGap_px = 28.0;            // plan (or its y chain) to the column
constexpr double kColumn_px = 330.0;        // legend, schedule and title block, including the right margin
constexpr double kMaxPlanWidth_px = 620.0;
constexpr double kMaxPlanHeight_px = 640.0;
constexpr double kBottom_px = 72.0;         // tick labels, x label, scale bar
constexpr double kChainZone_px = 46.0;      // above the plan (x chain) and right of it (y chain)
constexpr double kChainOffset_px = 20.0;    // the chain's line from the plan's frame
constexpr double kTick_px = 5.0;
constexpr double kMinLuminaire_px = 4.0;
constexpr double kRow_px = 15.0;
constexpr int kMaxChainStops = 14;          // more rows than this: no chain (the schedule gives positions)
constexpr int kMaxScheduleRows = 36;
constexpr std::string_view kGradientId = "ilp-plan-lux";
constexpr std::string_view kClipId = "ilp-plan-frame";

using svg::cat;
using svg::char_count;
using svg::exact;
using svg::fixed;
using svg::px;
using svg::significant;
using svg::text_element;
using svg::xml_escape;
using svg::xy;
using Box = Eigen::AlignedBox2d;
using V2 = Eigen::Vector2d;
using Frame = svg::PlanFrame;

double text_px(std::string_view text, double char_px = kCharWidth_px) {
  return static_cast<double>(char_count(text)) * char_px;
}

// ---- checks and extents ----------------------------------------------------------

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
    if (!l.position_m.allFinite() || !std::isfinite(l.size_m) || l.size_m < 0.0 || !std::isfinite(l.flux_lm) ||
        !std::isfinite(l.rotation_deg) || !std::isfinite(l.tilt_deg))
      throw std::invalid_argument(
          cat("render_plan_svg: luminaire '", l.id, "' has a non-finite position, size or flux, or a negative size"));
  for (const PlanGrid& g : view.grids)
    if (g.points_m.size() != g.lux.size())
      throw std::invalid_argument(cat("render_plan_svg: grid '", g.name, "' needs one value per point"));
  if (!(view.maintenance_factor > 0.0 && view.maintenance_factor <= 1.0))
    throw std::invalid_argument("render_plan_svg: the maintenance factor must be in (0, 1]");
}

void extend(Box& box, const Patch& p) {
  for (const Eigen::Vector3d& v : p.vertices_m) box.extend(v.head<2>());
}

// A box with neither side (nearly) zero: a single point or a line still gets a plan.
Box padded(Box box) {
  if (box.isEmpty()) return Box(V2::Zero(), V2::Ones());
  const double least = std::max(1e-3, 0.02 * box.sizes().maxCoeff());
  for (int axis = 0; axis < 2; ++axis) {
    const double missing = least - box.sizes()[axis];
    if (missing <= 0.0) continue;
    box.min()[axis] -= 0.5 * missing;
    box.max()[axis] += 0.5 * missing;
  }
  return box;
}

// The luminaire's outline in the plane: its real one, or a square of size_m.
std::vector<V2> plan_outline_m(const PlanLuminaire& l) {
  if (!l.outline_m.empty()) return l.outline_m;
  const V2 c = l.position_m.head<2>();
  const double h = 0.5 * l.size_m;
  return {c + V2(-h, -h), c + V2(h, -h), c + V2(h, h), c + V2(-h, h)};
}

// The outline in px, grown about the centre to at least kMinLuminaire_px across.
std::vector<V2> outline_px(const Frame& f, const PlanLuminaire& l) {
  const V2 c = f.to_px(l.position_m.head<2>());
  std::vector<V2> out;
  Box box(c, c);
  for (const V2& v : plan_outline_m(l)) {
    out.push_back(f.to_px(v));
    box.extend(out.back());
  }
  const double grow = std::max(1.0, kMinLuminaire_px / std::max(1e-9, box.sizes().maxCoeff()));
  for (V2& q : out) q = c + grow * (q - c);
  return out;
}

Box box_of(const std::vector<V2>& points) {
  Box b;
  for (const V2& p : points) b.extend(p);
  return b;
}

// The plan's frame in metres: the outline patches' bounding rectangle.
Box outline_frame_m(const Scene& scene, const PlanView& view) {
  Box frame;
  const std::vector<int>& outline = view.outline_patches.empty() ? scene.all_patches() : view.outline_patches;
  for (int p : outline) extend(frame, scene.patches[static_cast<std::size_t>(p)]);
  return frame;
}

bool has_chains(const PlanView& view) { return view.dimensions && !view.luminaires.empty(); }

// ---- the layout -------------------------------------------------------------------

struct Geometry {
  Frame f;
  Box frame_m;         // the outline's frame
  double legend_x = 0.0, bar_top = 0.0, bar_px = 0.0;
  double width_px = 0.0, height_px = 0.0;
};

int schedule_rows(const PlanView& view) { return std::min<int>(static_cast<int>(view.luminaires.size()), kMaxScheduleRows); }

double column_svg(const PlanView& view, double x, double y, std::string* svg_out);

// Where the column's text starts: under the colour bar.
double column_top(const PlanView& view, const Geometry& g) {
  return g.bar_top + g.bar_px + (view.maintenance_factor < 1.0 ? 16.0 : 0.0) + 24.0;
}

Geometry geometry(const Scene& scene, const PlanView& view) {
  Geometry g;
  g.frame_m = outline_frame_m(scene, view);
  Box extent = g.frame_m;
  for (int p : view.goal_patches) extend(extent, scene.patches[static_cast<std::size_t>(p)]);
  for (const PlanLuminaire& l : view.luminaires)
    for (const V2& v : plan_outline_m(l)) extent.extend(v);
  for (const PlanGrid& grid : view.grids)
    for (const V2& p : grid.points_m) {
      extent.extend(V2(p - 0.5 * grid.cell_m));
      extent.extend(V2(p + 0.5 * grid.cell_m));
    }
  const double chains = has_chains(view) ? kChainZone_px : 0.0;
  g.f.extent_m = padded(extent);
  if (view.architecture.cut_height_m > 0.0) {  // room for the walls' thick lines at the frame
    const double pad = 0.02 * g.f.extent_m.sizes().maxCoeff();
    g.f.extent_m.min() -= V2::Constant(pad);
    g.f.extent_m.max() += V2::Constant(pad);
  }
  g.f.scale_px_per_m = std::min(kMaxPlanWidth_px / g.f.extent_m.sizes().x(), kMaxPlanHeight_px / g.f.extent_m.sizes().y());
  g.f.left_px = kLeft_px;
  g.f.top_px = (view.title.empty() ? 24.0 : 52.0) + chains;
  g.legend_x = g.f.left_px + g.f.width_px() + chains + kGap_px;
  g.bar_top = (view.title.empty() ? 24.0 : 52.0) + 22.0;
  g.bar_px = 200.0;
  g.width_px = g.legend_x + kColumn_px;
  const double column_bottom = column_svg(view, g.legend_x, column_top(view, g), nullptr) + 16.0;
  g.height_px = std::max(g.f.top_px + g.f.height_px() + kBottom_px, column_bottom);
  return g;
}

// Walls for the chains: the architecture's wall cut, else the outline's frame.
std::vector<SectionLine> chain_walls(const PlanView& view, const Box& frame_m) {
  if (!view.architecture.walls.empty()) return view.architecture.walls;
  if (frame_m.isEmpty()) return {};
  SectionLine l;
  l.closed = true;
  l.points_m = {frame_m.corner(Box::BottomLeft), frame_m.corner(Box::BottomRight), frame_m.corner(Box::TopRight),
                frame_m.corner(Box::TopLeft)};
  return {l};
}

PlanLayout layout_of(const Scene& scene, const PlanView& view, const Geometry& g) {
  PlanLayout out;
  out.width_px = g.width_px;
  out.height_px = g.height_px;
  out.plan_px = Box(V2(g.f.left_px, g.f.top_px), V2(g.f.left_px + g.f.width_px(), g.f.top_px + g.f.height_px()));
  out.scale_px_per_m = g.f.scale_px_per_m;
  std::vector<LabelRequest> requests;
  for (const PlanLuminaire& l : view.luminaires) {
    out.outline_px.push_back(box_of(outline_px(g.f, l)));
    const V2 size(text_px(l.id, kBoldCharWidth_px) + 4.0, kSmallFont_px + 4.0);
    requests.push_back({out.outline_px.back(), size});
  }
  for (const PlacedLabel& p : place_labels(requests, {}, out.plan_px)) {
    out.label_px.push_back(p.placed ? p.box_px : Box());
    out.leader.push_back(p.placed && p.leader);
  }
  if (has_chains(view)) {
    std::vector<V2> centres;
    for (const PlanLuminaire& l : view.luminaires) centres.push_back(l.position_m.head<2>());
    const std::vector<SectionLine> walls = chain_walls(view, g.frame_m);
    for (int axis = 0; axis < 2; ++axis) {
      DimensionChain chain = dimension_chain(centres, axis, walls);
      if (chain.stops_m.size() < 2 || static_cast<int>(chain.stops_m.size()) > kMaxChainStops) chain.stops_m.clear();
      std::vector<std::string> text;
      for (double length : chain.lengths_m()) text.push_back(metres_2(length));
      (axis == 0 ? out.along_x : out.along_y) = chain;
      (axis == 0 ? out.along_x_text : out.along_y_text) = text;
    }
  }
  (void)scene;
  return out;
}

// ---- drawing ----------------------------------------------------------------------

std::string polygon_d(const std::vector<V2>& points_px, bool closed) {
  std::string d;
  for (const V2& p : points_px) d += cat(d.empty() ? "M" : "L", xy(p.x(), p.y()));
  return closed && !d.empty() ? d + "Z" : d;
}

std::vector<V2> to_px(const Frame& f, const std::vector<V2>& points_m) {
  std::vector<V2> out;
  for (const V2& p : points_m) out.push_back(f.to_px(p));
  return out;
}

// The architecture, clipped to the plan's frame: furniture outlines thin, the section's
// material filled dark (loops with the material inside, and holes in them) and every
// section line thick.
std::string architecture_svg(const Frame& f, const PlanArchitecture& a) {
  if (a.cut_height_m <= 0.0) return {};
  std::string svg = cat("<g class=\"architecture\" clip-path=\"url(#", kClipId, ")\" stroke-linejoin=\"miter\">\n");
  std::string furniture;
  for (const Ring2& ring : a.furniture) furniture += polygon_d(to_px(f, ring), true);
  if (!furniture.empty())
    svg += cat("<path class=\"furniture\" d=\"", furniture,
               "\" fill=\"#ffffff\" fill-opacity=\"0.25\" stroke=\"#4d4d4d\" stroke-width=\"1\"/>\n");
  std::string material, lines;
  for (const SectionLine& l : a.section) {
    lines += polygon_d(to_px(f, l.points_m), l.closed);
    if (section_material(l, a.section)) material += polygon_d(to_px(f, l.points_m), true);
  }
  if (!material.empty()) svg += cat("<path class=\"section-fill\" d=\"", material, "\" fill=\"#595959\" stroke=\"none\"/>\n");
  if (!lines.empty())
    svg += cat("<path class=\"section\" d=\"", lines, "\" fill=\"none\" stroke=\"#111111\" stroke-width=\"2.2\"/>\n");
  return svg + "</g>\n";
}

std::string grid_cells(const Frame& f, const PlanView& view, const ColourScale& scale) {
  std::string svg;
  for (const PlanGrid& g : view.grids) {
    if (!(g.cell_m.x() > 0.0 && g.cell_m.y() > 0.0)) continue;
    svg += cat("<g class=\"grid\" opacity=\"0.85\" stroke-width=\"0.5\"><title>", xml_escape(g.name), "</title>\n");
    const double w = g.cell_m.x() * f.scale_px_per_m, h = g.cell_m.y() * f.scale_px_per_m;
    for (std::size_t k = 0; k < g.points_m.size(); ++k) {
      const double lux = g.lux[k] * view.maintenance_factor;
      const std::string colour = svg_colour(colour_map(scale.fraction(lux)));
      const V2 c = f.to_px(g.points_m[k]);
      svg += cat("<rect x=\"", px(c.x() - 0.5 * w), "\" y=\"", px(c.y() - 0.5 * h), "\" width=\"", px(w),
                 "\" height=\"", px(h), "\" fill=\"", colour, "\" stroke=\"", colour, "\"/>\n");
    }
    svg += "</g>\n";
  }
  return svg;
}

// Outline, a cross along the luminaire's axes, and for a tilted one an arrow along its aim.
std::string luminaire_svg(const Frame& f, const PlanLuminaire& l) {
  const std::vector<V2> outline = outline_px(f, l);
  const V2 c = f.to_px(l.position_m.head<2>());
  std::string d = polygon_d(outline, true);
  if (outline.size() == 4) {
    const V2 a = 0.5 * (outline[1] - outline[0]), b = 0.5 * (outline[3] - outline[0]);
    d += cat('M', xy((c - a - b).x(), (c - a - b).y()), 'L', xy((c + a + b).x(), (c + a + b).y()), 'M',
             xy((c + a - b).x(), (c + a - b).y()), 'L', xy((c - a + b).x(), (c - a + b).y()));
  } else {
    const Box box = box_of(outline);
    d += cat('M', xy(box.min().x(), c.y()), 'L', xy(box.max().x(), c.y()), 'M', xy(c.x(), box.min().y()), 'L',
             xy(c.x(), box.max().y()));
  }
  const Eigen::Vector3d& p = l.position_m;
  std::string tip = cat(l.id, ": ", significant(l.flux_lm), " lm, ",
                        l.product.empty() ? cat(significant(l.size_m), " m square") : l.product, " at (",
                        significant(p.x()), ", ", significant(p.y()), ", ", significant(p.z()), ") m");
  if (std::isfinite(l.above_floor_m)) tip += cat(", ", metres_2(l.above_floor_m), " m above the floor");
  if (l.rotation_deg != 0.0) tip += cat(", turned ", significant(l.rotation_deg), " deg");
  if (l.tilt_deg != 0.0) tip += cat(", tilted ", significant(l.tilt_deg), " deg");
  std::string svg = cat("<g class=\"luminaire\">\n<title>", xml_escape(tip), "</title>\n", "<path d=\"", d,
                        "\" fill=\"#ffffff\" fill-opacity=\"0.55\" stroke=\"white\" stroke-width=\"3.5\"/>\n",
                        "<path d=\"", d, "\" fill=\"none\" stroke=\"#111111\" stroke-width=\"1.25\"/>\n");
  if (l.tilt_deg > 0.0) {
    // The aim's direction in plan: (cos r, sin r), y up; the arrow grows with the tilt.
    const double r = l.rotation_deg * std::numbers::pi / 180.0;
    const double length = 14.0 + 22.0 * std::sin(l.tilt_deg * std::numbers::pi / 180.0);
    const V2 dir(std::cos(r), -std::sin(r));
    const V2 tip_px = c + length * dir, side(-dir.y(), dir.x());
    const V2 h1 = tip_px - 7.0 * dir + 4.0 * side, h2 = tip_px - 7.0 * dir - 4.0 * side;
    svg += cat("<path class=\"aim\" d=\"M", xy(c.x(), c.y()), 'L', xy(tip_px.x(), tip_px.y()), "M", xy(h1.x(), h1.y()), 'L',
               xy(tip_px.x(), tip_px.y()), 'L', xy(h2.x(), h2.y()), "\" fill=\"none\" stroke=\"#c0392b\" stroke-width=\"1.6\"/>\n");
  }
  return svg + "</g>\n";
}

std::string labels_svg(const PlanView& view, const PlanLayout& layout) {
  std::string leaders, texts;
  for (std::size_t k = 0; k < view.luminaires.size(); ++k) {
    const Box& b = layout.label_px[k];
    if (b.isEmpty()) continue;
    const V2 c = b.center();
    if (layout.leader[k]) {
      const V2 to = layout.outline_px[k].center();
      const V2 from(std::clamp(to.x(), b.min().x(), b.max().x()), std::clamp(to.y(), b.min().y(), b.max().y()));
      leaders += cat('M', xy(from.x(), from.y()), 'L', xy(to.x(), to.y()));
    }
    texts += text_element(c.x(), c.y() + 0.36 * kSmallFont_px, "middle", view.luminaires[k].id);
  }
  std::string svg;
  if (!leaders.empty()) svg += cat("<path class=\"leaders\" d=\"", leaders, "\" stroke=\"#111111\" stroke-width=\"0.8\"/>\n");
  return svg + cat("<g class=\"luminaire-labels\" font-size=\"11\" font-weight=\"bold\" fill=\"#111111\" stroke=\"white\" "
                   "stroke-width=\"3\" stroke-linejoin=\"round\" paint-order=\"stroke\">\n",
                   texts, "</g>\n");
}

// One dimension chain outside the plan: a line with slashes at the stops, extension
// lines to the frame, the lengths between stops (staggered where a gap is too narrow).
std::string chain_svg(const Frame& f, const DimensionChain& chain, const std::vector<std::string>& text) {
  if (chain.stops_m.size() < 2) return {};
  const bool x = chain.axis == 0;
  const double plan_edge = x ? f.top_px : f.left_px + f.width_px();
  const double line = x ? plan_edge - kChainOffset_px : plan_edge + kChainOffset_px;
  const auto at = [&](double v) { return x ? f.x_px(v) : f.y_px(v); };
  const auto point = [&](double along, double across) { return x ? xy(along, across) : xy(across, along); };
  std::string d = cat('M', point(at(chain.stops_m.front()), line), 'L', point(at(chain.stops_m.back()), line));
  for (double s : chain.stops_m) {
    const double a = at(s);
    d += cat('M', point(a, x ? line - 6.0 : line + 6.0), 'L', point(a, x ? plan_edge : plan_edge));  // extension
    d += cat('M', point(a - 4.0, x ? line + 4.0 : line - 4.0), 'L', point(a + 4.0, x ? line - 4.0 : line + 4.0));  // slash
  }
  std::string labels;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const double a0 = at(chain.stops_m[k]), a1 = at(chain.stops_m[k + 1]);
    const double mid = 0.5 * (a0 + a1);
    const bool narrow = std::abs(a1 - a0) < text_px(text[k]) + 6.0;
    const double lift = 4.0 + (narrow && k % 2 == 1 ? 12.0 : 0.0);
    if (x)
      labels += text_element(mid, line - lift, "middle", text[k]);
    else
      labels += text_element(line + lift + 8.0, mid, "middle", text[k],
                             cat(" transform=\"rotate(-90 ", px(line + lift + 8.0), ' ', px(mid), ")\""));
  }
  return cat("<g class=\"dimensions-", x ? "x" : "y", "\" font-size=\"11\">\n<path d=\"", d,
             "\" stroke=\"#1f4e79\" stroke-width=\"0.9\" fill=\"none\"/>\n<g fill=\"#1f4e79\">\n", labels, "</g>\n</g>\n");
}

// The colour bar with ticks at quarters of the scale, then the values' min and max.
std::string legend(const ColourScale& scale, double lo, double hi, double mf, double x, double top, double bar_px) {
  constexpr double kBar_px = 18.0;
  std::string svg = text_element(x, top - 12.0, "start", mf < 1.0 ? "maintained illuminance (lx)" : "illuminance (lx)",
                                 " font-weight=\"bold\"");
  if (mf < 1.0) svg += text_element(x + 26.0, top + 6.0, "start", cat("= initial x maintenance factor ", fixed(mf, 2)));
  const double bar_top = top + (mf < 1.0 ? 16.0 : 0.0), bar_bottom = bar_top + bar_px;
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
  if (lo <= hi) {
    svg += text_element(x + 80.0, bar_top + 0.35 * bar_px, "start", cat("max ", significant(hi), " lx"));
    svg += text_element(x + 80.0, bar_top + 0.35 * bar_px + kRow_px, "start", cat("min ", significant(lo), " lx"));
  }
  return svg;
}

// "2.95 m" when every known height is the same, "2.80 - 2.95 m" otherwise; empty: none known.
std::string heights_text(const std::vector<PlanLuminaire>& luminaires) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const PlanLuminaire& l : luminaires)
    if (std::isfinite(l.above_floor_m)) {
      lo = std::min(lo, l.above_floor_m);
      hi = std::max(hi, l.above_floor_m);
    }
  if (!(lo <= hi)) return {};
  return metres_2(lo) == metres_2(hi) ? cat(metres_2(lo), " m (all)") : cat(metres_2(lo), " - ", metres_2(hi), " m");
}

// Lines of at most max_chars characters, broken at spaces (a longer word stays whole);
// continuation lines start with two spaces.
std::vector<std::string> wrapped(const std::string& text, std::size_t max_chars) {
  std::vector<std::string> out;
  std::string line;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(start, end - start);
    if (!line.empty() && char_count(line) + 1 + char_count(word) > max_chars) {
      out.push_back(line);
      line = "  " + word;
    } else {
      line += (line.empty() ? "" : " ") + word;
    }
    start = end + 1;
  }
  if (!line.empty() || out.empty()) out.push_back(line);
  return out;
}

// The column under the legend: grids, the luminaire schedule, the title block with the
// axes. Returns the y (px) under it; `svg` may be null to measure only.
double column_svg(const PlanView& view, double x, double y, std::string* svg_out) {
  std::string svg;
  const std::size_t max_chars = static_cast<std::size_t>((kColumn_px - 24.0) / kCharWidth_px);
  const auto row = [&](const std::string& text, std::string_view extra = "") {
    for (const std::string& line : wrapped(text, max_chars)) {
      svg += text_element(x, y, "start", line, extra);
      y += kRow_px;
    }
  };
  for (const PlanGrid& g : view.grids) {
    double sum = 0.0;
    for (double lux : g.lux) sum += lux * view.maintenance_factor;
    std::string line = cat("grid ", g.name, ": Em ", fixed(g.lux.empty() ? 0.0 : sum / static_cast<double>(g.lux.size()), 0),
                           " lx");
    row(line);
    if (!g.see.empty()) row(cat("values: ", g.see));
  }
  if (!view.luminaires.empty()) {
    y += 6.0;
    row("luminaire schedule", " font-weight=\"bold\"");
    const auto cells = [&](const std::array<std::string, 5>& c, std::string_view extra) {
      constexpr std::array<double, 5> kAt = {0.0, 78.0, 130.0, 182.0, 250.0};
      for (std::size_t k = 0; k < c.size(); ++k)
        svg += text_element(x + kAt[k], y, k == 0 ? "start" : "end", c[k], extra);
      y += kRow_px;
    };
    cells({"id", "x m", "y m", "h m", "flux lm"}, " fill=\"#555555\"");
    const int rows = schedule_rows(view);
    for (int k = 0; k < rows; ++k) {
      const PlanLuminaire& l = view.luminaires[static_cast<std::size_t>(k)];
      cells({l.id, metres_2(l.position_m.x()), metres_2(l.position_m.y()),
             std::isfinite(l.above_floor_m) ? metres_2(l.above_floor_m) : std::string("-"), fixed(l.flux_lm, 0)},
            "");
    }
    if (static_cast<int>(view.luminaires.size()) > rows)
      row(cat("... and ", std::to_string(view.luminaires.size() - static_cast<std::size_t>(rows)),
              " more (result.json)"));
  }
  // The title block, framed.
  y += 10.0;
  const double top = y - 14.0;
  for (std::size_t k = 0; k < view.title_block.size(); ++k)
    row(view.title_block[k], k == 0 ? " font-weight=\"bold\"" : "");
  if (view.architecture.cut_height_m > 0.0)
    row(cat("section cut at ", metres_2(view.architecture.cut_height_m), " m above the floor"));
  if (const std::string h = heights_text(view.luminaires); !h.empty()) row(cat("luminaires above the floor: ", h));
  if (has_chains(view)) row("dimensions in m, to luminaire centres");
  // Axes: x to the right, y up (the model's axes; north is not known).
  const double ax = x + 14.0, ay = y + 44.0;
  svg += cat("<path class=\"axes\" d=\"M", xy(ax, ay), "h34M", xy(ax + 34.0, ay), "l-6,-4M", xy(ax + 34.0, ay), "l-6,4M",
             xy(ax, ay), "v-34M", xy(ax, ay - 34.0), "l-4,6M", xy(ax, ay - 34.0), "l4,6", "\" stroke=\"#222222\" fill=\"none\" stroke-width=\"1.3\"/>\n",
             text_element(ax + 40.0, ay + 4.0, "start", "x"), text_element(ax, ay - 38.0, "middle", "y"),
             text_element(ax + 60.0, ay - 12.0, "start", "model axes, m"));
  y = ay + 12.0;
  svg += cat("<rect class=\"title-block\" x=\"", px(x - 8.0), "\" y=\"", px(top), "\" width=\"", px(kColumn_px - 16.0),
             "\" height=\"", px(y - top), "\" fill=\"none\" stroke=\"#333333\"/>\n");
  if (svg_out) *svg_out += svg;
  return y;
}

}  // namespace

std::string metres_2(double v) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v, std::chars_format::fixed, 2);
  std::string s(buffer.data(), result.ptr);
  return s == "-0.00" ? "0.00" : s;
}

PlanLayout plan_svg_layout(const Scene& scene, const PlanView& view) {
  check(scene, view);
  return layout_of(scene, view, geometry(scene, view));
}

std::string render_plan_svg(const Scene& scene, const PlanView& view) {
  check(scene, view);
  const Geometry g = geometry(scene, view);
  const Frame& f = g.f;
  const PlanLayout layout = layout_of(scene, view, g);
  const std::vector<int>& outline = view.outline_patches.empty() ? scene.all_patches() : view.outline_patches;

  std::string svg = cat("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"", px(g.width_px), "\" height=\"",
                        px(g.height_px), "\" viewBox=\"0 0 ", px(g.width_px), ' ', px(g.height_px),
                        "\" font-family=\"DejaVu Sans, sans-serif\" font-size=\"", px(kFont_px), "\">\n");
  svg += cat("<defs>\n", svg::colour_map_gradient(kGradientId), "<clipPath id=\"", kClipId, "\"><rect x=\"",
             px(layout.plan_px.min().x()), "\" y=\"", px(layout.plan_px.min().y()), "\" width=\"",
             px(layout.plan_px.sizes().x()), "\" height=\"", px(layout.plan_px.sizes().y()), "\"/></clipPath>\n</defs>\n");
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  if (!view.title.empty())
    svg += text_element(16.0, 30.0, "start", view.title, " font-size=\"15\" font-weight=\"bold\"");

  // Room: the outline triangles as one path, each turned the same way round, so that
  // nonzero filling gives their union without anti-aliasing seams between them.
  std::string room;
  for (int p : outline) {
    std::array<V2, 3> v;
    for (int k = 0; k < 3; ++k) v[k] = f.to_px(scene.patches[static_cast<std::size_t>(p)].vertices_m[k].head<2>());
    const double doubled_area = (v[1] - v[0]).x() * (v[2] - v[0]).y() - (v[1] - v[0]).y() * (v[2] - v[0]).x();
    if (std::abs(doubled_area) < 1e-6) continue;  // seen edge-on, e.g. a wall
    if (doubled_area < 0.0) std::swap(v[1], v[2]);
    room += cat('M', xy(v[0].x(), v[0].y()), 'L', xy(v[1].x(), v[1].y()), 'L', xy(v[2].x(), v[2].y()), 'Z');
  }
  if (!room.empty()) svg += cat("<path d=\"", room, "\" fill=\"#ececec\"/>\n");

  // The colour scale over every value drawn (maintained when a factor is given).
  std::vector<double> all;
  for (Eigen::Index i = 0; i < view.goal_lux.size(); ++i) all.push_back(view.goal_lux[i] * view.maintenance_factor);
  for (const PlanGrid& grid : view.grids)
    for (double lux : grid.lux) all.push_back(lux * view.maintenance_factor);
  const Eigen::VectorXd all_lux = Eigen::Map<const Eigen::VectorXd>(all.data(), static_cast<Eigen::Index>(all.size()));
  const ColourScale scale = colour_scale_for(all_lux);

  // Goal patches, lowest mean height first; the stroke in the fill colour covers the
  // hairline seams anti-aliasing leaves between neighbours.
  std::vector<std::size_t> order(view.goal_patches.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto height = [&](std::size_t i) {
    const auto& v = scene.patches[static_cast<std::size_t>(view.goal_patches[i])].vertices_m;
    return v[0].z() + v[1].z() + v[2].z();
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return height(a) < height(b); });
  svg += "<g stroke-width=\"0.5\" stroke-linejoin=\"round\">\n";
  for (std::size_t i : order) {
    const Patch& patch = scene.patches[static_cast<std::size_t>(view.goal_patches[i])];
    const std::string colour =
        svg_colour(colour_map(scale.fraction(view.goal_lux[static_cast<Eigen::Index>(i)] * view.maintenance_factor)));
    std::string points;
    for (const Eigen::Vector3d& q : patch.vertices_m) points += cat(points.empty() ? "" : " ", xy(f.x_px(q.x()), f.y_px(q.y())));
    svg += cat("<polygon points=\"", points, "\" fill=\"", colour, "\" stroke=\"", colour, "\"/>\n");
  }
  svg += "</g>\n";
  svg += grid_cells(f, view, scale);
  // The outline's frame; with the architecture drawn, the walls are the room's edge and
  // the frame is the plan's border.
  const bool drawn_walls = view.architecture.cut_height_m > 0.0;
  if (drawn_walls)
    svg += cat("<rect x=\"", px(layout.plan_px.min().x()), "\" y=\"", px(layout.plan_px.min().y()), "\" width=\"",
               px(layout.plan_px.sizes().x()), "\" height=\"", px(layout.plan_px.sizes().y()),
               "\" fill=\"none\" stroke=\"#9a9a9a\" stroke-width=\"0.8\"/>\n");
  else if (!g.frame_m.isEmpty())
    svg += cat("<rect x=\"", px(f.x_px(g.frame_m.min().x())), "\" y=\"", px(f.y_px(g.frame_m.max().y())), "\" width=\"",
               px(g.frame_m.sizes().x() * f.scale_px_per_m), "\" height=\"", px(g.frame_m.sizes().y() * f.scale_px_per_m),
               "\" fill=\"none\" stroke=\"#333333\" stroke-width=\"1.5\"/>\n");
  svg += architecture_svg(f, view.architecture);
  svg += svg::plan_axes(f);
  svg += svg::plan_scale_bar(f);
  svg += chain_svg(f, layout.along_x, layout.along_x_text);
  svg += chain_svg(f, layout.along_y, layout.along_y_text);

  if (!view.luminaires.empty()) {
    svg += "<g stroke-linejoin=\"round\">\n";
    for (const PlanLuminaire& l : view.luminaires) svg += luminaire_svg(f, l);
    svg += "</g>\n";
    svg += labels_svg(view, layout);
  }
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : all)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  svg += legend(scale, lo, hi, view.maintenance_factor, g.legend_x, g.bar_top, g.bar_px);
  column_svg(view, g.legend_x, column_top(view, g), &svg);
  svg += "</svg>\n";
  return svg;
}

}  // namespace ilp
