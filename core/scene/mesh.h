// A triangle mesh as read from a file: positions in the file's units and axes,
// each triangle tagged with a surface name and, where the file has one, a material
// whose Kd is the default reflectance. Nothing here is in metres yet: see scene.h.
// OBJ, PLY and OFF are read by mesh_io.cpp; glTF 2.0/GLB, 3DS, DAE, FBX and IFC2x3
// through assimp by mesh_import.cpp, which also says what the file states of its frame.
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

// Which file axis points up.
enum class UpAxis { y, z };

// What a file states of the frame its positions are in (as the reader hands them
// over): metres per unit and the up axis, each where the file or its format's
// specification states it (glTF: metres, y up). OBJ, PLY, OFF and 3DS state neither.
// `notes` say where each came from, or that the file does not state it.
struct MeshFrame {
  std::optional<double> scale_to_m = std::nullopt;
  std::optional<UpAxis> up_axis = std::nullopt;
  std::string unit_note = {};  // e.g. "metres (glTF 2.0's specification)"
  std::string up_note = {};
};

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
  // Imported formats (mesh_import.cpp): the frame the file states, triangles of zero
  // area dropped on reading, and what the reader did for the run log.
  MeshFrame frame = {};
  std::size_t zero_area_dropped = 0;
  std::vector<std::string> notes = {};
};

// Limits on the child process that reads a model through assimp (mesh_import.h). They
// decide only whether a file gives its mesh, never which mesh, so the cache key leaves
// them out.
struct ImportLimits {
  double max_time_s = 600.0;  // wall time, > 0; then the child is killed and the file refused
  // Memory the child may map beyond what the parent had mapped when it forked
  // (RLIMIT_AS; memory the parent's allocator held free is reused without counting);
  // none: the system's limits only. The job runner sets the job's budget.
  std::optional<double> max_memory_bytes = std::nullopt;
};

struct MeshReadOptions {
  SurfaceNaming surface_naming = SurfaceNaming::group;
  ImportLimits import_limits = {};
};

// The operator cache's key (core/base/key_hash.h): every field but import_limits.
void hash_fields(KeyWriter& k, const MeshReadOptions& o);

// Reads .obj (with its mtllib), or .ply / .off through OpenMesh (one surface named
// after the file stem), or .gltf, .glb, .3ds, .dae, .fbx, .ifc through assimp
// (mesh_import.h says how). Throws SceneError naming the file and line of any defect
// that makes the file unreadable; a file with no faces is an error.
TriangleMesh load_mesh(const std::string& path, const MeshReadOptions& options = {});

}  // namespace ilp
