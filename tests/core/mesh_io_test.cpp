// Reading meshes (load_mesh): OBJ tags that name surfaces and the fallback chain,
// face syntax, fan triangulation, CRLF, MTL Kd; PLY and OFF through OpenMesh; and
// defects that must be SceneErrors naming file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "core/scene/mesh.h"
#include "tests/test_support.h"

namespace fs = std::filesystem;

namespace {

using ilp::test::Contains;
using ilp::test::StartsWith;
using ilp::test::TempDir;

// load_mesh must throw a SceneError; returns its message.
std::string mesh_error(const std::string& path, const ilp::MeshReadOptions& options = {}) {
  return ilp::test::error_of<ilp::SceneError>([&] { (void)ilp::load_mesh(path, options); },
                                              "load_mesh(" + path + ")");
}

// load_mesh(path) must throw a SceneError whose message starts with `start` and
// contains each of `says`.
void expect_mesh_error(const std::string& path, const std::string& start, const std::vector<std::string>& says) {
  ilp::test::expect_message(mesh_error(path), start, says);
}

// Surface name of every triangle, in file order.
std::vector<std::string> triangle_surface_names(const ilp::TriangleMesh& mesh) {
  std::vector<std::string> out;
  for (int s : mesh.triangle_surface) out.push_back(mesh.surface_names.at(static_cast<std::size_t>(s)));
  return out;
}

using Names = std::vector<std::string>;

// ---------------------------------------------------------------------------------
// Surface naming

// Five triangles whose tags differ:
//   1: no tag at all
//   2: usemtl paint
//   3: o chair, usemtl paint
//   4: g seat, o chair, usemtl paint
//   5: g (cleared), o chair, usemtl paint
const char* kTaggedObj =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0 1 0\n"
    "f 1 2 3\n"
    "usemtl paint\n"
    "f 1 2 3\n"
    "o chair\n"
    "f 1 2 3\n"
    "g seat\n"
    "f 1 2 3\n"
    "g\n"
    "f 1 2 3\n";

TEST(MeshIoObj, SurfacesFromGroupFallBackToObjectMaterialDefault) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("tags.obj", kTaggedObj), {ilp::SurfaceNaming::group});
  EXPECT_EQ(triangle_surface_names(mesh), (Names{"default", "paint", "chair", "seat", "chair"}));
  EXPECT_EQ(mesh.surface_names, (Names{"default", "paint", "chair", "seat"}));  // order of first use
}

TEST(MeshIoObj, SurfacesFromObjectSkipGroups) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("tags.obj", kTaggedObj), {ilp::SurfaceNaming::object});
  EXPECT_EQ(triangle_surface_names(mesh), (Names{"default", "paint", "chair", "chair", "chair"}));
  EXPECT_EQ(mesh.surface_names, (Names{"default", "paint", "chair"}));
}

TEST(MeshIoObj, SurfacesFromMaterialSkipGroupsAndObjects) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("tags.obj", kTaggedObj), {ilp::SurfaceNaming::material});
  EXPECT_EQ(triangle_surface_names(mesh), (Names{"default", "paint", "paint", "paint", "paint"}));
  EXPECT_EQ(mesh.surface_names, (Names{"default", "paint"}));
}

TEST(MeshIoObj, DefaultNamingIsGroup) {
  EXPECT_EQ(ilp::MeshReadOptions{}.surface_naming, ilp::SurfaceNaming::group);
}

TEST(MeshIoObj, GroupsObjectsAndMaterialsPerFace) {
  TempDir dir;
  const std::string path = dir.write("room.obj",
                                     "# room\n"
                                     "o room\n"
                                     "v 0 0 0\n"
                                     "v 1 0 0\n"
                                     "v 1 1 0\n"
                                     "v 0 1 0\n"
                                     "g floor\n"
                                     "usemtl tiles\n"
                                     "f 1 2 3\n"
                                     "g wall north\n"  // a name with a space is kept whole
                                     "usemtl plaster\n"
                                     "f 1 3 4\n"
                                     "g floor\n"
                                     "usemtl tiles\n"
                                     "f 2 3 4\n");
  const ilp::TriangleMesh mesh = ilp::load_mesh(path);
  EXPECT_EQ(mesh.path, path);
  EXPECT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.surface_names, (Names{"floor", "wall north"}));
  EXPECT_EQ(mesh.triangle_surface, (std::vector<int>{0, 1, 0}));
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_EQ(mesh.materials[0].name, "tiles");
  EXPECT_EQ(mesh.materials[1].name, "plaster");
  EXPECT_FALSE(mesh.materials[0].kd.has_value());  // no mtllib
  EXPECT_EQ(mesh.triangle_material, (std::vector<int>{0, 1, 0}));
}

