// Bad input that once crashed ilp, changed the job silently or gave a misleading
// message (issue 13, docs/reliability.md): each is now an error naming the file, the
// line and the key, or the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "job/config.h"
#include "job/plan.h"
#include "core/base/error.h"
#include "job/job_scene.h"
#include "core/scene/mesh.h"
#include "core/scene/scene.h"
#include "tests/core/config_room.h"
#include "tests/test_support.h"

namespace {

namespace fs = std::filesystem;
using ilp::test::Contains;
using ilp::test::error_of;
using ilp::test::TempDir;

using ilp::test::config_error;
using ilp::test::kRoomObj;
const std::string kScene = ilp::test::kRoomScene;

// The message names the file, the line and the key (file:line:column: key = value: rule).
void expect_located(const std::string& message, const TempDir& dir, int line, const std::string& key,
                    const std::string& rule) {
  EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":" + std::to_string(line) + ":"));
  EXPECT_TRUE(Contains(message, key));
  EXPECT_TRUE(Contains(message, rule));
}

struct Bound {
  const char* name;
  std::string yaml;  // the config after kScene
  int line;          // of the bad value
  const char* key;
  const char* rule;
};

void PrintTo(const Bound& b, std::ostream* os) { *os << b.name; }

class ReliabilityConfigBound : public ::testing::TestWithParam<Bound> {};

// Each was accepted before and overflowed later: an Embree assertion (size 1e200), an
// infinite exitance reported at a patch without a line (flux 1e308, size 1e-200),
// "non-finite value -nan" (scale 1e37), a silent 14-patch room (edge 1e-12), a
// 4-candidate grid (spacing 1e-12), a float-to-int overflow in the search's deadline
// (max_seconds 1e300).
TEST_P(ReliabilityConfigBound, IsRefusedWithFileLineAndKey) {
  const Bound& b = GetParam();
  TempDir dir;
  expect_located(config_error(dir, kScene + b.yaml), dir, b.line, b.key, b.rule);
}

const std::string kPlaced = "luminaires:\n  size_m: 0.3\n  placed:\n    - {name: L1, position_m: [2, 2, 2.4], flux_lm: 100}\n";
const std::string kGoals = "goals:\n  - surface: floor\n    average_lux: 100\n";
const std::string kSearch =
    "luminaires:\n  size_m: 0.3\n  mounting_surface: ceiling\n  flux_lm: [10, 1000]\n" + kGoals;

INSTANTIATE_TEST_SUITE_P(
    Reliability, ReliabilityConfigBound,
    ::testing::Values(
        Bound{"HugeLuminaireSize", "luminaires:\n  size_m: 1e200\n", 5, "luminaires.size_m = 1e200", "at most 100 m"},
        Bound{"TinyLuminaireSize", "luminaires:\n  size_m: 1e-200\n", 5, "luminaires.size_m = 1e-200",
              "at least 0.001 m"},
        Bound{"HugePlacedFlux", "luminaires:\n  placed:\n    - {name: L1, position_m: [2, 2, 2.4], flux_lm: 1e308}\n", 6,
              "luminaires.placed[0].flux_lm = 1e308", "at most 1e+09 lm"},
        Bound{"HugeSearchFlux", "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [10, 1e308]\n", 6,
              "luminaires.flux_lm[1] = 1e308", "at most 1e+09 lm"},
        Bound{"HugeExitance", "  emitting_surfaces:\n    - {surface: ceiling, exitance_lm_per_m2: 1e300}\n", 5,
              "exitance_lm_per_m2 = 1e300", "at most 1e+09 lm/m²"},
        Bound{"HugeScale", "  scale_to_m: 1e37\n", 4, "scene.scale_to_m = 1e37", "at most 1e+06"},
        Bound{"TinyScale", "  scale_to_m: 1e-300\n", 4, "scene.scale_to_m = 1e-300", "at least 1e-06"},
        Bound{"TinyPatchEdge", "  max_patch_edge_m: 1e-12\n", 4, "scene.max_patch_edge_m = 1e-12", "at least 0.0001 m"},
        Bound{"TinyCandidateSpacing",
              "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [10, 1000]\n  candidate_spacing_m: 1e-12\n" + kGoals, 7,
              "luminaires.candidate_spacing_m = 1e-12", "at least 0.001 m"},
        Bound{"HugeMinDistance", kSearch + "constraints:\n  min_distance_m: 1e300\n", 12,
              "constraints.min_distance_m = 1e300", "at most 100000 m"},
        Bound{"HugeEfficacy",
              "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [10, 1000]\n  efficacy_lm_per_w: 1e9\n" + kGoals, 7, "luminaires.efficacy_lm_per_w", "at most 1000"},
        Bound{"HugeMaxSeconds", kSearch + "optimizer:\n  max_seconds: 1e300\n", 12, "optimizer.max_seconds = 1e300",
              "at most 1e+07 s"},
        Bound{"HugeGoalTarget",
              "luminaires:\n  size_m: 0.3\n  mounting_surface: ceiling\n  flux_lm: [10, 1000]\n"
              "goals:\n  - surface: floor\n    average_lux: 1e300\n",
              10, "average_lux = 1e300", "at most 1e+07 lx"},
        Bound{"HugeArraySpacing",
              "luminaires:\n  mounting_surface: ceiling\n  flux_lm: [10, 1000]\n  layout: array\n"
              "  array: {rows: 2, columns: 2, spacing_m: [1e300, 1]}\n",
              8, "spacing_m[0] = 1e300", "at most 1e+05 m"}),
    [](const ::testing::TestParamInfo<Bound>& info) { return std::string(info.param.name); });

