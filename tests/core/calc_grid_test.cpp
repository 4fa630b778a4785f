// Calculation grids and illuminance at points: EN 12464-1's spacing, the border band,
// points inside solids, the direct light at a point under a Lambertian disc (closed
// form), a luminous ceiling over a floor (the infinite-room limit), and the operator
// at points against the exact solve with the same rays (census).
#include "core/grid/calc_grid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "job/config.h"
#include "core/base/error.h"
#include "core/exact/exact_solver.h"
#include "job/job_scene.h"
#include "job/plan.h"
#include "core/transport/direct_light.h"
#include "core/exact/point_illuminance.h"
#include "core/scene/reference_scenes.h"
#include "core/operator/sample_operator.h"
#include "job/setting_keys.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

TEST(CalcGrid, SpacingFollowsTheStandardsFormulaAndTable) {
  // p = 0.2 x 5^log10(d); LIGHTING.md's rounded table: 1 m -> 0.2, 5 -> 0.6, 10 -> 1.0, 25 -> 2.0, 50 -> 3.0, 100 -> 5.0.
  EXPECT_NEAR(en12464_grid_spacing_m(1.0), 0.2, 1e-12);
  EXPECT_NEAR(en12464_grid_spacing_m(10.0), 1.0, 1e-12);
  EXPECT_NEAR(en12464_grid_spacing_m(100.0), 5.0, 1e-12);
  const std::pair<double, double> table[] = {{5.0, 0.6}, {25.0, 2.0}, {50.0, 3.0}};
  for (const auto& [d, p] : table) EXPECT_NEAR(en12464_grid_spacing_m(d), p, 0.11) << d;  // the table rounds
  EXPECT_NEAR(en12464_grid_spacing_m(5.0), 0.6160, 1e-4);
  EXPECT_EQ(en12464_grid_spacing_m(1e6), 10.0);  // capped
  // Points along the longer side: the nearest whole number of d / p (table: 1 m >= 5, 5 m >= 8, 10 m >= 10, 100 m >= 20).
  const std::pair<double, int> points[] = {{1.0, 5}, {5.0, 8}, {10.0, 10}, {100.0, 20}};
  for (const auto& [d, n] : points) EXPECT_EQ(grid_cell_counts(d, d, en12464_grid_spacing_m(d)).x(), n) << d;
}

TEST(CalcGrid, CellAspectStaysWithinHalfAndTwo) {
  const Eigen::Vector2i n = grid_cell_counts(10.0, 0.3, 1.0);  // a narrow strip: 10 x 1 cells would be 1 x 0.3
  EXPECT_EQ(n.y(), 1);
  const double aspect = (10.0 / n.x()) / (0.3 / n.y());
  EXPECT_LE(aspect, 2.0);
  EXPECT_GE(aspect, 0.5);
  EXPECT_EQ(n.x(), 17);  // the fewest cells with 10 / n <= 0.6
}

TEST(CalcGrid, SimplePolygons) {
  EXPECT_TRUE(polygon_is_simple({V2(0, 0), V2(4, 0), V2(4, 3), V2(0, 3)}));
  EXPECT_TRUE(polygon_is_simple({V2(0, 0), V2(4, 0), V2(4, 3), V2(2, 1), V2(0, 3)}));  // concave
  EXPECT_FALSE(polygon_is_simple({V2(0, 0), V2(4, 3), V2(4, 0), V2(0, 3)}));            // a bow tie
  EXPECT_FALSE(polygon_is_simple({V2(0, 0), V2(4, 0)}));
  EXPECT_FALSE(polygon_is_simple({V2(0, 0), V2(2, 0), V2(4, 0)}));                      // no area
}

// A 6 x 4 x 3 m room (faces inwards) with a closed 1 x 1 x 1 m box on the floor (faces outwards).
Scene room_with_box() {
  const V r = V::Constant(0.5);
  Scene room = reference::make_closed_box(V::Zero(), V(6, 4, 3), 0.5, 0.5);
  const double x0 = 1, y0 = 1, z0 = 0, x1 = 2, y1 = 2, z1 = 1;
  const Scene box = reference::make_quad_scene(
      {{"box", V(x0, y0, z1), V(x1, y0, z1), V(x1, y1, z1), V(x0, y1, z1), r},
       {"box", V(x0, y0, z0), V(x0, y1, z0), V(x1, y1, z0), V(x1, y0, z0), r},
       {"box", V(x0, y0, z0), V(x1, y0, z0), V(x1, y0, z1), V(x0, y0, z1), r},
       {"box", V(x1, y1, z0), V(x0, y1, z0), V(x0, y1, z1), V(x1, y1, z1), r},
       {"box", V(x0, y1, z0), V(x0, y0, z0), V(x0, y0, z1), V(x0, y1, z1), r},
       {"box", V(x1, y0, z0), V(x1, y1, z0), V(x1, y1, z1), V(x1, y0, z1), r}},
      0.5);
  const int offset = static_cast<int>(room.surfaces.size());
  room.surfaces.push_back(box.surfaces[0]);
  for (Patch p : box.patches) {
    p.surface += offset;
    room.patches.push_back(p);
  }
  return room;
}

