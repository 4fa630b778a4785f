// libFuzzer harness: the OBJ and MTL readers (core/scene/mesh_io.cpp). The input is an OBJ
// file; from a line "#mtl" on it is the MTL file room.mtl beside it (seeds say
// "mtllib room.mtl"). Every input must give a mesh or a SceneError (an IlpError).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/base/error.h"
#include "core/scene/mesh.h"
#include "fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const std::size_t split = std::min(text.find("\n#mtl\n"), size);
  const std::string obj = ilp::fuzz::write_input("room.obj", data, split);
  const std::size_t mtl_start = std::min(size, split + 6);
  ilp::fuzz::write_input("room.mtl", data + mtl_start, size - mtl_start);
  for (const ilp::SurfaceNaming naming : {ilp::SurfaceNaming::group, ilp::SurfaceNaming::material}) {
    try {
      ilp::MeshReadOptions options;
      options.surface_naming = naming;
      const ilp::TriangleMesh mesh = ilp::load_mesh(obj, options);
      // What the rest of ilp relies on: indices in range, one surface and material per triangle.
      for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
          if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= mesh.positions.size()) __builtin_trap();
      if (mesh.triangle_surface.size() != mesh.triangles.size() || mesh.triangle_material.size() != mesh.triangles.size())
        __builtin_trap();
    } catch (const ilp::IlpError&) {
    }
  }
  return 0;
}
