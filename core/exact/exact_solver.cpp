#include "core/exact/exact_solver.h"

#include <chrono>
#include <algorithm>
#include <iomanip>
#include <ostream>

#include "core/rays/ray_caster.h"

namespace ilp {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Fills emitted, absorbed and lost flux. Light leaving a reflecting patch is lost in
// the fraction of its gathered rays that struck a back face or escaped; a
// luminaire's light travels through its closed-form column, so what it loses is its
// flux minus what its column delivers (sum over receivers of A_i F_il E_l).
void account_flux(const Scene& scene, const FormFactorRows& rows, const RadiositySolution& solution,
                  ExactSolveSummary& s) {
  const Eigen::Index n = static_cast<Eigen::Index>(scene.patches.size());
  Eigen::VectorXd delivered_by_luminaire = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (SparseRows::InnerIterator it(rows.F, i); it; ++it)
      if (scene.surfaces[scene.patches[it.col()].surface].is_luminaire())
        delivered_by_luminaire[it.col()] += scene.patches[i].area_m2 * it.value();
  Eigen::RowVectorXd absorbed = Eigen::RowVectorXd::Zero(scene.channels), lost = absorbed;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Patch& p = scene.patches[i];
    s.emitted_lm += p.area_m2 * p.exitance_lm_per_m2;
    for (int c = 0; c < scene.channels; ++c) {
      absorbed[c] += p.area_m2 * (1.0 - p.reflectance[c]) * solution.illuminance_lux(i, c);
      if (scene.surfaces[p.surface].is_luminaire())
        lost[c] += p.exitance_lm_per_m2 * (p.area_m2 - delivered_by_luminaire[i]);
      else
        lost[c] += p.area_m2 * solution.radiosity_lm_per_m2(i, c) * (rows.back_hit_fraction[i] + rows.escaped_fraction[i]);
    }
  }
  s.absorbed_lm = photometric(absorbed);
  s.lost_lm = photometric(lost);
}

}  // namespace

ExactSolution solve_exact(const Scene& scene, const ExactSolveOptions& options, const ProgressCallback& progress) {
  ExactSolution out;
  ExactSolveSummary& s = out.summary;
  s.patches = scene.patches.size();

  auto start = std::chrono::steady_clock::now();
  const RayCaster caster(scene, options.form_factors.threads);
  s.bvh_seconds = seconds_since(start);
  s.ray_offset_m = caster.ray_offset_m();

  std::vector<int> rays(scene.patches.size(), options.form_factors.rays_per_patch);
  if (options.precise_patches && options.other_rays_per_patch > 0) {
    std::fill(rays.begin(), rays.end(), std::min(options.other_rays_per_patch, options.form_factors.rays_per_patch));
    for (int p : *options.precise_patches) rays.at(static_cast<std::size_t>(p)) = options.form_factors.rays_per_patch;
  }
  FormFactorRows rows =
      compute_form_factor_rows(scene, caster, scene.all_patches(), rays, options.form_factors, progress);
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
  if (!options.precise_patches) {
    s.shadow_rays = replace_emitter_columns(scene, caster, options.direct_light, rows);
  } else {
    CheapDirectLight cheap{std::vector<bool>(scene.patches.size(), true), options.other_direct_light};
    cheap.options.seed = options.direct_light.seed;
    cheap.options.threads = options.direct_light.threads;
    for (int p : *options.precise_patches) cheap.rows.at(static_cast<std::size_t>(p)) = false;  // rows are all patches, in order
    s.shadow_rays = replace_emitter_columns(scene, caster, options.direct_light, rows, &cheap);
  }
  if (progress) progress("direct light", 1, 1);
  s.direct_light_seconds = seconds_since(start);

  if (progress) progress("radiosity solve (Gauss-Seidel)", 0, 1);
  out.radiosity = solve_radiosity(scene, rows.F, options.radiosity);
  if (progress) progress("radiosity solve (Gauss-Seidel)", 1, 1);
  s.solve_seconds = out.radiosity.seconds;
  s.iterations = out.radiosity.iterations;
  s.relative_residual = out.radiosity.relative_residual;
  account_flux(scene, rows, out.radiosity, s);
  return out;
}

std::ostream& operator<<(std::ostream& os, const ExactSolveSummary& s) {
  const auto flags = os.flags();
  const auto precision = os.precision();
  os << std::fixed << std::setprecision(3);
  os << "BVH: " << s.patches << " patches in " << s.bvh_seconds << " s, ray offset " << std::setprecision(1)
     << s.ray_offset_m * 1e6 << " um\n"
     << std::setprecision(3)
     << "form factors: " << s.rays_cast << " rays in " << s.form_factor_seconds << " s ("
     << std::setprecision(2) << s.rays_per_second / 1e6 << " M rays/s)\n"
     << std::setprecision(3) << "direct light (luminaires): " << s.direct_light_seconds << " s, " << s.shadow_rays
     << " shadow rays\n"
     << "Gauss-Seidel: " << s.iterations << " sweeps in " << s.solve_seconds << " s, relative residual "
     << std::scientific << std::setprecision(1) << s.relative_residual << "\n"
     << std::fixed << std::setprecision(4) << "light escaping the scene: " << 100.0 * s.mean_escaped_fraction
     << " %, absorbed by back faces: " << 100.0 * s.mean_back_hit_fraction << " % (area-weighted)\n"
     << std::setprecision(1) << "flux: emitted " << s.emitted_lm << " lm, absorbed " << s.absorbed_lm
     << " lm, lost on back faces or escaping " << s.lost_lm << " lm";
  if (s.emitted_lm > 0.0)
    os << ": balance " << std::showpos << std::setprecision(3)
       << 100.0 * (s.absorbed_lm + s.lost_lm - s.emitted_lm) / s.emitted_lm << std::noshowpos << " % (ray noise)";
  os.flags(flags);
  os.precision(precision);
  return os;
}

}  // namespace ilp
