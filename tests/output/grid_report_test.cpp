// From a calculation grid to what the grid writers take: the room outline traced from
// a floor's triangles (T-junctions leave no inner lines), a vertical grid's plane
// coordinates, luminaires at their real size, the lattice of values and file stems.
#include "output/grid_report.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using ilp::CalcGrid;
using ilp::GridKind;
using ilp::GridLight;
using V2 = Eigen::Vector2d;

double ring_area(const std::vector<V2>& ring) {
  double a = 0.0;
  for (std::size_t k = 0; k < ring.size(); ++k) {
    const V2& p = ring[k];
    const V2& q = ring[(k + 1) % ring.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * std::abs(a);
}

// An L-shaped floor (4 x 4 m less its 2 x 2 m upper right quarter) as triangles, the
// lower left square cut finer than its neighbours (T-junctions along their edges).
CalcGrid l_shaped_floor() {
  CalcGrid g;
  g.name = "floor plane";
  auto square = [&](V2 lo, double side, int cuts) {
    const double s = side / cuts;
    for (int j = 0; j < cuts; ++j)
      for (int i = 0; i < cuts; ++i) {
        const V2 a = lo + V2(i * s, j * s), b = a + V2(s, 0), c = a + V2(s, s), d = a + V2(0, s);
        g.outline_triangles_m.push_back({a, b, c});
        g.outline_triangles_m.push_back({a, c, d});
      }
  };
  square(V2(0, 0), 2.0, 4);
  square(V2(2, 0), 2.0, 1);
  square(V2(0, 2), 2.0, 1);
  return g;
}

TEST(GridRoomOutline, TracesTheBoundaryOfAFloorsTrianglesAsOneRing) {
  const auto rings = ilp::grid_room_outline_m(l_shaped_floor());
  ASSERT_EQ(rings.size(), 1u) << "one closed ring, no lines along the T-junctions inside";
  EXPECT_NEAR(ring_area(rings[0]), 12.0, 12.0 * 0.01);
  EXPECT_LE(rings[0].size(), 24u) << "simplified: an L has 6 corners (plus a few cut at the raster's corners)";
  for (const V2& p : rings[0]) {
    EXPECT_GE(p.minCoeff(), -0.02);
    EXPECT_LE(p.maxCoeff(), 4.02);
    EXPECT_FALSE(p.x() > 2.02 && p.y() > 2.02) << "no point in the missing quarter: " << p.transpose();
  }
}

TEST(GridRoomOutline, APolygonGridIsDrawnOverItsPolygon) {
  CalcGrid g;
  g.outline_polygon_m = {V2(0, 0), V2(3, 0), V2(3, 1), V2(0, 1)};
  const auto rings = ilp::grid_room_outline_m(g);
  ASSERT_EQ(rings.size(), 1u);
  EXPECT_EQ(rings[0], g.outline_polygon_m);
}

// A vertical grid on the segment (1, 0) -> (1, 4) from z 0.5 to 2.5, band 0.25 m, 0.5 m cells.
CalcGrid wall_grid() {
  CalcGrid g;
  g.name = "wall";
  g.kind = GridKind::vertical;
  g.u_axis = Eigen::Vector3d::UnitY();
  g.v_axis = Eigen::Vector3d::UnitZ();
  g.border_m = 0.25;
  g.origin_m = Eigen::Vector3d(1.0, 0.0, 0.5) + 0.25 * (g.u_axis + g.v_axis);
  g.cells_u = 7;
  g.cells_v = 3;
  g.cell_u_m = g.cell_v_m = 0.5;
  for (int j = 0; j < g.cells_v; ++j)
    for (int i = 0; i < g.cells_u; ++i) {
      if (i == 3 && j == 1) continue;  // dropped inside a solid
      g.points.push_back({g.origin_m + (i + 0.5) * 0.5 * g.u_axis + (j + 0.5) * 0.5 * g.v_axis, -Eigen::Vector3d::UnitX()});
      g.cell_of_point.emplace_back(i, j);
    }
  return g;
}

TEST(GridPlan, AVerticalGridIsDrawnAlongItsSegmentAndInHeight) {
  const CalcGrid g = wall_grid();
  EXPECT_TRUE(ilp::grid_plan_position_m(g, Eigen::Vector3d(1.0, 3.0, 1.2)).isApprox(V2(3.0, 1.2)));
  const auto rings = ilp::grid_room_outline_m(g);
  ASSERT_EQ(rings.size(), 1u);
  EXPECT_NEAR(ring_area(rings[0]), 4.0 * 2.0, 1e-9) << "the plane: 4 m along, 0.5 .. 2.5 m high";

  GridLight light;
  light.total_initial_lux = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(g.points.size()), 100.0, 300.0);
  light.direct_initial_lux = 0.5 * light.total_initial_lux;
  light.maintenance_factor = 0.8;
  const ilp::IsoluxGridView view = ilp::isolux_grid_view(g, light, {});
  EXPECT_EQ(view.nx, 7);
  EXPECT_EQ(view.ny, 3);
  EXPECT_TRUE(view.origin_m.isApprox(V2(0.5, 1.0))) << view.origin_m.transpose();
  EXPECT_TRUE(std::isnan(view.maintained_lux[1 * 7 + 3])) << "no point: no value";
  EXPECT_DOUBLE_EQ(view.maintained_lux[0], 0.8 * 100.0);
  EXPECT_TRUE(std::isnan(view.target_lux)) << "no goal: the plan scales on the grid's own average";
  EXPECT_EQ(view.y_label, "height z (m)");

  const ilp::GridCsvGrid csv = ilp::grid_csv_grid(g, light);
  ASSERT_EQ(csv.points.size(), g.points.size());
  EXPECT_DOUBLE_EQ(csv.points[2].total_initial_lux, light.total_initial_lux[2]);
  EXPECT_DOUBLE_EQ(csv.maintenance_factor, 0.8);

  GridLight short_light = light;
  short_light.total_initial_lux.conservativeResize(3);
  EXPECT_THROW(ilp::isolux_grid_view(g, short_light, {}), std::invalid_argument);
}

TEST(GridPlan, LuminairesKeepTheirRealSizeAndRotation) {
  CalcGrid g;
  ilp::LuminaireType linear = ilp::LuminaireType::square_lambertian(0.6);
  linear.length_m = 1.2;
  linear.width_m = 0.1;
  ilp::LuminaireType disc = linear;
  disc.shape = ilp::OutlineShape::disc;
  disc.length_m = disc.width_m = 0.3;
  const auto drawn = ilp::isolux_luminaires(
      g, {{"L1", "linear", linear, {Eigen::Vector3d(1, 2, 2.9), 30.0}}, {"L2", "", disc, {Eigen::Vector3d(3, 1, 2.9), 0.0}}});
  ASSERT_EQ(drawn.size(), 2u);
  EXPECT_TRUE(drawn[0].centre_m.isApprox(V2(1, 2)));
  EXPECT_DOUBLE_EQ(drawn[0].length_m, 1.2);
  EXPECT_DOUBLE_EQ(drawn[0].width_m, 0.1);
  EXPECT_DOUBLE_EQ(drawn[0].rotation_deg, 30.0);
  EXPECT_FALSE(drawn[0].round);
  EXPECT_TRUE(drawn[1].round);
  // On a vertical plane: the projection's extent along the plane, at its height, at least 2 cm thick.
  const auto on_wall = ilp::isolux_luminaires(wall_grid(), {{"L1", "", linear, {Eigen::Vector3d(2, 2, 2.4), 0.0}}});
  ASSERT_EQ(on_wall.size(), 1u);
  EXPECT_TRUE(on_wall[0].centre_m.isApprox(V2(2.0, 2.4)));
  EXPECT_NEAR(on_wall[0].length_m, 0.1, 1e-9) << "its width lies along the wall's direction (y)";
  EXPECT_DOUBLE_EQ(on_wall[0].width_m, 0.02);
}

TEST(GridPlan, ATiltedLuminaireIsDrawnAsItsOutlineProjectedOnThePlan) {
  // 1.2 x 0.1 m, turned 30 degrees and tilted 60 about its width axis: on the plan its
  // length shrinks to 1.2 cos 60 = 0.6 m, still along 30 degrees, centred where it hangs.
  CalcGrid g;
  ilp::LuminaireType linear = ilp::LuminaireType::square_lambertian(0.6);
  linear.length_m = 1.2;
  linear.width_m = 0.1;
  ilp::LuminairePlacement at{Eigen::Vector3d(1, 2, 2.9), 30.0, 60.0};
  const auto drawn = ilp::isolux_luminaires(g, {{"L1", "linear", linear, at}});
  ASSERT_EQ(drawn.size(), 1u);
  EXPECT_TRUE(drawn[0].centre_m.isApprox(V2(1, 2)));
  EXPECT_NEAR(drawn[0].length_m, 0.6, 1e-9);
  EXPECT_NEAR(drawn[0].width_m, 0.1, 1e-9);
  EXPECT_DOUBLE_EQ(drawn[0].rotation_deg, 30.0);
  EXPECT_FALSE(drawn[0].round);
}

TEST(GridFiles, StemsAreSafeFileNamesAndUnique) {
  EXPECT_EQ(ilp::isolux_file_stems({"work_plane", "board/left", "board left", "Tafel-1.a"}),
            (std::vector<std::string>{"isolux_work_plane", "isolux_board_left", "isolux_board_left_2", "isolux_Tafel-1.a"}));
}

}  // namespace