TEST(CalcGrid, WorkPlaneOverAFloorWithBandAndAPointInsideABoxDropped) {
  const Scene scene = room_with_box();
  const RayCaster caster(scene);
  CalcGridSetting s;
  s.name = "work";
  s.over_surface = "floor";
  s.height_m = 0.8;  // inside the 1 m box where it stands
  s.border_m = 0.5;
  const CalcGrid grid = make_calc_grid(scene, caster, s);
  // 5 x 3 m after the band: d = 5, p = 0.617, 8 cells along x and round(3 / 0.617) = 5 along y.
  EXPECT_EQ(grid.cells_u, 8);
  EXPECT_EQ(grid.cells_v, 5);
  EXPECT_NEAR(grid.cell_u_m, 5.0 / 8, 1e-12);
  EXPECT_NEAR(grid.cell_v_m, 3.0 / 5, 1e-12);
  EXPECT_EQ(grid.outside_outline, 0u);
  // Cell centres inside x, y in (1, 2): x = 0.5 + (i + 0.5) 0.625 -> i = 1 (0.8125 no), i = 1: 1.4375; y = 0.5 + (j + 0.5) 0.6 -> j = 1: 1.4.
  EXPECT_EQ(grid.inside_solid, 1u);
  EXPECT_EQ(grid.points.size(), 39u);
  for (const ReceiverPoint& p : grid.points) {
    EXPECT_NEAR(p.position_m.z(), 0.8, 1e-12);
    EXPECT_GE(p.position_m.x(), 0.5);
    EXPECT_LE(p.position_m.x(), 5.5);
    EXPECT_FALSE(p.position_m.x() > 1 && p.position_m.x() < 2 && p.position_m.y() > 1 && p.position_m.y() < 2);
  }
  EXPECT_NEAR(grid.area_m2, 39 * 0.625 * 0.6, 1e-9);
  // Given spacing.
  s.spacing_m = 0.25;
  const CalcGrid fine = make_calc_grid(scene, caster, s);
  EXPECT_EQ(fine.cells_u, 20);
  EXPECT_EQ(fine.cells_v, 12);
}

