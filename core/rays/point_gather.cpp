#include "core/rays/point_gather.h"

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

#include "core/rays/sampling.h"

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

PointIlluminance exact_point_illuminance(const Scene& scene, const RayCaster& caster, const RadiositySolution& solution,
                                         std::span<const ReceiverPoint> points, const FormFactorOptions& row_options,
                                         const DirectLightOptions& direct, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index Q = static_cast<Eigen::Index>(points.size());
  if (solution.radiosity_lm_per_m2.rows() != static_cast<Eigen::Index>(scene.patches.size()))
    throw std::invalid_argument("exact_point_illuminance: the solution is not of this scene");
  // Luminaires (real ones: this is the verification's scene) and their flux.
  std::vector<int> luminaires, slot(scene.surfaces.size(), -1);
  std::vector<double> flux, area;
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s)
    if (scene.surfaces[s].is_luminaire()) {
      slot[s] = static_cast<int>(luminaires.size());
      luminaires.push_back(static_cast<int>(s));
      flux.push_back(0.0);
      area.push_back(0.0);
    }
  for (const Patch& p : scene.patches)
    if (const int l = slot[static_cast<std::size_t>(p.surface)]; l >= 0) {
      flux[static_cast<std::size_t>(l)] += p.area_m2 * p.exitance_lm_per_m2;
      area[static_cast<std::size_t>(l)] += p.area_m2;
    }
  std::vector<int> with_area;
  for (std::size_t l = 0; l < luminaires.size(); ++l)
    if (area[l] > 0.0) with_area.push_back(static_cast<int>(l));
  std::vector<int> surfaces;
  for (int l : with_area) surfaces.push_back(luminaires[static_cast<std::size_t>(l)]);
  const LuminaireLight light = compute_luminaire_light_at_points(scene, caster, points, surfaces, direct);
  PointIlluminance out;
  out.direct_lux = Eigen::VectorXd::Zero(Q);
  Eigen::VectorXd closed = Eigen::VectorXd::Zero(Q);  // share of each point's light reaching luminaires
  for (std::size_t c = 0; c < with_area.size(); ++c) {
    const std::size_t l = static_cast<std::size_t>(with_area[c]);
    out.direct_lux += light.lux_per_lm.col(static_cast<Eigen::Index>(c)) * flux[l];
    closed += light.form_factor.col(static_cast<Eigen::Index>(c));
  }
  out.total_lux = out.direct_lux;
  out.rows = compute_point_rows(scene, caster, points, row_options, progress);
  const FormFactorRows& rows = out.rows;
  out.rays_cast = rows.rays_cast;
  const int channels = static_cast<int>(solution.radiosity_lm_per_m2.cols());
  out.indirect_standard_error_lux = Eigen::VectorXd::Zero(Q);
  const double rays = row_options.rays_per_patch;
  for (Eigen::Index q = 0; q < Q; ++q) {
    double kept = 0.0, struck = 0.0;
    Eigen::RowVectorXd gathered = Eigen::RowVectorXd::Zero(channels);
    double emitted = 0.0;
    double mean = 0.0, square = 0.0;  // of a ray's photometric value (0 for a ray that gathers nothing)
    for (SparseRows::InnerIterator it(rows.F, q); it; ++it) {
      const Patch& p = scene.patches[static_cast<std::size_t>(it.col())];
      if (scene.surfaces[static_cast<std::size_t>(p.surface)].is_luminaire()) {
        struck += it.value();
        continue;
      }
      kept += it.value();
      gathered += it.value() * solution.radiosity_lm_per_m2.row(it.col());
      emitted += it.value() * p.exitance_lm_per_m2;
      const double value = photometric(solution.radiosity_lm_per_m2.row(it.col()));
      mean += it.value() * value;
      square += it.value() * value * value;
    }
    const double scale = kept > 0.0 ? std::max(0.0, kept + struck - closed[q]) / kept : 0.0;
    out.total_lux[q] += scale * photometric(gathered);
    out.direct_lux[q] += scale * emitted;
    out.indirect_standard_error_lux[q] = scale * std::sqrt(std::max(0.0, square - mean * mean) / rays);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::vector<int> dominant_patches(const Scene& scene, const FormFactorRows& point_rows,
                                  const RadiositySolution& solution, std::span<const int> which, double share) {
  std::vector<int> out;
  for (int q : which) {
    if (q < 0 || q >= point_rows.F.rows()) throw std::invalid_argument("dominant_patches: no such point row");
    std::vector<std::pair<int, double>> light;
    double total = 0.0;
    for (SparseRows::InnerIterator it(point_rows.F, q); it; ++it) {
      const Patch& p = scene.patches[static_cast<std::size_t>(it.col())];
      if (scene.surfaces[static_cast<std::size_t>(p.surface)].is_luminaire()) continue;
      const double value = it.value() * photometric(solution.radiosity_lm_per_m2.row(it.col()));
      light.emplace_back(static_cast<int>(it.col()), value);
      total += value;
    }
    if (!(total > 0.0)) continue;
    for (const auto& [patch, value] : light)
      if (value >= share * total) out.push_back(patch);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace ilp
