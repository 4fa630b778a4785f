// Calculation grids (EN 12464-1, as DIALux and Relux users know them): a plane of
// receiver points where goals are judged, instead of mesh patches. A horizontal grid
// lies at a height over a named floor surface's outline or over an explicit
// rectangle or polygon, minus a border band; a vertical grid stands on a segment
// between two heights and faces one side of it. Points sit at cell centres; the
// spacing is given or EN 12464-1's p = 0.2 x 5^log10(d) (d the longer side, p <= 10 m),
// with the cell aspect kept in [0.5, 2]. Points inside solid objects (a desk, a
// partition) are dropped and counted. Points are virtual: they neither shade nor reflect.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/base/error.h"
#include "core/transport/direct_light.h"
#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

enum class GridKind { horizontal, vertical };

// grids: one entry of the job file (docs/config.md), every value with its location.
struct CalcGridSetting {
  std::string name;
  FileLoc loc;                            // the entry
  GridKind kind = GridKind::horizontal;
  // horizontal: exactly one of over_surface, polygon_m (a rectangle_m becomes its 4 corners)
  std::string over_surface;               // the outline of this surface's patches facing up
  std::vector<Eigen::Vector2d> polygon_m; // x, y in the scene frame, counter-clockwise or not
  FileLoc shape_loc;
  double height_m = 0.8;                  // above the floor surface (over_surface) or above z = 0
  FileLoc height_loc;
  // vertical: the plane over the segment from -> to, bottom_m to top_m (z), facing
  // left (normal = the segment's direction turned +90 degrees about z) or right.
  Eigen::Vector2d from_m = Eigen::Vector2d::Zero(), to_m = Eigen::Vector2d::Zero();
  double bottom_m = 0.0, top_m = 0.0;
  bool facing_left = true;
  double border_m = 0.5;                  // band left out at the edges (vertical grids: default 0)
  FileLoc border_loc;
  std::optional<double> spacing_m;        // default: EN 12464-1's formula
  FileLoc spacing_loc;
  int max_points = 20000;
  FileLoc max_points_loc;
  // > 0: this grid is the band of this width around polygon_m (EN 12464-1's immediate
  // surrounding area of a task area): the polygon grown by band_width_m (edges moved
  // out, corners mitred) less the polygon, clipped to the scene's plan bounds, at
  // height_m. Its cells are squares of band_width_m / ceil(band_width_m / p) (p the
  // spacing: given, or EN 12464-1's for the grown outline's longer side), laid from
  // the grown outline's lower corner, so the band's inner edges on that side fall on
  // cell edges; points over no floor are dropped (outside_room), not an error.
  double band_width_m = 0.0;
  FileLoc band_loc;
};

// The operator cache's key (core/base/key_hash.h): every value that places the points
// and the name (the model's log names the grid). Left out: the FileLocs, and
// max_points, a limit that refuses a grid and never changes one.
void hash_fields(KeyWriter& k, const CalcGridSetting& s);

// Is p inside a solid object? It sees the backs of its faces: the first hit is a back
// face in at least 4 of the 6 axis directions (a grid point, an observer's eye).
bool inside_solid(const RayCaster& caster, const Eigen::Vector3d& p);

// EN 12464-1: p = 0.2 x 5^log10(d) m for the longer side d (m), at most 10 m.
double en12464_grid_spacing_m(double longer_side_m);

// Cells along two sides for spacing p: the nearest whole number of side / p (at least 1)
// each, then more cells on the side whose cells are over twice as long as the other's, so
// that the cell aspect is in [0.5, 2].
Eigen::Vector2i grid_cell_counts(double side_u_m, double side_v_m, double spacing_m);

// The polygon grown by width_m (> 0): each edge moved out by width_m along its normal,
// neighbours meeting at mitred corners (a rectangle stays a rectangle). Counter-clockwise
// or not; for a concave polygon much narrower than 2 x width_m the result may cross itself.
std::vector<Eigen::Vector2d> grow_polygon(const std::vector<Eigen::Vector2d>& polygon, double width_m);

// True when no two non-adjacent edges of the closed polygon meet and no adjacent edges
// overlap (at least 3 distinct vertices, non-zero area).
bool polygon_is_simple(const std::vector<Eigen::Vector2d>& polygon);

struct CalcGrid {
  std::string name;
  GridKind kind = GridKind::horizontal;
  std::vector<ReceiverPoint> points;     // the points kept, cell order (u fastest)
  // The lattice: point of cell (i, j) at origin + (i + 0.5) cell_u u + (j + 0.5) cell_v v.
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero(), u_axis = Eigen::Vector3d::UnitX(),
                  v_axis = Eigen::Vector3d::UnitY();
  int cells_u = 0, cells_v = 0;
  double cell_u_m = 0.0, cell_v_m = 0.0;
  double spacing_m = 0.0;                // the spacing asked for (given or from the formula)
  std::vector<Eigen::Vector2i> cell_of_point;  // (i, j) per kept point
  std::size_t outside_outline = 0;       // cells whose centre is outside the outline less its band
  std::size_t inside_solid = 0;          // dropped: inside a solid object
  std::size_t outside_room = 0;          // a band's cells dropped: outside the scene's bounds or over no floor
  double area_m2 = 0.0;                  // kept points x cell area
  double border_m = 0.0;                 // the band left out at the edges
  // What the grid lies over, for drawing (x, y in the scene frame): a horizontal grid's
  // polygon (rectangle_m, polygon_m; a band's grown outline, its hole in outline_hole_m) or the over_surface's triangles facing up; empty
  // for a vertical grid (its plane is the rectangle from_m .. to_m, bottom_m .. top_m).
  std::vector<Eigen::Vector2d> outline_polygon_m;
  std::vector<Eigen::Vector2d> outline_hole_m;  // a band's task outline (not part of the grid)
  std::vector<std::array<Eigen::Vector2d, 3>> outline_triangles_m;
};

// What laying a grid costs, known without a ray: its cells (the most points it can
// have) and the outline's triangles or polygon edges each cell is tested against.
// Throws the ConfigErrors of make_calc_grid that need no ray (max_points among them).
struct CalcGridSize {
  std::size_t cells = 0;
  std::size_t outline_parts = 0;
};
CalcGridSize calc_grid_size(const Scene& scene, const CalcGridSetting& setting);

// Builds the grid on the scene. Throws ConfigError (at the setting's file:line) when the
// surface is unknown or has no patch facing up, the band leaves nothing, the grid would
// have more than max_points points, the height is outside the scene, the grid lies
// outside the scene's bounds or over no floor (a ray straight down from a point escapes),
// a band is wider than the room (band_width_m above the scene's longer plan side),
// or every point is dropped.
CalcGrid make_calc_grid(const Scene& scene, const RayCaster& caster, const CalcGridSetting& setting);

}  // namespace ilp
