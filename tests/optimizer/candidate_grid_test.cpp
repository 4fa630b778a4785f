// The candidate grid on a mounting surface and the blend that makes positions
// continuous, checked against geometry worked out by hand.
#include "optimizer/candidate_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/scene/scene.h"

namespace ilp {
namespace {

// A ceiling at z = 3 facing down, made of axis-aligned rectangles [x0, x1] x [y0, y1],
// plus a floor rectangle facing up under the first one.
Scene ceiling_scene(const std::vector<Eigen::Vector4d>& rectangles) {
  TriangleMesh mesh;
  mesh.surface_names = {"ceiling", "floor"};
  auto add = [&](const Eigen::Vector4d& r, double z, int surface, bool down) {
    const int base = static_cast<int>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {Eigen::Vector3d(r[0], r[2], z), Eigen::Vector3d(r[1], r[2], z),
                                                 Eigen::Vector3d(r[1], r[3], z), Eigen::Vector3d(r[0], r[3], z)});
    for (Eigen::Vector3i t : {Eigen::Vector3i(base, base + 1, base + 2), Eigen::Vector3i(base, base + 2, base + 3)}) {
      if (down) std::swap(t[1], t[2]);
      mesh.triangles.push_back(t);
      mesh.triangle_surface.push_back(surface);
      mesh.triangle_material.push_back(-1);
    }
  };
  for (const Eigen::Vector4d& r : rectangles) add(r, 3.0, 0, true);
  add(rectangles.front(), 0.0, 1, false);
  return make_scene(mesh, TriangleReflectance(mesh.triangles.size(), Eigen::Vector3d::Constant(0.5)),
                    {.max_patch_edge_m = 0.5});
}

TEST(CandidateGrid, CoversARectangleEvenly) {
  const Scene scene = ceiling_scene({Eigen::Vector4d(0, 6, 0, 4)});
  const CandidateGrid grid(scene, scene.find_surface("ceiling"), {.spacing_m = 0.5, .half_footprint_m = Eigen::Vector2d::Constant(0.3),
                                                                   .mount_offset_m = 0.05});
  // Centres in [0.3, 5.7] x [0.3, 3.7]: 5.4 / 0.5 -> 11 cells, 3.4 / 0.5 -> 7 cells.
  EXPECT_EQ(grid.nodes_x(), 12);
  EXPECT_EQ(grid.nodes_y(), 8);
  EXPECT_EQ(grid.size(), 96u);
  EXPECT_NEAR(grid.spacing_m().x(), 5.4 / 11, 1e-12);
  EXPECT_NEAR(grid.spacing_m().y(), 3.4 / 7, 1e-12);
  EXPECT_NEAR(grid.lower_m().x(), 0.3, 1e-12);
  EXPECT_NEAR(grid.upper_m().y(), 3.7, 1e-12);
  for (const Eigen::Vector3d& p : grid.positions_m()) EXPECT_NEAR(p.z(), 2.95, 1e-12);
  EXPECT_NEAR(grid.mounting_area_m2(), 24.0, 1e-9);
  EXPECT_EQ(grid.ignored_patches(), 0u);
}

// A shell surface (the classroom's Mesh042) faces down at its ceiling and under its floor
// slab: luminaires hang from the ceiling wherever the slab's patches come first (the
// first patch over a point was taken), and where the ceiling has a hole and only the
// slab is over a point there is no position (it threw "would hang under the floor"
// for the whole job). With no ceiling at all that is still the error.
Scene shell_scene(bool ceiling) {
  TriangleMesh mesh;
  mesh.surface_names = {"shell", "ground"};
  auto add = [&](double x1, double z, int surface, bool down) {  // [0, x1] x [0, 4] at z
    const int base = static_cast<int>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {Eigen::Vector3d(0, 0, z), Eigen::Vector3d(x1, 0, z),
                                                 Eigen::Vector3d(x1, 4, z), Eigen::Vector3d(0, 4, z)});
    for (Eigen::Vector3i t : {Eigen::Vector3i(base, base + 1, base + 2), Eigen::Vector3i(base, base + 2, base + 3)}) {
      if (down) std::swap(t[1], t[2]);
      mesh.triangles.push_back(t);
      mesh.triangle_surface.push_back(surface);
      mesh.triangle_material.push_back(-1);
    }
  };
  add(6.0, 0.0, 0, true);             // under the slab, first in the mesh
  if (ceiling) add(3.0, 3.0, 0, true);  // a ceiling over half the room: a hole over x > 3
  add(6.0, -0.02, 1, false);          // the ground, the scene's lowest point
  return make_scene(mesh, TriangleReflectance(mesh.triangles.size(), Eigen::Vector3d::Constant(0.5)),
                    {.max_patch_edge_m = 0.5});
}

