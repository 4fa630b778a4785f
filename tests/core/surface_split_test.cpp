// scene.surfaces_from: connected and scene.regions: surfaces from a one-group mesh,
// checked on small synthetic meshes whose pieces are known by construction.
#include "core/scene/surface_split.h"

#include <gtest/gtest.h>

#include <map>

#include "job/config.h"
#include "job/plan.h"
#include "job/job_scene.h"
#include "tests/test_support.h"
#include "job/setting_keys.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;
using test::Contains;
using test::TempDir;

// Appends an axis-aligned box [lo, hi] (z up) as 12 triangles sharing its 8 corners,
// wound to face inwards (a room) or outwards (a solid), all in surface 0.
void add_box(TriangleMesh& mesh, const V& lo, const V& hi, bool inwards, bool with_top = true,
             bool with_bottom = true) {
  const int base = static_cast<int>(mesh.positions.size());
  for (int k = 0; k < 8; ++k)
    mesh.positions.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  // Quads wound counter-clockwise seen from outside.
  std::vector<std::array<int, 4>> quads;
  if (with_bottom) quads.push_back({0, 2, 3, 1});
  if (with_top) quads.push_back({4, 5, 7, 6});
  for (const auto& q : std::vector<std::array<int, 4>>{{0, 1, 5, 4}, {1, 3, 7, 5}, {3, 2, 6, 7}, {2, 0, 4, 6}})
    quads.push_back(q);
  for (const auto& q : quads) {
    Eigen::Vector3i a(base + q[0], base + q[1], base + q[2]), b(base + q[0], base + q[2], base + q[3]);
    if (inwards) {
      std::swap(a[1], a[2]);
      std::swap(b[1], b[2]);
    }
    mesh.triangles.push_back(a);
    mesh.triangles.push_back(b);
  }
  mesh.triangle_surface.resize(mesh.triangles.size(), 0);
  mesh.triangle_material.resize(mesh.triangles.size(), -1);
}

TriangleMesh empty_mesh() {
  TriangleMesh mesh;
  mesh.path = "<test>";
  mesh.surface_names = {"room"};
  return mesh;
}

// Triangles per surface name.
std::map<std::string, int> triangles_by_name(const TriangleMesh& mesh) {
  std::map<std::string, int> out;
  for (int s : mesh.triangle_surface) ++out[mesh.surface_names[static_cast<std::size_t>(s)]];
  return out;
}

TEST(SurfaceSplit, TwoDisjointOpenBoxesBecomeTwoSurfacesLargestFirst) {
  // Walls only (no top or bottom): each box is one vertical piece.
  TriangleMesh mesh = empty_mesh();
  add_box(mesh, V(5, 0, 0), V(6, 1, 1), true, false, false);  // small, first in the file
  add_box(mesh, V(0, 0, 0), V(3, 3, 2), true, false, false);  // large
  SurfaceSplitOptions options;
  options.connected = true;
  const SurfaceSplitReport report = split_surfaces(mesh, {}, options);
  EXPECT_EQ(report.pieces, 2u);
  ASSERT_EQ(mesh.surface_names.size(), 2u);
  // room.1 is the larger box, whatever the file order.
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    EXPECT_EQ(mesh.surface_names[static_cast<std::size_t>(mesh.triangle_surface[t])], t < 8 ? "room.2" : "room.1");
}

TEST(SurfaceSplit, ABoxSplitsByFacingIntoFloorCeilingAndWalls) {
  TriangleMesh mesh = empty_mesh();
  add_box(mesh, V(0, 0, 0), V(4, 3, 2.5), true);
  SurfaceSplitOptions options;
  options.connected = true;
  split_surfaces(mesh, {}, options);
  // Walls 2 x (4 + 3) x 2.5 = 35 m² > floor = ceiling = 12 m²; floor and ceiling tie,
  // the earlier triangle (the floor) first.
  EXPECT_EQ(triangles_by_name(mesh), (std::map<std::string, int>{{"room.1", 8}, {"room.2", 2}, {"room.3", 2}}));
  EXPECT_EQ(mesh.surface_names[static_cast<std::size_t>(mesh.triangle_surface[0])], "room.2");  // floor
}

TEST(SurfaceSplit, RegionRulesNameFloorCeilingTableAndWalls) {
  TriangleMesh mesh = empty_mesh();
  add_box(mesh, V(0, 0, 0), V(4, 3, 2.5), true);        // the room
  add_box(mesh, V(1, 1, 0.7), V(3, 2, 0.75), false);    // a table top slab, facing out
  SurfaceSplitOptions options;
  options.regions = {{"floor", Facing::up, std::pair{-0.1, 0.1}, 0.0, {}},
                     {"ceiling", Facing::down, std::pair{2.4, 2.6}, 0.0, {}},
                     {"table", Facing::up, std::pair{0.6, 0.8}, 0.0, {}},
                     {"walls", Facing::vertical, std::nullopt, 5.0, {}}};
  const SurfaceSplitReport report = split_surfaces(mesh, {}, options);
  // The slab's underside (down at 0.7) and its edges (vertical, 0.3 m² < 5) stay in "room".
  EXPECT_EQ(triangles_by_name(mesh), (std::map<std::string, int>{
                                         {"floor", 2}, {"ceiling", 2}, {"table", 2}, {"walls", 8}, {"room", 10}}));
  EXPECT_EQ(mesh.surface_names.front(), "floor");  // rules first, in rule order
  EXPECT_NEAR(report.rule_area_m2[2], 2.0, 1e-12);
  EXPECT_EQ(report.rule_pieces[3], 1u);
}

