// The radiosity scene: planar triangular patches in metres (z up), each with a
// surface, a reflectance per colour channel and an emitted exitance. Built from a
// TriangleMesh by transforming to metres, dropping degenerate faces and subdividing
// until no patch edge exceeds a length. Luminaires are added as emitting patches.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "core/light/luminaire.h"
#include "core/scene/mesh.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

// Linear-sRGB luminance weights: the photometric (lux) value of an RGB quantity
// whose channels each carry the emitted white light.
inline const Eigen::Vector3d kLuminanceWeights(0.2126, 0.7152, 0.0722);

struct Surface {
  std::string name;
  double exitance_lm_per_m2 = 0.0;  // emitted, Lambertian, from the front side
  int luminaire = -1;               // index into Scene::luminaires: a luminaire added from the job, not the mesh
  // A candidate luminaire position: it emits, but it was added after the ray caster was
  // built, so it blocks and absorbs nothing (see optimizer/lighting_model.h).
  bool is_virtual = false;
  bool is_luminaire() const { return luminaire >= 0; }
};

struct Patch {
  std::array<Eigen::Vector3d, 3> vertices_m{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                            Eigen::Vector3d::Zero()};  // counter-clockwise seen from the front
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit, front side
  double area_m2 = 0.0;
  int surface = -1;                                   // index into Scene::surfaces
  Eigen::Vector3d reflectance = Eigen::Vector3d::Zero();  // per channel, each in [0, 1); equal channels = gray
  double exitance_lm_per_m2 = 0.0;  // emitted from the front side
};

struct SceneStats {
  std::size_t faces_read = 0;            // polygons in the mesh file
  std::size_t triangles_read = 0;        // after fan triangulation
  std::size_t degenerate_dropped = 0;    // zero-area or collinear triangles
  std::size_t duplicate_dropped = 0;     // the same triangle again in its surface, facing the same way
  std::size_t mesh_patches = 0;          // made from the mesh by subdivision (luminaires come on top)
  std::size_t contact_segments = 0;      // pieces of contact lines the faces were cut along (contact_cuts.h)
  std::size_t patches_cut = 0;           // subdivision patches cut along them (each into 2 or more)
};

// A luminaire of the scene: its opening is the patches of surface `surface`, which
// absorb light like any black patch; its light comes from its type's distribution.
struct SceneLuminaire {
  LuminaireType type;
  LuminairePlacement placement;
  int surface = -1;
  double flux_lm = 0.0;
};

struct Scene {
  std::vector<Surface> surfaces;
  std::vector<SceneLuminaire> luminaires;
  std::vector<Patch> patches;
  int channels = 1;                 // 1 when every reflectance is gray, else 3
  Eigen::AlignedBox3d bounds_m;
  SceneStats stats;

  // Index of the surface with this name, or -1.
  int find_surface(const std::string& name) const;
  // 0, 1, ..., #patches - 1: every patch, for functions that take a list of patches.
  std::vector<int> all_patches() const;
  // Patches of the named surfaces, ascending, each once (every patch when `names` is
  // empty). Throws std::invalid_argument naming a surface the scene lacks.
  std::vector<int> patches_of(const std::vector<std::string>& names) const;
  double total_area_m2() const;
  // Reflectance of a patch in one channel (channel 0 for gray scenes).
  double reflectance(int patch, int channel) const { return patches[patch].reflectance[channel]; }
};

struct SceneOptions {
  UpAxis up_axis = UpAxis::z;
  double scale_to_m = 1.0;        // metres per file unit, > 0
  double max_patch_edge_m = 0.0;  // 0: no subdivision
  std::size_t max_patches = 5'000'000;  // refuse meshing that would exceed this
  // Cut faces where another face touches or crosses them (core/scene/contact_cuts.h), so
  // that no patch lies half under a solid. Off by default for now: the pieces wholly
  // under a solid (the floor under the office's partition) are then patches of their
  // surface that no light reaches, and a goal's minimum over that surface reads 0
  // (the shipped office job becomes infeasible); they must first be left out of goals.
  bool cut_at_contacts = false;
};

// The operator cache's key (core/base/key_hash.h): every field but max_patches, a
// limit that refuses a scene and never changes one (prepare_job also lowers it to the
// memory budget).
void hash_fields(KeyWriter& k, const SceneOptions& o);

// A file position in metres, z up (scale_to_m, then up_axis), as make_scene places it.
Eigen::Vector3d to_scene_frame(const Eigen::Vector3d& file_position, const SceneOptions& options);

// A triangle whose doubled area is at most this fraction of the squared diagonal of the
// mesh's bounds is degenerate (dropped by make_scene).
inline constexpr double kDegenerateRelArea = 1e-14;

// Meshing would make more patches than SceneOptions::max_patches allows.
class PatchLimitError : public SceneError {
 public:
  using SceneError::SceneError;
};

// Reflectance of each mesh triangle, already resolved from config and MTL.
using TriangleReflectance = std::vector<Eigen::Vector3d>;

// Transforms to metres with z up, drops degenerate triangles (counted in stats),
// subdivides each triangle uniformly so that every patch edge is at most
// max_patch_edge_m, cuts the patches along the lines where other faces touch or cross
// their triangle (cut_at_contacts: a desk's foot on the floor, a partition's foot;
// the pieces keep the patch's plane, winding and area), and sets channels (3 if any
// reflectance is coloured).
// Throws SceneError when no face survives, PatchLimitError when meshing would
// exceed max_patches.
Scene make_scene(const TriangleMesh& mesh, const TriangleReflectance& reflectance,
                 const SceneOptions& options);

// Adds a luminaire of `type` at `at`, facing down (-z), emitting flux_lm: one surface
// whose patches are its opening (a fan of triangles, reflectance 0, emitting side
// down) and one SceneLuminaire. Returns the surface index.
int add_luminaire(Scene& scene, const std::string& name, const LuminaireType& type, const LuminairePlacement& at,
                  double flux_lm);
// The shipped test model: a square Lambertian panel of side size_m.
int add_square_luminaire(Scene& scene, const std::string& name, const Eigen::Vector3d& position_m,
                         double size_m, double flux_lm);

// The luminaire whose opening is `surface` (which must be a luminaire surface).
const SceneLuminaire& luminaire_of(const Scene& scene, int surface);

// Sets the exitance of every patch of a surface.
void set_surface_exitance(Scene& scene, int surface, double exitance_lm_per_m2);

std::ostream& operator<<(std::ostream& os, const SceneStats& stats);

}  // namespace ilp
