// The isolux plan: levels tied to the target, a colour scale a hot spot cannot move,
// labels that never overlap and sit where they belong, missing points left out,
// luminaires at their real size, a well-formed document, and the PNG beside it.
#include "output/isolux_plan.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/colour_map.h"
#include "output/svg_plan_parts.h"
#include "output/svg_text.h"
#include "tests/output/isolux_demo.h"
#include "tests/output/png_checks.h"
#include "tests/output/svg_checks.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::Contains;
using test::WellFormed;
using V2 = Eigen::Vector2d;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t i = text.find(part); i != std::string::npos; i = text.find(part, i + 1)) ++n;
  return n;
}

// The group `<g class="name" ...> ... </g>` of the document.
std::string group(const std::string& svg, const std::string& name) {
  const std::size_t start = svg.find("<g class=\"" + name + "\"");
  if (start == std::string::npos) return {};
  return svg.substr(start, svg.find("</g>", start) - start);
}

// True if a number was written as "nan" or "inf" (to_chars' text for them), i.e.
// either not preceded by a letter (as in "maintenance").
bool has_non_finite_number(const std::string& svg) {
  for (const char* word : {"nan", "inf"})
    for (std::size_t i = svg.find(word); i != std::string::npos; i = svg.find(word, i + 1))
      if (i == 0 || !std::isalpha(static_cast<unsigned char>(svg[i - 1]))) return true;
  return false;
}

int count_kind(const IsoluxLayout& layout, IsoluxLabel::Kind kind) {
  int n = 0;
  for (const IsoluxLabel& l : layout.labels) n += l.kind == kind;
  return n;
}

// Every pair of label boxes is disjoint and every box lies in the plan's frame.
::testing::AssertionResult LabelsApart(const IsoluxLayout& layout) {
  for (std::size_t a = 0; a < layout.labels.size(); ++a) {
    if (!layout.plan_px.contains(layout.labels[a].box_px))
      return ::testing::AssertionFailure() << "label '" << layout.labels[a].text << "' leaves the plan";
    for (std::size_t b = a + 1; b < layout.labels.size(); ++b)
      if (!layout.labels[a].box_px.intersection(layout.labels[b].box_px).isEmpty())
        return ::testing::AssertionFailure() << "labels " << a << " '" << layout.labels[a].text << "' and " << b << " '"
                                             << layout.labels[b].text << "' overlap";
  }
  return ::testing::AssertionSuccess();
}

// Distance in px from p (metres) to a line's polyline (a closed one joined round).
double distance_px(const V2& p, const ContourLine& line, double scale_px_per_m) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = line.points_m.size();
  for (std::size_t k = 0; k + (line.closed ? 0 : 1) < n; ++k) {
    const V2& a = line.points_m[k];
    const V2 d = line.points_m[(k + 1) % n] - a;
    const double t = d.squaredNorm() > 0.0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    best = std::min(best, (a + t * d - p).norm() * scale_px_per_m);
  }
  return best;
}

// From px (y down) to metres (y up), given where one point in metres lands.
struct PxToM {
  V2 anchor_px, anchor_m;
  double scale;
  V2 operator()(const V2& q) const { return anchor_m + V2(q.x() - anchor_px.x(), anchor_px.y() - q.y()) / scale; }
};

std::string cat_points(int n) { return ilp::svg::cat(">", std::to_string(n), " points, values at</text>"); }

TEST(IsoluxLevels, AreFractionsOfTheTargetRoundedToTwoDigits) {
  EXPECT_EQ(isolux_levels(500.0), (std::vector<double>{250, 300, 350, 400, 500, 600, 750, 1000}));
  EXPECT_EQ(isolux_levels(300.0), (std::vector<double>{150, 180, 210, 240, 300, 360, 450, 600}));
  // 0.5 x 750 = 375 rounds to 380, 1.5 x 750 = 1125 to 1100; the target stays exact.
  EXPECT_EQ(isolux_levels(750.0), (std::vector<double>{380, 450, 530, 600, 750, 900, 1100, 1500}));
  EXPECT_EQ(isolux_levels(333.0), (std::vector<double>{170, 200, 230, 270, 333, 400, 500, 670}));
  EXPECT_THROW(isolux_levels(0.0), std::invalid_argument);
  EXPECT_THROW(isolux_levels(kNaN), std::invalid_argument);
}

