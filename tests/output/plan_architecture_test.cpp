// The architecture a plan draws: section cuts against their closed forms (a box cut
// at a height is its rectangle, the material side from the faces' winding), outlines
// from above, the office mesh's walls, partition and desks, dimension chains and the
// label placer.
#include "output/plan_architecture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/scene/mesh.h"
#include "core/scene/reference_scenes.h"
#include "output/plan_dimensions.h"
#include "output/plan_labels.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
using V2 = Eigen::Vector2d;

// A quad a-b-c-d (counter-clockwise seen from the front) as two triangles.
void quad(std::vector<Triangle3>& out, const V& a, const V& b, const V& c, const V& d) {
  out.push_back({a, b, c});
  out.push_back({a, c, d});
}

// The four side faces (and top and bottom) of an axis-aligned box; outward: faces point
// out of the solid; else into the box (a room).
std::vector<Triangle3> box(const V& lo, const V& hi, bool outward) {
  std::vector<Triangle3> t;
  const double x0 = lo.x(), y0 = lo.y(), z0 = lo.z(), x1 = hi.x(), y1 = hi.y(), z1 = hi.z();
  quad(t, V(x0, y0, z0), V(x1, y0, z0), V(x1, y0, z1), V(x0, y0, z1));  // south, normal -y
  quad(t, V(x1, y1, z0), V(x0, y1, z0), V(x0, y1, z1), V(x1, y1, z1));  // north, +y
  quad(t, V(x0, y1, z0), V(x0, y0, z0), V(x0, y0, z1), V(x0, y1, z1));  // west, -x
  quad(t, V(x1, y0, z0), V(x1, y1, z0), V(x1, y1, z1), V(x1, y0, z1));  // east, +x
  quad(t, V(x0, y0, z1), V(x1, y0, z1), V(x1, y1, z1), V(x0, y1, z1));  // top, +z
  quad(t, V(x0, y0, z0), V(x0, y1, z0), V(x1, y1, z0), V(x1, y0, z0));  // bottom, -z
  if (!outward)
    for (Triangle3& tri : t) std::swap(tri[1], tri[2]);
  return t;
}

// Every corner of `expected` is a point of `points` (within tol) and there are no others.
void expect_corners(const std::vector<V2>& points, const std::vector<V2>& expected, double tol) {
  ASSERT_EQ(points.size(), expected.size());
  for (const V2& e : expected)
    EXPECT_TRUE(std::any_of(points.begin(), points.end(), [&](const V2& p) { return (p - e).norm() <= tol; }))
        << "no point at (" << e.x() << ", " << e.y() << ")";
}

TEST(SectionCut, ABoxCutAtAHeightIsItsRectangleWithTheMaterialInside) {
  const std::vector<SectionLine> lines = section_cut(box(V(1.0, 2.0, 0.0), V(3.0, 2.5, 2.0), true), 0.8, 1e-6);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(lines[0].closed);
  expect_corners(lines[0].points_m, {V2(1, 2), V2(3, 2), V2(3, 2.5), V2(1, 2.5)}, 1e-12);
  EXPECT_NEAR(lines[0].signed_area_m2, 2.0 * 0.5, 1e-12);  // > 0: solid inside
}

TEST(SectionCut, ARoomsInwardWallsHaveTheMaterialOutside) {
  const std::vector<SectionLine> lines = section_cut(box(V(0, 0, 0), V(6, 4, 3), false), 1.2, 1e-6);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(lines[0].closed);
  expect_corners(lines[0].points_m, {V2(0, 0), V2(6, 0), V2(6, 4), V2(0, 4)}, 1e-12);
  EXPECT_NEAR(lines[0].signed_area_m2, -24.0, 1e-12);
}

