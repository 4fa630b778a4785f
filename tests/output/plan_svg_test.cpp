// Room plans: a well-formed document, one coloured polygon per goal patch (lower
// patches first), y up at one scale on both axes, luminaire labels, escaped text and
// the input checks.
#include "output/plan_svg.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/reference_scenes.h"
#include "output/colour_map.h"
#include "output/plan_architecture.h"
#include "tests/output/svg_checks.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::Contains;
using test::WellFormed;
using V = Eigen::Vector3d;


std::size_t count(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t i = text.find(part); i != std::string::npos; i = text.find(part, i + 1)) ++n;
  return n;
}

// True if a number was written as "nan" or "inf" (to_chars' text for them), i.e.
// either not preceded by a letter (as in "illuminance").
bool has_non_finite_number(const std::string& svg) {
  for (const char* word : {"nan", "inf"})
    for (std::size_t i = svg.find(word); i != std::string::npos; i = svg.find(word, i + 1))
      if (i == 0 || !std::isalpha(static_cast<unsigned char>(svg[i - 1]))) return true;
  return false;
}

// The value of attribute `name` in the tag `tag` (which starts at '<').
std::string attribute(const std::string& tag, const std::string& name) {
  const std::size_t at = tag.find(" " + name + "=\"");
  if (at == std::string::npos) return {};
  const std::size_t start = at + name.size() + 3;
  return tag.substr(start, tag.find('"', start) - start);
}

// Every <polygon .../> tag, in document order.
std::vector<std::string> polygons(const std::string& svg) {
  std::vector<std::string> out;
  for (std::size_t i = svg.find("<polygon"); i != std::string::npos; i = svg.find("<polygon", i + 1))
    out.push_back(svg.substr(i, svg.find('>', i) - i + 1));
  return out;
}

// The points of a polygon tag, in px.
std::vector<Eigen::Vector2d> points(const std::string& polygon) {
  std::vector<Eigen::Vector2d> out;
  std::string list = attribute(polygon, "points");
  std::replace(list.begin(), list.end(), ',', ' ');
  std::istringstream in(list);
  double x = 0.0, y = 0.0;
  while (in >> x >> y) out.emplace_back(x, y);
  return out;
}

// The opening tag of the <text> element whose content is exactly `content`.
std::string text_tag(const std::string& svg, const std::string& content) {
  const std::size_t end = svg.find(">" + content + "</text>");
  if (end == std::string::npos) return {};
  const std::size_t start = svg.rfind("<text", end);
  return svg.substr(start, end - start + 1);
}

bool has_text(const std::string& svg, const std::string& content) { return !text_tag(svg, content).empty(); }

double text_position(const std::string& svg, const std::string& content, const char* axis) {
  const std::string tag = text_tag(svg, content);
  EXPECT_FALSE(tag.empty()) << "no text '" << content << "'";
  return tag.empty() ? std::numeric_limits<double>::quiet_NaN() : std::stod(attribute(tag, axis));
}

// A 4 m x 3 m floor (patches 0, 1), a 1 m desk at 0.75 m (2, 3) and a ceiling (4, 5).
Scene office() {
  const V rho = V::Constant(0.5);
  return reference::make_quad_scene(
      {{"floor", V(0, 0, 0), V(4, 0, 0), V(4, 3, 0), V(0, 3, 0), rho},
       {"desk", V(1, 1, 0.75), V(2, 1, 0.75), V(2, 2, 0.75), V(1, 2, 0.75), rho},
       {"ceiling", V(0, 0, 2.8), V(0, 3, 2.8), V(4, 3, 2.8), V(4, 0, 2.8), rho}},
      0.0);
}

// A luminaire drawn as a square of side size_m (no outline, no product).
PlanLuminaire square(std::string id, const V& position_m, double size_m, double flux_lm) {
  return {std::move(id), position_m, size_m, flux_lm, {}, {}};
}