TEST(IsoluxPlan, OfficeDocumentIsWellFormedAndSaysWhatItShows) {
  const IsoluxGridView v = test::office_isolux_view();
  const std::string svg = isolux_plan_svg(v);
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_TRUE(Contains(svg, ">work plane</text>"));
  EXPECT_TRUE(Contains(svg, ">office, 0.80 m above the floor, 0.5 m band</text>"));
  EXPECT_TRUE(Contains(svg, ">maintained illuminance (lx)</text>"));
  EXPECT_TRUE(Contains(svg, "maintenance factor 0.8"));
  EXPECT_TRUE(Contains(svg, ">target Em 500 lx</text>"));
  EXPECT_TRUE(Contains(svg, ">x (m)</text>"));
  EXPECT_TRUE(Contains(svg, " m</text>"));  // the scale bar
  EXPECT_TRUE(Contains(svg, ">N</text>"));  // north arrow
  EXPECT_EQ(isolux_plan_svg(v), svg) << "deterministic";
  // One filled cell per point with a value.
  const IsoluxLayout layout = isolux_plan_layout(v);
  const int finite = static_cast<int>(
      std::count_if(v.maintained_lux.begin(), v.maintained_lux.end(), [](double lux) { return std::isfinite(lux); }));
  EXPECT_LT(finite, v.nx * v.ny) << "the demo has a solid";
  EXPECT_EQ(layout.points, finite);
  EXPECT_EQ(count(group(svg, "cells"), "<rect "), static_cast<std::size_t>(finite));
  EXPECT_TRUE(Contains(svg, cat_points(finite)));
  EXPECT_TRUE(Contains(svg, ">every 2nd point</text>"));
  EXPECT_TRUE(Contains(svg, ">250 300 350 400</text>"));
  EXPECT_TRUE(Contains(svg, ">500 600 750 1000</text>"));
}

TEST(IsoluxPlan, ColourScaleIsTiedToTheTargetNotToAHotSpot) {
  IsoluxGridView v = test::office_isolux_view();
  const IsoluxLayout before = isolux_plan_layout(v);
  EXPECT_DOUBLE_EQ(before.scale.min_lux, 0.0);
  EXPECT_DOUBLE_EQ(before.scale.max_lux, 1000.0);
  const std::string svg_before = isolux_plan_svg(v);

  // A hot spot at 10 x target in one corner point.
  v.maintained_lux[0] = 5000.0;
  const IsoluxLayout after = isolux_plan_layout(v);
  EXPECT_DOUBLE_EQ(after.scale.max_lux, 1000.0);
  EXPECT_EQ(after.levels_lux, before.levels_lux);
  EXPECT_DOUBLE_EQ(after.max_lux, 5000.0);
  const std::string svg_after = isolux_plan_svg(v);
  EXPECT_TRUE(Contains(svg_after, ">above 1000 lx: top colour</text>"));
  EXPECT_FALSE(Contains(svg_before, "top colour").operator bool());
  // Every other cell keeps its colour: the cells' fills differ in the hot one only.
  const auto fills = [](const std::string& document) {
    const std::string svg = group(document, "cells");
    std::vector<std::string> out;
    for (std::size_t i = svg.find("<rect x="); i != std::string::npos; i = svg.find("<rect x=", i + 1)) {
      const std::size_t f = svg.find("fill=\"", i);
      out.push_back(svg.substr(f, 14));
    }
    return out;
  };
  const std::vector<std::string> a = fills(svg_before), b = fills(svg_after);
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), static_cast<std::size_t>(before.points));
  int changed = 0;
  for (std::size_t k = 0; k < a.size(); ++k) changed += a[k] != b[k];
  EXPECT_EQ(changed, 1);
  EXPECT_EQ(b[0], ilp::svg::cat("fill=\"", svg_colour(colour_map(1.0)), "\""));  // the hot cell: the top colour
}

