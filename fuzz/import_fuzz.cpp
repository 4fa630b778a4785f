// libFuzzer harness: the models read through assimp (core/scene/mesh_import.cpp). The
// first byte picks the format (its value modulo 6: .glb, .gltf, .3ds, .dae, .fbx,
// .ifc), the rest is the file. Every input must give a mesh or a SceneError (an IlpError).
// assimp itself is the system library, not instrumented: a crash inside it is assimp's,
// and the finding shows which input reaches it.
//
// It calls load_with_assimp, the in-process reader, not load_mesh's isolated one: in the
// child process a crash in assimp (or in ilp's conversion after it) would come back as a
// SceneError and libFuzzer would never see it, and a fork per input would cost more than
// most inputs take to read. Findings here are still worth having: each says which input
// reaches a crash that ilp itself now only reports, and which check could name the defect
// better (a line, a field) than "assimp crashed reading it". The message the child sends
// has its own harness, import_message_fuzz.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/base/error.h"
#include "core/scene/mesh.h"
#include "core/scene/mesh_import.h"
#include "fuzz/fuzz_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {".glb", ".gltf", ".3ds", ".dae", ".fbx", ".ifc"};
  const std::string path = ilp::fuzz::write_input(std::string("model") + kExtensions[data[0] % 6], data + 1, size - 1);
  for (const ilp::SurfaceNaming naming : {ilp::SurfaceNaming::group, ilp::SurfaceNaming::material}) {
    try {
      ilp::MeshReadOptions options;
      options.surface_naming = naming;
      const ilp::TriangleMesh mesh = ilp::load_with_assimp(path, kExtensions[data[0] % 6], options);
      for (const auto& t : mesh.triangles)
        for (int k = 0; k < 3; ++k)
          if (t[k] < 0 || static_cast<std::size_t>(t[k]) >= mesh.positions.size()) __builtin_trap();
      if (mesh.triangle_surface.size() != mesh.triangles.size() || mesh.triangle_material.size() != mesh.triangles.size())
        __builtin_trap();
      for (int m : mesh.triangle_material)
        if (m < -1 || m >= static_cast<int>(mesh.materials.size())) __builtin_trap();
      for (const auto& p : mesh.positions)
        if (!p.allFinite()) __builtin_trap();
    } catch (const ilp::IlpError&) {
    }
  }
  return 0;
}
