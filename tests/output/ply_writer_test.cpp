// PLY export of illuminance: the header and the binary body read back byte by byte
// (independently of the writer), NaN lux, the input check, and OpenMesh (through
// load_mesh) reading the file.
#include "output/ply_writer.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/scene/mesh.h"
#include "tests/test_support.h"

namespace ilp {
namespace {

using test::read_file;
using test::TempDir;
using V = Eigen::Vector3d;

Patch triangle(const V& a, const V& b, const V& c) {
  Patch p;
  p.vertices_m = {a, b, c};
  p.centroid_m = (a + b + c) / 3.0;
  p.normal = (b - a).cross(c - a).normalized();
  p.area_m2 = 0.5 * (b - a).cross(c - a).norm();
  p.surface = 0;
  return p;
}

// Two patches: a floor triangle and one above it, with coordinates floats cannot hold
// exactly (0.1, -0.3).
Scene two_patches() {
  Scene scene;
  scene.surfaces.push_back({"floor"});
  scene.patches.push_back(triangle(V(0, 0, 0), V(1, 0, 0), V(0.1, 2.5, 0)));
  scene.patches.push_back(triangle(V(1, 0, -0.3), V(1, 1, -0.3), V(0, 1, -0.3)));
  for (const Patch& p : scene.patches)
    for (const V& v : p.vertices_m) scene.bounds_m.extend(v);
  return scene;
}

// Little-endian reads from the body, independent of the host's byte order.
struct Reader {
  const std::string& bytes;
  std::size_t at = 0;

  std::uint8_t u8() { return static_cast<std::uint8_t>(bytes.at(at++)); }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int shift = 0; shift < 32; shift += 8) v |= static_cast<std::uint32_t>(u8()) << shift;
    return v;
  }
  float f32() { return std::bit_cast<float>(u32()); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
};

struct Rgb {
  int r, g, b;
  bool operator==(const Rgb&) const = default;
};

Rgb bytes_of(const Eigen::Vector3d& c) {
  return {static_cast<int>(std::lround(c[0] * 255)), static_cast<int>(std::lround(c[1] * 255)),
          static_cast<int>(std::lround(c[2] * 255))};
}

std::ostream& operator<<(std::ostream& os, const Rgb& c) { return os << c.r << ' ' << c.g << ' ' << c.b; }

TEST(PlyWriter, HeaderAndBinaryBodyReadBack) {
  TempDir dir;
  const std::string path = dir.file("lux.ply");
  const Scene scene = two_patches();
  Eigen::VectorXd lux(2);
  lux << 250.0, std::numeric_limits<double>::quiet_NaN();
  write_illuminance_ply(path, scene, lux, ColourScale{0.0, 500.0});
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));

  const std::string file = read_file(path);
  const std::size_t header_end = file.find("end_header\n");
  ASSERT_NE(header_end, std::string::npos);
  std::vector<std::string> header;
  std::istringstream lines(file.substr(0, header_end + 11));
  for (std::string line; std::getline(lines, line);) header.push_back(line);
  const std::vector<std::string> expected = {"ply",
                                             "format binary_little_endian 1.0",
                                             "comment ilp illuminance, lux from 0 to 500",
                                             "element vertex 6",
                                             "property float x",
                                             "property float y",
                                             "property float z",
                                             "property uchar red",
                                             "property uchar green",
                                             "property uchar blue",
                                             "element face 2",
                                             "property list uchar int vertex_indices",
                                             "property uchar red",
                                             "property uchar green",
                                             "property uchar blue",
                                             "property float lux",
                                             "end_header"};
  EXPECT_EQ(header, expected);

  const std::string body = file.substr(header_end + 11);
  ASSERT_EQ(body.size(), 6u * (3 * 4 + 3) + 2u * (1 + 3 * 4 + 3 + 4));
  Reader in{body};
  const Rgb half = bytes_of(colour_map(0.5)), grey{128, 128, 128};
  const std::vector<Rgb> face_colour = {half, grey};
  for (std::size_t p = 0; p < 2; ++p)
    for (const V& v : scene.patches[p].vertices_m) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(in.f32(), static_cast<float>(v[c])) << "patch " << p << " axis " << c;
      const Rgb colour{in.u8(), in.u8(), in.u8()};
      EXPECT_EQ(colour, face_colour[p]) << "patch " << p;
    }
  for (int p = 0; p < 2; ++p) {
    EXPECT_EQ(in.u8(), 3);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(in.i32(), 3 * p + k);
    const Rgb colour{in.u8(), in.u8(), in.u8()};
    EXPECT_EQ(colour, face_colour[p]) << "face " << p;
    const float value = in.f32();
    if (p == 0) EXPECT_EQ(value, 250.0f);
    else EXPECT_TRUE(std::isnan(value));
  }
  EXPECT_EQ(in.at, body.size());
}

TEST(PlyWriter, ColoursSpanTheGivenScale) {
  TempDir dir;
  const std::string path = dir.file("lux.ply");
  Eigen::VectorXd lux(2);
  lux << 100.0, 900.0;  // the scale's minimum, and beyond its maximum
  write_illuminance_ply(path, two_patches(), lux, ColourScale{100.0, 600.0});
  const std::string file = read_file(path);
  EXPECT_NE(file.find("comment ilp illuminance, lux from 100 to 600\n"), std::string::npos);
  const std::string body = file.substr(file.find("end_header\n") + 11);
  Reader in{body};
  in.at = 12;  // first vertex's colour
  EXPECT_EQ((Rgb{in.u8(), in.u8(), in.u8()}), (Rgb{0x44, 0x01, 0x54}));
  in.at = 3 * 15 + 12;  // fourth vertex, the second patch
  EXPECT_EQ((Rgb{in.u8(), in.u8(), in.u8()}), (Rgb{0xfd, 0xe7, 0x25}));
}

TEST(PlyWriter, OpenMeshReadsIt) {
  TempDir dir;
  const std::string path = dir.file("lux.ply");
  const Scene scene = two_patches();
  write_illuminance_ply(path, scene, Eigen::VectorXd::Constant(2, 42.0), ColourScale{0.0, 50.0});
  const TriangleMesh mesh = load_mesh(path);
  ASSERT_EQ(mesh.positions.size(), 6u);
  ASSERT_EQ(mesh.triangles.size(), 2u);
  for (int p = 0; p < 2; ++p) {
    EXPECT_EQ(mesh.triangles[p], Eigen::Vector3i(3 * p, 3 * p + 1, 3 * p + 2));
    for (int k = 0; k < 3; ++k)
      EXPECT_TRUE(mesh.positions[3 * p + k].isApprox(scene.patches[p].vertices_m[k], 1e-6))
          << mesh.positions[3 * p + k].transpose();
  }
}

TEST(PlyWriter, RejectsAWrongLuxCountAndReportsUnwritablePaths) {
  TempDir dir;
  const std::string path = dir.file("lux.ply");
  EXPECT_THROW(write_illuminance_ply(path, two_patches(), Eigen::VectorXd::Zero(3), ColourScale{}),
               std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_THROW(write_illuminance_ply(dir.file("missing/lux.ply"), two_patches(), Eigen::VectorXd::Zero(2), ColourScale{}),
               IlpError);
}

}  // namespace
}  // namespace ilp
