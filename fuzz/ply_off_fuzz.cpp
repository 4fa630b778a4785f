// libFuzzer harness: the PLY and OFF readers (core/scene/mesh_io.cpp over OpenMesh). The
// first byte picks the format (even: .ply, odd: .off), the rest is the file. Every
// input must give a mesh or a SceneError (an IlpError); a header's counts must never
// make it allocate more than the file could hold.
#include <cstddef>
#include <cstdint>

#include "core/base/error.h"
#include "core/scene/mesh.h"
#include "fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string path = ilp::fuzz::write_input(data[0] % 2 == 0 ? "mesh.ply" : "mesh.off", data + 1, size - 1);
  try {
    const ilp::TriangleMesh mesh = ilp::load_mesh(path, {});
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k)
        if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= mesh.positions.size()) __builtin_trap();
  } catch (const ilp::IlpError&) {
  }
  return 0;
}
