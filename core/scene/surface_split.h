// Surfaces from a mesh that has too few groups (a whole room in one group): each
// surface is split into pieces, triangles connected through shared vertices (welded
// by position) that face the same way (up, down or vertical), and the pieces are
// named by rules on facing and height (scene.regions) or numbered by area
// (scene.surfaces_from: connected). Works on the TriangleMesh before make_scene, so
// every later step (reflectances, exclusions, goals) sees the new names.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/base/error.h"
#include "core/scene/mesh.h"
#include "core/scene/scene.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

// How a triangle faces, in the scene frame (z up): within about 25 degrees of up or
// down (|n_z| >= 0.9, as goals' `facing`), else vertical (walls, and every slope).
enum class Facing { up, down, vertical };
std::string_view to_string(Facing facing);
Facing facing_of(const Eigen::Vector3d& unit_normal);

// scene.regions entry: pieces facing `facing` (any when absent) whose whole height
// range lies in height_m and whose area is at least min_area_m2 take `name`.
struct RegionRule {
  std::string name;
  std::optional<Facing> facing;
  std::optional<std::pair<double, double>> height_m;  // [low, high], m, scene frame
  double min_area_m2 = 0.0;
  FileLoc loc;
};

// The operator cache's key (core/base/key_hash.h): every field but loc.
void hash_fields(KeyWriter& k, const RegionRule& r);

struct SurfaceSplitOptions {
  bool connected = false;          // number the pieces no rule takes GROUP.1, GROUP.2, ... (by area)
  double weld_tolerance_m = 1e-3;  // vertices closer than this are one vertex
  std::vector<RegionRule> regions;
  bool active() const { return connected || !regions.empty(); }
};

// The operator cache's key: every field.
void hash_fields(KeyWriter& k, const SurfaceSplitOptions& o);

struct SurfaceSplitReport {
  std::size_t pieces = 0;          // connected pieces of one facing found
  std::size_t welded_vertices = 0; // distinct vertices after welding
  std::vector<std::size_t> rule_pieces;  // pieces each rule took
  std::vector<double> rule_area_m2;      // their area
  std::vector<std::string> log;    // for the run log
};

// A mesh's vertices in the scene frame (metres, z up), which of them triangles use, and
// the squared diagonal of the used ones' bounds (the scale of the degenerate-area test).
struct FramedVertices {
  std::vector<Eigen::Vector3d> positions;
  std::vector<bool> used;
  double diagonal2 = 0.0;
};
FramedVertices framed_vertices(const TriangleMesh& mesh, const SceneOptions& frame);

// Welds positions closer than tolerance_m: each used position maps to the
// lowest-numbered representative within the tolerance, else becomes one (unused
// positions map to -1). Deterministic in position order. `representatives` receives
// how many there are.
std::vector<int> weld_positions(const std::vector<Eigen::Vector3d>& positions, const std::vector<bool>& used,
                                double tolerance_m, std::size_t& representatives);

// Renames the surfaces of `mesh` (surface_names and triangle_surface). Pieces are
// taken by the first rule they match, in rule order; the rest are GROUP.N (connected,
// N = 1 for the largest piece of GROUP, ties by first triangle) or stay in GROUP.
// Degenerate triangles (no normal) join the largest piece of their surface. Surfaces
// left without triangles disappear. Deterministic: depends only on the mesh and the
// options. `frame` gives metres and the up axis (scale_to_m, up_axis).
SurfaceSplitReport split_surfaces(TriangleMesh& mesh, const SceneOptions& frame, const SurfaceSplitOptions& options);

}  // namespace ilp
