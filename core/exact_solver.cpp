#include "core/exact_solver.h"

#include <chrono>
#include <iomanip>
#include <ostream>

#include "core/ray_caster.h"

namespace ilp {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

ExactSolution solve_exact(const Scene& scene, const ExactSolveOptions& options, const ProgressCallback& progress) {
  ExactSolution out;
  ExactSolveSummary& s = out.summary;
  s.patches = scene.patches.size();

  auto start = std::chrono::steady_clock::now();
  const RayCaster caster(scene, options.form_factors.threads);
  s.bvh_seconds = seconds_since(start);

  FormFactorRows rows = compute_form_factor_rows(scene, caster, {}, options.form_factors, progress);
  s.form_factor_seconds = rows.seconds;
  s.rays_cast = rows.rays_cast;
  s.rays_per_second = rows.seconds > 0.0 ? static_cast<double>(rows.rays_cast) / rows.seconds : 0.0;
  double area = 0.0;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const double a = scene.patches[i].area_m2;
    area += a;
    s.mean_escaped_fraction += a * rows.escaped_fraction[static_cast<Eigen::Index>(i)];
    s.mean_back_hit_fraction += a * rows.back_hit_fraction[static_cast<Eigen::Index>(i)];
  }
  s.mean_escaped_fraction /= area;
  s.mean_back_hit_fraction /= area;

  start = std::chrono::steady_clock::now();
  if (progress) progress("direct light", 0, 1);
  replace_emitter_columns(scene, caster, luminaire_patches(scene), options.direct_light, rows);
  if (progress) progress("direct light", 1, 1);
  s.direct_light_seconds = seconds_since(start);

  out.radiosity = solve_radiosity(scene, rows.F, options.radiosity);
  s.solve_seconds = out.radiosity.seconds;
  s.iterations = out.radiosity.iterations;
  s.relative_residual = out.radiosity.relative_residual;
  return out;
}

std::ostream& operator<<(std::ostream& os, const ExactSolveSummary& s) {
  const auto flags = os.flags();
  const auto precision = os.precision();
  os << std::fixed << std::setprecision(3);
  os << "BVH: " << s.patches << " patches in " << s.bvh_seconds << " s\n"
     << "form factors: " << s.rays_cast << " rays in " << s.form_factor_seconds << " s ("
     << std::setprecision(2) << s.rays_per_second / 1e6 << " M rays/s)\n"
     << std::setprecision(3) << "direct light (luminaires): " << s.direct_light_seconds << " s\n"
     << "Gauss-Seidel: " << s.iterations << " sweeps in " << s.solve_seconds << " s, relative residual "
     << std::scientific << std::setprecision(1) << s.relative_residual << "\n"
     << std::fixed << std::setprecision(4) << "light escaping the scene: " << 100.0 * s.mean_escaped_fraction
     << " %, absorbed by back faces: " << 100.0 * s.mean_back_hit_fraction << " % (area-weighted)";
  os.flags(flags);
  os.precision(precision);
  return os;
}

}  // namespace ilp
