// ilp inspect's diagnosis: geometry, topology, winding and openings, on rooms whose
// defects are known by construction.
#include "core/study/scene_inspect.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
using test::Contains;

// A 4 x 3 x 2.5 m room as 6 surfaces (floor, ceiling, 4 walls) sharing corners,
// wound inwards; `flip_wall` winds wall_x1 outwards; `no_ceiling` leaves it out.
TriangleMesh room(bool flip_wall, bool no_ceiling) {
  TriangleMesh mesh;
  mesh.path = "<room>";
  const V lo(0, 0, 0), hi(4, 3, 2.5);
  for (int k = 0; k < 8; ++k)
    mesh.positions.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  struct Face {
    const char* name;
    std::array<int, 4> q;  // counter-clockwise seen from outside
  };
  const Face faces[] = {{"floor", {0, 2, 3, 1}}, {"ceiling", {4, 5, 7, 6}}, {"wall_y0", {0, 1, 5, 4}},
                        {"wall_x1", {1, 3, 7, 5}}, {"wall_y1", {3, 2, 6, 7}}, {"wall_x0", {2, 0, 4, 6}}};
  for (const Face& f : faces) {
    if (no_ceiling && std::string(f.name) == "ceiling") continue;
    const int s = static_cast<int>(mesh.surface_names.size());
    mesh.surface_names.push_back(f.name);
    const bool outwards = flip_wall && std::string(f.name) == "wall_x1";
    for (const Eigen::Vector3i& t : {Eigen::Vector3i(f.q[0], f.q[1], f.q[2]), Eigen::Vector3i(f.q[0], f.q[2], f.q[3])}) {
      mesh.triangles.push_back(outwards ? t : Eigen::Vector3i(t[0], t[2], t[1]));
      mesh.triangle_surface.push_back(s);
      mesh.triangle_material.push_back(-1);
    }
  }
  mesh.faces_read = mesh.triangles.size();
  return mesh;
}

struct Inspected {
  Scene scene;
  SceneInspection in;
};

Inspected inspect(const TriangleMesh& mesh) {
  SceneOptions options;
  options.max_patch_edge_m = 0.5;
  Inspected out;
  out.scene = make_scene(mesh, TriangleReflectance(mesh.triangles.size(), V::Constant(0.5)), options);
  const RayCaster caster(out.scene, 1);
  out.in = inspect_scene(out.scene, mesh, options, caster);
  return out;
}

const SurfaceInspection& surface(const SceneInspection& in, const std::string& name) {
  const auto it = std::find_if(in.surfaces.begin(), in.surfaces.end(), [&](const auto& s) { return s.name == name; });
  EXPECT_NE(it, in.surfaces.end()) << name;
  return *it;
}

bool warned(const SceneInspection& in, const std::string& part) {
  return std::any_of(in.warnings.begin(), in.warnings.end(), [&](const std::string& w) { return Contains(w, part); });
}

TEST(SceneInspect, AClosedRoomHasNoDefectsAndSuggestsCeilingAndFloor) {
  const Inspected r = inspect(room(false, false));
  const SceneInspection& in = r.in;
  EXPECT_EQ(in.open_edges, 0u);
  EXPECT_EQ(in.flipped_edges, 0u);
  EXPECT_EQ(in.nonmanifold_edges, 0u);
  EXPECT_LT(in.escape_share, 0.01);  // (a ray may slip through an edge in float)
  EXPECT_LT(in.back_hit_share, 0.01);
  EXPECT_NEAR(in.area_m2, 2 * 12.0 + 2 * (4 + 3) * 2.5, 1e-9);
  const SurfaceInspection& floor = surface(in, "floor");
  EXPECT_EQ(floor.triangles, 2u);
  EXPECT_EQ(floor.patches, r.scene.patches_of({"floor"}).size());
  EXPECT_DOUBLE_EQ(floor.up_share, 1.0);
  EXPECT_NEAR(surface(in, "wall_x1").vertical_share, 1.0, 1e-12);
  EXPECT_NEAR(surface(in, "wall_x1").bounds_m.max().z(), 2.5, 1e-12);
  ASSERT_GE(in.mounting, 0);
  ASSERT_GE(in.floor, 0);
  EXPECT_EQ(in.surfaces[static_cast<std::size_t>(in.mounting)].name, "ceiling");
  EXPECT_EQ(in.surfaces[static_cast<std::size_t>(in.floor)].name, "floor");
  EXPECT_TRUE(in.warnings.empty()) << in.warnings.front();
}