TEST(IsoluxPlan, MinimumAndMaximumPointsAreMarkedAndNoLabelCoversThem) {
  const IsoluxGridView v = test::office_isolux_view();
  const IsoluxLayout layout = isolux_plan_layout(v);
  ASSERT_GE(layout.min_point, 0);
  ASSERT_GE(layout.max_point, 0);
  EXPECT_DOUBLE_EQ(v.maintained_lux[layout.min_point], layout.min_lux);
  EXPECT_DOUBLE_EQ(v.maintained_lux[layout.max_point], layout.max_lux);
  for (double lux : v.maintained_lux)
    if (std::isfinite(lux)) {
      EXPECT_GE(lux, layout.min_lux);
      EXPECT_LE(lux, layout.max_lux);
    }
  const std::string svg = isolux_plan_svg(v);
  EXPECT_EQ(count(svg, "class=\"min-marker\""), 1u);
  EXPECT_EQ(count(svg, "class=\"max-marker\""), 1u);
  EXPECT_TRUE(Contains(svg, ilp::svg::cat("<title>min ", std::to_string(std::lround(layout.min_lux)), " lx</title>")));
  // Each marker's apex, in px, from the point's place: metres -> px as the frame maps them.
  const double pad = 0.03 * 6.0;
  for (int point : {layout.min_point, layout.max_point}) {
    const V2 p_m = v.origin_m + V2((point % v.nx) * v.spacing_m.x(), (point / v.nx) * v.spacing_m.y());
    const V2 p_px(layout.plan_px.min().x() + (p_m.x() + pad) * layout.scale_px_per_m,
                  layout.plan_px.max().y() - (p_m.y() + pad) * layout.scale_px_per_m);
    const Eigen::AlignedBox2d marker(p_px - V2::Constant(6.0), p_px + V2::Constant(6.0));
    for (const IsoluxLabel& l : layout.labels)
      EXPECT_TRUE(l.box_px.intersection(marker).isEmpty()) << "label '" << l.text << "' covers a marker";
  }
}

TEST(IsoluxPlan, TargetLevelsLinesAreDrawnThickerAndAllLevelsInRangeAppear) {
  const IsoluxGridView v = test::office_isolux_view();
  const IsoluxLayout layout = isolux_plan_layout(v);
  // Every level strictly inside the field's range has a line, none outside it has one.
  ASSERT_LT(layout.min_lux, 400.0);
  ASSERT_GT(layout.max_lux, 500.0);
  for (double level : layout.levels_lux) {
    int lines = 0;
    for (const ContourLine& l : layout.lines) lines += l.level == level;
    if (level > layout.min_lux && level < layout.max_lux)
      EXPECT_GT(lines, 0) << level << " lx";
    else
      EXPECT_EQ(lines, 0) << level << " lx";
  }
  for (const ContourLine& l : layout.lines) EXPECT_NE(l.level, 1000.0);
  const std::string svg = isolux_plan_svg(v);
  EXPECT_GT(count(svg, "stroke-width=\"2.2\"><title>500 lx</title>"), 0u);
  EXPECT_GT(count(svg, "stroke-width=\"1.1\"><title>400 lx</title>"), 0u);
}

TEST(IsoluxPlan, LabelsNeverOverlapAndSitOnTheirLinesOrPoints) {
  const IsoluxGridView v = test::office_isolux_view();
  const IsoluxLayout layout = isolux_plan_layout(v);
  EXPECT_TRUE(LabelsApart(layout));
  EXPECT_EQ(count_kind(layout, IsoluxLabel::Kind::luminaire), 4);
  EXPECT_GE(count_kind(layout, IsoluxLabel::Kind::contour), 4);
  EXPECT_GE(count_kind(layout, IsoluxLabel::Kind::value), 20);

  // Metres from px: the plan's frame is the drawing's extent, [0, 6] x [0, 4] m, padded
  // by 3 % of its larger side.
  const double pad = 0.03 * 6.0;
  const PxToM to_m{V2(layout.plan_px.min().x(), layout.plan_px.max().y()), V2(-pad, -pad), layout.scale_px_per_m};
  int beside = 0;
  for (const IsoluxLabel& l : layout.labels) {
    const V2 c_m = to_m(l.box_px.center());
    if (l.kind == IsoluxLabel::Kind::contour) {
      // Its centre lies on a line of the level it names (within a px).
      double best = std::numeric_limits<double>::infinity();
      for (const ContourLine& line : layout.lines)
        if (std::to_string(static_cast<int>(line.level)) == l.text)
          best = std::min(best, distance_px(c_m, line, layout.scale_px_per_m));
      // On its line (within a px), or beside a short one: touching it, about half the box away.
      const double allowed = l.on_line ? 1.0 : 0.5 * l.box_px.sizes().norm() + 4.0;
      EXPECT_LT(best, allowed) << "contour label " << l.text << " is " << best << " px from its line";
      beside += !l.on_line;
    } else if (l.kind == IsoluxLabel::Kind::value) {
      // Centred on a point, and it prints that point's value.
      const double fi = (c_m.x() - v.origin_m.x()) / v.spacing_m.x(), fj = (c_m.y() - v.origin_m.y()) / v.spacing_m.y();
      const int i = static_cast<int>(std::lround(fi)), j = static_cast<int>(std::lround(fj));
      EXPECT_NEAR(fi, i, 1e-6);
      EXPECT_NEAR(fj, j, 1e-6);
      ASSERT_TRUE(i >= 0 && i < v.nx && j >= 0 && j < v.ny);
      const double lux = v.maintained_lux[j * v.nx + i];
      ASSERT_TRUE(std::isfinite(lux)) << "a value printed at a missing point";
      EXPECT_EQ(l.text, std::to_string(static_cast<int>(std::lround(lux))));
    }
  }
  EXPECT_GE(beside, 2) << "the short 400 lx arcs in the corners are labelled beside them";
  // Neighbouring values at least 44 px apart: at 0.2 m spacing the step is 2 points
  // at this scale (> 110 px/m).
  EXPECT_GE(layout.value_step_x * v.spacing_m.x() * layout.scale_px_per_m, 44.0 - 1e-9);
  EXPECT_GE(layout.value_step_y * v.spacing_m.y() * layout.scale_px_per_m, 44.0 - 1e-9);
  EXPECT_LT((layout.value_step_x - 1) * v.spacing_m.x() * layout.scale_px_per_m, 44.0);
}

