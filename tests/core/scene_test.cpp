// Meshing: units and axes, degenerate faces, subdivision, luminaires.
#include "core/scene/scene.h"

#include <gtest/gtest.h>

#include <sstream>

#include <algorithm>

#include "job/config.h"
#include "job/plan.h"
#include "core/transport/form_factors.h"
#include "job/job_scene.h"
#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

TriangleMesh one_surface_mesh(std::vector<V> positions, std::vector<Eigen::Vector3i> triangles) {
  TriangleMesh mesh;
  mesh.path = "<test>";
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  mesh.surface_names = {"s"};
  mesh.triangle_surface.assign(mesh.triangles.size(), 0);
  mesh.triangle_material.assign(mesh.triangles.size(), -1);
  mesh.faces_read = mesh.triangles.size();
  return mesh;
}

TEST(Scene, SubdivisionBoundsEdgesAndKeepsAreaSurfaceAndOrientation) {
  const TriangleMesh mesh = one_surface_mesh({V(0, 0, 0), V(5, 0, 0), V(0, 3, 0), V(5, 3, 1)},
                                             {{0, 1, 2}, {1, 3, 2}});
  SceneOptions options;
  options.max_patch_edge_m = 0.3;
  const Scene scene = make_scene(mesh, {V::Constant(0.5), V::Constant(0.5)}, options);
  double area = 0.0;
  for (const Patch& p : scene.patches) {
    for (int k = 0; k < 3; ++k)
      ASSERT_LE((p.vertices_m[k] - p.vertices_m[(k + 1) % 3]).norm(), 0.3 + 1e-12);
    ASSERT_EQ(p.surface, 0);
    area += p.area_m2;
  }
  const double expected = 0.5 * 15.0 + 0.5 * (V(5, 3, 1) - V(5, 0, 0)).cross(V(0, 3, 0) - V(5, 0, 0)).norm();
  EXPECT_NEAR(area, expected, 1e-9 * expected);
  // The first triangle's patches all face +z, like their parent.
  EXPECT_TRUE(scene.patches.front().normal.isApprox(V::UnitZ()));
  EXPECT_EQ(scene.stats.mesh_patches, scene.patches.size());
}

TEST(Scene, PatchesOfNamedSurfaces) {
  const Scene box = reference::make_closed_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(2, 2, 2), 0.5, 1.0);
  const std::vector<int> floor = reference::patches_of(box, "floor"), ceiling = reference::patches_of(box, "ceiling");
  ASSERT_FALSE(floor.empty());
  std::vector<int> both = floor;
  both.insert(both.end(), ceiling.begin(), ceiling.end());
  std::sort(both.begin(), both.end());
  EXPECT_EQ(box.patches_of({"ceiling", "floor", "ceiling"}), both);  // ascending, each once
  EXPECT_EQ(box.patches_of({}), box.all_patches());
  EXPECT_THROW(box.patches_of({"floor", "roof"}), std::invalid_argument);
}

TEST(Scene, DropsAndCountsDegenerateFaces) {
  const TriangleMesh mesh = one_surface_mesh({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(2, 0, 0)},
                                             {{0, 1, 2}, {0, 1, 3}, {0, 0, 2}});  // collinear, repeated vertex
  const Scene scene = make_scene(mesh, TriangleReflectance(3, V::Constant(0.5)), {});
  EXPECT_EQ(scene.stats.degenerate_dropped, 2u);
  EXPECT_EQ(scene.patches.size(), 1u);
  // A tiny but real triangle is kept.
  const TriangleMesh sliver = one_surface_mesh({V(0, 0, 0), V(10, 0, 0), V(0, 10, 0), V(1e-5, 0, 0), V(0, 1e-5, 0)},
                                               {{0, 1, 2}, {0, 3, 4}});
  EXPECT_EQ(make_scene(sliver, TriangleReflectance(2, V::Constant(0.5)), {}).patches.size(), 2u);
}

TEST(Scene, DropsAndCountsDuplicateTrianglesOfASurface) {
  // Triangle 0; 1 repeats it through other vertex records, rotated (same winding);
  // 2 is its reversed twin (back to back, kept); 3 repeats it in another surface (kept).
  TriangleMesh mesh = one_surface_mesh({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 0, 0), V(0, 1, 0), V(0, 0, 0)},
                                       {{0, 1, 2}, {4, 5, 3}, {0, 2, 1}, {0, 1, 2}});
  mesh.surface_names.push_back("paper");
  mesh.triangle_surface[3] = 1;
  const Scene scene = make_scene(mesh, TriangleReflectance(4, V::Constant(0.5)), {});
  EXPECT_EQ(scene.stats.duplicate_dropped, 1u);
  ASSERT_EQ(scene.patches.size(), 3u);
  EXPECT_GT(scene.patches[0].normal.z(), 0.0);
  EXPECT_LT(scene.patches[1].normal.z(), 0.0) << "the reversed twin";
  EXPECT_EQ(scene.patches[2].surface, 1);
  std::ostringstream os;
  os << scene.stats;
  EXPECT_NE(os.str().find("1 duplicates dropped"), std::string::npos) << os.str();
}