TEST(ReliabilityConfig, SecondYamlDocumentIsRefused) {
  TempDir dir;
  const std::string message = config_error(dir, kScene + kPlaced + "---\nscene:\n  mesh: other.obj\n");
  EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":8:"));  // the --- line
  EXPECT_TRUE(Contains(message, "second YAML document"));
}

// yaml-cpp stops at a NUL byte, and reading every document then looped for ever
// (found by config_fuzz).
TEST(ReliabilityConfig, NulByteIsRefusedWithItsLine) {
  TempDir dir;
  std::string text = kScene;  // appended: GCC 12 warns falsely (-Wrestrict) on string + string&&
  text.append(std::string("\0\0ification:\n", 14));
  const std::string message = config_error(dir, text);
  EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ":4:"));
  EXPECT_TRUE(Contains(message, "NUL byte"));
}

TEST(ReliabilityConfig, FolderAsConfigIsNamed) {
  TempDir dir;
  fs::create_directories(dir.file("job.yaml"));
  const std::string message =
      error_of<ilp::ConfigError>([&] { (void)ilp::load_job_config(dir.file("job.yaml")); }, "load_job_config");
  EXPECT_TRUE(Contains(message, dir.file("job.yaml") + ": is a folder, not a config file"));
}

// ---------------------------------------------------------------------------------
// Meshes

std::string mesh_error(const std::string& path) {
  return error_of<ilp::SceneError>([&] { (void)ilp::load_mesh(path, {}); }, "load_mesh(" + path + ")");
}

TEST(ReliabilityMesh, FolderAsMeshIsNamed) {
  TempDir dir;
  for (const char* name : {"room.obj", "room.ply", "room.off"}) {
    fs::create_directories(dir.file(name));
    EXPECT_TRUE(Contains(mesh_error(dir.file(name)), dir.file(name) + ": is a folder, not a mesh file")) << name;
  }
}

TEST(ReliabilityMesh, FolderAsMtllibIsNamedWithTheObjLine) {
  TempDir dir;
  fs::create_directories(dir.file("room.mtl"));
  const std::string obj = dir.write("room.obj", std::string("# exported\nmtllib room.mtl\n") + kRoomObj);
  const std::string message = mesh_error(obj);
  EXPECT_TRUE(Contains(message, obj + ":2:"));
  EXPECT_TRUE(Contains(message, "is a folder, not a material file"));
}