TEST(CalcGrid, BadGridsAreConfigErrors) {
  name_settings_by_key();  // as load_job_config and the ilp command do: messages name the job file's keys
  const Scene scene = room_with_box();
  const RayCaster caster(scene);
  CalcGridSetting s;
  s.name = "g";
  s.loc = {"job.yaml", 7, 5};
  s.border_loc = {"job.yaml", 9, 13};
  s.spacing_loc = {"job.yaml", 10, 14};
  s.height_loc = {"job.yaml", 8, 13};
  s.shape_loc = {"job.yaml", 11, 5};
  auto message = [&](const CalcGridSetting& setting) {
    try {
      make_calc_grid(scene, caster, setting);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CalcGridSetting band = s;
  band.over_surface = "floor";
  band.border_m = 2.5;  // 4 m wide room
  EXPECT_NE(message(band).find("job.yaml:9:13: grids.g.border_m"), std::string::npos) << message(band);
  CalcGridSetting many = s;
  many.over_surface = "floor";
  many.spacing_m = 0.01;
  EXPECT_NE(message(many).find("job.yaml:10:14: grids.g: a spacing of 0.01 m"), std::string::npos) << message(many);
  EXPECT_NE(message(many).find("more than max_points (20000)"), std::string::npos);
  CalcGridSetting high = s;
  high.over_surface = "floor";
  high.height_m = 3.5;
  EXPECT_NE(message(high).find("job.yaml:8:13: grids.g.height_m"), std::string::npos) << message(high);
  CalcGridSetting outside = s;
  outside.polygon_m = {V2(5, 1), V2(8, 1), V2(8, 3), V2(5, 3)};
  EXPECT_NE(message(outside).find("job.yaml:11:5: grids.g: the grid reaches outside the scene"), std::string::npos)
      << message(outside);
  CalcGridSetting unknown = s;
  unknown.over_surface = "no_such_floor";
  EXPECT_NE(message(unknown).find("unknown surface 'no_such_floor'"), std::string::npos);
  CalcGridSetting all_inside = s;  // a plane wholly inside the box
  all_inside.polygon_m = {V2(1.1, 1.1), V2(1.9, 1.1), V2(1.9, 1.9), V2(1.1, 1.9)};
  all_inside.border_m = 0.0;
  all_inside.height_m = 0.5;
  EXPECT_NE(message(all_inside).find("no point is left"), std::string::npos) << message(all_inside);
}

TEST(CalcGrid, GridOverNoFloorIsAnError) {
  // A room without its floor: nothing under the points.
  Scene scene = reference::make_quad_scene(
      {{"ceiling", V(0, 0, 3), V(0, 4, 3), V(6, 4, 3), V(6, 0, 3)}, {"ground", V(-1, -1, -1), V(7, -1, -1), V(7, 0, -1), V(-1, 0, -1)}},
      0.0);
  const RayCaster caster(scene);
  CalcGridSetting s;
  s.name = "g";
  s.polygon_m = {V2(0, 0), V2(6, 0), V2(6, 4), V2(0, 4)};
  s.height_m = 0.8;
  try {
    make_calc_grid(scene, caster, s);
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("have no floor under them"), std::string::npos) << e.what();
  }
}

// EN 12464-1's immediate surrounding area: the band around a task area, its points in
// the ring between the task outline and that outline grown by the width, and nowhere else.
CalcGridSetting task_band(const std::vector<V2>& task, double width_m) {
  CalcGridSetting s;
  s.name = "desk_surrounding";
  s.polygon_m = task;
  s.height_m = 0.8;
  s.border_m = 0.0;
  s.band_width_m = width_m;
  s.band_loc = {"job.yaml", 12, 30};
  return s;
}

bool in_rectangle(const V& p, const V2& lo, const V2& hi) {
  return p.x() > lo.x() && p.x() < hi.x() && p.y() > lo.y() && p.y() < hi.y();
}

TEST(CalcGridBand, TheBandAroundARectangleTaskAreaLiesInTheRingOnly) {
  const Scene scene = reference::make_closed_box(V::Zero(), V(6, 4, 3), 0.5, 0.5);
  const RayCaster caster(scene);
  // A 2 x 2 m task area, a 0.5 m band: the grown outline is 3 x 3 m, p = 0.2 x 5^log10(3)
  // = 0.431 m, so 2 cells of 0.25 m across the band: 12 x 12 cells less the task's 8 x 8.
  const CalcGrid grid = make_calc_grid(scene, caster, task_band({V2(2, 1), V2(4, 1), V2(4, 3), V2(2, 3)}, 0.5));
  EXPECT_NEAR(grid.spacing_m, 0.2 * std::pow(5.0, std::log10(3.0)), 1e-12);
  EXPECT_DOUBLE_EQ(grid.cell_u_m, 0.25);
  EXPECT_DOUBLE_EQ(grid.cell_v_m, 0.25);
  EXPECT_EQ(grid.cells_u, 12);
  EXPECT_EQ(grid.cells_v, 12);
  ASSERT_EQ(grid.points.size(), 144u - 64u);
  EXPECT_EQ(grid.outside_outline, 64u) << "the task area's own cells";
  EXPECT_EQ(grid.outside_room, 0u);
  EXPECT_NEAR(grid.area_m2, 9.0 - 4.0, 1e-9);
  int left = 0, right = 0, below = 0, above = 0;
  for (const ReceiverPoint& p : grid.points) {
    EXPECT_NEAR(p.position_m.z(), 0.8, 1e-12);
    EXPECT_TRUE(in_rectangle(p.position_m, V2(1.5, 0.5), V2(4.5, 3.5))) << p.position_m.transpose();
    EXPECT_FALSE(in_rectangle(p.position_m, V2(2, 1), V2(4, 3))) << p.position_m.transpose();
    // Cell centres: 0.125 m and 0.375 m from the task's edge.
    const double fx = (p.position_m.x() - 1.5) / 0.25 - 0.5, fy = (p.position_m.y() - 0.5) / 0.25 - 0.5;
    EXPECT_NEAR(fx, std::round(fx), 1e-9);
    EXPECT_NEAR(fy, std::round(fy), 1e-9);
    left += p.position_m.x() < 2.0;
    right += p.position_m.x() > 4.0;
    below += p.position_m.y() < 1.0;
    above += p.position_m.y() > 3.0;
  }
  EXPECT_EQ(left, 2 * 12);
  EXPECT_EQ(right, 2 * 12);
  EXPECT_EQ(below, 2 * 12);
  EXPECT_EQ(above, 2 * 12);
  // Drawn as the grown outline with the task area as its hole.
  EXPECT_EQ(grid.outline_polygon_m.size(), 4u);
  EXPECT_EQ(grid.outline_hole_m.size(), 4u);
}

TEST(CalcGridBand, ABandReachingPastAWallIsClippedToTheRoom) {
  const Scene scene = reference::make_closed_box(V::Zero(), V(6, 4, 3), 0.5, 0.5);
  const RayCaster caster(scene);
  // A 1 x 1 m task 0.2 m from the wall x = 0: the grown outline reaches x = -0.3. Its
  // 2 x 2 m lattice at p(2 m) = 0.325 m: 0.25 m cells, 8 x 8; the column at x < 0 is
  // outside the room, the task's 4 x 4 cells are not the band.
  const CalcGrid grid = make_calc_grid(scene, caster, task_band({V2(0.2, 1), V2(1.2, 1), V2(1.2, 2), V2(0.2, 2)}, 0.5));
  EXPECT_EQ(grid.cells_u, 8);
  EXPECT_EQ(grid.cells_v, 8);
  EXPECT_EQ(grid.points.size(), 64u - 8u - 16u);
  for (const ReceiverPoint& p : grid.points) {
    EXPECT_GT(p.position_m.x(), 0.0);
    EXPECT_FALSE(in_rectangle(p.position_m, V2(0.2, 1), V2(1.2, 2)));
  }
}

TEST(CalcGridBand, ABandWiderThanTheRoomIsAConfigError) {
  name_settings_by_key();  // as load_job_config and the ilp command do: messages name the job file's keys
  const Scene scene = reference::make_closed_box(V::Zero(), V(6, 4, 3), 0.5, 0.5);
  const RayCaster caster(scene);
  try {
    make_calc_grid(scene, caster, task_band({V2(2, 1), V2(4, 1), V2(4, 3), V2(2, 3)}, 7.0));
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("job.yaml:12:30: grids.desk_surrounding: a surrounding band 7 m wide is wider than the room", 0),
              0u) << what;
  }
}

