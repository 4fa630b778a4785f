// A triangle mesh as read from a file: positions in the file's units and axes,
// each triangle tagged with a surface name and, where the file has one, a material
// whose Kd is the default reflectance. Nothing here is in metres yet: see scene.h.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/base/error.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

// Which OBJ tag names a face's surface. A face lacking the chosen tag falls back
// to the next one in the order group -> object -> material -> "default".
enum class SurfaceNaming { group, object, material };

struct MeshMaterial {
  std::string name;
  std::optional<Eigen::Vector3d> kd;  // diffuse reflectance from the MTL, per channel
  FileLoc kd_loc;                      // where Kd was read (for error messages)
};

struct TriangleMesh {
  std::string path;                        // file it was read from
  std::vector<Eigen::Vector3d> positions;  // file units and axes
  std::vector<Eigen::Vector3i> triangles;  // indices into positions, counter-clockwise = front
  std::vector<int> triangle_surface;       // index into surface_names, per triangle
  std::vector<int> triangle_material;      // index into materials, or -1, per triangle
  std::vector<std::string> surface_names;
  std::vector<MeshMaterial> materials;
  std::size_t faces_read = 0;              // polygons in the file before triangulation
  std::size_t polygons_split = 0;          // faces with more than 3 vertices (fan-triangulated)
};

struct MeshReadOptions {
  SurfaceNaming surface_naming = SurfaceNaming::group;
};

// The operator cache's key (core/base/key_hash.h): every field.
void hash_fields(KeyWriter& k, const MeshReadOptions& o);

// Reads .obj (with its mtllib), or .ply / .off through OpenMesh (one surface named
// after the file stem). Throws SceneError naming the file and line of any defect
// that makes the file unreadable; a file with no faces is an error.
TriangleMesh load_mesh(const std::string& path, const MeshReadOptions& options = {});

}  // namespace ilp