TEST(ReliabilityMesh, ByteOrderMarkBeforeMtllibStillReadsTheMaterials) {
  TempDir dir;
  dir.write("room.mtl", "\xEF\xBB\xBFnewmtl white\nKd 0.8 0.8 0.8\n");
  const std::string obj = dir.write("room.obj", std::string("\xEF\xBB\xBFmtllib room.mtl\nusemtl white\n") + kRoomObj);
  const ilp::TriangleMesh mesh = ilp::load_mesh(obj, {});
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_EQ(mesh.materials[0].name, "white");
  ASSERT_TRUE(mesh.materials[0].kd.has_value());
  EXPECT_DOUBLE_EQ((*mesh.materials[0].kd)[0], 0.8);
}

struct BadHeader {
  const char* name;
  const char* file;
  std::string text;
  std::vector<std::string> says;
};

void PrintTo(const BadHeader& b, std::ostream* os) { *os << b.name; }

class ReliabilityMeshHeader : public ::testing::TestWithParam<BadHeader> {};

// Each once ended in std::bad_alloc (no file named) or was read with a made-up face.
TEST_P(ReliabilityMeshHeader, IsAnErrorNamingTheFile) {
  const BadHeader& b = GetParam();
  TempDir dir;
  const std::string path = dir.write(b.file, b.text);
  const std::string message = mesh_error(path);
  EXPECT_TRUE(Contains(message, path));
  for (const std::string& part : b.says) EXPECT_TRUE(Contains(message, part));
}

const std::string kPlyHead = "ply\nformat ascii 1.0\n";
const std::string kPlyProps =
    "property float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
    "end_header\n";