// The band's average under an isotropic point source of intensity I at height h over the
// task's centre, against the closed form: the flux a rectangle centred under the source
// receives is I x its solid angle, 4 atan(a b / (h sqrt(h^2 + a^2 + b^2))) for half sides
// a, b, so the ring's average is I (omega(grown) - omega(task)) / (its area).
TEST(CalcGridBand, TheBandsAverageUnderAPointSourceMatchesTheClosedForm) {
  const Scene scene = reference::make_closed_box(V::Zero(), V(6, 4, 3), 0.5, 0.5);
  const RayCaster caster(scene);
  CalcGridSetting s = task_band({V2(2, 1), V2(4, 1), V2(4, 3), V2(2, 3)}, 0.5);
  s.spacing_m = 0.05;
  const CalcGrid grid = make_calc_grid(scene, caster, s);
  ASSERT_EQ(grid.points.size(), 60u * 60u - 40u * 40u);
  const double I = 1000.0, h = 1.5;
  const V source(3.0, 2.0, 0.8 + h);
  double sum = 0.0;
  for (const ReceiverPoint& p : grid.points) {
    const double d = (source - p.position_m).norm();
    sum += I * h / (d * d * d);  // E = I cos(theta) / d^2
  }
  auto omega = [&](double a, double b) { return 4.0 * std::atan(a * b / (h * std::sqrt(h * h + a * a + b * b))); };
  const double closed = I * (omega(1.5, 1.5) - omega(1.0, 1.0)) / (9.0 - 4.0);
  // The midpoint rule on 5 cm cells: about (c^2 / 24) |E''| / E, a few 1e-4.
  constexpr double kMidpointRuleTolerance = 1e-3;
  EXPECT_NEAR(sum / grid.points.size(), closed, kMidpointRuleTolerance * closed);
}