TEST(CandidateGrid, AShellSurfaceMountsAtItsCeilingNotUnderItsSlab) {
  const CandidateGridOptions linear{.spacing_m = 0.5, .half_footprint_m = Eigen::Vector2d(0.63, 0.03), .mount_offset_m = 0.05};
  const Scene scene = shell_scene(true);
  const CandidateGrid grid(scene, 0, linear);
  ASSERT_GT(grid.size(), 0u);
  for (const Eigen::Vector3d& p : grid.positions_m()) {
    EXPECT_NEAR(p.z(), 2.95, 1e-12);
    EXPECT_LE(p.x() + 0.63, 3.0 + 1e-9) << "only under the ceiling";
  }
  EXPECT_THROW(CandidateGrid(shell_scene(false), 0, linear), std::out_of_range) << "no ceiling: under the floor";
}

TEST(CandidateGrid, BlendReproducesNodesAndLinearFunctions) {
  const Scene scene = ceiling_scene({Eigen::Vector4d(0, 6, 0, 4)});
  const CandidateGrid grid(scene, 0, {.spacing_m = 0.5, .half_footprint_m = Eigen::Vector2d::Constant(0.3), .mount_offset_m = 0.05});
  // At a node: that candidate alone.
  const Eigen::Vector3d node = grid.positions_m()[13];
  const GridPoint at_node = grid.locate(node.head<2>());
  double weight_on_node = 0.0, other = 0.0;
  for (int k = 0; k < GridPoint::kMaxCandidates; ++k) {
    if (at_node.candidates[k] == 13) weight_on_node += at_node.weights[k];
    else if (at_node.candidates[k] >= 0) other += std::abs(at_node.weights[k]);
  }
  EXPECT_NEAR(weight_on_node, 1.0, 1e-12);
  EXPECT_NEAR(other, 0.0, 1e-12);
  // Between nodes, also next to the edges: weights sum to 1 and reproduce x and y
  // (Catmull-Rom is exact for linear functions away from clamped edges).
  for (const Eigen::Vector2d& xy : {Eigen::Vector2d(2.13, 1.91), Eigen::Vector2d(0.41, 3.6), Eigen::Vector2d(5.69, 0.31)}) {
    const GridPoint g = grid.locate(xy);
    double sum = 0.0;
    Eigen::Vector2d blended = Eigen::Vector2d::Zero();
    int used = 0;
    for (int k = 0; k < GridPoint::kMaxCandidates; ++k) {
      if (g.candidates[k] < 0) continue;
      ++used;
      sum += g.weights[k];
      blended += g.weights[k] * grid.positions_m()[static_cast<std::size_t>(g.candidates[k])].head<2>();
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_GT(used, 4) << "a bicubic blend, not bilinear";
    EXPECT_NEAR(g.position_m.x(), xy.x(), 1e-12);
    if (xy.x() > 1.0 && xy.x() < 5.0) {
      EXPECT_NEAR(blended.x(), xy.x(), 1e-9);
    }
  }
  // Outside the extent: clamped onto it.
  const GridPoint outside = grid.locate(Eigen::Vector2d(-3.0, 9.0));
  EXPECT_NEAR(outside.position_m.x(), 0.3, 1e-12);
  EXPECT_NEAR(outside.position_m.y(), 3.7, 1e-12);
}

TEST(CandidateGrid, LShapedCeilingHasNoCandidatesOverTheGap) {
  // L: [0, 4] x [0, 2] and [0, 2] x [2, 4]; the square [2, 4] x [2, 4] is open.
  const Scene scene = ceiling_scene({Eigen::Vector4d(0, 4, 0, 2), Eigen::Vector4d(0, 2, 2, 4)});
  const CandidateGrid grid(scene, 0, {.spacing_m = 0.4, .half_footprint_m = Eigen::Vector2d::Constant(0.2), .mount_offset_m = 0.05});
  for (const Eigen::Vector3d& p : grid.positions_m()) {
    const bool in_gap = p.x() + 0.2 > 2.0 + 1e-9 && p.y() + 0.2 > 2.0 + 1e-9;
    EXPECT_FALSE(in_gap) << "candidate at " << p.transpose() << " would overhang the open corner";
  }
  EXPECT_LT(grid.size(), static_cast<std::size_t>(grid.nodes_x() * grid.nodes_y()));
  // A position over the gap snaps to the nearest candidate.
  const GridPoint g = grid.locate(Eigen::Vector2d(3.5, 3.5));
  EXPECT_EQ(g.weights[0], 1.0);
  const Eigen::Vector3d snapped = grid.positions_m()[static_cast<std::size_t>(g.candidates[0])];
  EXPECT_EQ(g.position_m, snapped);
  EXPECT_TRUE(snapped.x() <= 1.8 + 1e-9 || snapped.y() <= 1.8 + 1e-9);
}

TEST(CandidateGrid, RejectsSurfacesThatCannotHoldALuminaire) {
  const Scene scene = ceiling_scene({Eigen::Vector4d(0, 6, 0, 4)});
  try {
    CandidateGrid(scene, scene.find_surface("floor"), {});
    ADD_FAILURE() << "a floor (facing up) was accepted as a mounting surface";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'floor' has no patch facing down"), std::string::npos) << e.what();
  }
  EXPECT_THROW(CandidateGrid(scene, 0, {.spacing_m = 0.5, .half_footprint_m = Eigen::Vector2d::Constant(3.5), .mount_offset_m = 0.05}),
               std::invalid_argument);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

TEST(CandidateGrid, AWallDistanceAndACeilingModuleShapeWhereCandidatesGo) {
  // A 6 x 4 m ceiling; a 1.2 x 0.1 m linear luminaire turned 90 degrees (0.05 x 0.6 half extents).
  const Scene scene = ceiling_scene({Eigen::Vector4d(0, 6, 0, 4)});
  LuminaireType linear = LuminaireType::square_lambertian(1.2);
  linear.width_m = 0.1;
  const Eigen::Vector2d half = linear.half_footprint_m(90.0);
  EXPECT_NEAR(half.x(), 0.05, 1e-12);
  EXPECT_NEAR(half.y(), 0.6, 1e-12);
  const CandidateGrid walls(scene, 0, {.spacing_m = 0.5, .half_footprint_m = half, .wall_distance_m = 0.4,
                                       .mount_offset_m = 0.05});
  for (const Eigen::Vector3d& p : walls.positions_m()) {
    EXPECT_GE(p.x() - half.x(), 0.4 - 1e-9);
    EXPECT_LE(p.x() + half.x(), 6.0 - 0.4 + 1e-9);
    EXPECT_GE(p.y() - half.y(), 0.4 - 1e-9);
    EXPECT_LE(p.y() + half.y(), 4.0 - 0.4 + 1e-9);
  }
  EXPECT_NEAR(walls.lower_m().y(), 1.0, 1e-12);  // 0.4 m from the wall + 0.6 m half length
  // A 0.6 m module: every candidate at a cell centre (0.3 + 0.6 k), none off it.
  const CandidateGrid module(scene, 0, {.spacing_m = 0.5, .half_footprint_m = Eigen::Vector2d::Constant(0.3),
                                        .module_m = 0.6, .mount_offset_m = 0.05});
  ASSERT_EQ(module.size(), 10u * 6u);
  for (const Eigen::Vector3d& p : module.positions_m())
    for (int axis = 0; axis < 2; ++axis) {
      const double k = (p[axis] - 0.3) / 0.6;
      EXPECT_NEAR(k, std::round(k), 1e-9) << p.transpose();
    }
  EXPECT_NEAR(module.nearest_candidate_m(Eigen::Vector2d(1.1, 2.05)).x(), 0.9, 1e-12);
  EXPECT_NEAR(module.nearest_candidate_m(Eigen::Vector2d(1.1, 2.05)).y(), 2.1, 1e-12);
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

TEST(CandidateGrid, AZoneKeepsCentresInsideIt) {
  const Scene scene = ceiling_scene({Eigen::Vector4d(0, 6, 0, 4)});
  const CandidateGrid grid(scene, 0,
                           {.spacing_m = 0.5, .half_footprint_m = Eigen::Vector2d::Constant(0.3), .mount_offset_m = 0.05,
                            .zone_m = Eigen::AlignedBox2d(Eigen::Vector2d(1.0, -2.0), Eigen::Vector2d(3.0, 2.5))});
  // x: the zone [1, 3]; y: the surface's [0.3, ...] up to the zone's 2.5.
  EXPECT_NEAR(grid.lower_m().x(), 1.0, 1e-12);
  EXPECT_NEAR(grid.upper_m().x(), 3.0, 1e-12);
  EXPECT_NEAR(grid.lower_m().y(), 0.3, 1e-12);
  EXPECT_NEAR(grid.upper_m().y(), 2.5, 1e-12);
  for (const Eigen::Vector3d& p : grid.positions_m()) {
    EXPECT_GE(p.x(), 1.0 - 1e-12);
    EXPECT_LE(p.x(), 3.0 + 1e-12);
  }
  EXPECT_LT((grid.surface_box_m().min() - Eigen::Vector2d(0, 0)).norm(), 1e-9);
  EXPECT_LT((grid.surface_box_m().max() - Eigen::Vector2d(6, 4)).norm(), 1e-9);
  EXPECT_THROW(CandidateGrid(scene, 0, {.spacing_m = 0.5, .half_footprint_m = Eigen::Vector2d::Constant(0.3),
                                        .mount_offset_m = 0.05,
                                        .zone_m = Eigen::AlignedBox2d(Eigen::Vector2d(7, 1), Eigen::Vector2d(9, 2))}),
               std::invalid_argument)
      << "a zone beside the surface holds no position";
}

TEST(CandidateGrid, MountDistanceIsZeroWhereALuminaireFitsAndTheGapElsewhere) {
  // L: [0, 4] x [0, 2] and [0, 2] x [2, 4], a 0.4 m luminaire: centres in x, y >= 0.2
  // and, over the upper arm, x <= 1.8.
  const Scene scene = ceiling_scene({Eigen::Vector4d(0, 4, 0, 2), Eigen::Vector4d(0, 2, 2, 4)});
  const CandidateGrid grid(scene, 0, {.spacing_m = 0.4, .half_footprint_m = Eigen::Vector2d::Constant(0.2), .mount_offset_m = 0.05});
  EXPECT_EQ(grid.mount_distance_m(Eigen::Vector2d(1.0, 1.0)), 0.0);
  EXPECT_EQ(grid.mount_distance_m(Eigen::Vector2d(1.0, 3.0)), 0.0);
  // 0.15 m beyond the surface's lower edge (centres from y = 0.2): 0.15 + 0.2 away.
  EXPECT_NEAR(grid.mount_distance_m(Eigen::Vector2d(1.0, -0.15)), 0.35, 1e-9);
  // Over the open corner: at least to the arm's last centres (x 1.8 or y 1.8).
  // Over the open corner: the nearest centre is (3.4, 1.8) or (1.8, 3.4) (nodes every 0.4 m from 0.2).
  EXPECT_NEAR(grid.mount_distance_m(Eigen::Vector2d(3.5, 3.5)), std::hypot(0.1, 1.7), 1e-9);
  EXPECT_EQ(grid.mount_distance_m(Eigen::Vector2d(std::nan(""), 1.0)), std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace ilp