TEST(IsoluxPlan, CrowdedPlanStillHasNoOverlappingLabels) {
  // A fine grid with a busy field (a ripple crossing every level many times) and 24
  // luminaires close together: many labels compete for room.
  IsoluxGridView v = test::office_isolux_view(1650.0, 0.05);
  for (int j = 0; j < v.ny; ++j)
    for (int i = 0; i < v.nx; ++i) {
      double& lux = v.maintained_lux[j * v.nx + i];
      if (std::isfinite(lux)) lux *= 1.0 + 0.6 * std::sin(3.0 * i * 0.05) * std::cos(4.0 * j * 0.05);
    }
  v.luminaires.clear();
  for (int k = 0; k < 24; ++k)
    v.luminaires.push_back({ilp::svg::cat("luminaire-", std::to_string(k)), "", V2(0.6 + 0.22 * k, 2.0 + 0.3 * (k % 3)), 0.6, 0.1,
                            15.0 * k, k % 4 == 0});
  const IsoluxLayout layout = isolux_plan_layout(v);
  EXPECT_TRUE(LabelsApart(layout));
  EXPECT_GT(count_kind(layout, IsoluxLabel::Kind::contour), 5);
  EXPECT_TRUE(WellFormed(isolux_plan_svg(v)));
  if (const char* keep = std::getenv("ILP_ISOLUX_DEMO_DIR"))
    write_isolux_plan(std::string(keep) + "/crowded.svg", std::string(keep) + "/crowded.png", v);
}

