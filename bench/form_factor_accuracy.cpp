// Accuracy of the ray-cast form factors against Howell's closed forms: for parallel
// unit squares at three separations and a range of rays per patch, the RMS and
// worst error over 20 seeds, next to the standard deviation independent rays would
// give (the binomial sigma). The tests' tolerances rest on this table
// (docs/foundation.md).
//
//   ./build/bench/form_factor_accuracy
#include <cmath>
#include <cstdio>

#include "core/transport/form_factors.h"
#include "core/transport/ray_caster.h"
#include "core/scene/reference_scenes.h"

int main() {
  using V = Eigen::Vector3d;
  constexpr int kSeeds = 20;
  std::printf("%-14s %8s %10s %10s %10s %12s\n", "separation_m", "rays", "exact_F", "rms_error", "worst_error",
              "rms/sigma");
  for (double separation : {0.5, 1.0, 2.0}) {
    const ilp::Scene scene = ilp::reference::make_quad_scene(
        {{"bottom", V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0)},
         {"top", V(0, 0, separation), V(0, 1, separation), V(1, 1, separation), V(1, 0, separation)}},
        0.0);
    const ilp::RayCaster caster(scene);
    const double exact = ilp::reference::parallel_rectangles_form_factor(1.0, 1.0, separation);
    const double source_patches = static_cast<double>(ilp::reference::patches_of(scene, "bottom").size());
    for (int rays : {64, 256, 1024, 4096, 16384, 65536}) {
      double sum_squares = 0.0, worst = 0.0;
      for (int seed = 1; seed <= kSeeds; ++seed) {
        ilp::FormFactorOptions options;
        options.rays_per_patch = rays;
        options.seed = static_cast<std::uint64_t>(seed);
        const auto rows = ilp::compute_form_factor_rows(scene, caster, scene.all_patches(), options);
        const double error = ilp::surface_form_factor(scene, rows, "bottom", "top") - exact;
        sum_squares += error * error;
        worst = std::max(worst, std::abs(error));
      }
      const double rms = std::sqrt(sum_squares / kSeeds);
      const double sigma = std::sqrt(exact * (1.0 - exact) / (rays * source_patches));
      std::printf("%-14.1f %8d %10.6f %10.2e %10.2e %12.2f\n", separation, rays, exact, rms, worst, rms / sigma);
    }
  }
  return 0;
}