TEST(SceneInspect, AWallWoundOutwardsIsNamed) {
  const SceneInspection in = inspect(room(true, false)).in;
  // Its 4 edges with the neighbouring surfaces run the same way as theirs (its diagonal agrees with itself).
  EXPECT_EQ(in.flipped_edges, 4u);
  const SurfaceInspection& wall = surface(in, "wall_x1");
  EXPECT_EQ(wall.flipped_edges, 4u);
  EXPECT_DOUBLE_EQ(wall.escape_share, 1.0);        // its front looks out of the closed room
  EXPECT_GT(wall.back_struck_share, 0.99);         // the room sees its back
  EXPECT_TRUE(warned(in, "'wall_x1': 100 % of the probe rays from its front leave the model"));
  EXPECT_TRUE(warned(in, "'wall_x1': 100 % of the probe rays reaching it strike its back"));
  EXPECT_TRUE(warned(in, "4 edges where neighbouring triangles are wound inconsistently, most in 'wall_x1' (4)"));
}

TEST(SceneInspect, ATwoSidedSurfaceGetsNoWindingWarnings) {
  const TriangleMesh mesh = room(true, false);
  SceneOptions options;
  const Scene scene = make_scene(mesh, TriangleReflectance(mesh.triangles.size(), V::Constant(0.5)), options);
  const RayCaster caster(scene, 1);
  InspectOptions inspect_options;
  inspect_options.two_sided.assign(scene.surfaces.size(), false);
  inspect_options.two_sided[static_cast<std::size_t>(scene.find_surface("wall_x1"))] = true;
  const SceneInspection in = inspect_scene(scene, mesh, options, caster, inspect_options);
  EXPECT_TRUE(surface(in, "wall_x1").two_sided);
  EXPECT_FALSE(warned(in, "'wall_x1': 100 %"));
  EXPECT_TRUE(warned(in, "wound inconsistently"));  // the edges still say so
}

TEST(SceneInspect, AnOpenRoomCountsItsRimAndTheLightLeaving) {
  const SceneInspection in = inspect(room(false, true)).in;
  EXPECT_EQ(in.open_edges, 4u);  // the top rim of the four walls
  EXPECT_GT(in.escape_share, 0.1);
  EXPECT_EQ(in.mounting, -1);
  EXPECT_TRUE(warned(in, "4 open edges"));
  EXPECT_TRUE(warned(in, "nothing to suggest as a mounting surface"));
}

TEST(SceneInspect, OneSurfaceForEverythingIsWarnedAndDegenerateTrianglesCounted) {
  TriangleMesh mesh = room(false, false);
  for (int& s : mesh.triangle_surface) s = 0;
  mesh.surface_names = {"everything"};
  mesh.positions.emplace_back(1, 1, 0.0);
  mesh.positions.emplace_back(2, 1, 0.0);
  mesh.positions.emplace_back(3, 1, 0.0);  // collinear: a degenerate triangle
  const int n = static_cast<int>(mesh.positions.size());
  mesh.triangles.emplace_back(n - 3, n - 2, n - 1);
  mesh.triangle_surface.push_back(0);
  mesh.triangle_material.push_back(-1);
  const SceneInspection in = inspect(mesh).in;
  ASSERT_EQ(in.surfaces.size(), 1u);
  EXPECT_EQ(in.surfaces[0].triangles, 13u);
  EXPECT_EQ(in.surfaces[0].degenerate, 1u);
  EXPECT_TRUE(warned(in, "one surface ('everything') for the whole model"));
  EXPECT_TRUE(warned(in, "1 degenerate triangles"));
}

}  // namespace
}  // namespace ilp
