// The scene as ilp sees it (after units, axes, exclusions and surface splitting),
// surface by surface, with what is likely wrong with it: for `ilp inspect`. Geometry
// (areas, facing, heights, bounds) comes from the patches; topology (open,
// non-manifold and inconsistently wound edges) from the mesh triangles welded by
// position; winding and openings from a few probe rays per patch (along the normal
// and at 60 degrees around it): a surface whose front sees nothing faces out of the
// model, one whose back is struck from inside is wound the wrong way (or one-sided).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/mesh.h"
#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp {

struct SurfaceInspection {
  std::string name;
  bool is_luminaire = false;
  bool two_sided = false;
  std::size_t triangles = 0;          // of the mesh (after exclusions), degenerate ones included
  std::size_t degenerate = 0;         // of those, dropped by meshing
  std::size_t patches = 0;
  double area_m2 = 0.0;
  double up_share = 0.0, down_share = 0.0, vertical_share = 0.0;  // of the area (facing as goals' `facing`)
  double down_mean_z_m = 0.0, up_mean_z_m = 0.0;                  // area-weighted heights of those parts
  Eigen::AlignedBox3d bounds_m;       // z is the height range
  std::size_t open_edges = 0;         // used by one triangle only
  std::size_t nonmanifold_edges = 0;  // used by three or more
  std::size_t flipped_edges = 0;      // two triangles traverse it the same way: inconsistent winding
  double escape_share = 0.0;          // probe rays from its front that leave the scene (area-weighted)
  double back_struck_share = 0.0;     // probe rays striking this surface that strike its back
  std::size_t rays_received = 0;
};

struct SceneInspection {
  std::vector<SurfaceInspection> surfaces;  // in scene order (empty surfaces left out)
  int mounting = -1;                        // index into surfaces: large, facing down, high
  int floor = -1;                           // large, facing up, low
  std::vector<std::string> warnings;
  std::size_t patches = 0, triangles = 0, open_edges = 0, nonmanifold_edges = 0, flipped_edges = 0;
  std::size_t welded_vertices = 0;
  double area_m2 = 0.0;
  double escape_share = 0.0;        // of all probe rays (area-weighted)
  double back_hit_share = 0.0;      // of all probe rays, striking a back face
  std::uint64_t probe_rays = 0;
  Eigen::AlignedBox3d bounds_m;
  double seconds = 0.0;
};

struct InspectOptions {
  double weld_tolerance_m = 1e-3;          // for the edge topology
  std::size_t max_probe_patches = 400000;  // probe every patch up to this, else an even stride
  int threads = 0;
  // Per scene surface: doubled back to back (scene.two_sided). Its twins face out, so
  // escapes and back hits say nothing about its winding: no winding warnings for it.
  std::vector<bool> two_sided;
};

// `mesh` is the one the scene was made from (after exclusions; file units: `frame`
// converts them). Deterministic for any thread count.
SceneInspection inspect_scene(const Scene& scene, const TriangleMesh& mesh, const SceneOptions& frame,
                              const RayCaster& caster, const InspectOptions& options = {});

}  // namespace ilp
