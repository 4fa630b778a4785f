#include "core/scene/reference_scenes.h"

#include <cmath>
#include <map>
#include <numbers>

namespace ilp::reference {

Scene make_quad_scene(const std::vector<QuadSpec>& quads, double max_patch_edge_m) {
  SceneOptions options;
  options.max_patch_edge_m = max_patch_edge_m;
  return make_quad_scene(quads, options);
}

Scene make_quad_scene(const std::vector<QuadSpec>& quads, const SceneOptions& options) {
  TriangleMesh mesh;
  mesh.path = "<test>";
  TriangleReflectance rho;
  std::map<std::string, int> surfaces;
  for (const QuadSpec& q : quads) {
    auto [it, inserted] = surfaces.emplace(q.surface, static_cast<int>(mesh.surface_names.size()));
    if (inserted) mesh.surface_names.push_back(q.surface);
    const int base = static_cast<int>(mesh.positions.size());
    for (const Eigen::Vector3d& p : {q.a, q.b, q.c, q.d}) mesh.positions.push_back(p);
    for (const Eigen::Vector3i& t : {Eigen::Vector3i(base, base + 1, base + 2), Eigen::Vector3i(base, base + 2, base + 3)}) {
      mesh.triangles.push_back(t);
      mesh.triangle_surface.push_back(it->second);
      mesh.triangle_material.push_back(-1);
      rho.push_back(q.reflectance);
    }
    ++mesh.faces_read;
  }
  return make_scene(mesh, rho, options);
}

Scene make_closed_box(const Eigen::Vector3d& o, const Eigen::Vector3d& s, double rho, double max_patch_edge_m) {
  const double x0 = o.x(), y0 = o.y(), z0 = o.z(), x1 = o.x() + s.x(), y1 = o.y() + s.y(), z1 = o.z() + s.z();
  using V = Eigen::Vector3d;
  const V r = V::Constant(rho);
  return make_quad_scene({{"floor", V(x0, y0, z0), V(x1, y0, z0), V(x1, y1, z0), V(x0, y1, z0), r},
                          {"ceiling", V(x0, y0, z1), V(x0, y1, z1), V(x1, y1, z1), V(x1, y0, z1), r},
                          {"wall_x0", V(x0, y0, z0), V(x0, y1, z0), V(x0, y1, z1), V(x0, y0, z1), r},
                          {"wall_x1", V(x1, y0, z0), V(x1, y0, z1), V(x1, y1, z1), V(x1, y1, z0), r},
                          {"wall_y0", V(x0, y0, z0), V(x0, y0, z1), V(x1, y0, z1), V(x1, y0, z0), r},
                          {"wall_y1", V(x0, y1, z0), V(x1, y1, z0), V(x1, y1, z1), V(x0, y1, z1), r}},
                         max_patch_edge_m);
}

std::vector<int> patches_of(const Scene& scene, const std::string& surface) {
  const int s = scene.find_surface(surface);
  std::vector<int> out;
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    if (scene.patches[i].surface == s) out.push_back(static_cast<int>(i));
  return out;
}

double parallel_rectangles_form_factor(double a, double b, double c) {
  const double X = a / c, Y = b / c;
  const double X2 = 1 + X * X, Y2 = 1 + Y * Y;
  return 2.0 / (std::numbers::pi * X * Y) *
         (0.5 * std::log(X2 * Y2 / (1 + X * X + Y * Y)) + X * std::sqrt(Y2) * std::atan(X / std::sqrt(Y2)) +
          Y * std::sqrt(X2) * std::atan(Y / std::sqrt(X2)) - X * std::atan(X) - Y * std::atan(Y));
}

double perpendicular_rectangles_form_factor(double l, double w, double h) {
  const double W = w / l, H = h / l;
  const double W2 = W * W, H2 = H * H, S = W2 + H2;
  const double log_term = std::log((1 + W2) * (1 + H2) / (1 + S)) +
                          W2 * std::log(W2 * (1 + S) / ((1 + W2) * S)) + H2 * std::log(H2 * (1 + S) / ((1 + H2) * S));
  return 1.0 / (std::numbers::pi * W) *
         (W * std::atan(1 / W) + H * std::atan(1 / H) - std::sqrt(S) * std::atan(1 / std::sqrt(S)) + 0.25 * log_term);
}

double point_to_corner_rectangle_form_factor(double a, double b, double c) {
  const double X = a / c, Y = b / c;
  const double sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
  return 1.0 / (2.0 * std::numbers::pi) * (X / sx * std::atan(Y / sx) + Y / sy * std::atan(X / sy));
}

}  // namespace ilp::reference
