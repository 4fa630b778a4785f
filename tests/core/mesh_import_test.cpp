// Models read through assimp (core/scene/mesh_import.cpp): the office converted by
// assimp's own converter against ilp's OBJ reader, the real models of ../shared/scenes,
// and the files assimp cannot read or that hold no triangles.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <tuple>
#include <string>

#include "core/exact/exact_solver.h"
#include "core/scene/mesh.h"
#include "core/scene/mesh_import.h"
#include "core/scene/mesh_message.h"
#include "core/scene/scene.h"
#include "job/config.h"
#include "job/plan.h"
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
  return load_job_scene(scene_spec(load_job_config(dir.write("job.yaml", office_job(mesh, frame)))));
}

// The model alone (no luminaires, one reflectance), as the file states its frame.
JobScene bare_scene(const TempDir& dir, const std::string& mesh) {
  return load_job_scene(scene_spec(load_job_config(dir.write("bare.yaml", "scene:\n  mesh: " + mesh + "\n  default_reflectance: 0.5\n"))));
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
    // it): the job's up_axis overrides it. 3DS states no frame: the job states the unit
    // (without it the file is refused) and the default up axis (z) holds.
    const JobScene imported =
        office_scene(dir, kImport + file, std::string(file) == "office.glb" ? "  up_axis: z\n" : "  scale_to_m: 1.0\n");
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
  // 3DS states neither: the job's unit is used (without one the file is refused:
  // MeshImport.AUnitNeitherTheFileNorTheJobStatesIsAnError), the log says so, and the
  // default up axis is taken and said to be.
  const JobScene tds = office_scene(dir, kImport + "office.3ds", "  scale_to_m: 1.0\n");
  EXPECT_TRUE(contains(tds.log, "unit: scene.scale_to_m = 1 m per unit, as the job sets it"));
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
      scene_spec(load_job_config(dir.write("house.yaml", "scene:\n  mesh: " + ifc + "\n  default_reflectance: 0.5\n"))));
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

// ---- A unit the file does not state (issue 22).

// 3DS carries no unit: unless the job sets scene.scale_to_m the job is refused, naming
// the job's line, the file and the key.
TEST(MeshImport, AUnitNeitherTheFileNorTheJobStatesIsAnError) {
  TempDir dir;
  const std::string job = dir.write("job.yaml", "scene:\n  mesh: " + kImport + "office.3ds\n  default_reflectance: 0.5\n");
  const std::string what = test::error_of<ConfigError>([&] { (void)load_job_scene(scene_spec(load_job_config(job))); });
  EXPECT_NE(what.find(job + ":2:"), std::string::npos) << what;
  EXPECT_NE(what.find("scene.mesh: " + kImport + "office.3ds: the file does not state its unit (3DS files carry none): "
                      "set scene.scale_to_m"),
            std::string::npos)
      << what;
  // The same job with the unit set loads, in the job's unit.
  const JobScene mm = load_job_scene(scene_spec(load_job_config(
      dir.write("mm.yaml", "scene:\n  mesh: " + kImport + "office.3ds\n  scale_to_m: 0.001\n  default_reflectance: 0.5\n"))));
  EXPECT_NEAR(mm.scene.bounds_m.max().x(), 0.006, 1e-9) << "the 6 m office read as 6 mm";
  // (An FBX always states one to ilp: assimp gives its UnitScaleFactor, 1 cm where the
  // file has none, FBX's default; COLLADA without <unit> is 1 m, its default.)
}

// ---- The import in a child process (mesh_import.h, load_with_assimp_isolated).

// office.dae with one array's count attribute gone, the words " count=" hidden in
// another attribute's value so that the pre-check (which looks for " count=" in the
// element) lets it through: assimp 5.2.5 dereferences a null pointer on it (SIGSEGV,
// found by fuzz/import_fuzz.cpp's finding turned about).
std::string crashing_dae(const TempDir& dir) {
  std::string text = test::read_file(kImport + "office.dae");
  const std::string with = "<float_array id=\"floor_2-positions-array\" count=\"12\">";
  EXPECT_NE(text.find(with), std::string::npos);
  text.replace(text.find(with), with.size(), "<float_array id=\"floor_2-positions-array\" name=\" count=\">");
  return dir.write("crash.dae", text);
}

// The premise of the next test: the file does crash assimp when read in this process.
// (Should a later assimp read it, this fails and the file no longer tests the child.)
TEST(MeshImportDeathTest, TheCrashingFileCrashesAssimpInProcess) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  TempDir dir;
  const std::string dae = crashing_dae(dir);
  if (test::kAddressSanitizer)  // ASan reports the SEGV and exits 1
    EXPECT_EXIT((void)load_with_assimp(dae, ".dae", {}), testing::ExitedWithCode(1), "AddressSanitizer: SEGV");
  else
    EXPECT_EXIT((void)load_with_assimp(dae, ".dae", {}), testing::KilledBySignal(SIGSEGV), "");
}