TEST(CalcGridBand, GrowingAPolygonMovesEveryEdgeOut) {
  // Clockwise or not, a rectangle grows into a rectangle.
  for (const bool clockwise : {false, true}) {
    std::vector<V2> r{V2(0, 0), V2(2, 0), V2(2, 1), V2(0, 1)};
    if (clockwise) std::reverse(r.begin(), r.end());
    const std::vector<V2> g = grow_polygon(r, 0.5);
    Eigen::AlignedBox2d box;
    for (const V2& p : g) box.extend(p);
    EXPECT_TRUE(box.min().isApprox(V2(-0.5, -0.5))) << box.min().transpose();
    EXPECT_TRUE(box.max().isApprox(V2(2.5, 1.5))) << box.max().transpose();
  }
  // An L: its inner corner moves out along both edges (to (1.5, 1.5) from (1, 1)).
  const std::vector<V2> l = grow_polygon({V2(0, 0), V2(2, 0), V2(2, 1), V2(1, 1), V2(1, 2), V2(0, 2)}, 0.5);
  EXPECT_TRUE(l[3].isApprox(V2(1.5, 1.5))) << l[3].transpose();
}

TEST(CalcGrid, VerticalGridFacesItsSide) {
  const Scene scene = room_with_box();
  const RayCaster caster(scene);
  CalcGridSetting s;
  s.name = "board";
  s.kind = GridKind::vertical;
  s.from_m = V2(6, 0.5);
  s.to_m = V2(6, 3.5);  // along +y on the wall x = 6; facing left = -x, into the room
  s.bottom_m = 1.0;
  s.top_m = 2.0;
  s.border_m = 0.0;
  const CalcGrid grid = make_calc_grid(scene, caster, s);
  EXPECT_EQ(grid.cells_u * grid.cells_v, static_cast<int>(grid.points.size()));
  for (const ReceiverPoint& p : grid.points) {
    EXPECT_NEAR(p.normal.x(), -1.0, 1e-12);
    EXPECT_GE(p.position_m.z(), 1.0);
    EXPECT_LE(p.position_m.z(), 2.0);
  }
}

// A Lambertian disc of radius R at height h facing down, fanned into 512 triangles.
Scene disc_luminaire(double R, double h, double flux_lm) {
  Scene scene;
  scene.surfaces.push_back({"disc", 0.0});
  // Registered as a Lambertian disc luminaire whose opening is these 512 patches.
  LuminaireType disc = LuminaireType::square_lambertian(2.0 * R);
  disc.shape = OutlineShape::disc;
  scene.surfaces[0].luminaire = 0;
  scene.luminaires.push_back({disc, {V(0, 0, h), 0.0}, 0, flux_lm});
  constexpr int kSides = 512;
  double area = 0.0;
  for (int k = 0; k < kSides; ++k) {
    const double a0 = 2 * std::numbers::pi * k / kSides, a1 = 2 * std::numbers::pi * (k + 1) / kSides;
    Patch p;
    // Counter-clockwise seen from below (normal -z).
    p.vertices_m = {V(0, 0, h), V(R * std::cos(a1), R * std::sin(a1), h), V(R * std::cos(a0), R * std::sin(a0), h)};
    p.normal = -V::UnitZ();
    p.area_m2 = 0.5 * R * R * std::sin(a1 - a0);
    p.centroid_m = (p.vertices_m[0] + p.vertices_m[1] + p.vertices_m[2]) / 3.0;
    p.surface = 0;
    area += p.area_m2;
    scene.patches.push_back(p);
  }
  for (Patch& p : scene.patches) p.exitance_lm_per_m2 = flux_lm / area;
  for (const Patch& p : scene.patches)
    for (const V& v : p.vertices_m) scene.bounds_m.extend(v);
  scene.bounds_m.extend(V(-R, -R, -1.0));
  return scene;
}

