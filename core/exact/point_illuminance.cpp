#include "core/exact/point_illuminance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

namespace ilp {

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