// Regression: load_mesh read the file in this process and the program died (SIGSEGV).
// In the child the crash becomes an error naming the file, the signal and the reason.
TEST(MeshImport, AFileThatCrashesAssimpIsAnErrorNamingTheFileAndTheSignal) {
  TempDir dir;
  const std::string dae = crashing_dae(dir);
  const std::string what = test::error_of<SceneError>([&] { (void)load_mesh(dae); });
  EXPECT_EQ(what, dae + ": assimp crashed reading it (signal 11, SIGSEGV); the file is malformed or uses a feature "
                      "assimp 5.2.5 cannot read");
  // Through a job: the job's line in front.
  const std::string job = dir.write("job.yaml", "scene:\n  mesh: " + dae + "\n  default_reflectance: 0.5\n");
  const std::string job_what = test::error_of<SceneError>([&] { (void)load_job_scene(scene_spec(load_job_config(job))); });
  EXPECT_NE(job_what.find(job + ":2:"), std::string::npos) << job_what;
  EXPECT_NE(job_what.find("scene.mesh: " + dae + ": assimp crashed reading it (signal 11, SIGSEGV)"), std::string::npos)
      << job_what;
}

// Patches of the scene made from `mesh` (one reflectance, metres, z up).
Scene scene_of(const TriangleMesh& mesh) {
  SceneOptions options;
  options.max_patch_edge_m = 0.25;
  return make_scene(mesh, TriangleReflectance(mesh.triangles.size(), Eigen::Vector3d::Constant(0.5)), options);
}

// Through the child, every test model gives the in-process mesh bit for bit (the message
// carries doubles as they are), hence the same patches and areas.
TEST(MeshImport, TheChildGivesTheInProcessMeshBitForBit) {
  std::vector<std::string> files;
  for (const char* f : {"office.glb", "office.3ds", "office.dae", "office.fbx"}) files.push_back(kImport + f);
  files.push_back(kScenes + "gltf-living-room/living_room.glb");
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    const std::string ext = std::filesystem::path(path).extension().string();
    for (const SurfaceNaming naming : {SurfaceNaming::group, SurfaceNaming::material}) {
      MeshReadOptions options;
      options.surface_naming = naming;
      const TriangleMesh here = load_with_assimp(path, ext, options);
      const TriangleMesh child = load_with_assimp_isolated(path, ext, options);
      EXPECT_EQ(child.path, here.path);
      EXPECT_EQ(child.positions, here.positions);  // exact: == on doubles
      EXPECT_EQ(child.triangles, here.triangles);
      EXPECT_EQ(child.triangle_surface, here.triangle_surface);
      EXPECT_EQ(child.triangle_material, here.triangle_material);
      EXPECT_EQ(child.surface_names, here.surface_names);
      ASSERT_EQ(child.materials.size(), here.materials.size());
      for (std::size_t m = 0; m < here.materials.size(); ++m) {
        EXPECT_EQ(child.materials[m].name, here.materials[m].name);
        EXPECT_EQ(child.materials[m].kd, here.materials[m].kd) << here.materials[m].name;
        EXPECT_EQ(child.materials[m].kd_loc.file, here.materials[m].kd_loc.file);
      }
      EXPECT_EQ(child.faces_read, here.faces_read);
      EXPECT_EQ(child.zero_area_dropped, here.zero_area_dropped);
      EXPECT_EQ(child.frame.scale_to_m, here.frame.scale_to_m);
      EXPECT_EQ(child.frame.up_axis, here.frame.up_axis);
      EXPECT_EQ(child.frame.unit_note, here.frame.unit_note);
      EXPECT_EQ(child.frame.up_note, here.frame.up_note);
      EXPECT_EQ(child.notes, here.notes);
    }
    // The patches: as many, each of the same area.
    const Scene a = scene_of(load_with_assimp(path, ext, {})), b = scene_of(load_mesh(path));
    ASSERT_EQ(b.patches.size(), a.patches.size());
    for (std::size_t i = 0; i < a.patches.size(); ++i) ASSERT_EQ(b.patches[i].area_m2, a.patches[i].area_m2) << i;
  }
}

// An error the reader throws in the child comes back as the same error.
TEST(MeshImport, TheChildsErrorsAreTheInProcessErrors) {
  TempDir dir;
  const std::string glb = dir.write("broken.glb", "glTF but not really");
  const std::string here = test::error_of<SceneError>([&] { (void)load_with_assimp(glb, ".glb", {}); });
  const std::string child = test::error_of<SceneError>([&] { (void)load_with_assimp_isolated(glb, ".glb", {}); });
  EXPECT_EQ(child, here);
  EXPECT_EQ(child.rfind(glb + ": assimp cannot read it: ", 0), 0u) << child;
}