TEST(PointDirectLight, PointUnderALambertianDiscMatchesTheClosedForm) {
  for (double h : {0.5, 1.0, 3.0}) {
    const double R = 0.8, flux = 3000.0;
    const Scene scene = disc_luminaire(R, h, flux);
    const RayCaster caster(scene);
    const std::vector<ReceiverPoint> points{{V::Zero(), V::UnitZ()}, {V(0, 0, h - 0.2), V::UnitZ()}};
    const std::vector<int> luminaires{0};
    const Eigen::MatrixXd E = compute_luminaire_light_at_points(scene, caster, points, luminaires, {}).lux_per_lm;
    // E = pi L R^2 / (R^2 + h^2), L = M / pi, M = flux / (pi R^2) (the polygon's area differs by < 3e-5).
    const double M = flux / (std::numbers::pi * R * R);
    for (std::size_t q = 0; q < points.size(); ++q) {
      const double d = h - points[q].position_m.z();
      EXPECT_NEAR(E(static_cast<Eigen::Index>(q), 0) * flux, M * R * R / (R * R + d * d), 1e-4 * M) << "h " << d;
    }
    // Facing away, or above the disc: nothing.
    const std::vector<ReceiverPoint> away{{V::Zero(), -V::UnitZ()}, {V(0, 0, h + 1), -V::UnitZ()}};
    EXPECT_EQ(compute_luminaire_light_at_points(scene, caster, away, luminaires, {}).lux_per_lm.cwiseAbs().maxCoeff(), 0.0);
  }
}

TEST(PointDirectLight, ShadowRaysSeeBlockers) {
  Scene scene = disc_luminaire(0.5, 2.0, 1000.0);
  // A blocker over the half x < 0 at z = 1.9 (facing down), and one wholly under the disc elsewhere.
  const Scene blocker = reference::make_quad_scene({{"blocker", V(-1, -1, 1.9), V(-1, 1, 1.9), V(0, 1, 1.9), V(0, -1, 1.9)}}, 0.0);
  scene.surfaces.push_back(blocker.surfaces[0]);
  for (Patch p : blocker.patches) {
    p.surface = 1;
    scene.patches.push_back(p);
  }
  const RayCaster caster(scene);
  DirectLightOptions o;
  o.shadow_rays = 256;
  const std::vector<ReceiverPoint> under{{V(0, 0, 1.8), V::UnitZ()}, {V(0, 0, 0.0), V::UnitZ()}};
  const std::vector<ReceiverPoint> open_points{{V(0, 0, 1.8), V::UnitZ()}};
  const Eigen::MatrixXd E = compute_luminaire_light_at_points(scene, caster, under, std::vector<int>{0}, o).lux_per_lm;
  const Scene bare = disc_luminaire(0.5, 2.0, 1000.0);
  const RayCaster bare_caster(bare);
  const Eigen::MatrixXd E0 = compute_luminaire_light_at_points(bare, bare_caster, under, std::vector<int>{0}, o).lux_per_lm;
  // 0.1 m under the blocker's edge, the point sees half the disc, minus a sliver.
  EXPECT_NEAR(E(0, 0) / E0(0, 0), 0.5, 0.06);
  EXPECT_NEAR(E(1, 0) / E0(1, 0), 0.5, 0.06);
  EXPECT_THROW(compute_luminaire_light_at_points(scene, caster, under, std::vector<int>{1}, o), std::out_of_range);
}

// A luminous ceiling (exitance M, reflectance rho_c) 1 m over a floor of reflectance
// rho_f, 30 x 30 m with black walls. Between infinite planes an upward point sees the
// ceiling's radiosity, E = M / (1 - rho_c rho_f) = E_direct / (1 - rho) with rho =
// rho_c rho_f. At the centre the finite box loses per bounce the share of a diffuse
// source beyond 15 m, h^2 / (h^2 + r^2) = 0.44 %, over about 1 / (1 - rho) = 2 bounces:
// under 1 %, so 1.5 % covers it and the rays' noise.
TEST(PointIlluminance, LuminousCeilingOverAFloorApproachesTheInfiniteRoom) {
  const double rho_c = 0.99, rho_f = 0.5, M = 1000.0;
  Scene scene = reference::make_closed_box(V::Zero(), V(30, 30, 1), 0.0, 3.0);  // about 1,900 patches
  const int ceiling = scene.find_surface("ceiling"), floor = scene.find_surface("floor");
  for (Patch& p : scene.patches) {
    if (p.surface == ceiling) p.reflectance.setConstant(rho_c);
    if (p.surface == floor) p.reflectance.setConstant(rho_f);
  }
  set_surface_exitance(scene, ceiling, M);
  const RayCaster caster(scene);
  const std::vector<ReceiverPoint> points{{V(15, 15, 0.5), V::UnitZ()}, {V(14.3, 15.6, 0.2), V::UnitZ()}};
  SampleOperatorOptions o;
  o.sample_size = static_cast<int>(scene.patches.size());  // census: the operator is the exact solve
  o.form_factors.rays_per_patch = 1024;
  const std::vector<LightSource> sources = scene_light_sources(scene);
  const GoalRows rows = compute_goal_rows(scene, caster, {}, points, sources, o);
  const SampleOperator op = build_sample_operator(scene, caster, rows, o);
  ASSERT_EQ(op.total_lux_per_lm.rows(), 2);
  const Eigen::VectorXd flux = source_flux_lm(scene, sources);
  const Eigen::VectorXd total = op.illuminance_lux(flux), direct = op.direct_lux(flux);
  const double rho = rho_c * rho_f;
  for (int q = 0; q < 2; ++q) {
    EXPECT_NEAR(direct[q], M, 0.01 * M) << q;  // the ceiling fills nearly the whole hemisphere
    EXPECT_NEAR(total[q] / (direct[q] / (1.0 - rho)), 1.0, 0.015) << q;
  }
}