TEST(SectionCut, SubdividedFacesGiveTheSameRectangle) {
  // Patches of 0.1 m: hundreds of collinear pieces, joined and simplified to 4 corners.
  std::vector<reference::QuadSpec> quads;
  const V rho = V::Constant(0.5);
  const double x0 = 0.5, y0 = 0.25, x1 = 1.75, y1 = 0.55, z1 = 1.5;
  quads.push_back({"s", V(x0, y0, 0), V(x1, y0, 0), V(x1, y0, z1), V(x0, y0, z1), rho});
  quads.push_back({"n", V(x1, y1, 0), V(x0, y1, 0), V(x0, y1, z1), V(x1, y1, z1), rho});
  quads.push_back({"w", V(x0, y1, 0), V(x0, y0, 0), V(x0, y0, z1), V(x0, y1, z1), rho});
  quads.push_back({"e", V(x1, y0, 0), V(x1, y1, 0), V(x1, y1, z1), V(x1, y0, z1), rho});
  const Scene scene = reference::make_quad_scene(quads, 0.1);
  ASSERT_GT(scene.patches.size(), 400u);
  const PlanArchitecture a = plan_architecture(scene, {.floor_z_m = 0.0, .cut_height_m = 0.7});
  ASSERT_EQ(a.section.size(), 1u);
  EXPECT_TRUE(a.section[0].closed);
  expect_corners(a.section[0].points_m, {V2(x0, y0), V2(x1, y0), V2(x1, y1), V2(x0, y1)}, 1e-9);
  EXPECT_NEAR(a.section[0].signed_area_m2, (x1 - x0) * (y1 - y0), 1e-9);
  EXPECT_TRUE(a.furniture.empty());  // no face up below the cut
}

TEST(SectionCut, FacesInThePlaneGiveNothingAndEdgesInItAreCutOnce) {
  // A box whose top lies in the cut plane: the top gives nothing, the sides their top edges.
  const std::vector<SectionLine> top = section_cut(box(V(0, 0, 0), V(1, 1, 0.8), true), 0.8, 1e-6);
  ASSERT_EQ(top.size(), 1u);
  expect_corners(top[0].points_m, {V2(0, 0), V2(1, 0), V2(1, 1), V2(0, 1)}, 1e-12);
  // Wholly above or below: nothing.
  EXPECT_TRUE(section_cut(box(V(0, 0, 1), V(1, 1, 2), true), 0.8, 1e-6).empty());
  EXPECT_TRUE(section_cut(box(V(0, 0, 0), V(1, 1, 0.5), true), 0.8, 1e-6).empty());
  EXPECT_THROW(section_cut({}, 0.8, 0.0), std::invalid_argument);
}

TEST(SectionCut, AnOpenWallIsAnOpenLine) {
  std::vector<Triangle3> t;
  quad(t, V(0, 0, 0), V(2, 0, 0), V(2, 0, 3), V(0, 0, 3));
  const std::vector<SectionLine> lines = section_cut(t, 1.0, 1e-6);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_FALSE(lines[0].closed);
  EXPECT_EQ(lines[0].signed_area_m2, 0.0);
  expect_corners(lines[0].points_m, {V2(0, 0), V2(2, 0)}, 1e-12);
}

TEST(UnionOutline, TwoTrianglesOfARectangleGiveItsCornersWithinOneCell) {
  const std::vector<Triangle2> t = {{V2(1, 1), V2(2.6, 1), V2(2.6, 1.8)}, {V2(1, 1), V2(2.6, 1.8), V2(1, 1.8)}};
  const std::vector<Ring2> rings = union_outline(t, 200);
  ASSERT_EQ(rings.size(), 1u);
  // Marching squares cuts each corner across a cell: every point lies within a cell of
  // the rectangle's boundary and each corner within 1.5 cells of a point.
  const double cell = 1.6 / 200;
  EXPECT_LE(rings[0].size(), 8u);
  for (const V2& p : rings[0]) {
    const double to_edge = std::min({std::abs(p.x() - 1.0), std::abs(p.x() - 2.6), std::abs(p.y() - 1.0), std::abs(p.y() - 1.8)});
    EXPECT_LE(to_edge, cell) << p.transpose();
  }
  for (const V2& corner : {V2(1, 1), V2(2.6, 1), V2(2.6, 1.8), V2(1, 1.8)})
    EXPECT_TRUE(std::any_of(rings[0].begin(), rings[0].end(), [&](const V2& p) { return (p - corner).norm() <= 1.5 * cell; }))
        << corner.transpose();
  EXPECT_TRUE(union_outline({}, 200).empty());
}

