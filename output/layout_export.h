// Files other tools read, of a verified layout in its scene: the luminaire schedule
// (CSV), a Radiance scene to re-check ilp with (radiance_export.cpp), the scene coloured
// by illuminance as glTF 2.0 (gltf_export.cpp) and a DXF plan for CAD (dxf_plan.cpp).
// Everything is in metres, z up (the scene's frame) unless a format says otherwise.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "core/light/luminaire.h"
#include "core/scene/scene.h"
#include "output/colour_map.h"

namespace ilp {

struct Photometry;

// One luminaire of the layout (or placed by the job), as the exports describe it.
struct ExportLuminaire {
  std::string id;                 // "L1", or the job's name of a placed luminaire
  std::string product;            // "" for the plain panel
  LuminaireType type;             // outline and distribution
  LuminairePlacement placement;   // centre of the opening, rotation, tilt
  double flux_lm = 0.0;           // as set
  double rated_flux_lm = 0.0;     // at full output (0: unknown)
  double power_w = 0.0;           // as set
  std::optional<double> above_floor_m = std::nullopt;  // the opening's height above the floor, when known
  bool placed_by_job = false;     // luminaires.placed, not the layout found
};

// A calculation grid's points (for Radiance's .pts).
struct ExportGrid {
  std::string name;
  std::vector<Eigen::Vector3d> positions_m;
  std::vector<Eigen::Vector3d> normals;
};

// The luminaire schedule: a header with units, then one row per luminaire:
// id, product, x_m, y_m, z_m, height_above_floor_m (empty when unknown), rotation_deg,
// tilt_deg, flux_lm, output_percent (of rated; empty when unknown), power_w, source
// (layout or placed). Fields with commas or quotes are quoted.
void write_schedule_csv(std::ostream& out, const std::vector<ExportLuminaire>& luminaires);

// ---- Radiance (radiance_export.cpp)

// A file name made of the letters, digits, '-' and '_' of `name` (others become '_').
std::string file_safe_name(const std::string& name);

// The files the Radiance export writes for these products (each photometric product's
// distribution, as ies2rad writes it) and grids: radiance_scene.rad,
// radiance_<product>.dat, radiance_<grid>.pts. Two names that come out alike get
// "_2", "_3", ... in order.
struct RadianceNames {
  std::string scene = "radiance_scene.rad";
  std::vector<std::pair<std::string, std::string>> product_dat;  // product name, file name
  std::vector<std::pair<std::string, std::string>> grid_pts;     // grid name, file name
  std::vector<std::string> all() const;
};
RadianceNames radiance_names(const std::vector<std::string>& products, const std::vector<std::string>& grids);

// Writes the Radiance scene through `write(name, writer)` (one call per file, names
// from `names`):
//  - radiance_scene.rad: a `plastic` material per surface (its reflectance, no
//    specularity) and its patches as polygons, every luminaire as ies2rad describes one:
//    a `brightdata` pattern on its product's .dat with source.cal's flatcorr (A1 =
//    flux / web flux / opening area) and src_phi src_theta, turned by the placement
//    (-ry -tilt -rz rotation), modifying a `light` of RGB 1 1 1, on the opening's polygon
//    facing down; the plain panel as a `light` of radiance flux / (pi area 179);
//  - radiance_<product>.dat: the file's candela web / 179 (Radiance's white efficacy),
//    expanded over its symmetry to C 0..360 (dimension 1: C = src_phi, dimension 2:
//    gamma = src_theta), each dimension as ies2rad writes it;
//  - radiance_<grid>.pts: one "x y z nx ny nz" line per point (rtrace -I).
// The scene file's header says how to run it. Throws std::invalid_argument for a
// product with no name in `names`.
using FileWriter = std::function<void(const std::string& name, const std::function<void(std::ostream&)>& write)>;
void write_radiance_scene(const Scene& scene, const std::vector<ExportLuminaire>& luminaires,
                          const std::vector<ExportGrid>& grids, const RadianceNames& names, const FileWriter& write);

// The .dat of one photometric web (see above), alone (for tests).
void write_radiance_distribution(std::ostream& out, const Photometry& photometry);

// ---- glTF 2.0 (gltf_export.cpp)

// Writes a binary glTF (.glb; y up, metres, as glTF wants: scene (x, y, z) -> (x, z, -y)):
// one node per surface of the scene named after it, its patches as triangles with a
// COLOR_0 from the colour map over `scale` (the PLY's colours), unlit; one node per
// luminaire named by its id, holding its opening as an emissive polygon facing its
// aim. `lux_per_patch` has one value per patch (NaN: no value, grey). Written
// atomically. Throws std::invalid_argument on a size mismatch, IlpError when the
// file cannot be written.
void write_illuminance_gltf(const std::string& path, const Scene& scene, const Eigen::VectorXd& lux_per_patch,
                            const ColourScale& scale, const std::vector<ExportLuminaire>& luminaires);

// ---- DXF plan (dxf_plan.cpp)

// Writes an ASCII DXF (R12, $INSUNITS metres) plan seen from above, on layers:
//  ILP_WALLS       the scene cut at `cut_height_m` (walls, partitions: every surface
//                  the plane crosses), as LINEs;
//  ILP_FURNITURE   the outlines of up-facing surfaces between the floor and the cut
//                  (desk tops, shelves), as LINEs;
//  ILP_LUMINAIRES  each luminaire's outline as a closed POLYLINE;
//  ILP_LABELS      each luminaire's id and product as TEXT beside it.
// `floor_z_m` is the floor's height (the furniture band's bottom). Luminaire surfaces
// are left out of the walls and furniture.
void write_dxf_plan(std::ostream& out, const Scene& scene, const std::vector<ExportLuminaire>& luminaires,
                    double floor_z_m, double cut_height_m);

}  // namespace ilp
