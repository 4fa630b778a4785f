// Models read through assimp (core/scene/mesh_import.cpp): the office converted by
// assimp's own converter against ilp's OBJ reader, the real models of ../shared/scenes,
// and the files assimp cannot read or that hold no triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>
#include <string>

#include "core/exact/exact_solver.h"
#include "core/scene/mesh.h"
#include "job/config.h"
#include "job/job_scene.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::TempDir;

const std::string kSource = ILP_SOURCE_DIR;
const std::string kImport = kSource + "/tests/data/import/";
const std::string kScenes = kSource + "/../shared/scenes/";

// The office job of configs/office_fixed.yaml on `mesh` (four placed panels).
std::string office_job(const std::string& mesh, const std::string& frame) {
  return "scene:\n  mesh: " + mesh + "\n" + frame +
         "  max_patch_edge_m: 0.25\n"
         "  reflectance: {floor: 0.2, walls: 0.5, ceiling: 0.7, desk_1: 0.45, desk_2: 0.45}\n"
         "luminaires:\n  size_m: 0.6\n  placed:\n"
         "    - {name: L1, position_m: [1.5, 1.0, 2.95], flux_lm: 3400}\n"
         "    - {name: L2, position_m: [4.5, 1.0, 2.95], flux_lm: 3400}\n"
         "    - {name: L3, position_m: [1.5, 3.0, 2.95], flux_lm: 3400}\n"
         "    - {name: L4, position_m: [4.5, 3.0, 2.95], flux_lm: 3400}\n"
         "solver: {rays_per_patch: 256, seed: 1, relative_residual: 1.0e-8}\n";
}

JobScene office_scene(const TempDir& dir, const std::string& mesh, const std::string& frame) {
  return load_job_scene(load_job_config(dir.write("job.yaml", office_job(mesh, frame))));
}

// The model alone (no luminaires, one reflectance), as the file states its frame.
JobScene bare_scene(const TempDir& dir, const std::string& mesh) {
  return load_job_scene(load_job_config(dir.write("bare.yaml", "scene:\n  mesh: " + mesh + "\n  default_reflectance: 0.5\n")));
}

// Area-weighted mean of the patches' total illuminance per surface name.
std::map<std::string, double> surface_lux(const Scene& scene, const Eigen::VectorXd& lux) {
  std::map<std::string, double> area, sum;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const std::string& name = scene.surfaces[static_cast<std::size_t>(scene.patches[i].surface)].name;
    area[name] += scene.patches[i].area_m2;
    sum[name] += scene.patches[i].area_m2 * lux[static_cast<Eigen::Index>(i)];
  }
  for (auto& [name, s] : sum) s /= area[name];
  return sum;
}

bool contains(const std::vector<std::string>& log, const std::string& text) {
  for (const std::string& line : log)
    if (line.find(text) != std::string::npos) return true;
  return false;
}

// The office converted by `assimp export` gives the OBJ's patches (same surfaces, areas
// and centroids) and the same exact illuminance within 0.1 %.
TEST(MeshImport, OfficeConvertedToGltfAnd3dsGivesTheObjsPatchesAndIlluminance) {
  TempDir dir;
  const JobScene obj = office_scene(dir, kSource + "/data/office.obj", "  up_axis: z\n");
  ExactSolveOptions options;
  options.form_factors.rays_per_patch = 256;
  options.form_factors.seed = 1;
  options.radiosity.relative_residual = 1e-8;
  const std::map<std::string, double> obj_lux = surface_lux(obj.scene, solve_exact(obj.scene, options).radiosity.total_lux);
  for (const std::string file : {"office.glb", "office.3ds"}) {
    SCOPED_TRACE(file);
    // office.glb claims glTF's y up for z-up geometry (assimp's converter does not turn
    // it): the job's up_axis overrides it. 3DS states no frame: the job's default holds.
    const JobScene imported = office_scene(dir, kImport + file, std::string(file) == "office.glb" ? "  up_axis: z\n" : "");
    ASSERT_EQ(imported.scene.patches.size(), obj.scene.patches.size());
    // Each OBJ patch has one imported patch of its surface with its centroid and area
    // (to the float precision the converted files store positions in).
    std::vector<bool> matched(imported.scene.patches.size(), false);
    std::size_t unmatched = 0;
    for (const Patch& p : obj.scene.patches) {
      const std::string& name = obj.scene.surfaces[static_cast<std::size_t>(p.surface)].name;
      bool found = false;
      for (std::size_t k = 0; k < imported.scene.patches.size() && !found; ++k) {
        const Patch& q = imported.scene.patches[k];
        if (matched[k] || imported.scene.surfaces[static_cast<std::size_t>(q.surface)].name != name) continue;
        if ((q.centroid_m - p.centroid_m).norm() < 1e-5 && std::abs(q.area_m2 - p.area_m2) < 1e-6) matched[k] = found = true;
      }
      if (!found) ++unmatched;
    }
    EXPECT_EQ(unmatched, 0u) << "OBJ patches without their twin (surface, centroid, area)";
    const std::map<std::string, double> lux =
        surface_lux(imported.scene, solve_exact(imported.scene, options).radiosity.total_lux);
    for (const auto& [name, value] : obj_lux) {
      ASSERT_TRUE(lux.count(name)) << name;
      EXPECT_NEAR(lux.at(name), value, 1e-3 * value) << name;
    }
  }
}