TEST(Scene, NoUsableFaceIsAnError) {
  const TriangleMesh mesh = one_surface_mesh({V(0, 0, 0), V(1, 0, 0), V(2, 0, 0)}, {{0, 1, 2}});
  EXPECT_THROW(make_scene(mesh, {V::Constant(0.5)}, {}), SceneError);
}

TEST(Scene, YUpMillimetresBecomeZUpMetres) {
  // A 2000 x 1000 mm floor in the xz plane, facing +y (up in a Y-up file).
  const TriangleMesh mesh = one_surface_mesh({V(0, 0, 0), V(0, 0, 1000), V(2000, 0, 1000), V(2000, 0, 0)},
                                             {{0, 1, 2}, {0, 2, 3}});
  SceneOptions options;
  options.up_axis = UpAxis::y;
  options.scale_to_m = 0.001;
  const Scene scene = make_scene(mesh, TriangleReflectance(2, V::Constant(0.5)), options);
  EXPECT_NEAR(scene.total_area_m2(), 2.0, 1e-12);
  for (const Patch& p : scene.patches) EXPECT_TRUE(p.normal.isApprox(V::UnitZ())) << p.normal.transpose();
  EXPECT_NEAR(scene.bounds_m.sizes().x(), 2.0, 1e-12);
  EXPECT_NEAR(scene.bounds_m.sizes().y(), 1.0, 1e-12);
}

TEST(Scene, LuminaireIsADownwardSquareEmittingItsFlux) {
  Scene scene = reference::make_closed_box(V::Zero(), V(2, 2, 2), 0.5, 0.0);
  const int s = add_square_luminaire(scene, "L1", V(1, 1, 1.9), 0.6, 3600.0);
  double flux = 0.0, area = 0.0;
  for (const Patch& p : scene.patches) {
    if (p.surface != s) continue;
    EXPECT_TRUE(p.normal.isApprox(-V::UnitZ()));
    EXPECT_EQ(p.reflectance, V::Zero());
    flux += p.area_m2 * p.exitance_lm_per_m2;
    area += p.area_m2;
  }
  EXPECT_NEAR(area, 0.36, 1e-12);
  EXPECT_NEAR(flux, 3600.0, 1e-9);
  EXPECT_TRUE(scene.surfaces[s].is_luminaire());
}

TEST(Scene, ChannelsFollowTheReflectances) {
  const TriangleMesh mesh = one_surface_mesh({V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)}, {{0, 1, 2}});
  EXPECT_EQ(make_scene(mesh, {V::Constant(0.4)}, {}).channels, 1);
  EXPECT_EQ(make_scene(mesh, {V(0.4, 0.5, 0.4)}, {}).channels, 3);
}

TEST(Scene, RefusesMeshingBeyondThePatchLimit) {
  const TriangleMesh mesh = one_surface_mesh({V(0, 0, 0), V(100, 0, 0), V(0, 100, 0)}, {{0, 1, 2}});
  SceneOptions options;
  options.max_patch_edge_m = 0.01;
  options.max_patches = 1000;
  EXPECT_THROW(make_scene(mesh, {V::Constant(0.5)}, options), SceneError);
}


// The shipped Cornell box: coloured walls from the MTL, and a closed room (no ray
// leaves it), which its one-sided, inward-facing walls need to be lit correctly.
TEST(Scene, ShippedCornellBoxIsColouredAndClosed) {
  const JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/cornell.yaml");
  const Scene scene = load_job_scene(scene_spec(job)).scene;
  EXPECT_EQ(scene.channels, 3);
  const int left = scene.find_surface("left_wall");
  const int right = scene.find_surface("right_wall");
  ASSERT_GE(left, 0);
  ASSERT_GE(right, 0);
  int left_patches = 0, right_patches = 0, wrong_colour = 0;
  for (const Patch& p : scene.patches) {
    if (p.surface == left) {
      ++left_patches;
      wrong_colour += p.reflectance.x() <= p.reflectance.y();  // must be red
    } else if (p.surface == right) {
      ++right_patches;
      wrong_colour += p.reflectance.y() <= p.reflectance.x();  // must be green
    }
  }
  EXPECT_GT(left_patches, 0);
  EXPECT_GT(right_patches, 0);
  EXPECT_EQ(wrong_colour, 0);

  const RayCaster caster(scene, 0);
  std::vector<int> rows;
  for (int i = 0; i < static_cast<int>(scene.patches.size()); i += 50) rows.push_back(i);
  FormFactorOptions options;
  options.rays_per_patch = 256;
  const FormFactorRows ff = compute_form_factor_rows(scene, caster, rows, options);
  ASSERT_EQ(ff.escaped_fraction.size(), static_cast<Eigen::Index>(rows.size()));
  int leaking = 0, first_leaking = -1;
  for (std::size_t r = 0; r < rows.size(); ++r) {
    if (ff.escaped_fraction[static_cast<Eigen::Index>(r)] < 1e-3) continue;
    if (leaking++ == 0) first_leaking = rows[r];
  }
  EXPECT_EQ(leaking, 0) << leaking << " of " << rows.size() << " rows leak light, the first from patch "
                        << first_leaking;
}

}  // namespace
}  // namespace ilp