// A child past its time is killed and the file refused; within its memory it reads the
// model. The IFC house takes about 0.8 s and 40 MB to read.
TEST(MeshImport, TheChildsTimeAndMemoryAreLimited) {
  const std::string ifc = kScenes + "ifc-fzk-haus/AC14-FZK-Haus.ifc";
  ASSERT_TRUE(std::filesystem::exists(ifc)) << ifc;
  MeshReadOptions slow;
  slow.import_limits.max_time_s = 0.05;
  const auto start = std::chrono::steady_clock::now();
  const std::string late = test::error_of<SceneError>([&] { (void)load_mesh(ifc, slow); });
  EXPECT_EQ(late, ifc + ": assimp took longer than 0.05 s reading it (stopped)");
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5)
      << "killed at the limit, not waited for";

  MeshReadOptions ample;
  ample.import_limits.max_memory_bytes = 2e9;
  EXPECT_EQ(load_mesh(ifc, ample).triangles.size(), 35902u);
}

// Beyond its memory the child's import fails (assimp's allocation fails, or it aborts):
// an error naming the file. In a fresh process (a death test's): the limit counts new
// mappings, and memory this process's allocator already holds free from earlier tests
// would be reused without counting.
TEST(MeshImportDeathTest, TheChildsMemoryIsLimited) {
  // Under ASan a child out of its address space does not throw std::bad_alloc: ASan's
  // allocator reports it, and its report (the symbolizer it starts) can hang under the
  // same limit (measured: 0.4 s once, over 300 s the next time). The plain build tests it.
  if (test::kAddressSanitizer) GTEST_SKIP() << "ASan replaces the allocator whose failure this watches";
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  const std::string ifc = kScenes + "ifc-fzk-haus/AC14-FZK-Haus.ifc";
  ASSERT_TRUE(std::filesystem::exists(ifc)) << ifc;
  MeshReadOptions tight;
  tight.import_limits.max_memory_bytes = 4e6;
  EXPECT_EXIT(
      {
        try {
          (void)load_mesh(ifc, tight);
        } catch (const SceneError& e) {
          std::fprintf(stderr, "%s\n", e.what());
          std::_Exit(3);
        }
        std::_Exit(0);
      },
      testing::ExitedWithCode(3),
      "AC14-FZK-Haus.ifc: (out of memory reading the model \\(the import's memory limit was reached\\)|assimp crashed "
      "reading it)");
}

// The message: a mesh and an error survive the trip; a truncated, extended or damaged one
// is refused with where and what, never read past its end.
TEST(MeshImport, TheChildsMessageRefusesTruncatedAndDamagedBytes) {
  const TriangleMesh mesh = load_with_assimp(kImport + "office.glb", ".glb", {});
  const std::string bytes = encode_mesh_message(mesh);
  const MeshMessage back = decode_mesh_message(bytes);
  ASSERT_FALSE(back.is_error);
  EXPECT_EQ(back.mesh.positions, mesh.positions);
  EXPECT_EQ(back.mesh.notes, mesh.notes);
  const MeshMessage error = decode_mesh_message(encode_error_message("x.glb: no"));
  EXPECT_TRUE(error.is_error);
  EXPECT_EQ(error.error, "x.glb: no");
  // The seeds of fuzz/import_message_fuzz.cpp (written by hand from the format) decode.
  const MeshMessage seed = decode_mesh_message(test::read_file(kSource + "/fuzz/corpus/import_message/triangle"));
  EXPECT_EQ(seed.mesh.triangles.size(), 1u);
  EXPECT_EQ(seed.mesh.surface_names, std::vector<std::string>{"floor"});
  EXPECT_TRUE(decode_mesh_message(test::read_file(kSource + "/fuzz/corpus/import_message/error")).is_error);

  auto refusal = [](const std::string& b) { return test::error_of<MeshMessageError>([&] { (void)decode_mesh_message(b); }); };
  EXPECT_NE(refusal("").find("truncated in the header"), std::string::npos);
  for (std::size_t cut : {std::size_t{9}, std::size_t{20}, bytes.size() / 2, bytes.size() - 1})
    EXPECT_NE(refusal(bytes.substr(0, cut)).find("truncated"), std::string::npos) << cut;
  EXPECT_NE(refusal(bytes + "x").find("trailing bytes"), std::string::npos);
  // The first triangle's first vertex (after header 9 bytes, the vertex count and positions, the triangle count).
  std::string damaged = bytes;
  const std::size_t first_vertex = 9 + 8 + mesh.positions.size() * 24 + 8;
  const std::int32_t beyond = static_cast<std::int32_t>(mesh.positions.size());
  std::memcpy(damaged.data() + first_vertex, &beyond, sizeof beyond);
  EXPECT_NE(refusal(damaged).find("triangle 0 names vertex " + std::to_string(beyond)), std::string::npos);
  // A count far beyond the message asks for no memory.
  std::string huge = bytes;
  const std::uint64_t many = std::uint64_t{1} << 60;
  std::memcpy(huge.data() + 9, &many, sizeof many);
  EXPECT_NE(refusal(huge).find("truncated or damaged: positions count 1152921504606846976 is beyond the "),
            std::string::npos);
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
