// The models architects send, read through assimp (the only file that includes it is
// mesh_import.cpp): glTF 2.0 (.gltf, .glb), 3DS, COLLADA (.dae), FBX and IFC2x3 (.ifc).
// load_mesh (mesh.h) reads them in isolation (load_with_assimp_isolated, in
// mesh_import_child.cpp): assimp runs in a child process, so that its crashes and hangs
// on malformed files become errors; nothing else needs to call these.
#pragma once

#include <string>

#include "core/scene/mesh.h"

namespace ilp {

// True for the extensions (lower case, with the dot) read through assimp.
bool is_imported_format(const std::string& extension);

// Reads a model through assimp into a TriangleMesh:
//  - every node's meshes at their world position (node transforms applied; a mirroring
//    transform reverses the winding so the front stays the front), each instance of a
//    shared mesh once per node;
//  - surfaces: with SurfaceNaming group or object, the node's name; a node assimp names by
//    type only (no name, "$..." or "IfcMappedItem": an IFC window's geometry) or the only
//    child of a node without meshes (a 3DS object under its hierarchy node) takes its
//    parent's name; with material, the material's name; a node or material without a
//    name falls back to the other, then to "default";
//  - materials: a reflectance (kd) from glTF's base colour x (1 - metallic) or the diffuse
//    colour, where plausible: every channel in [0, 1) and no texture over it; what was
//    taken and what not is in `notes`; translucent materials are noted (ilp is opaque);
//  - the frame: `frame` says what the file states (glTF: metres, y up; IFC and COLLADA:
//    assimp applies their unit and turns them y up; FBX: UnitScaleFactor and UpAxis, a
//    rotation applied when the up axis is neither +y nor +z; 3DS: nothing, its positions
//    as in the file, which 3ds Max writes z up);
//  - triangles whose doubled area is at most kDegenerateRelArea of the squared diagonal
//    of the model's bounds (scene.h) are dropped and counted (zero_area_dropped); point
//    and line primitives are ignored and counted in `notes`.
// Throws SceneError naming the file and the reason: a file assimp cannot read (an IFC4
// file says its schema), an incomplete scene, no triangles.
// In this process: a crash inside assimp takes the program with it. The child of
// load_with_assimp_isolated and the fuzz harness call it; everything else calls that.
TriangleMesh load_with_assimp(const std::string& path, const std::string& extension, const MeshReadOptions& options);

// load_with_assimp in a child process (fork), which sends the mesh or its SceneError back
// over a pipe (mesh_message.h): the same mesh, bit for bit, or the same error. What the
// child cannot send becomes a SceneError naming the file:
//  - killed by a signal: "FILE: assimp crashed reading it (signal 11, SIGSEGV); the file is
//    malformed or uses a feature assimp 5.2.5 cannot read";
//  - no answer within options.import_limits.max_time_s: killed, "FILE: assimp took longer
//    than N s reading it";
//  - out of the memory options.import_limits.max_memory_bytes allows (RLIMIT_AS in the
//    child): assimp's allocation fails, "FILE: out of memory reading the model", or it
//    aborts (a crash as above);
//  - exited with a status other than 0, or sent a truncated or malformed message;
//  - a time limit outside (0, 1e7] s is refused before anything starts.
// The child calls only load_with_assimp (assimp, the standard library, Eigen) and then
// write(2) and _exit(2): no atexit handlers, no flush of the parent's stdio buffers, no
// TBB. After fork in a program with threads (TBB's pools) only async-signal-safe calls
// are guaranteed; assimp allocates, which glibc's fork makes safe in practice (it resets
// malloc's locks in the child), and the child never touches TBB, whose workers do not
// exist in it.
TriangleMesh load_with_assimp_isolated(const std::string& path, const std::string& extension,
                                       const MeshReadOptions& options);

}  // namespace ilp