// What a file states of its frame is applied when the job does not set it; the log says
// where each came from or that the file does not state it.
TEST(MeshImport, UnitsAndUpAxisComeFromTheFileWhereItStatesThem) {
  TempDir dir;
  const std::string text = test::read_file(kImport + "office.dae");
  ASSERT_NE(text.find("Y_UP"), std::string::npos);
  // COLLADA: the file says Z_UP and 1 m; assimp turns it y up, ilp back to z up.
  std::string z_up = text;
  z_up.replace(z_up.find("Y_UP"), 4, "Z_UP");
  const JobScene dae = office_scene(dir, dir.write("office_z.dae", z_up), "");
  // (The converted files store positions as floats: 1e-6 m.)
  EXPECT_NEAR(dae.scene.bounds_m.max().z(), 3.0, 1e-6);
  EXPECT_NEAR(dae.scene.bounds_m.max().x(), 6.0, 1e-6);
  EXPECT_NEAR(dae.scene.bounds_m.max().y(), 4.0, 1e-6);
  EXPECT_TRUE(contains(dae.log, "up axis: y up (the file's <up_axis>")) << "the log says where the axis came from";
  // In centimetres: the unit applied (the room is 6 cm long).
  std::string cm = z_up;
  cm.replace(cm.find("meter=\"1\""), 9, "meter=\"0.01\"");
  EXPECT_NEAR(bare_scene(dir, dir.write("cm.dae", cm)).scene.bounds_m.max().x(), 0.06, 1e-8);
  // FBX: UnitScaleFactor 1 (cm) and UpAxis 1 (y) as stated; with 100 (m) and UpAxis 2 (z) the office.
  const std::string fbx = test::read_file(kImport + "office.fbx");
  const JobScene stated = bare_scene(dir, kImport + "office.fbx");
  EXPECT_NEAR(stated.scene.bounds_m.max().x(), 0.06, 1e-8) << "1 cm per unit";
  EXPECT_NEAR(stated.scene.bounds_m.max().z(), 0.04, 1e-8) << "y up: the file's y (4 m x 1 cm) becomes z";
  EXPECT_TRUE(contains(stated.log, "UnitScaleFactor 1 cm"));
  std::string metres = fbx;
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"\"UnitScaleFactor\", \"double\", \"Number\", \"\", 1",
                                                                     "\"UnitScaleFactor\", \"double\", \"Number\", \"\", 100"},
                                 {"\"UpAxis\", \"int\", \"Integer\", \"\", 1", "\"UpAxis\", \"int\", \"Integer\", \"\", 2"}}) {
    ASSERT_NE(metres.find(from), std::string::npos) << from;
    metres.replace(metres.find(from), from.size(), to);
  }
  const JobScene fixed = office_scene(dir, dir.write("metres.fbx", metres), "");
  EXPECT_NEAR(fixed.scene.bounds_m.max().x(), 6.0, 1e-6);
  EXPECT_NEAR(fixed.scene.bounds_m.max().z(), 3.0, 1e-6);
  // 3DS states neither: the log says so, and the job's settings are used.
  const JobScene tds = office_scene(dir, kImport + "office.3ds", "");
  EXPECT_TRUE(contains(tds.log, "the file does not state its unit"));
  EXPECT_TRUE(contains(tds.log, "the file does not state its up axis"));
  // A job that sets the axis overrides the file and says so.
  const JobScene glb = office_scene(dir, kImport + "office.glb", "  up_axis: z\n");
  EXPECT_TRUE(contains(glb.log, "up axis: scene.up_axis = z, as the job sets it (the file states y up (glTF 2.0's"));
}

// Reflectances come from the materials' colours, and the log says which.
TEST(MeshImport, ReflectancesComeFromTheMaterialsColours) {
  const TriangleMesh mesh = load_mesh(kImport + "office.glb");
  std::map<std::string, double> kd;
  for (const MeshMaterial& m : mesh.materials)
    if (m.kd) kd[m.name] = (*m.kd)[0];
  EXPECT_DOUBLE_EQ(kd.at("floor"), 0.3f);  // data/office.mtl's Kd, as glTF's base colour (float)
  EXPECT_DOUBLE_EQ(kd.at("wall"), 0.6f);
  bool said = false;
  for (const std::string& note : mesh.notes) said = said || note.find("reflectance from the materials' colour: 'floor' 0.3") != std::string::npos;
  EXPECT_TRUE(said);
}