INSTANTIATE_TEST_SUITE_P(
    Reliability, ReliabilityMeshHeader,
    ::testing::Values(
        BadHeader{"PlyHugeVertexCount", "big.ply", kPlyHead + "element vertex 3000000000\n" + kPlyProps + "0 0 0\n",
                  {":3:", "3000000000 vertexs", "bytes"}},
        BadHeader{"PlyNegativeVertexCount", "neg.ply", kPlyHead + "element vertex -5\n" + kPlyProps,
                  {":3:", "'-5' is not a whole number >= 0"}},
        BadHeader{"BinaryPlyHugeVertexCount", "big_bin.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 100000\n" + kPlyProps + "abcdefgh",
                  {"bytes", "truncated"}},
        BadHeader{"TruncatedAsciiPly", "short.ply",
                  kPlyHead + "element vertex 3\n" + kPlyProps + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
                  {":13:", "face 0 has 3 values", "call for 4"}},
        BadHeader{"AsciiPlyEndingEarly", "shorter.ply", kPlyHead + "element vertex 3\n" + kPlyProps + "0 0 0\n1 0 0\n",
                  {"ends after 2 of the 3 vertex lines"}},
        // OpenMesh printed "Unsupported keyword" for ever on these (found by ply_off_fuzz).
        BadHeader{"PlyHeaderWithUnknownKeyword", "odd.ply", "ply\nformat ascii 1.0\nelement vertex 3\npr3\n",
                  {":4:", "unknown PLY header keyword 'pr3'"}},
        BadHeader{"PlyHeaderWithoutEnd", "open.ply", "ply\nformat ascii 1.0\nelement vertex 0\n", {"no end_header"}},
        BadHeader{"PlyUnknownPropertyType", "type.ply", kPlyHead + "element vertex 1\nproperty quad x\nend_header\n0\n",
                  {":4:", "property must"}},
        // OpenMesh reserved whatever it made of these (found by ply_off_fuzz).
        BadHeader{"OffGarbageAfterTheKeyword", "junk.off", std::string("OFF\0plyf\n\n111111q111\n", 22),
                  {"not an OFF file"}},
        BadHeader{"OffCountsNotNumbers", "words.off", "OFF\n1111q11 1 0\n", {":2:", "'1111q11' is not a whole number"}},
        BadHeader{"OffCountsOnTheKeywordLine", "same.off", "OFF 0\n1 -10\n0 1  1\nH", {":1:", "alone on its line"}},
        BadHeader{"BinaryOff", "bin.off", "OFF BINARY\n\x01\x02", {"binary OFF is not read"}},
        BadHeader{"OffHugeVertexCount", "big.off", "OFF\n3000000000 1 0\n0 0 0\n", {":2:", "3000000000", "bytes"}},
        BadHeader{"OffNegativeVertexCount", "neg.off", "OFF\n-5 1 0\n", {":2:", "'-5' is not a whole number >= 0"}},
        BadHeader{"OffTruncatedFace", "short.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1\n",
                  {":6:", "fewer vertex indices"}},
        // OpenMesh reads PLY and OFF word by word, with no comments: a '#' glued to
        // end_header left its header parser looping for ever (found by ply_off_fuzz; the
        // check had dropped everything from '#' on, as in OBJ).
        BadHeader{"PlyEndHeaderWithHash", "hash.ply", kPlyHead + "element vertex 3\n" + kPlyProps.substr(0, kPlyProps.size() - 11) +
                                                          "end_header#\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
                  {":9:", "unknown PLY header keyword 'end_header#'"}},
        BadHeader{"PlyEndHeaderNotAlone", "tail.ply", kPlyHead + "element vertex 0\nend_header 7\n", {":4:", "alone"}},
        // Where OpenMesh's word-by-word reading and the line-by-line check part ways, a
        // later number becomes a face's vertex count: 4e9 push_backs, memory exhausted.
        BadHeader{"PlyListInVertexElement", "vlist.ply",
                  kPlyHead + "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                             "property list uchar int foo\nelement face 1\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0 1 4000000000\n3 0 0 0\n",
                  {":7:", "list property 'foo' of element 'vertex'"}},
        BadHeader{"PlyFacePropertyBeforeVertexIndices", "flags.ply",
                  kPlyHead + "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
                             "end_header\n0 0 0\n1 0 0\n0 1 0\n4000000000 3 0 1 2\n",
                  {":9:", "vertex_indices must be the face element's first property"}},
        BadHeader{"PlySecondFaceElement", "faces2.ply",
                  kPlyHead + "element vertex 3\n" + kPlyProps.substr(0, kPlyProps.size() - 11) +
                      "element face 5\nproperty uint q\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n4000000000\n2\n3\n4\n5\n",
                  {":9:", "a second 'face' element"}},
        BadHeader{"BinaryPlyListCountBeyondTheFile", "count.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n" +
                      std::string(36, '\0') + std::string("\xff\xff\xff\x7f\0\0\0\0\x01\0\0\0\x02\0\0\0", 16),
                  {"face 0 has a list of 2147483647 values", "bytes left"}},
        // OpenMesh reads binary coordinates as 4-byte floats: a uint8 x shifted the faces,
        // whose vertex count then read 2^31 - 1 and filled memory (found by ply_off_fuzz).
        BadHeader{"BinaryPlyCoordinateNotAFloat", "uint8_x.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty uint8 x\nproperty float y\n"
                  "property float z\nelement face 2\nproperty list int int vertex_indices\nend_header\n" +
                      std::string(24, '\0') + std::string("\x02\0\0\0\0\0\0\0\0\0\0\0\xff\xff\xff\x7f\0\0\0\0\x01\0\0\0\x02\0\0;\0", 29),
                  {":4:", "vertex property 'x' is 'uint8'", "float"}},
        BadHeader{"BinaryPlyNegativeListCount", "neg_count.ply",
                  "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n" +
                      std::string(36, '\0') + std::string("\xff\xff\xff\xfd\0\0\0\0\0\0\0\x01\0\0\0\x02", 16),
                  {"face 0 has a list of -3 values"}},
        // OpenMesh takes the binary body to start 12 bytes after the last header word; a
        // comment there moved it by a byte and the mesh was read from shifted bytes.
        BadHeader{"BinaryPlyCommentBeforeEndHeader", "shifted.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                  "property float z\nelement face 1\nproperty list uchar int vertex_indices\ncomment last\nend_header\n" +
                      std::string(36, '\0') + std::string("\x03\0\0\0\0\x01\0\0\0\x02\0\0\0", 13),
                  {"end_header must directly follow"}},
        BadHeader{"OffVertexLineShortOfValues", "vshort.off", "OFF\n2 1 0\n0 0\n0 1 0 0\n3 0 1 1\n4000000000\n",
                  {":3:", "vertex 0 has 2 values, fewer than the 3"}},
        BadHeader{"OffCountsWithoutTheEdgeCount", "noedge.off",
                  "OFF\n3 2\n0 0 0 1\n1 0 0\n0 1 0\n4000000000 0 0\n3 0 1 2\n3 0 1 2\n",
                  {":2:", "counts alone (found 2 values)"}},
        BadHeader{"OffFaceColourWithoutCoff", "colour.off",
                  "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 4000000000\n3 0 1 2\n",
                  {":6:", "face 0 has values after its 3 vertex indices", "COFF"}},
        BadHeader{"OffFaceIndexNotAVertex", "index.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n",
                  {":6:", "vertex index '7' is not one of the 3 vertices"}}),
    [](const ::testing::TestParamInfo<BadHeader>& info) { return std::string(info.param.name); });

