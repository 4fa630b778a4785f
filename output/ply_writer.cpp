#include "output/ply_writer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/atomic_file.h"

namespace ilp {
namespace {

// Shortest text that reads back as v, independent of the locale: "0", "500", "2.5".
std::string shortest(double v) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), v);
  return std::string(buffer.data(), result.ptr);
}

// Appends the bytes of a 32-bit value, least significant first, whatever the host's
// byte order.
void put_u32(std::string& out, std::uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out += static_cast<char>((v >> shift) & 0xFFu);
}

void put_float(std::string& out, double v) { put_u32(out, std::bit_cast<std::uint32_t>(static_cast<float>(v))); }

void put_int(std::string& out, int v) { put_u32(out, static_cast<std::uint32_t>(v)); }

std::array<char, 3> rgb_bytes(const Eigen::Vector3d& rgb) {
  std::array<char, 3> bytes{};
  for (int c = 0; c < 3; ++c)
    bytes[c] = static_cast<char>(static_cast<unsigned char>(std::lround(std::clamp(rgb[c], 0.0, 1.0) * 255.0)));
  return bytes;
}

}  // namespace

void write_illuminance_ply(const std::string& path, const Scene& scene, const Eigen::VectorXd& lux_per_patch,
                           const ColourScale& scale) {
  const std::size_t n = scene.patches.size();
  if (static_cast<std::size_t>(lux_per_patch.size()) != n)
    throw std::invalid_argument(path + ": " + std::to_string(lux_per_patch.size()) + " lux values for " +
                                std::to_string(n) + " patches");
  if (3 * n > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::invalid_argument(path + ": too many patches for a PLY with int vertex indices");

  const std::string header = "ply\n"
                             "format binary_little_endian 1.0\n"
                             "comment ilp illuminance, lux from " + shortest(scale.min_lux) + " to " +
                             shortest(scale.max_lux) + "\n"
                             "element vertex " + std::to_string(3 * n) + "\n"
                             "property float x\n"
                             "property float y\n"
                             "property float z\n"
                             "property uchar red\n"
                             "property uchar green\n"
                             "property uchar blue\n"
                             "element face " + std::to_string(n) + "\n"
                             "property list uchar int vertex_indices\n"
                             "property uchar red\n"
                             "property uchar green\n"
                             "property uchar blue\n"
                             "property float lux\n"
                             "end_header\n";

  std::vector<std::array<char, 3>> colours(n);
  for (std::size_t i = 0; i < n; ++i)
    colours[i] = rgb_bytes(colour_map(scale.fraction(lux_per_patch[static_cast<Eigen::Index>(i)])));

  write_file_atomically(path, [&](std::ostream& out) {
    out << header;
    // The body goes through a buffer of about 1 MB: byte order and float conversion
    // are done here rather than by the stream, and a large scene is never held whole.
    std::string buffer;
    const auto flush_if_full = [&](bool last) {
      if (!last && buffer.size() < (1u << 20)) return;
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    };
    for (std::size_t i = 0; i < n; ++i) {
      for (const Eigen::Vector3d& v : scene.patches[i].vertices_m) {
        for (int c = 0; c < 3; ++c) put_float(buffer, v[c]);
        buffer.append(colours[i].data(), 3);
      }
      flush_if_full(false);
    }
    for (std::size_t i = 0; i < n; ++i) {
      buffer += static_cast<char>(3);
      for (int k = 0; k < 3; ++k) put_int(buffer, static_cast<int>(3 * i) + k);
      buffer.append(colours[i].data(), 3);
      put_float(buffer, lux_per_patch[static_cast<Eigen::Index>(i)]);
      flush_if_full(false);
    }
    flush_if_full(true);
  });
}

}  // namespace ilp