// data/office.obj as the job loads it (metres, z up, 0.25 m patches).
Scene office_scene() {
  const TriangleMesh mesh = load_mesh(std::string(ILP_SOURCE_DIR) + "/data/office.obj");
  return make_scene(mesh, TriangleReflectance(mesh.triangles.size(), V::Constant(0.5)),
                    {.up_axis = UpAxis::z, .scale_to_m = 1.0, .max_patch_edge_m = 0.25});
}

TEST(PlanArchitecture, TheOfficeShowsItsWallsPartitionAndDesks) {
  const Scene scene = office_scene();
  const PlanArchitecture a = plan_architecture(scene, {.floor_z_m = 0.0, .cut_height_m = 0.8, .wall_cut_height_m = 2.8});
  // Cut at 0.8 m: the room's walls (material outside) and the partition (inside); the
  // desks' legs end at 0.71 m.
  ASSERT_EQ(a.section.size(), 2u);
  const auto walls = std::find_if(a.section.begin(), a.section.end(), [](const SectionLine& l) { return l.signed_area_m2 < 0; });
  const auto partition = std::find_if(a.section.begin(), a.section.end(), [](const SectionLine& l) { return l.signed_area_m2 > 0; });
  ASSERT_NE(walls, a.section.end());
  ASSERT_NE(partition, a.section.end());
  expect_corners(walls->points_m, {V2(0, 0), V2(6, 0), V2(6, 4), V2(0, 4)}, 1e-6);
  EXPECT_NEAR(walls->signed_area_m2, -24.0, 1e-6);
  expect_corners(partition->points_m, {V2(2.975, 0.5), V2(3.025, 0.5), V2(3.025, 2.7), V2(2.975, 2.7)}, 1e-6);
  EXPECT_NEAR(partition->signed_area_m2, 0.05 * 2.2, 1e-6);
  // Under the luminaires only the walls.
  ASSERT_EQ(a.walls.size(), 1u);
  EXPECT_NEAR(a.walls[0].signed_area_m2, -24.0, 1e-6);
  // The two desk tops (1.6 x 0.8 m at (1.7, 1.6) and (4.3, 1.6)) from above, within a raster cell.
  ASSERT_EQ(a.furniture.size(), 2u);
  std::vector<V2> centres;
  for (const Ring2& ring : a.furniture) {
    Eigen::AlignedBox2d b;
    for (const V2& p : ring) b.extend(p);
    EXPECT_NEAR(b.sizes().x(), 1.6, 0.01);
    EXPECT_NEAR(b.sizes().y(), 0.8, 0.01);
    centres.push_back(b.center());
  }
  std::sort(centres.begin(), centres.end(), [](const V2& p, const V2& q) { return p.x() < q.x(); });
  EXPECT_NEAR((centres[0] - V2(1.7, 1.6)).norm(), 0.0, 0.01);
  EXPECT_NEAR((centres[1] - V2(4.3, 1.6)).norm(), 0.0, 0.01);
  // A cut through the desk tops' thickness (0.71 - 0.75 m) draws them as sections instead.
  const PlanArchitecture low = plan_architecture(scene, {.floor_z_m = 0.0, .cut_height_m = 0.73});
  EXPECT_TRUE(low.furniture.empty());
  EXPECT_GE(low.section.size(), 4u);  // walls, partition, two desk tops
  EXPECT_THROW(plan_architecture(scene, {.cut_height_m = 0.0}), std::invalid_argument);
}

