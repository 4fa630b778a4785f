// libFuzzer harness: the message an isolated import's child sends its parent
// (core/scene/mesh_message.h). Any bytes must decode to a mesh whose indices stay inside
// it, or throw MeshMessageError; a decoded mesh must encode back to the same bytes.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/scene/mesh_message.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  try {
    const ilp::MeshMessage m = ilp::decode_mesh_message(bytes);
    if (m.is_error) {
      if (ilp::encode_error_message(m.error) != bytes) __builtin_trap();
      return 0;
    }
    for (const auto& t : m.mesh.triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= m.mesh.positions.size()) __builtin_trap();
    if (m.mesh.triangle_surface.size() != m.mesh.triangles.size() ||
        m.mesh.triangle_material.size() != m.mesh.triangles.size())
      __builtin_trap();
  } catch (const ilp::MeshMessageError&) {
  }
  return 0;
}