TEST(IsoluxPlan, MissingPointsGetNoCellNoValueAndNoLine) {
  IsoluxGridView v = test::office_isolux_view();
  // Every point NaN: no cells, no lines, no values, and the document still stands.
  std::fill(v.maintained_lux.begin(), v.maintained_lux.end(), kNaN);
  const IsoluxLayout layout = isolux_plan_layout(v);
  EXPECT_EQ(layout.points, 0);
  EXPECT_TRUE(layout.lines.empty());
  EXPECT_EQ(count_kind(layout, IsoluxLabel::Kind::value), 0);
  const std::string svg = isolux_plan_svg(v);
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_FALSE(has_non_finite_number(svg));
  // Infinite values count as missing too.
  v.maintained_lux.assign(v.maintained_lux.size(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(isolux_plan_layout(v).points, 0);
}

TEST(IsoluxPlan, LuminairesAreDrawnAtTheirRealSizeAndOrientation) {
  IsoluxGridView v = test::office_isolux_view();
  v.luminaires = {{"long", "", V2(3.0, 2.0), 1.2, 0.3, 90.0, false}, {"disc", "", V2(1.0, 1.0), 0.6, 0.0, 0.0, true}};
  const IsoluxLayout layout = isolux_plan_layout(v);
  const std::string svg = isolux_plan_svg(v);
  const double s = layout.scale_px_per_m;
  // The disc: a circle of radius 0.3 m.
  EXPECT_TRUE(Contains(svg, ilp::svg::cat("r=\"", ilp::svg::px(0.3 * s), "\"")));
  // The rotated rectangle: 0.3 m wide (x) and 1.2 m tall (y) on the plan.
  const std::size_t at = svg.find("<title>long: 1.2 x 0.3 m at 90 deg");
  ASSERT_NE(at, std::string::npos);
  const std::size_t d = svg.rfind("<path d=\"M", at);
  const std::string path = svg.substr(d + 9, svg.find('"', d + 9) - d - 9);
  Eigen::AlignedBox2d box;
  for (std::size_t i = 0; i < path.size();) {
    if (path[i] == 'M' || path[i] == 'L') {
      const std::size_t comma = path.find(',', i);
      const std::size_t end = path.find_first_of("MLZ", comma);
      box.extend(V2(std::stod(path.substr(i + 1, comma - i - 1)), std::stod(path.substr(comma + 1, end - comma - 1))));
      i = end;
    } else {
      ++i;
    }
  }
  EXPECT_NEAR(box.sizes().x(), 0.3 * s, 0.02);
  EXPECT_NEAR(box.sizes().y(), 1.2 * s, 0.02);
}

TEST(IsoluxPlan, WithoutATargetTheScaleRestsOnTheAverage) {
  IsoluxGridView v;
  v.name = "floor";
  v.nx = 3;
  v.ny = 2;
  v.maintained_lux = {100, 200, 300, 100, 200, 300};
  const IsoluxLayout layout = isolux_plan_layout(v);
  EXPECT_FALSE(layout.reference_is_target);
  EXPECT_DOUBLE_EQ(layout.reference_lux, 200.0);
  EXPECT_DOUBLE_EQ(layout.scale.max_lux, 400.0);
  const std::string svg = isolux_plan_svg(v);
  EXPECT_TRUE(Contains(svg, "no target: scale on Em 200 lx"));
  EXPECT_TRUE(Contains(svg, "= initial (maintenance factor 1)"));
  EXPECT_TRUE(WellFormed(svg));
}

TEST(IsoluxPlan, VerticalGridNamesItsAxesAndNeedsNoRoomOrLuminaires) {
  // A board 3 m wide, 1.2 m high: a linear ramp from 200 to 400 lx along it.
  IsoluxGridView v;
  v.name = "board";
  v.nx = 15;
  v.ny = 6;
  v.spacing_m = V2(0.2, 0.2);
  v.origin_m = V2(0.1, 0.1);
  for (int j = 0; j < v.ny; ++j)
    for (int i = 0; i < v.nx; ++i) v.maintained_lux.push_back(200.0 + 200.0 * (0.1 + 0.2 * i) / 3.0);
  v.target_lux = 300.0;
  v.x_label = "along the board (m)";
  v.y_label = "height above its bottom (m)";
  const std::string svg = isolux_plan_svg(v);
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_TRUE(Contains(svg, ">along the board (m)</text>"));
  EXPECT_TRUE(Contains(svg, ">height above its bottom (m)</text>"));
  EXPECT_FALSE(Contains(svg, ">N</text>").operator bool()) << "no north without north_deg";
  // The ramp's isolines are vertical lines at x = 3 (E - 200) / 200 m: 210 lx at 0.15 m ... 300 at 1.5 m.
  const IsoluxLayout layout = isolux_plan_layout(v);
  for (const ContourLine& l : layout.lines)
    for (const V2& p : l.points_m) EXPECT_NEAR(p.x(), 3.0 * (l.level - 200.0) / 200.0, 1e-9) << l.level;
  EXPECT_TRUE(LabelsApart(layout));
}

TEST(IsoluxPlan, RandomViewsNeverFailAndKeepTheirLabelsApart) {
  // Fields with NaN and infinite values, luminaires anywhere (sizes up to the room's),
  // spacings from 1 mm to 1 m, with or without a target: no exception, a well-formed
  // document, labels apart. Seeded, so the same views every run.
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    IsoluxGridView v;
    v.name = ilp::svg::cat("random ", std::to_string(trial));
    v.nx = 1 + static_cast<int>(unit(rng) * 40);
    v.ny = 1 + static_cast<int>(unit(rng) * 40);
    const double spacing = std::pow(10.0, -3.0 + 3.0 * unit(rng));
    v.spacing_m = V2(spacing, spacing * (0.5 + unit(rng)));
    v.origin_m = V2(unit(rng) * 10.0 - 5.0, unit(rng) * 10.0 - 5.0);
    const double scale_lux = std::pow(10.0, 4.0 * unit(rng));
    for (int k = 0; k < v.nx * v.ny; ++k) {
      const double r = unit(rng);
      v.maintained_lux.push_back(r < 0.1 ? kNaN : r < 0.12 ? std::numeric_limits<double>::infinity()
                                                            : scale_lux * (0.5 + std::sin(0.3 * k) * unit(rng)));
    }
    const V2 size(v.nx * v.spacing_m.x(), v.ny * v.spacing_m.y());
    v.room_outline_m = {{v.origin_m - 0.2 * size, v.origin_m + V2(1.2 * size.x(), -0.2 * size.y()),
                         v.origin_m + 1.2 * size}};
    for (int k = 0; k < static_cast<int>(unit(rng) * 12); ++k)
      v.luminaires.push_back({ilp::svg::cat("L", std::to_string(k)), "",
                              v.origin_m + V2(unit(rng) * size.x(), unit(rng) * size.y()), unit(rng) * size.x(),
                              unit(rng) * size.y(), 360.0 * unit(rng), unit(rng) < 0.3});
    if (unit(rng) < 0.7) v.target_lux = scale_lux * (0.2 + unit(rng));
    v.maintenance_factor = 0.5 + 0.5 * unit(rng);
    if (unit(rng) < 0.5) v.north_deg = 360.0 * unit(rng);
    SCOPED_TRACE(ilp::svg::cat("trial ", std::to_string(trial)));
    std::string svg;
    ASSERT_NO_THROW(svg = isolux_plan_svg(v));
    EXPECT_TRUE(WellFormed(svg));
    EXPECT_FALSE(has_non_finite_number(svg));
    EXPECT_TRUE(LabelsApart(isolux_plan_layout(v)));
  }
  // A luminaire far away makes the drawing too wide: an error, not a plan of specks.
  IsoluxGridView far = test::office_isolux_view();
  far.luminaires[0].centre_m = V2(1e9, 0.0);
  EXPECT_THROW(isolux_plan_svg(far), std::invalid_argument);
}

TEST(IsoluxPlan, TextIsEscaped) {
  IsoluxGridView v = test::office_isolux_view();
  v.name = "desk <A> & \"B\"";
  v.luminaires[0].id = "L<1>";
  const std::string svg = isolux_plan_svg(v);
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_TRUE(Contains(svg, "desk &lt;A&gt; &amp; &quot;B&quot;"));
  EXPECT_TRUE(Contains(svg, "L&lt;1&gt;"));
}

TEST(IsoluxPlan, BadInputIsRejected) {
  const IsoluxGridView good = test::office_isolux_view();
  auto v = good;
  v.maintained_lux.pop_back();
  EXPECT_THROW(isolux_plan_svg(v), std::invalid_argument);
  v = good;
  v.spacing_m.x() = 0.0;
  EXPECT_THROW(isolux_plan_svg(v), std::invalid_argument);
  v = good;
  v.target_lux = -5.0;
  EXPECT_THROW(isolux_plan_svg(v), std::invalid_argument);
  v = good;
  v.maintenance_factor = 1.5;
  EXPECT_THROW(isolux_plan_svg(v), std::invalid_argument);
  v = good;
  v.luminaires[1].length_m = kNaN;
  EXPECT_THROW(isolux_plan_svg(v), std::invalid_argument);
  v = good;
  v.room_outline_m[0][2].x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(isolux_plan_svg(v), std::invalid_argument);
}

TEST(IsoluxPlan, WritesTheSvgAndAPngOfTwiceItsSize) {
  test::TempDir dir;
  const IsoluxGridView v = test::office_isolux_view();
  const std::string svg_path = dir.file("work_plane.svg"), png_path = dir.file("work_plane.png");
  write_isolux_plan(svg_path, png_path, v);
  EXPECT_EQ(test::read_file(svg_path), isolux_plan_svg(v));
  const IsoluxLayout layout = isolux_plan_layout(v);
  const auto [w, h] = test::png_size(test::read_file(png_path));
  EXPECT_EQ(w, std::lround(2.0 * layout.width_px));
  EXPECT_EQ(h, std::lround(2.0 * layout.height_px));
  EXPECT_FALSE(std::filesystem::exists(png_path + ".tmp"));
  // The demo for people to look at: ILP_ISOLUX_DEMO_DIR=/tmp/somewhere keeps a copy.
  if (const char* keep = std::getenv("ILP_ISOLUX_DEMO_DIR"))
    write_isolux_plan(std::string(keep) + "/office_work_plane.svg", std::string(keep) + "/office_work_plane.png", v);
}

}  // namespace
}  // namespace ilp
