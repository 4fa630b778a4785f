// Checks shared by the tests that write PNG files: the signature and the IHDR chunk.
#pragma once

#include <string>
#include <utility>

namespace ilp::test {

// A PNG's width and height from its IHDR chunk (which must come first, after the
// 8-byte signature); {-1, -1} when `bytes` is not a PNG.
inline std::pair<long, long> png_size(const std::string& bytes) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 33 || bytes.compare(0, 8, signature) != 0 || bytes.compare(12, 4, "IHDR") != 0) return {-1, -1};
  const auto be32 = [&](std::size_t at) {
    long v = 0;
    for (int k = 0; k < 4; ++k) v = v * 256 + static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  if (be32(8) != 13) return {-1, -1};  // IHDR's data is 13 bytes
  return {be32(16), be32(20)};
}

}  // namespace ilp::test