TEST(DimensionChain, ValuesAreTheFieldsSpacingsAndTheDistancesToTheWalls) {
  // A 3 x 2 field in the 6 x 4 m office: columns 2.00 m apart, rows 2.50 m, 1.00 / 0.75 m to the walls.
  std::vector<V2> centres;
  for (double y : {0.75, 3.25})
    for (double x : {1.0, 3.0, 5.0}) centres.emplace_back(x + 1e-4 * y, y);  // within the 1 cm tolerance
  const std::vector<SectionLine> walls = section_cut(box(V(0, 0, 0), V(6, 4, 3), false), 2.8, 1e-6);
  const DimensionChain x = dimension_chain(centres, 0, walls);
  ASSERT_EQ(x.stops_m.size(), 5u);
  EXPECT_TRUE(x.wall_first && x.wall_last);
  const std::vector<double> lx = x.lengths_m();
  const std::vector<double> expected_x = {1.0, 2.0, 2.0, 1.0};
  for (std::size_t k = 0; k < lx.size(); ++k) EXPECT_NEAR(lx[k], expected_x[k], 1e-3) << k;
  const DimensionChain y = dimension_chain(centres, 1, walls);
  const std::vector<double> ly = y.lengths_m();
  ASSERT_EQ(ly.size(), 3u);
  EXPECT_NEAR(ly[0], 0.75, 1e-12);
  EXPECT_NEAR(ly[1], 2.5, 1e-12);
  EXPECT_NEAR(ly[2], 0.75, 1e-12);
  // No walls: centres only.
  EXPECT_EQ(dimension_chain(centres, 0, {}).stops_m.size(), 3u);
  EXPECT_TRUE(dimension_chain({}, 0, walls).stops_m.empty());
}

TEST(DimensionChain, TheNearestWallOfTheOuterRowCounts) {
  // An L-shaped wall line: the outer column's lower member sees a wall 0.5 m away, its
  // upper one 2 m away; the chain takes the nearer.
  SectionLine wall;
  wall.points_m = {V2(0.5, 0), V2(0.5, 1), V2(-1, 1), V2(-1, 3)};
  const DimensionChain x = dimension_chain({V2(1, 0.5), V2(1, 2), V2(3, 0.5)}, 0, {wall});
  ASSERT_TRUE(x.wall_first);
  EXPECT_FALSE(x.wall_last);
  EXPECT_NEAR(x.lengths_m().front(), 0.5, 1e-12);
}

TEST(LabelPlacement, ADenseLayoutGetsEveryLabelWithNoTwoBoxesOverlapping) {
  // 10 x 10 outlines of 20 px, 40 px apart: labels of 30 x 15 px do not fit beside an
  // outline (20 px between them), only above or below, and no label may cover another
  // or any outline.
  std::vector<LabelRequest> requests;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) {
      const V2 c(100.0 + 40.0 * i, 100.0 + 40.0 * j);
      requests.push_back({Eigen::AlignedBox2d(c - V2(10, 10), c + V2(10, 10)), V2(30, 15)});
    }
  const Eigen::AlignedBox2d bounds(V2(0, 0), V2(500, 500));
  const std::vector<PlacedLabel> placed = place_labels(requests, {}, bounds);
  ASSERT_EQ(placed.size(), requests.size());
  for (std::size_t a = 0; a < placed.size(); ++a) {
    ASSERT_TRUE(placed[a].placed) << a;
    EXPECT_TRUE(bounds.contains(placed[a].box_px));
    EXPECT_NEAR(placed[a].box_px.sizes().x(), 30.0, 1e-9);
    for (std::size_t b = 0; b < placed.size(); ++b) {
      if (b != a) {
        EXPECT_FALSE(boxes_overlap(placed[a].box_px, placed[b].box_px)) << a << " and " << b;
      }
      EXPECT_FALSE(boxes_overlap(placed[a].box_px, requests[b].anchor_px)) << "label " << a << " on outline " << b;
    }
  }
  // Too little room: a label is left out rather than placed over another.
  const std::vector<PlacedLabel> cramped =
      place_labels(requests, {}, Eigen::AlignedBox2d(V2(85, 85), V2(475, 475)), {.rings = 1});
  std::size_t left_out = 0;
  for (std::size_t a = 0; a < cramped.size(); ++a) {
    left_out += cramped[a].placed ? 0 : 1;
    for (std::size_t b = a + 1; b < cramped.size(); ++b)
      if (cramped[a].placed && cramped[b].placed) {
        EXPECT_FALSE(boxes_overlap(cramped[a].box_px, cramped[b].box_px));
      }
  }
  EXPECT_GT(left_out, 0u);
}

}  // namespace
}  // namespace ilp