// With every reflecting patch in the sample (k = n) the operator at points is the exact
// solve followed by each point's gather with the same rays: equal to round-off.
TEST(PointIlluminance, CensusOperatorAtPointsEqualsTheExactSolve) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  job.scene.max_patch_edge_m = 0.6;
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  for (double x : {0.7, 1.9, 3.1, 4.3, 5.5})
    for (double y : {0.6, 2.0, 3.4}) points.push_back({V(x, y, 0.8), V::UnitZ()});
  points.push_back({V(3.0, 2.0, 2.0), -V::UnitZ()});  // facing down: no direct light, only reflected
  for (IndirectMethod method : {IndirectMethod::sample_gather, IndirectMethod::exact_second_bounce}) {
    SampleOperatorOptions o;
    o.sample_size = static_cast<int>(scene.patches.size());
    o.indirect = method;
    const std::vector<int> goals = scene.patches_of({"desk_1"});
    const GoalRows rows = compute_goal_rows(scene, caster, goals, points, scene_light_sources(scene), o);
    const SampleOperator op = build_sample_operator(scene, caster, rows, o);
    ASSERT_EQ(op.total_lux_per_lm.rows(), static_cast<Eigen::Index>(goals.size() + points.size()));
    const Eigen::VectorXd flux = source_flux_lm(scene, op.sources);
    const Eigen::VectorXd H = op.illuminance_lux(flux), D = op.direct_lux(flux);
    ExactSolveOptions exact;
    exact.radiosity.relative_residual = 1e-12;
    const ExactSolution solution = solve_exact(scene, exact);
    FormFactorOptions point_rows = o.form_factors;
    point_rows.rays_per_patch *= kPointRayFactor;  // as compute_goal_rows casts them
    const PointIlluminance at = exact_point_illuminance(scene, caster, solution.radiosity, points, point_rows, o.direct_light);
    const Eigen::Index G = static_cast<Eigen::Index>(goals.size());
    for (std::size_t q = 0; q < points.size(); ++q) {
      const Eigen::Index r = G + static_cast<Eigen::Index>(q);
      EXPECT_NEAR(D[r], at.direct_lux[static_cast<Eigen::Index>(q)], 1e-9 * at.direct_lux[static_cast<Eigen::Index>(q)] + 1e-12);
      EXPECT_NEAR(H[r], at.total_lux[static_cast<Eigen::Index>(q)], 1e-7 * at.total_lux[static_cast<Eigen::Index>(q)])
          << "point " << q << " with " << to_string(method);
      EXPECT_GT(H[r], D[r]);
    }
    // The patch rows are as they were without points.
    const GoalRows plain_rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
    const SampleOperator plain = build_sample_operator(scene, caster, plain_rows, o);
    EXPECT_EQ((plain.total_lux_per_lm - op.total_lux_per_lm.topRows(G)).cwiseAbs().maxCoeff(), 0.0);
  }
}

