// What the child process of an isolated import (mesh_import.h) sends its parent over a
// pipe: the TriangleMesh it read, or the error message it would have thrown, in a
// plain binary form. Both ends are the same program on the same machine, so numbers
// travel in host byte order, doubles bit for bit: the parent gets exactly the mesh
// the child built. No assimp here: the decoder is tested and fuzzed on its own.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

#include "core/scene/mesh.h"

namespace ilp {

// A message that is truncated or breaks the format; what() says where and how.
class MeshMessageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The bytes for a mesh (every TriangleMesh field but `path`, which the parent knows).
std::string encode_mesh_message(const TriangleMesh& mesh);

// The bytes for an error: the child's SceneError text (it names the file).
std::string encode_error_message(const std::string& error);

// One decoded message: a mesh (`is_error` false) or an error text.
struct MeshMessage {
  bool is_error = false;
  std::string error;
  TriangleMesh mesh;
};

// Decodes a whole message. Throws MeshMessageError when the bytes are truncated, carry
// trailing bytes, a wrong tag or counts beyond the message, or a mesh whose indices
// point outside it (a triangle's vertex, a surface, a material).
MeshMessage decode_mesh_message(std::string_view bytes);

}  // namespace ilp