TEST(SurfaceSplit, HeightsAreInTheSceneFrameAfterScaleAndUpAxis) {
  // The same room in millimetres with y up: the rules still speak metres, z up.
  TriangleMesh mesh = empty_mesh();
  add_box(mesh, V(0, 0, 0), V(4000, 3000, 2500), true);
  for (V& p : mesh.positions) p = V(p.x(), p.z(), -p.y());  // z up -> y up
  SceneOptions frame;
  frame.scale_to_m = 0.001;
  frame.up_axis = UpAxis::y;
  SurfaceSplitOptions options;
  options.weld_tolerance_m = 1e-3;
  options.regions = {{"ceiling", Facing::down, std::pair{2.4, 2.6}, 0.0, {}}};
  split_surfaces(mesh, frame, options);
  EXPECT_EQ(triangles_by_name(mesh), (std::map<std::string, int>{{"ceiling", 2}, {"room", 10}}));
}

TEST(SurfaceSplit, WeldToleranceJoinsNearlySharedVertices) {
  // Two floor triangles whose shared edge is 10 µm apart: one piece when welded at 1 mm, two at 1 µm.
  auto make = [] {
    TriangleMesh mesh = empty_mesh();
    mesh.positions = {V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(1, 1e-5, 0), V(1, 1, 0), V(1e-5, 1, 0)};
    mesh.triangles = {{0, 1, 2}, {3, 4, 5}};
    mesh.triangle_surface = {0, 0};
    mesh.triangle_material = {-1, -1};
    return mesh;
  };
  SurfaceSplitOptions options;
  options.connected = true;
  TriangleMesh coarse = make();
  EXPECT_EQ(split_surfaces(coarse, {}, options).pieces, 1u);
  options.weld_tolerance_m = 1e-6;
  TriangleMesh fine = make();
  EXPECT_EQ(split_surfaces(fine, {}, options).pieces, 2u);
}

TEST(SurfaceSplit, ARuleNoPieceMatchesIsAConfigErrorAtTheRule) {
  name_settings_by_key();  // as load_job_config and the ilp command do: messages name the job file's keys
  TriangleMesh mesh = empty_mesh();
  add_box(mesh, V(0, 0, 0), V(4, 3, 2.5), true);
  SurfaceSplitOptions options;
  options.regions = {{"table", Facing::up, std::pair{0.6, 0.8}, 0.0, {"job.yaml", 7, 5}}};
  const std::string msg = test::error_of<ConfigError>([&] { split_surfaces(mesh, {}, options); });
  EXPECT_TRUE(Contains(msg, "job.yaml:7:5"));
  EXPECT_TRUE(Contains(msg, "scene.regions[0] 'table': no piece"));
}

TEST(SurfaceSplit, ConfigKeysReachTheSceneAndBadValuesNameTheKey) {
  TempDir dir;
  // A room box as OBJ (one group), z up, metres.
  TriangleMesh box = empty_mesh();
  add_box(box, V(0, 0, 0), V(4, 3, 2.5), true);
  std::string obj = "g everything\n";
  for (const V& p : box.positions) obj += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
  for (const Eigen::Vector3i& t : box.triangles)
    obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  dir.write("room.obj", obj);
  const std::string yaml = dir.write("job.yaml",
                                     "scene:\n  mesh: room.obj\n  default_reflectance: 0.5\n  surfaces_from: connected\n"
                                     "  regions:\n    - {name: floor, facing: up, height_m: [-0.1, 0.1]}\n"
                                     "  reflectance:\n    floor: 0.2\n    everything.1: 0.7\n");
  const JobConfig job = load_job_config(yaml);
  const JobScene loaded = load_job_scene(scene_spec(job));
  const Scene& scene = loaded.scene;
  ASSERT_GE(scene.find_surface("floor"), 0);
  ASSERT_GE(scene.find_surface("everything.1"), 0);  // the walls, the largest piece left
  for (const Patch& p : scene.patches)
    EXPECT_DOUBLE_EQ(p.reflectance[0], scene.surfaces[static_cast<std::size_t>(p.surface)].name == "floor" ? 0.2
                                       : scene.surfaces[static_cast<std::size_t>(p.surface)].name == "everything.1" ? 0.7
                                                                                                                  : 0.5);
  const std::string bad = dir.write("bad.yaml",
                                    "scene:\n  mesh: room.obj\n  regions:\n    - {name: floor, facing: sideways}\n");
  const std::string msg = test::error_of<ConfigError>([&] { (void)load_job_config(bad); });
  EXPECT_TRUE(Contains(msg, "scene.regions[0].facing = sideways: must be up, down, vertical or any"));
}

}  // namespace
}  // namespace ilp