// A vertex at 5e11 made float ray origins and patch counts overflow without a word.
TEST(ReliabilityMesh, VertexFarFromTheOriginIsRefused) {
  TempDir dir;
  dir.write("room.obj", std::string(kRoomObj) + "v 5e11 0 0\nv 5e11 1 0\nv 5e11 0 1\ng far\nf 9 10 11\n");
  const std::string path = dir.write("job.yaml", kScene + "  max_patch_edge_m: 0.5\n");
  const ilp::JobConfig job = ilp::load_job_config(path);
  const std::string message = error_of<ilp::SceneError>([&] { (void)ilp::load_job_scene(scene_spec(job)); }, "load_job_scene");
  EXPECT_TRUE(Contains(message, path + ":2:"));  // scene.mesh
  EXPECT_TRUE(Contains(message, "vertex 9 lies at"));
  EXPECT_TRUE(Contains(message, "beyond the 1e+06 m"));
}

// The cast of ceil(edge / 1e-12) to int overflowed and meshed the room as 14 patches.
TEST(ReliabilityMesh, TinyPatchEdgeIsAPatchLimitNotAnOverflow) {
  TempDir dir;
  const ilp::TriangleMesh mesh = ilp::load_mesh(dir.write("room.obj", kRoomObj), {});
  ilp::SceneOptions options;
  options.max_patch_edge_m = 1e-12;
  const ilp::TriangleReflectance rho(mesh.triangles.size(), Eigen::Vector3d::Constant(0.5));
  const std::string message = error_of<ilp::PatchLimitError>([&] { (void)ilp::make_scene(mesh, rho, options); });
  EXPECT_TRUE(Contains(message, "would make more than 5000000 patches"));
}

TEST(ReliabilityJob, ReportSurfaceLeftOutIsAnError) {
  TempDir dir;
  dir.write("room.obj", kRoomObj);
  const std::string path = dir.write(
      "job.yaml", kScene + "  exclude_surfaces: [floor]\n" + kPlaced + "report:\n  surfaces: [walls, floor]\n");
  const ilp::JobConfig job = ilp::load_job_config(path);
  const std::string message = error_of<ilp::ConfigError>([&] { (void)ilp::load_job_scene(scene_spec(job)); }, "load_job_scene");
  EXPECT_TRUE(Contains(message, path + ":10:"));
  EXPECT_TRUE(Contains(message, "report.surfaces: surface 'floor' has no patch left"));
}

TEST(ReliabilityJob, GoalSurfaceLeftOutIsAnError) {
  TempDir dir;
  dir.write("room.obj", kRoomObj);
  const std::string path = dir.write("job.yaml", kScene + "  exclude_surfaces: [floor]\n" + kSearch);
  const ilp::JobConfig job = ilp::load_job_config(path);
  const std::string message = error_of<ilp::ConfigError>([&] { (void)ilp::load_job_scene(scene_spec(job)); }, "load_job_scene");
  EXPECT_TRUE(Contains(message, "goals."));
  EXPECT_TRUE(Contains(message, "surface 'floor' has no patch left"));
}

}  // namespace