TEST(MeshIoObj, FacesBeforeAnyUsemtlHaveNoMaterial) {
  TempDir dir;
  const ilp::TriangleMesh mesh =
      ilp::load_mesh(dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nusemtl red\nf 1 2 3\n"));
  EXPECT_EQ(mesh.triangle_material, (std::vector<int>{-1, 0}));
}

// ---------------------------------------------------------------------------------
// Face syntax and triangulation

TEST(MeshIoObj, NegativeIndicesAreRelativeToTheVerticesAbove) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("neg.obj",
                                                          "v 0 0 0\n"
                                                          "v 1 0 0\n"
                                                          "v 1 1 0\n"
                                                          "f -3 -2 -1\n"
                                                          "v 0 1 0\n"
                                                          "f -4 -2 -1\n"
                                                          "f 1 -3 -1\n"));
  ASSERT_EQ(mesh.triangles.size(), 3u);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(0, 1, 3));
}

TEST(MeshIoObj, TextureAndNormalReferencesAreIgnored) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("vtvn.obj",
                                                          "v 0 0 0\n"
                                                          "v 1 0 0\n"
                                                          "v 1 1 0\n"
                                                          "v 0 1 0\n"
                                                          "vt 0 0\n"
                                                          "vt 1 0\n"
                                                          "vt 1 1\n"
                                                          "vn 0 0 1\n"
                                                          "s off\n"
                                                          "f 1/1/1 2/2/1 3/3/1\n"
                                                          "f 1//1 3//1 4//1\n"
                                                          "f 2/2 3/3 4/1\n"
                                                          "f -4/-3/-1 -3/-2/-1 -1/-1/-1\n"));
  ASSERT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(1, 2, 3));
  EXPECT_EQ(mesh.triangles[3], Eigen::Vector3i(0, 1, 3));
  EXPECT_EQ(mesh.positions.size(), 4u);  // vt and vn are not positions
}

TEST(MeshIoObj, QuadAndPentagonAreFanTriangulated) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("poly.obj",
                                                          "v 0 0 0\n"
                                                          "v 1 0 0\n"
                                                          "v 1 1 0\n"
                                                          "v 0 1 0\n"
                                                          "v 2 0 0\n"
                                                          "v 3 0 0\n"
                                                          "v 3 1 0\n"
                                                          "v 2.5 2 0\n"
                                                          "v 2 1 0\n"
                                                          "g quad\n"
                                                          "f 1 2 3 4\n"
                                                          "g pentagon\n"
                                                          "f 5 6 7 8 9\n"
                                                          "g triangle\n"
                                                          "f 1 2 3\n"));
  EXPECT_EQ(mesh.faces_read, 3u);
  EXPECT_EQ(mesh.polygons_split, 2u);
  ASSERT_EQ(mesh.triangles.size(), 2u + 3u + 1u);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(4, 5, 6));
  EXPECT_EQ(mesh.triangles[3], Eigen::Vector3i(4, 6, 7));
  EXPECT_EQ(mesh.triangles[4], Eigen::Vector3i(4, 7, 8));
  EXPECT_EQ(mesh.triangles[5], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(triangle_surface_names(mesh), (Names{"quad", "quad", "pentagon", "pentagon", "pentagon", "triangle"}));
}

TEST(MeshIoObj, VertexCoordinatesAreRead) {
  TempDir dir;
  const ilp::TriangleMesh mesh =
      ilp::load_mesh(dir.write("v.obj", "v -1.5 2e-3 +4\nv\t1 0 0 1.0\n  v 0 1 0\nf 1 2 3\n"));
  ASSERT_EQ(mesh.positions.size(), 3u);
  EXPECT_EQ(mesh.positions[0], Eigen::Vector3d(-1.5, 0.002, 4.0));
  EXPECT_EQ(mesh.positions[1], Eigen::Vector3d(1, 0, 0));  // optional w is ignored
  EXPECT_EQ(mesh.positions[2], Eigen::Vector3d(0, 1, 0));
}