Eigen::VectorXd values(std::initializer_list<double> v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

// Desk patches listed first, so that only sorting by height puts the floor first.
PlanView office_view() {
  PlanView view;
  view.title = "office: optimal layout, total 152 W";
  view.goal_patches = {2, 3, 0, 1};
  view.goal_lux = values({500.0, 400.0, 0.0, 250.0});
  view.outline_patches = {0, 1};
  view.luminaires = {square("L1", V(0.8, 0.5, 2.8), 0.6, 1500.0), square("L2", V(0.8, 2.5, 2.8), 0.6, 1500.0),
                     square("L3", V(2.0, 0.5, 2.8), 0.6, 800.4)};
  return view;
}

TEST(PlanSvg, IsAWellFormedStandaloneDocument) {
  const std::string svg = render_plan_svg(office(), office_view());
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_TRUE(svg.ends_with("</svg>\n"));
  EXPECT_TRUE(WellFormed(svg));
  for (const char* element : {"text", "g", "title", "linearGradient", "defs"})
    EXPECT_EQ(count(svg, std::string("<") + element + ">") + count(svg, std::string("<") + element + " "),
              count(svg, std::string("</") + element + ">"))
        << element;
  for (const char* text : {"office: optimal layout, total 152 W", "illuminance (lx)", "x (m)", "y (m)", "0.5 m"})
    EXPECT_TRUE(has_text(svg, text)) << text;
  EXPECT_FALSE(has_non_finite_number(svg));
  EXPECT_EQ(render_plan_svg(office(), office_view()), svg);  // deterministic
}

TEST(PlanSvg, OnePolygonPerGoalPatchColouredByLuxLowestFirst) {
  const std::string svg = render_plan_svg(office(), office_view());
  const std::vector<std::string> drawn = polygons(svg);
  ASSERT_EQ(drawn.size(), 4u);
  std::vector<std::string> fills;
  for (const std::string& p : drawn) {
    EXPECT_EQ(points(p).size(), 3u) << p;
    EXPECT_EQ(attribute(p, "fill"), attribute(p, "stroke")) << p;
    fills.push_back(attribute(p, "fill"));
  }
  // The scale is [0, 500]: 0 lx is viridis' first colour, 500 lx its last.
  EXPECT_EQ(fills[0], "#440154");
  EXPECT_EQ(fills[1], svg_colour(colour_map(0.5)));
  EXPECT_EQ(fills[2], "#fde725");
  EXPECT_EQ(fills[3], svg_colour(colour_map(0.8)));
  for (const char* tick : {"0", "125", "250", "375", "500"}) EXPECT_TRUE(has_text(svg, tick)) << tick;
  EXPECT_TRUE(has_text(svg, "max 500 lx"));
  EXPECT_TRUE(has_text(svg, "min 0 lx"));
}

TEST(PlanSvg, YIsUpAtOneScaleOnBothAxes) {
  const std::string svg = render_plan_svg(office(), office_view());
  const std::vector<std::string> drawn = polygons(svg);
  ASSERT_EQ(drawn.size(), 4u);
  // The floor's two triangles span the 4 m x 3 m room.
  Eigen::AlignedBox2d floor_px;
  for (int k : {0, 1})
    for (const Eigen::Vector2d& p : points(drawn[k])) floor_px.extend(p);
  const double scale = floor_px.sizes().x() / 4.0;
  EXPECT_NEAR(floor_px.sizes().y() / 3.0, scale, 0.01);
  EXPECT_GT(floor_px.sizes().x(), 500.0);  // fitted to about 900 px
  EXPECT_LT(floor_px.sizes().x(), 900.0);
  // The desk (1..2 m, 1..2 m) back in metres, with y up.
  for (int k : {2, 3})
    for (const Eigen::Vector2d& p : points(drawn[k])) {
      const double x_m = (p.x() - floor_px.min().x()) / scale, y_m = 3.0 - (p.y() - floor_px.min().y()) / scale;
      EXPECT_TRUE(std::abs(x_m - 1.0) < 0.01 || std::abs(x_m - 2.0) < 0.01) << x_m;
      EXPECT_TRUE(std::abs(y_m - 1.0) < 0.01 || std::abs(y_m - 2.0) < 0.01) << y_m;
    }
  // Luminaires: L2 lies 2 m north of L1 (so higher up in the image), L3 1.2 m east.
  const double l1_x = text_position(svg, "L1", "x"), l1_y = text_position(svg, "L1", "y");
  const double l2_x = text_position(svg, "L2", "x"), l2_y = text_position(svg, "L2", "y");
  const double l3_x = text_position(svg, "L3", "x"), l3_y = text_position(svg, "L3", "y");
  EXPECT_LT(l2_y, l1_y);
  EXPECT_NEAR(l1_y - l2_y, 2.0 * scale, 0.05);
  EXPECT_NEAR(l3_x - l1_x, 1.2 * scale, 0.05);
  EXPECT_NEAR(l2_x, l1_x, 0.01);
  EXPECT_NEAR(l3_y, l1_y, 0.01);
}

TEST(PlanSvg, LuminairesAreLabelledWithTheirIdsAndListedInTheSchedule) {
  PlanView view = office_view();
  for (PlanLuminaire& l : view.luminaires) l.above_floor_m = 2.8;
  const std::string svg = render_plan_svg(office(), view);
  for (const char* text : {"L1", "L2", "L3", "luminaire schedule", "1500", "800", "0.80", "0.50", "2.80"})
    EXPECT_TRUE(has_text(svg, text)) << text;
  EXPECT_EQ(count(svg, ">1500</text>"), 2u);  // the schedule's flux column
  EXPECT_TRUE(has_text(svg, "luminaires above the floor: 2.80 m (all)"));
  EXPECT_TRUE(Contains(svg, "<title>L3: 800 lm, 0.6 m square at (2, 0.5, 2.8) m, 2.80 m above the floor</title>", "svg"));
}

TEST(PlanSvg, ALabelAtTheRightWallGoesLeftOfItsOutline) {
  PlanView view = office_view();
  view.luminaires = {square("east", V(3.8, 1.5, 2.8), 0.3, 1200.0)};
  const PlanLayout layout = plan_svg_layout(office(), view);
  ASSERT_EQ(layout.label_px.size(), 1u);
  EXPECT_LT(layout.label_px[0].max().x(), layout.outline_px[0].min().x());
  EXPECT_TRUE(layout.plan_px.contains(layout.label_px[0]));
}

TEST(PlanSvg, LabelsOfADenseLayoutCoverNoOtherLabelOrOutline) {
  // 8 x 6 luminaires of 0.3 m, 0.45 m apart over the 4 x 3 m room: ids such as "L48"
  // do not fit between two outlines, so most go above, below or farther out.
  PlanView view = office_view();
  view.luminaires.clear();
  for (int j = 0; j < 6; ++j)
    for (int i = 0; i < 8; ++i) {
      std::string id = "L";
      id += std::to_string(view.luminaires.size() + 1);  // (GCC 12 warns wrongly on "L" + string&&)
      view.luminaires.push_back(square(id, V(0.425 + 0.45 * i, 0.375 + 0.45 * j, 2.8), 0.3, 500.0));
    }
  const PlanLayout layout = plan_svg_layout(office(), view);
  ASSERT_EQ(layout.label_px.size(), 48u);
  for (std::size_t a = 0; a < 48; ++a) {
    ASSERT_FALSE(layout.label_px[a].isEmpty()) << "label " << a + 1 << " not placed";
    EXPECT_TRUE(layout.plan_px.contains(layout.label_px[a]));
    for (std::size_t b = 0; b < 48; ++b) {
      if (b != a) {
        EXPECT_TRUE(layout.label_px[a].intersection(layout.label_px[b]).isEmpty()) << a + 1 << " and " << b + 1;
      }
      EXPECT_TRUE(layout.label_px[a].intersection(layout.outline_px[b]).isEmpty()) << "label " << a + 1 << " on " << b + 1;
    }
  }
  const std::string svg = render_plan_svg(office(), view);
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_TRUE(has_text(svg, "L48"));
}

TEST(PlanSvg, DimensionChainsGiveTheSpacingsAndTheDistancesToTheWalls) {
  // A 2 x 2 field in the 4 x 3 m room: columns at 1 and 3 m, rows at 0.75 and 2.25 m.
  PlanView view = office_view();
  view.luminaires = {square("L1", V(1, 0.75, 2.8), 0.6, 1000.0), square("L2", V(3, 0.75, 2.8), 0.6, 1000.0),
                     square("L3", V(1, 2.25, 2.8), 0.6, 1000.0), square("L4", V(3, 2.25, 2.8), 0.6, 1000.0)};
  const PlanLayout layout = plan_svg_layout(office(), view);
  EXPECT_EQ(layout.along_x_text, (std::vector<std::string>{"1.00", "2.00", "1.00"}));
  EXPECT_EQ(layout.along_y_text, (std::vector<std::string>{"0.75", "1.50", "0.75"}));
  const std::string svg = render_plan_svg(office(), view);
  EXPECT_TRUE(Contains(svg, "class=\"dimensions-x\"", "svg"));
  EXPECT_TRUE(Contains(svg, "class=\"dimensions-y\"", "svg"));
  EXPECT_EQ(count(svg, ">2.00</text>"), 1u);
  EXPECT_EQ(count(svg, ">0.75</text>"), 4u);  // twice on the y chain, twice in the schedule (L1, L2)
  view.dimensions = false;
  EXPECT_TRUE(plan_svg_layout(office(), view).along_x.stops_m.empty());
  EXPECT_EQ(metres_2(2.0), "2.00");
  EXPECT_EQ(metres_2(0.745), "0.74");  // round half to even on the binary value 0.74499..
  EXPECT_EQ(metres_2(-0.001), "0.00");
}

TEST(PlanSvg, DrawsTheArchitectureGridsTiltAndTitleBlock) {
  // A partition (a box 0.1 x 1 m, 1.5 m high) cut at 0.8 m, the desk below the cut seen from above.
  std::vector<reference::QuadSpec> quads = {
      {"floor", V(0, 0, 0), V(4, 0, 0), V(4, 3, 0), V(0, 3, 0), V::Constant(0.5)},
      {"desk", V(1, 1, 0.75), V(2, 1, 0.75), V(2, 2, 0.75), V(1, 2, 0.75), V::Constant(0.5)},
      {"part", V(3, 1, 0), V(3.1, 1, 0), V(3.1, 1, 1.5), V(3, 1, 1.5), V::Constant(0.5)},
      {"part", V(3.1, 2, 0), V(3, 2, 0), V(3, 2, 1.5), V(3.1, 2, 1.5), V::Constant(0.5)},
      {"part", V(3, 2, 0), V(3, 1, 0), V(3, 1, 1.5), V(3, 2, 1.5), V::Constant(0.5)},
      {"part", V(3.1, 1, 0), V(3.1, 2, 0), V(3.1, 2, 1.5), V(3.1, 1, 1.5), V::Constant(0.5)}};
  const Scene scene = reference::make_quad_scene(quads, 0.0);
  PlanView view;
  view.outline_patches = {0, 1};
  view.architecture = plan_architecture(scene, {.floor_z_m = 0.0, .cut_height_m = 0.8});
  ASSERT_EQ(view.architecture.section.size(), 1u);
  ASSERT_EQ(view.architecture.furniture.size(), 1u);
  PlanLuminaire spot = square("S1", V(2, 1.5, 2.5), 0.2, 800.0);
  spot.rotation_deg = 90.0;  // aimed toward +y
  spot.tilt_deg = 30.0;
  view.luminaires = {spot};
  view.grids = {{"work plane", {Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(1.5, 0.5)}, Eigen::Vector2d(1, 1), {400, 600},
                 "isolux_work_plane.png"}};
  view.maintenance_factor = 0.8;
  view.title_block = {"office", "1 x spot 800 lm"};
  const std::string svg = render_plan_svg(scene, view);
  EXPECT_TRUE(WellFormed(svg));
  for (const char* part : {"class=\"section-fill\"", "class=\"section\"", "class=\"furniture\"", "class=\"aim\"",
                           "class=\"grid\"", "class=\"title-block\""})
    EXPECT_TRUE(Contains(svg, part, "svg")) << part;
  for (const char* text : {"office", "1 x spot 800 lm", "section cut at 0.80 m above the floor",
                           "maintained illuminance (lx)", "grid work plane: Em 400 lx", "values: isolux_work_plane.png",
                           "max 480 lx", "min 320 lx"})
    EXPECT_TRUE(has_text(svg, text)) << text;
  // The aim arrow points up the page (+y): its tip above the centre.
  const std::size_t aim = svg.find("class=\"aim\" d=\"M");
  ASSERT_NE(aim, std::string::npos);
  std::istringstream d(svg.substr(svg.find('M', aim) + 1));
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  char c = 0;
  d >> x0 >> c >> y0 >> c >> x1 >> c >> y1;
  EXPECT_NEAR(x1, x0, 0.01);
  EXPECT_LT(y1, y0 - 10.0);
}

TEST(PlanSvg, EscapesText) {
  PlanView view = office_view();
  view.title = "a<b & c";
  view.luminaires[0].id = "<L&1>";
  const std::string svg = render_plan_svg(office(), view);
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_TRUE(has_text(svg, "a&lt;b &amp; c"));
  EXPECT_TRUE(has_text(svg, "&lt;L&amp;1&gt;"));
  EXPECT_EQ(svg.find("a<b"), std::string::npos);
}

TEST(PlanSvg, NaNLuxIsGreyAndLeftOutOfTheScale) {
  PlanView view = office_view();
  view.goal_lux = values({std::numeric_limits<double>::quiet_NaN(), 300.0, 100.0, 200.0});
  const std::string svg = render_plan_svg(office(), view);
  EXPECT_TRUE(WellFormed(svg));
  const std::vector<std::string> drawn = polygons(svg);
  ASSERT_EQ(drawn.size(), 4u);
  EXPECT_EQ(attribute(drawn[2], "fill"), "#808080");
  EXPECT_EQ(attribute(drawn[3], "fill"), svg_colour(colour_map(300.0 / 400.0)));  // scale 0 to 400 lx
  EXPECT_TRUE(has_text(svg, "max 300 lx"));
  EXPECT_TRUE(has_text(svg, "min 100 lx"));
}

TEST(PlanSvg, EmptyViewAndEdgeOnGoalStillMakeAPlan) {
  const std::string empty = render_plan_svg(office(), {});
  EXPECT_TRUE(WellFormed(empty));
  EXPECT_EQ(polygons(empty).size(), 0u);
  EXPECT_TRUE(has_text(empty, "illuminance (lx)"));

  // A wall alone: its top view is a line, which still gets a (padded) plan.
  const Scene wall = reference::make_quad_scene(
      {{"wall", V(0, 0, 0), V(2, 0, 0), V(2, 0, 2), V(0, 0, 2), V::Constant(0.5)}}, 0.0);
  PlanView view;
  view.goal_patches = {0, 1};
  view.goal_lux = values({10.0, 20.0});
  const std::string svg = render_plan_svg(wall, view);
  EXPECT_TRUE(WellFormed(svg));
  EXPECT_EQ(polygons(svg).size(), 2u);
  EXPECT_FALSE(has_non_finite_number(svg));
}

TEST(PlanSvg, RejectsMismatchedSizesAndUnknownPatches) {
  const Scene scene = office();
  PlanView view = office_view();
  view.goal_lux = values({1.0, 2.0, 3.0});
  EXPECT_THROW(render_plan_svg(scene, view), std::invalid_argument);

  for (int bad : {-1, 6}) {
    view = office_view();
    view.goal_patches[1] = bad;
    EXPECT_THROW(render_plan_svg(scene, view), std::invalid_argument) << bad;
    view = office_view();
    view.outline_patches.push_back(bad);
    EXPECT_THROW(render_plan_svg(scene, view), std::invalid_argument) << bad;
  }

  view = office_view();
  view.luminaires[1].flux_lm = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(render_plan_svg(scene, view), std::invalid_argument);
  view = office_view();
  view.luminaires[1].size_m = -0.5;
  EXPECT_THROW(render_plan_svg(scene, view), std::invalid_argument);
}

}  // namespace
}  // namespace ilp
