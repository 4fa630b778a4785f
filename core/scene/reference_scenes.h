// Reference scenes with known answers: small analytic geometry built directly
// (no files) and closed-form form factors from Howell's catalogue. They are the
// independent yardsticks the ray-cast form factors and solvers are checked against,
// in the tests and in the accuracy benchmark.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace ilp::reference {

struct QuadSpec {
  std::string surface;
  Eigen::Vector3d a, b, c, d;  // counter-clockwise seen from the front
  Eigen::Vector3d reflectance = Eigen::Vector3d::Zero();
};

// One surface per distinct name; each quad becomes two triangles, then meshing.
Scene make_quad_scene(const std::vector<QuadSpec>& quads, double max_patch_edge_m);
Scene make_quad_scene(const std::vector<QuadSpec>& quads, const SceneOptions& options);

// Closed axis-aligned box [origin, origin + size], faces pointing inwards, named
// floor, ceiling, wall_x0, wall_x1, wall_y0, wall_y1, all with reflectance rho.
Scene make_closed_box(const Eigen::Vector3d& origin, const Eigen::Vector3d& size, double rho,
                      double max_patch_edge_m);

std::vector<int> patches_of(const Scene& scene, const std::string& surface);

// Directly opposed parallel rectangles a x b at distance c.
double parallel_rectangles_form_factor(double a, double b, double c);
// Perpendicular rectangles sharing an edge of length l; widths w (from) and h (to).
double perpendicular_rectangles_form_factor(double l, double w, double h);
// Differential area to a parallel rectangle a x b whose corner lies straight above it at distance c.
double point_to_corner_rectangle_form_factor(double a, double b, double c);

}  // namespace ilp::reference
