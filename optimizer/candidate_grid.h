// Where luminaires may go: a regular grid of candidate positions on a mounting
// surface that faces down (a ceiling). The operator gets one column of T per
// candidate; a luminaire between candidates gets a blend of the columns around it,
// which makes positions continuous for the search.
//
// The blend is Catmull-Rom (bicubic, 16 candidates): it reproduces the candidates
// exactly, is continuous with its slope, and can peak between candidates, which a
// bilinear blend cannot (its maximum over a cell is always at a corner, so a search
// on it would snap luminaires to the grid). A luminaire's light at a receiver varies
// smoothly with its position on the scale of the mounting height (cos^4 / h^2 falls
// off over about h), and the spacing is kept well below it; the verification places
// the real luminaires and measures what the blend missed. Near holes in the grid the
// blend falls back to bilinear, then to the nearest candidate.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

#include "core/operator/reflected_blend.h"
#include "core/scene/scene.h"

namespace ilp {

struct CandidateGridOptions {
  double spacing_m = 0.5;       // at most this between neighbouring candidates
  // Half the luminaire's extent along x and y as placed (LuminaireType::half_footprint_m):
  // its whole outline must lie on the surface.
  Eigen::Vector2d half_footprint_m = Eigen::Vector2d::Constant(0.3);
  double wall_distance_m = 0.0;   // and keep at least this from the surface's edges (its walls)
  double module_m = 0.0;          // > 0: candidates at the cell centres of a ceiling module of this size
  double mount_offset_m = 0.02;   // the emitting face hangs this far below the surface
  // Where centres may lie (the mounting zone, x and y); empty: the whole surface.
  Eigen::AlignedBox2d zone_m = Eigen::AlignedBox2d();
};

// One point of a continuous layout, resolved against the grid.
struct GridPoint {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // where the luminaire is (snapped onto the surface if it was off it)
  static constexpr int kMaxCandidates = 16;
  std::array<int, kMaxCandidates> candidates;     // columns blended (-1: unused)
  std::array<double, kMaxCandidates> weights;     // summing to 1 (Catmull-Rom weights can be negative)
  GridPoint() {
    candidates.fill(-1);
    weights.fill(0.0);
  }
};

class CandidateGrid {
 public:
  // Throws std::invalid_argument naming the surface if it has no patch facing down
  // or no position where a whole luminaire fits.
  CandidateGrid(const Scene& scene, int mounting_surface, const CandidateGridOptions& options);
  // Suspended luminaires: every node of the rectangle plane_m (x, y; less the
  // luminaire's half footprint and the wall distance, within options.zone_m) holds
  // one, its emitting face at height z_m; no surface is needed.
  CandidateGrid(const Eigen::AlignedBox2d& plane_m, double z_m, const CandidateGridOptions& options);
  // Wall-mounted luminaires: a line of candidates along the patches of wall_surface that
  // face `facing` (a horizontal axis, +-x or +-y, within about 8 degrees), their centres
  // at height z_m, options.mount_offset_m plus the luminaire's half extent across the
  // wall in front of it, options.spacing_m apart along the wall (within options.zone_m
  // along the wall; the zone's extent across it is ignored). A candidate exists where
  // the centre and both ends of the outline along the wall lie on those patches. The
  // grid is one column (or row) of nodes: its extent across the wall is a line.
  // Throws std::invalid_argument naming the surface when it has no patch facing that
  // way or no position at that height where a luminaire fits.
  CandidateGrid(const Scene& scene, int wall_surface, const Eigen::Vector2d& facing, double z_m,
                const CandidateGridOptions& options);
  CandidateGrid() = default;  // empty: no candidates

  std::size_t size() const { return positions_.size(); }
  // Centre of the emitting face of each candidate (z: surface height - offset), m.
  const std::vector<Eigen::Vector3d>& positions_m() const { return positions_; }
  // Where centres may lie: [lower, upper] in x and y, m.
  Eigen::Vector2d lower_m() const { return lower_; }
  Eigen::Vector2d upper_m() const { return upper_; }
  Eigen::Vector2d spacing_m() const { return step_; }
  // The plan extent (x, y) of the mounting surface's patches facing down.
  const Eigen::AlignedBox2d& surface_box_m() const { return surface_box_; }
  int nodes_x() const { return nx_ + 1; }
  int nodes_y() const { return ny_ + 1; }
  // Patches of the mounting surface facing down (the ones candidates sit under).
  const std::vector<int>& mounting_patches() const { return mounting_patches_; }
  std::size_t ignored_patches() const { return ignored_patches_; }  // of the surface, not facing down
  double mounting_area_m2() const { return mounting_area_m2_; }     // of the patches facing down

  // The blend for a centre at (x, y), clamped to the grid's extent: Catmull-Rom over
  // the 4 x 4 candidates around its cell when all exist (indices clamped at the
  // grid's edges), else bilinear over the cell's four, else the nearest candidate
  // (positions off the surface snap to it).
  GridPoint locate(const Eigen::Vector2d& xy_m) const;
  // How far (x, y) is from the nearest point where a luminaire may be centred: 0 inside
  // a cell whose four nodes hold candidates, else the distance to the nearest candidate.
  double mount_distance_m(const Eigen::Vector2d& xy_m) const;
  // The grid node nearest to (x, y) that holds a candidate (for layouts snapped to a
  // ceiling module); (x, y) itself when the grid is empty.
  Eigen::Vector2d nearest_candidate_m(const Eigen::Vector2d& xy_m) const;
  // The candidate at node (i, j) of the nodes_x() x nodes_y() lattice, -1 where none fits
  // or the node is outside it.
  int candidate_at_node(int i, int j) const {
    return i < 0 || j < 0 || i > nx_ || j > ny_ || candidate_of_node_.empty() ? -1 : node(i, j);
  }

 private:
  // The nodes' extent and spacing over a plan box (the surface's or the plane's).
  void lay_nodes(const Eigen::AlignedBox2d& box, const CandidateGridOptions& options, const std::string& name);
  int node(int i, int j) const { return candidate_of_node_[static_cast<std::size_t>(j * (nx_ + 1) + i)]; }

  Eigen::Vector2d lower_, upper_, step_;
  Eigen::AlignedBox2d surface_box_;
  int nx_ = 0, ny_ = 0;                  // cells per axis
  std::vector<int> candidate_of_node_;   // -1 where no luminaire fits
  std::vector<Eigen::Vector3d> positions_;
  std::vector<int> mounting_patches_;
  std::size_t ignored_patches_ = 0;
  double mounting_area_m2_ = 0.0;
};

// The candidates' reflected light (core/operator/reflected_blend.h) computed at every
// `stride`-th node along x and y (and the last node of each axis), and blended linearly
// (bilinearly) between those for the nodes in between; a node whose surrounding computed
// nodes do not all hold candidates (a hole, an outline's edge) is computed itself. The
// light sources are `fixed_sources` fixed ones (computed) and then one per candidate, in
// candidate order. stride 1: every source computed.
ReflectedBlend candidate_reflected_blend(const CandidateGrid& grid, std::size_t fixed_sources, int stride);

}  // namespace ilp