// The gather's error estimate (PointIlluminance::indirect_standard_error_lux, behind the
// verification's margin) against the spread it predicts: the same exact radiosity
// gathered at the same points with 12 independent ray seeds. The rays are a stratified
// low-discrepancy set, so the spread is at most the estimate (an upper estimate), and
// the estimate is not so loose that it would inflate margins (measured: 0.41 of it on
// this office at 128 rays; the bounds leave room for the 12 seeds' own noise).
TEST(PointIlluminance, TheGatherErrorEstimateBoundsTheSpreadOverSeeds) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  job.scene.max_patch_edge_m = 0.6;
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  const RayCaster caster(scene);
  std::vector<ReceiverPoint> points;
  for (double x : {0.7, 1.9, 3.1, 4.3, 5.5})
    for (double y : {0.6, 2.0, 3.4}) points.push_back({V(x, y, 0.8), V::UnitZ()});
  ExactSolveOptions exact;
  const ExactSolution solution = solve_exact(scene, exact);
  FormFactorOptions rows = exact.form_factors;
  rows.rays_per_patch = 128;
  constexpr int kSeeds = 12;
  const Eigen::Index Q = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd total(Q, kSeeds);
  Eigen::VectorXd estimate = Eigen::VectorXd::Zero(Q);
  for (int s = 0; s < kSeeds; ++s) {
    rows.seed = 1000 + static_cast<std::uint64_t>(s);
    const PointIlluminance at = exact_point_illuminance(scene, caster, solution.radiosity, points, rows, exact.direct_light);
    ASSERT_EQ(at.indirect_standard_error_lux.size(), Q);
    total.col(s) = at.total_lux;
    estimate += at.indirect_standard_error_lux / kSeeds;
  }
  double spread2 = 0.0, estimate2 = 0.0;
  for (Eigen::Index q = 0; q < Q; ++q) {
    const double mean = total.row(q).mean();
    spread2 += (total.row(q).array() - mean).square().sum() / (kSeeds - 1) / static_cast<double>(Q);
    estimate2 += estimate[q] * estimate[q] / static_cast<double>(Q);
    EXPECT_GT(estimate[q], 0.0) << q;
    EXPECT_LT(estimate[q], 0.1 * total.row(q).mean()) << q;
  }
  const double ratio = std::sqrt(spread2 / estimate2);
  std::cout << "gather error: RMS spread over seeds / RMS estimate = " << ratio << "\n";
  EXPECT_LE(ratio, 1.3);
  EXPECT_GE(ratio, 0.1);
}

// Issue 11's accuracy target: on the office (configs/office_fixed.yaml, 0.25 m patches,
// four placed panels) the operator at its default k (5 %) agrees with the exact
// point-wise solve (every row at 1024 rays, each point's gather at 1024 rays, rays
// independent of the operator's) within 2 % RMS and 5 % at worst over a 0.8 m work plane.
// docs/accuracy.md quotes the figures this prints.
TEST(PointIlluminance, OfficeWorkPlaneAtDefaultKAgreesWithTheExactPointwiseSolve) {
  const JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office_fixed.yaml");
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  const RayCaster caster(scene);
  CalcGridSetting plane;
  plane.name = "work_plane";
  plane.over_surface = "floor";
  plane.height_m = 0.8;
  plane.spacing_m = 0.25;
  const CalcGrid grid = make_calc_grid(scene, caster, plane);
  SampleOperatorOptions o = operator_options(job, {});
  o.sample_size = job.sample.size_for(reflecting_patches(scene).size());
  const GoalRows rows = compute_goal_rows(scene, caster, {}, grid.points, scene_light_sources(scene), o);
  const SampleOperator op = build_sample_operator(scene, caster, rows, o);
  const Eigen::VectorXd H = op.illuminance_lux(source_flux_lm(scene, op.sources));
  ExactSolveOptions exact = exact_options(job, {});
  exact.form_factors.rays_per_patch = 1024;
  exact.form_factors.seed = exact.direct_light.seed = 77;
  const ExactSolution solution = solve_exact(scene, exact);
  const PointIlluminance at =
      exact_point_illuminance(scene, caster, solution.radiosity, grid.points, exact.form_factors, exact.direct_light);
  double sum = 0.0, worst = 0.0;
  for (Eigen::Index q = 0; q < H.size(); ++q) {
    const double e = (H[q] - at.total_lux[q]) / at.total_lux[q];
    sum += e * e;
    worst = std::max(worst, std::abs(e));
  }
  const double rms = std::sqrt(sum / static_cast<double>(H.size()));
  std::cout << "office work plane: " << H.size() << " points, k = " << op.stats.sample_patches << ", operator "
            << op.stats.build_seconds() << " s; RMS relative error " << 100 * rms << " %, max " << 100 * worst
            << " %; mean exact " << at.total_lux.mean() << " lx (direct " << at.direct_lux.mean() << " lx)\n";
  EXPECT_LT(rms, 0.02);
  EXPECT_LT(worst, 0.05);
}

}  // namespace
}  // namespace ilp
