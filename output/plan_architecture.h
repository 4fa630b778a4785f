// The architecture a plan draws, from the scene's own triangles (metres, z up): what a
// horizontal plane at the cut height cuts (walls, columns, partitions: segments joined
// into polylines, closed ones knowing on which side the material is) and, below the
// cut, the outlines from above of what faces up (desk tops, shelves, sills). The plan
// writers (output/plan_svg.h, output/isolux_plan.h) take the result as plain polylines.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <vector>

#include "core/scene/scene.h"

namespace ilp {

// A triangle counter-clockwise seen from its front; the material is behind the front.
using Triangle3 = std::array<Eigen::Vector3d, 3>;
using Triangle2 = std::array<Eigen::Vector2d, 3>;
using Ring2 = std::vector<Eigen::Vector2d>;

// One polyline of a section. Closed: the last point joins the first (not repeated).
struct SectionLine {
  std::vector<Eigen::Vector2d> points_m;
  bool closed = false;
  // Closed lines: the area enclosed (m²), > 0 when the material (the back side of the
  // faces cut) lies inside, < 0 when outside (a room's inward-facing walls); 0 when open.
  double signed_area_m2 = 0.0;
};

// The section of the triangles by the plane z = cut_z_m. A triangle crossing it gives
// one segment, turned so that the triangle's back lies on its left; a vertex exactly on
// the plane counts as above it, so a face lying in the plane gives nothing and an edge
// in the plane is cut once. Segments whose ends lie within weld_m (> 0) are joined into
// polylines (following their direction where they can), and points within weld_m of
// the line through their neighbours are dropped. signed_area_m2 sums each segment in
// its own direction, so a loop of consistently wound faces gives its area with the
// sign above. Deterministic (input order). Throws std::invalid_argument for a weld_m
// not > 0 or a non-finite cut height.
std::vector<SectionLine> section_cut(const std::vector<Triangle3>& triangles, double cut_z_m, double weld_m);

// True when a plan fills the line as material: closed with the material inside
// (signed_area_m2 > 1e-6 m²), or closed with it outside but lying inside such a line
// (the inner face of a thick wall). A room's inward walls alone are not filled.
bool section_material(const SectionLine& line, const std::vector<SectionLine>& section);

// The boundary rings of the union of the triangles (either winding): a 0/1 raster of
// their cover with about `cells` (>= 8) cells across the larger side of their bounds,
// traced at 0.5 by marching squares and simplified to half a cell (so T-junctions and
// cracks between neighbours leave no lines inside). Within one cell of the exact
// boundary. Empty for no triangles or a union without area.
std::vector<Ring2> union_outline(const std::vector<Triangle2>& triangles, int cells);

struct ArchitectureOptions {
  double floor_z_m = 0.0;         // the finished floor (model frame)
  double cut_height_m = 0.8;      // the section plane over the floor, > 0
  // A second cut (over the floor, NaN: none) whose lines stand for the walls in
  // dimensions: e.g. just under the luminaires, where furniture is not cut.
  double wall_cut_height_m = std::numeric_limits<double>::quiet_NaN();
  // Faces up (normal z >= this) wholly between floor + furniture_min_m and the cut
  // are drawn from above; lower ones are the floor itself.
  double up_normal_min = 0.7;
  double furniture_min_m = 0.02;
  int outline_cells = 400;        // union_outline's raster, per surface
  double weld_m = 1e-3;           // section_cut's
};

struct PlanArchitecture {
  double floor_z_m = 0.0, cut_height_m = 0.0;  // as cut (cut_height_m 0: nothing drawn)
  std::vector<SectionLine> section;            // at the cut height
  std::vector<SectionLine> walls;              // at wall_cut_height_m (empty without)
  std::vector<Ring2> furniture;                // outlines from above, below the cut
};

// The architecture of every mesh surface of the scene (luminaires and candidate
// positions left out): section_cut of its patches at floor + cut height, and per
// surface union_outline of its patches facing up below the cut. Throws
// std::invalid_argument for a cut height not > 0 or non-finite options.
PlanArchitecture plan_architecture(const Scene& scene, const ArchitectureOptions& options);

}  // namespace ilp
