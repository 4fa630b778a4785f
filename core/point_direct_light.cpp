#include "core/point_direct_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/sampling.h"

namespace ilp {
namespace {

// One luminaire's patches and their cumulative areas (shadow-ray targets drawn by area).
struct Luminaire {
  std::vector<int> patches;
  std::vector<double> cumulative_area_m2;
  double area_m2() const { return cumulative_area_m2.empty() ? 0.0 : cumulative_area_m2.back(); }
};

std::vector<Luminaire> gather_luminaires(const Scene& scene, std::span<const int> surfaces) {
  std::vector<int> slot(scene.surfaces.size(), -1);
  std::vector<Luminaire> out(surfaces.size());
  for (std::size_t l = 0; l < surfaces.size(); ++l) {
    const int s = surfaces[l];
    if (s < 0 || s >= static_cast<int>(scene.surfaces.size()) || !scene.surfaces[static_cast<std::size_t>(s)].is_luminaire)
      throw std::invalid_argument("luminaire_lux_per_lm_at_points: surface " + std::to_string(s) + " is not a luminaire");
    slot[static_cast<std::size_t>(s)] = static_cast<int>(l);
  }
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const int l = slot[static_cast<std::size_t>(scene.patches[i].surface)];
    if (l < 0) continue;
    Luminaire& lum = out[static_cast<std::size_t>(l)];
    lum.patches.push_back(static_cast<int>(i));
    lum.cumulative_area_m2.push_back(lum.area_m2() + scene.patches[i].area_m2);
  }
  for (std::size_t l = 0; l < out.size(); ++l)
    if (!(out[l].area_m2() > 0.0))
      throw std::invalid_argument("luminaire_lux_per_lm_at_points: luminaire '" +
                                  scene.surfaces[static_cast<std::size_t>(surfaces[l])].name + "' has no area");
  return out;
}

}  // namespace

Eigen::MatrixXd luminaire_lux_per_lm_at_points(const Scene& scene, const RayCaster& caster,
                                               std::span<const ReceiverPoint> points,
                                               std::span<const int> luminaire_surfaces,
                                               const DirectLightOptions& options) {
  if (options.shadow_rays < 1) throw std::invalid_argument("luminaire_lux_per_lm_at_points: shadow_rays must be >= 1");
  const std::vector<Luminaire> luminaires = gather_luminaires(scene, luminaire_surfaces);
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(points.size()),
                                            static_cast<Eigen::Index>(luminaires.size()));
  const double offset = caster.ray_offset_m();
  const auto targets = halton4_points(static_cast<std::uint32_t>(options.shadow_rays));
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), 16), [&](const auto& range) {
      RayCaster::prepare_thread();
      for (std::size_t r = range.begin(); r != range.end(); ++r) {
        const ReceiverPoint& point = points[r];
        const Eigen::Vector3d origin = point.position_m + point.normal * offset;
        for (std::size_t l = 0; l < luminaires.size(); ++l) {
          const Luminaire& lum = luminaires[l];
          double unoccluded = 0.0;
          for (int p : lum.patches)
            unoccluded += point_to_triangle_form_factor(point.position_m, point.normal, scene.patches[static_cast<std::size_t>(p)]);
          if (!(unoccluded > 0.0)) continue;
          // The stream depends on the point and the luminaire surface only, not on threads.
          const RotatedHalton4 sequence(options.seed ^ 0xA0761D6478BD642Full,
                                        static_cast<std::uint64_t>(r) * 0x9E3779B1u +
                                            static_cast<std::uint64_t>(luminaire_surfaces[l]));
          int visible = 0;
          for (int k = 0; k < options.shadow_rays; ++k) {
            const auto v = sequence.rotate(targets[static_cast<std::size_t>(k)]);
            const auto pick = std::upper_bound(lum.cumulative_area_m2.begin(), lum.cumulative_area_m2.end(),
                                               v[2] * lum.area_m2());
            const std::size_t slot = std::min<std::size_t>(static_cast<std::size_t>(pick - lum.cumulative_area_m2.begin()),
                                                           lum.patches.size() - 1);
            const Patch& emitter = scene.patches[static_cast<std::size_t>(lum.patches[slot])];
            const Eigen::Vector3d y =
                sample_triangle(emitter.vertices_m[0], emitter.vertices_m[1], emitter.vertices_m[2], v[0], v[1]);
            if (!caster.occluded(origin, y + emitter.normal * offset)) ++visible;
          }
          // E = M F with M = flux / area: per lumen, F / area.
          E(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(l)) =
              unoccluded * (static_cast<double>(visible) / options.shadow_rays) / lum.area_m2();
        }
      }
    });
  });
  return E;
}

}  // namespace ilp