TEST(MeshIoObj, CrlfLineEndings) {
  TempDir dir;
  dir.write("crlf.mtl", "newmtl white\r\nKd 0.5 0.6 0.7\r\n");
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("crlf.obj",
                                                          "mtllib crlf.mtl\r\n"
                                                          "v 0 0 0\r\n"
                                                          "v 1 0 0\r\n"
                                                          "v 1 1 0\r\n"
                                                          "v 0 1 0\r\n"
                                                          "g floor\r\n"
                                                          "usemtl white\r\n"
                                                          "f 1 2 3 4\r\n"));
  EXPECT_EQ(mesh.surface_names, (Names{"floor"}));  // no trailing '\r'
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_EQ(mesh.materials[0].name, "white");
  ASSERT_TRUE(mesh.materials[0].kd.has_value());
  EXPECT_EQ(*mesh.materials[0].kd, Eigen::Vector3d(0.5, 0.6, 0.7));
  EXPECT_EQ(mesh.triangle_material, (std::vector<int>{0, 0}));
  EXPECT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.positions[3], Eigen::Vector3d(0, 1, 0));
}

TEST(MeshIoObj, CrlfErrorLineNumbers) {
  TempDir dir;
  const std::string path = dir.write("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\n\r\nf 1 2 3\r\n");
  expect_mesh_error(path, path + ":4:", {"'3'"});
}

// ---------------------------------------------------------------------------------
// MTL

TEST(MeshIoMtl, KdPerMaterial) {
  TempDir dir;
  const std::string mtl = dir.write("m.mtl",
                                    "# two materials with Kd, one without\n"
                                    "newmtl gray\n"
                                    "Ka 0 0 0\n"
                                    "Kd 0.25\n"
                                    "newmtl coloured\n"
                                    "Kd 0.1 0.2 0.3\n"
                                    "newmtl bare\n"
                                    "Ns 20\n"
                                    "newmtl unused\n"
                                    "Kd 0.9 0.9 0.9\n");
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("m.obj",
                                                          "mtllib m.mtl\n"
                                                          "v 0 0 0\n"
                                                          "v 1 0 0\n"
                                                          "v 0 1 0\n"
                                                          "usemtl coloured\n"
                                                          "f 1 2 3\n"
                                                          "usemtl gray\n"
                                                          "f 1 2 3\n"
                                                          "usemtl bare\n"
                                                          "f 1 2 3\n"
                                                          "usemtl undefined\n"
                                                          "f 1 2 3\n"));
  auto material = [&](const std::string& name) -> const ilp::MeshMaterial& {
    for (const ilp::MeshMaterial& m : mesh.materials)
      if (m.name == name) return m;
    throw std::runtime_error("no material " + name);
  };
  ASSERT_EQ(mesh.materials.size(), 5u);
  ASSERT_TRUE(material("gray").kd.has_value());
  EXPECT_EQ(*material("gray").kd, Eigen::Vector3d::Constant(0.25));
  EXPECT_EQ(material("gray").kd_loc.file, mtl);
  EXPECT_EQ(material("gray").kd_loc.line, 4);
  ASSERT_TRUE(material("coloured").kd.has_value());
  EXPECT_EQ(*material("coloured").kd, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(material("coloured").kd_loc.line, 6);
  EXPECT_FALSE(material("bare").kd.has_value());
  EXPECT_FALSE(material("undefined").kd.has_value());
  ASSERT_TRUE(material("unused").kd.has_value());
  // Each triangle points at the material named by the usemtl above it.
  const Names expected{"coloured", "gray", "bare", "undefined"};
  ASSERT_EQ(mesh.triangle_material.size(), 4u);
  for (std::size_t t = 0; t < 4; ++t) {
    ASSERT_GE(mesh.triangle_material[t], 0);
    EXPECT_EQ(mesh.materials[static_cast<std::size_t>(mesh.triangle_material[t])].name, expected[t]) << t;
  }
}