// ../shared/scenes/ifc-fzk-haus: walls, slabs and furniture as surfaces, metres, z up.
TEST(MeshImport, IfcHouseImportsWithWallsSlabsAndFurnitureInMetresZUp) {
  TempDir dir;
  const std::string ifc = kScenes + "ifc-fzk-haus/AC14-FZK-Haus.ifc";
  ASSERT_TRUE(std::filesystem::exists(ifc)) << ifc;
  const JobScene house = load_job_scene(
      load_job_config(dir.write("house.yaml", "scene:\n  mesh: " + ifc + "\n  default_reflectance: 0.5\n")));
  int walls = 0, slabs = 0, furniture = 0;
  for (const Surface& s : house.scene.surfaces) {
    walls += s.name.rfind("IfcWallStandardCase_", 0) == 0;
    slabs += s.name.rfind("IfcSlab_", 0) == 0;
    furniture += s.name.rfind("IfcFurnishingElement_", 0) == 0;
  }
  EXPECT_EQ(walls, 13);
  EXPECT_EQ(slabs, 4);
  EXPECT_EQ(furniture, 21);
  // The site plate (18 x 16 m, 1 m thick) under the house; the ridge 6.32 m above the floor.
  const Eigen::AlignedBox3d& b = house.scene.bounds_m;
  EXPECT_NEAR(b.min().z(), -1.0, 1e-3);
  EXPECT_NEAR(b.max().z(), 6.32, 0.01);
  EXPECT_NEAR(b.sizes().x(), 18.0, 0.01);
  EXPECT_NEAR(b.sizes().y(), 16.0, 0.01);
  EXPECT_TRUE(contains(house.log, "unit: metres (the IFC file's length unit"));
  EXPECT_TRUE(contains(house.log, "up axis: y up (IFC is z up; assimp turns it y up)"));
}

// ../shared/scenes/gltf-living-room: its 3,537 zero-area triangles are dropped and counted.
TEST(MeshImport, GltfLivingRoomDropsItsZeroAreaTriangles) {
  const TriangleMesh mesh = load_mesh(kScenes + "gltf-living-room/living_room.glb");
  EXPECT_EQ(mesh.zero_area_dropped, 3537u);
  EXPECT_EQ(mesh.triangles.size(), 1551u);
  EXPECT_EQ(mesh.triangles.size(), mesh.triangle_surface.size());
  EXPECT_EQ(mesh.triangles.size(), mesh.triangle_material.size());
  ASSERT_TRUE(mesh.frame.up_axis.has_value());
  EXPECT_EQ(*mesh.frame.up_axis, UpAxis::y);
  EXPECT_EQ(mesh.frame.scale_to_m.value_or(0.0), 1.0);
}

// ../shared/scenes/ifc4-wall: assimp 5.2.5 reads IFC2x3 only; the error names the file,
// assimp's reason and the schema.
TEST(MeshImport, Ifc4FileIsRefusedNamingTheFileAndTheReason) {
  const std::string ifc = kScenes + "ifc4-wall/wall-standard-case.ifc";
  const std::string what = test::error_of<SceneError>([&] { (void)load_mesh(ifc); });
  EXPECT_NE(what.find(ifc + ": assimp cannot read it: "), std::string::npos) << what;
  EXPECT_NE(what.find("IfcOwnerHistory"), std::string::npos) << what;
  EXPECT_NE(what.find("the file's schema is IFC4; assimp reads IFC2x3 only"), std::string::npos) << what;
}

// A glTF whose only mesh is points: no triangles, an error naming the file.
TEST(MeshImport, GltfWithoutTrianglesIsAnError) {
  TempDir dir;
  // Three points (36 bytes of float positions), base64 "AAAAAA..." = zeros and ones.
  const std::string gltf = dir.write("points.gltf", R"({
    "asset": {"version": "2.0"},
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": 0}]}],
    "nodes": [{"mesh": 0, "name": "dots"}],
    "scenes": [{"nodes": [0]}], "scene": 0})");
  const std::string what = test::error_of<SceneError>([&] { (void)load_mesh(gltf); });
  EXPECT_NE(what.find(gltf + ": "), std::string::npos) << what;
  EXPECT_NE(what.find("no triangles"), std::string::npos) << what;
}

// A COLLADA array without its count made assimp 5.2.5 crash (found by fuzz/import_fuzz.cpp):
// refused before assimp reads it, naming the file and line.
TEST(MeshImport, ColladaArrayWithoutCountIsRefusedBeforeAssimpCrashesOnIt) {
  TempDir dir;
  std::string text = test::read_file(kImport + "office.dae");
  const std::string with = "<float_array id=\"floor_2-positions-array\" count=\"12\">";
  ASSERT_NE(text.find(with), std::string::npos);
  text.replace(text.find(with), with.size(), "<float_array id=\"floor_2-positions-array\">");
  const std::string dae = dir.write("no_count.dae", text);
  const std::string what = test::error_of<SceneError>([&] { (void)load_mesh(dae); });
  EXPECT_NE(what.find(dae + ":233: <float_array> without its count attribute"), std::string::npos) << what;
}

// Bytes that are no model: assimp's reason, the file named.
TEST(MeshImport, UnreadableModelIsAnErrorNamingTheFile) {
  TempDir dir;
  const std::string glb = dir.write("broken.glb", "glTF but not really");
  const std::string what = test::error_of<SceneError>([&] { (void)load_mesh(glb); });
  EXPECT_EQ(what.rfind(glb + ": assimp cannot read it: ", 0), 0u) << what;
}

}  // namespace
}  // namespace ilp
