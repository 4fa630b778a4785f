#include "core/transport/point_gather.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/transport/sampling.h"

namespace ilp {
namespace {

// Point streams are kept apart from the patch streams of the same seed.
constexpr std::uint64_t kPointStreamSalt = 0x50494E54ull << 32;

using PointRow = RayCounts;

}  // namespace

FormFactorRows compute_point_rows(const Scene& scene, const RayCaster& caster, std::span<const ReceiverPoint> points,
                                  const FormFactorOptions& options, const ProgressCallback& progress) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("FormFactorOptions::" + error);
  const auto start = std::chrono::steady_clock::now();
  FormFactorRows out;
  const std::size_t rows = points.size();
  for (std::size_t r = 0; r < rows; ++r) out.row_patches.push_back(-1 - static_cast<int>(r));
  std::vector<PointRow> results(rows);
  const auto halton = halton4_points(static_cast<std::uint32_t>(options.rays_per_patch));
  std::atomic<std::size_t> done{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 16), [&](const tbb::blocked_range<std::size_t>& range) {
      const auto ray_modes = RayCaster::prepare_thread();
      std::vector<int> count(scene.patches.size(), 0), touched;
      for (std::size_t r = range.begin(); r != range.end(); ++r) {
        const ReceiverPoint& p = points[r];
        Eigen::Vector3d t, s;
        orthonormal_basis(p.normal, t, s);
        const RotatedHalton4 sequence(options.seed, kPointStreamSalt + r);
        const Eigen::Vector3d origin = p.position_m + p.normal * caster.ray_offset_m();
        PointRow& row = results[r];
        for (int k = 0; k < options.rays_per_patch; ++k) {
          const auto u = sequence.rotate(halton[static_cast<std::size_t>(k)]);
          const RayHit hit = caster.first_hit(origin, sample_cosine_hemisphere(p.normal, t, s, u[2], u[3]));
          if (hit.patch < 0) ++row.escaped;
          else if (!hit.front) ++row.back_hits;
          else if (count[static_cast<std::size_t>(hit.patch)]++ == 0) touched.push_back(hit.patch);
        }
        std::sort(touched.begin(), touched.end());
        for (int j : touched) {
          row.hits.emplace_back(j, count[static_cast<std::size_t>(j)]);
          count[static_cast<std::size_t>(j)] = 0;
        }
        touched.clear();
      }
      const std::size_t now = done.fetch_add(range.size()) + range.size();
      if (progress) progress("point rows", now, rows);
    });
  });
  assemble_rows(results, scene.patches.size(), options.rays_per_patch, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace ilp
