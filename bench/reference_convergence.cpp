// How noisy is the exact reference itself? Solves a job (configs/office_fixed.yaml, or
// the one given) with 64 to 4096 rays per patch and compares each answer with the
// 4096-ray one: area-weighted RMS and largest relative difference of total
// illuminance on the report surfaces, and each surface's average. The sample-based
// inverse is measured against this reference, so its noise bounds what can be seen.
//
//   ./build/bench/reference_convergence [CONFIG]
#include <cmath>
#include <cstdio>
#include <vector>

#include "job/config.h"
#include "core/exact/exact_solver.h"
#include "job/plan.h"
#include "job/job_scene.h"

int main(int argc, char** argv) {
  try {
    const ilp::JobConfig job = ilp::load_job_config(argc > 1 ? argv[1] : ILP_SOURCE_DIR "/configs/office_fixed.yaml");
    const ilp::Scene scene = ilp::load_job_scene(scene_spec(job)).scene;
    std::vector<int> surfaces;
    for (const std::string& name : job.report_surfaces) surfaces.push_back(scene.find_surface(name));
    if (surfaces.empty())
      for (std::size_t s = 0; s < scene.surfaces.size(); ++s)
        if (!scene.surfaces[s].is_luminaire()) surfaces.push_back(static_cast<int>(s));
    std::vector<bool> counted(scene.patches.size(), false);
    for (std::size_t i = 0; i < scene.patches.size(); ++i)
      for (int s : surfaces) counted[i] = counted[i] || scene.patches[i].surface == s;

    const std::vector<int> ray_counts = {64, 256, 1024, 4096};
    std::vector<Eigen::VectorXd> lux;
    std::vector<double> seconds;
    for (int rays : ray_counts) {
      ilp::ExactSolveOptions options = ilp::exact_options(job, {});
      options.form_factors.rays_per_patch = rays;
      const ilp::ExactSolution solution = ilp::solve_exact(scene, options);
      lux.push_back(solution.radiosity.total_lux);
      seconds.push_back(solution.summary.form_factor_seconds + solution.summary.direct_light_seconds +
                        solution.summary.solve_seconds);
    }
    std::printf("%8s %10s %14s %14s", "rays", "solve_s", "rms_rel_diff", "max_rel_diff");
    for (int s : surfaces) std::printf(" %12s", (scene.surfaces[s].name + "_lux").c_str());
    std::printf("\n");
    const Eigen::VectorXd& best = lux.back();
    for (std::size_t k = 0; k < ray_counts.size(); ++k) {
      double sum_sq = 0.0, area = 0.0, worst = 0.0;
      for (std::size_t i = 0; i < scene.patches.size(); ++i) {
        if (!counted[i] || best[static_cast<Eigen::Index>(i)] <= 0.0) continue;
        const double rel = lux[k][static_cast<Eigen::Index>(i)] / best[static_cast<Eigen::Index>(i)] - 1.0;
        sum_sq += scene.patches[i].area_m2 * rel * rel;
        area += scene.patches[i].area_m2;
        worst = std::max(worst, std::abs(rel));
      }
      std::printf("%8d %10.2f %14.2e %14.2e", ray_counts[k], seconds[k], std::sqrt(sum_sq / area), worst);
      for (int s : surfaces) {
        double weighted = 0.0, a = 0.0;
        for (std::size_t i = 0; i < scene.patches.size(); ++i)
          if (scene.patches[i].surface == s) {
            weighted += scene.patches[i].area_m2 * lux[k][static_cast<Eigen::Index>(i)];
            a += scene.patches[i].area_m2;
          }
        std::printf(" %12.2f", weighted / a);
      }
      std::printf("\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