TEST(MeshIoMtl, MtllibAfterUsemtlStillGivesKd) {
  TempDir dir;
  dir.write("late.mtl", "newmtl red\nKd 0.6 0.1 0.1\n");
  const ilp::TriangleMesh mesh =
      ilp::load_mesh(dir.write("late.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\nmtllib late.mtl\n"));
  ASSERT_EQ(mesh.materials.size(), 1u);
  ASSERT_TRUE(mesh.materials[0].kd.has_value());
  EXPECT_EQ(*mesh.materials[0].kd, Eigen::Vector3d(0.6, 0.1, 0.1));
}

TEST(MeshIoMtl, MissingMtlFile) {
  TempDir dir;
  const std::string obj = dir.write("m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib gone.mtl\nf 1 2 3\n");
  expect_mesh_error(obj, obj + ":4:", {"gone.mtl", "cannot open"});
}

// An OBJ whose m.mtl holds `mtl_text`: loading it must fail naming line `line` of
// the MTL and saying `says`.
void expect_mtl_error(const std::string& mtl_text, int line, const std::string& says) {
  TempDir dir;
  const std::string mtl = dir.write("m.mtl", mtl_text);
  const std::string obj = dir.write("m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_mesh_error(obj, mtl + ":" + std::to_string(line) + ":", {says});
}

TEST(MeshIoMtl, BadKdNamesMtlLine) {
  expect_mtl_error("newmtl a\nKd 0.5 0.5 0.5\nnewmtl b\nKd 0.5 abc 0.5\n", 4, "'abc'");
}

TEST(MeshIoMtl, NanKdNamesMtlLine) {
  expect_mtl_error("newmtl a\n\nKd nan\n", 3, "not a finite number");
}

TEST(MeshIoMtl, KdBeforeNewmtl) {
  expect_mtl_error("# header\nKd 0.5 0.5 0.5\nnewmtl a\n", 2, "before any newmtl");
}

// ---------------------------------------------------------------------------------
// OBJ defects

struct BadObj {
  const char* name;
  const char* text;  // the defect is on the last line
  const char* says;
};

void PrintTo(const BadObj& v, std::ostream* os) { *os << v.name; }

class MeshIoBadObj : public ::testing::TestWithParam<BadObj> {};

TEST_P(MeshIoBadObj, NamesFileAndLine) {
  const BadObj& p = GetParam();
  TempDir dir;
  const std::string text = p.text;
  const std::string path = dir.write("bad.obj", text);
  const int line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  expect_mesh_error(path, path + ":" + std::to_string(line) + ": ", {p.says});
}

#define TRI "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

INSTANTIATE_TEST_SUITE_P(
    Defects, MeshIoBadObj,
    ::testing::Values(
        BadObj{"IndexPastEnd", TRI "f 1 2 3\nf 1 2 4\n", "face vertex '4' refers to vertex 4 but only 3 are defined"},
        BadObj{"IndexPastEndWithSlashes", TRI "f 1/1/1 2/2/2 9/3/3\n", "face vertex '9/3/3'"},
        BadObj{"NegativeIndexTooFar", TRI "f -1 -2 -4\n", "face vertex '-4' refers to vertex -4"},
        BadObj{"ForwardReference", "v 0 0 0\nv 1 0 0\nf 1 2 3\n", "only 2 are defined above this line"},
        BadObj{"IndexZero", TRI "f 0 1 2\n", "face vertex '0' is not a valid index"},
        BadObj{"IndexNotANumber", TRI "f 1 2 x\n", "face vertex 'x' is not a valid index"},
        BadObj{"FaceTooShort", TRI "f 1 2\n", "face needs at least 3 vertices"},
        BadObj{"VertexTooShort", TRI "v 1 2\n", "vertex needs 3 coordinates"},
        BadObj{"VertexNan", "v 0 0 0\nv 0 nan 0\n", "vertex coordinate 'nan' is not a finite number"},
        BadObj{"VertexInf", "v 0 0 0\nv inf 0 0\n", "vertex coordinate 'inf' is not a finite number"},
        BadObj{"VertexNotANumber", "v 0 0 0\nv 0 0 1,5\n", "vertex coordinate '1,5' is not a number"}),
    [](const ::testing::TestParamInfo<BadObj>& info) { return std::string(info.param.name); });

#undef TRI

TEST(MeshIoErrors, UppercaseObjExtensionIsAccepted) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("MESH.OBJ", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  EXPECT_EQ(mesh.triangles.size(), 1u);
}

// ---------------------------------------------------------------------------------
// Files refused as a whole (OBJ, and PLY and OFF through OpenMesh)

struct BadFile {
  const char* name;
  const char* file;   // written into the test's folder
  const char* text;   // content of `file`; nullptr: `file` is looked for in a folder that does not exist
  const char* after;  // the message starts with the path and then this; nullptr: its start is not checked
  std::vector<std::string> says;  // texts the message must contain
};

void PrintTo(const BadFile& v, std::ostream* os) { *os << v.name; }

class MeshIoBadFile : public ::testing::TestWithParam<BadFile> {};

TEST_P(MeshIoBadFile, NamesTheFile) {
  const BadFile& p = GetParam();
  TempDir dir;
  const std::string path =
      p.text ? dir.write(p.file, p.text)
             : (fs::temp_directory_path() / "ilp_mesh_io_test_no_such_dir" / p.file).string();
  const std::string msg = mesh_error(path);
  if (p.after) {
    EXPECT_TRUE(StartsWith(msg, path + p.after));
  }
  for (const std::string& part : p.says) EXPECT_TRUE(Contains(msg, part));
}

INSTANTIATE_TEST_SUITE_P(
    MeshIoErrors, MeshIoBadFile,
    ::testing::Values(
        BadFile{"MissingObj", "x.obj", nullptr, ": ", {"cannot open mesh file"}},
        BadFile{"ObjWithNoFaces", "verts.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ng floor\n", ": ", {"no faces"}},
        BadFile{"EmptyObj", "empty.obj", "", nullptr, {"no faces"}},
        BadFile{"UnsupportedExtension", "mesh.stl", "solid x\nendsolid x\n", ": ",
                {"unsupported mesh format '.stl'", ".obj, .ply, .off, .gltf, .glb, .3ds, .dae, .fbx or .ifc"}},
        BadFile{"NoExtension", "mesh", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", nullptr,
                {"unsupported mesh format ''"}}),
    [](const ::testing::TestParamInfo<BadFile>& info) { return std::string(info.param.name); });

INSTANTIATE_TEST_SUITE_P(
    MeshIoOpenMesh, MeshIoBadFile,
    ::testing::Values(
        BadFile{"MissingFile", "x.ply", nullptr, ": ", {"cannot open mesh file"}},
        BadFile{"GarbagePly", "junk.ply", "this is not a ply file\n", ": ", {"could not read"}},
        BadFile{"OffWithNoFaces", "points.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n", ": ", {"no faces"}},
        // OpenMesh drops a face with an out-of-range index without a word, and makes up
        // a face (a copy of the previous one) when the file ends early: the loader checks
        // the header's counts to catch both.
        BadFile{"OffFaceIndexOutOfRangeIsAnError", "bad.off",
                "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 9\n", "", {}},
        BadFile{"TruncatedOffIsAnError", "short.off",
                "OFF\n4 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n", "", {}},
        BadFile{"OffNanCoordinateIsNamed", "nan.off", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "",
                {"finite"}}),  // today: "the mesh has no faces"
    [](const ::testing::TestParamInfo<BadFile>& info) { return std::string(info.param.name); });

// ---------------------------------------------------------------------------------
// PLY and OFF (OpenMesh)

const char* kSquareOff =
    "OFF\n"
    "4 1 0\n"
    "0 0 0\n"
    "1 0 0\n"
    "1 1 0\n"
    "0 1 0\n"
    "4 0 1 2 3\n";

void expect_unit_square(const ilp::TriangleMesh& mesh, const std::string& path, const std::string& stem) {
  EXPECT_EQ(mesh.path, path);
  ASSERT_EQ(mesh.positions.size(), 4u);
  EXPECT_EQ(mesh.positions[0], Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(mesh.positions[1], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(mesh.positions[2], Eigen::Vector3d(1, 1, 0));
  EXPECT_EQ(mesh.positions[3], Eigen::Vector3d(0, 1, 0));
  EXPECT_EQ(mesh.faces_read, 1u);
  EXPECT_EQ(mesh.polygons_split, 1u);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(mesh.surface_names, (Names{stem}));
  EXPECT_EQ(mesh.triangle_surface, (std::vector<int>{0, 0}));
  EXPECT_EQ(mesh.triangle_material, (std::vector<int>{-1, -1}));
  EXPECT_TRUE(mesh.materials.empty());
}

TEST(MeshIoOpenMesh, OffQuad) {
  TempDir dir;
  const std::string path = dir.write("square.off", kSquareOff);
  expect_unit_square(ilp::load_mesh(path), path, "square");
}

TEST(MeshIoOpenMesh, OffUppercaseExtension) {
  TempDir dir;
  const std::string path = dir.write("Floor.OFF", kSquareOff);
  expect_unit_square(ilp::load_mesh(path), path, "Floor");
}

TEST(MeshIoOpenMesh, PlyQuad) {
  TempDir dir;
  const std::string path = dir.write("tile.ply",
                                     "ply\n"
                                     "format ascii 1.0\n"
                                     "comment unit square\n"
                                     "element vertex 4\n"
                                     "property float x\n"
                                     "property float y\n"
                                     "property float z\n"
                                     "element face 1\n"
                                     "property list uchar int vertex_indices\n"
                                     "end_header\n"
                                     "0 0 0\n"
                                     "1 0 0\n"
                                     "1 1 0\n"
                                     "0 1 0\n"
                                     "4 0 1 2 3\n");
  expect_unit_square(ilp::load_mesh(path), path, "tile");
}

TEST(MeshIoOpenMesh, PlyPentagonAndTriangle) {
  TempDir dir;
  const std::string path = dir.write("shapes.ply",
                                     "ply\n"
                                     "format ascii 1.0\n"
                                     "element vertex 6\n"
                                     "property float x\n"
                                     "property float y\n"
                                     "property float z\n"
                                     "element face 2\n"
                                     "property list uchar int vertex_indices\n"
                                     "end_header\n"
                                     "0 0 0\n"
                                     "1 0 0\n"
                                     "1 1 0\n"
                                     "0.5 1.5 0\n"
                                     "0 1 0\n"
                                     "2 0 0\n"
                                     "5 0 1 2 3 4\n"
                                     "3 1 5 2\n");
  const ilp::TriangleMesh mesh = ilp::load_mesh(path);
  EXPECT_EQ(mesh.faces_read, 2u);
  EXPECT_EQ(mesh.polygons_split, 1u);
  ASSERT_EQ(mesh.triangles.size(), 4u);
  EXPECT_EQ(mesh.triangles[0], Eigen::Vector3i(0, 1, 2));
  EXPECT_EQ(mesh.triangles[1], Eigen::Vector3i(0, 2, 3));
  EXPECT_EQ(mesh.triangles[2], Eigen::Vector3i(0, 3, 4));
  EXPECT_EQ(mesh.triangles[3], Eigen::Vector3i(1, 5, 2));
  EXPECT_EQ(mesh.surface_names, (Names{"shapes"}));
}

// Three triangles sharing one edge cannot all live in OpenMesh's halfedge mesh; its
// importer then duplicates vertices. No face may be lost on the way.
TEST(MeshIoOpenMesh, NonManifoldEdgeKeepsEveryFace) {
  TempDir dir;
  const std::string path = dir.write("fin.off",
                                     "OFF\n"
                                     "5 3 0\n"
                                     "0 0 0\n"
                                     "1 0 0\n"
                                     "0 1 0\n"
                                     "0 -1 0\n"
                                     "0 0 1\n"
                                     "3 0 1 2\n"
                                     "3 0 1 3\n"
                                     "3 0 1 4\n");
  const ilp::TriangleMesh mesh = ilp::load_mesh(path);
  ASSERT_EQ(mesh.triangles.size(), 3u);
  const std::vector<Eigen::Vector3d> third_vertex{{0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  for (std::size_t t = 0; t < 3; ++t) {
    const Eigen::Vector3i& tri = mesh.triangles[t];
    EXPECT_EQ(mesh.positions.at(static_cast<std::size_t>(tri[0])), Eigen::Vector3d(0, 0, 0)) << t;
    EXPECT_EQ(mesh.positions.at(static_cast<std::size_t>(tri[1])), Eigen::Vector3d(1, 0, 0)) << t;
    EXPECT_EQ(mesh.positions.at(static_cast<std::size_t>(tri[2])), third_vertex[t]) << t;
  }
}

}  // namespace
