#include "core/direct_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/sampling.h"

namespace ilp {
namespace {

// Heights above an emitter's plane below this fraction of the distance (plus the
// emitter's size) count as in the plane: far above double round-off, far below any
// real geometry.
constexpr double kCoplanarRelTolerance = 1e-9;

// Keeps the part of polygon `in` where (v - point) . normal >= 0 (Sutherland-Hodgman).
std::vector<Eigen::Vector3d> clip_to_hemisphere(const std::vector<Eigen::Vector3d>& in,
                                                const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  std::vector<Eigen::Vector3d> out;
  const std::size_t n = in.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& a = in[k];
    const Eigen::Vector3d& b = in[(k + 1) % n];
    const double da = (a - point).dot(normal), db = (b - point).dot(normal);
    const bool a_inside = da >= 0.0, b_inside = db >= 0.0;
    if (a_inside) out.push_back(a);
    if (a_inside != b_inside) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

}  // namespace

double point_to_triangle_form_factor(const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                     const Patch& emitter) {
  // Behind the emitting side, or in its plane (a coplanar point, the emitter's own
  // patches included, exchanges no light; round-off must not make it see a hemisphere).
  const Eigen::Vector3d from_centroid = point - emitter.centroid_m;
  if (from_centroid.dot(emitter.normal) <= kCoplanarRelTolerance * (from_centroid.norm() + std::sqrt(emitter.area_m2)))
    return 0.0;
  const std::vector<Eigen::Vector3d> polygon = clip_to_hemisphere(
      {emitter.vertices_m[0], emitter.vertices_m[1], emitter.vertices_m[2]}, point, normal);
  if (polygon.size() < 3) return 0.0;
  // Lambert: F = 1/(2 pi) sum_k angle_k (n . unit(a_k x a_k+1)), a_k = v_k - point.
  double sum = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Eigen::Vector3d a = (polygon[k] - point).normalized();
    const Eigen::Vector3d b = (polygon[(k + 1) % polygon.size()] - point).normalized();
    const Eigen::Vector3d c = a.cross(b);
    const double sin_angle = c.norm();
    if (sin_angle <= 0.0) continue;
    const double angle = std::atan2(sin_angle, a.dot(b));
    sum += angle * normal.dot(c / sin_angle);
  }
  return std::abs(sum) / (2.0 * std::numbers::pi);
}

namespace {

// The emitter patches of one surface (one luminaire), which share their shadow rays.
struct EmitterGroup {
  int surface = -1;
  std::vector<std::size_t> slots;    // columns of the result
  std::vector<double> cumulative_area_m2;
};

std::vector<EmitterGroup> group_by_surface(const Scene& scene, std::span<const int> emitters) {
  std::vector<EmitterGroup> groups;
  for (std::size_t e = 0; e < emitters.size(); ++e) {
    const Patch& p = scene.patches[emitters[e]];
    auto it = std::find_if(groups.begin(), groups.end(), [&](const EmitterGroup& g) { return g.surface == p.surface; });
    if (it == groups.end()) it = groups.insert(groups.end(), EmitterGroup{p.surface, {}, {}});
    it->slots.push_back(e);
    it->cumulative_area_m2.push_back((it->cumulative_area_m2.empty() ? 0.0 : it->cumulative_area_m2.back()) + p.area_m2);
  }
  return groups;
}

}  // namespace

Eigen::MatrixXd compute_emitter_form_factors(const Scene& scene, const RayCaster& caster,
                                             std::span<const int> receivers, std::span<const int> emitters,
                                             const DirectLightOptions& options) {
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(receivers.size()),
                                            static_cast<Eigen::Index>(emitters.size()));
  const std::vector<EmitterGroup> groups = group_by_surface(scene, emitters);
  const double offset = caster.ray_offset_m();
  const auto receiver_points = halton4_points(static_cast<std::uint32_t>(options.receiver_points));
  const auto target_points = halton4_points(static_cast<std::uint32_t>(options.receiver_points * options.shadow_rays));
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers.size(), 16), [&](const auto& range) {
      RayCaster::prepare_thread();
      std::vector<double> unoccluded;
      for (std::size_t r = range.begin(); r != range.end(); ++r) {
        const Patch& receiver = scene.patches[receivers[r]];
        const RotatedHalton4 points(options.seed, static_cast<std::uint64_t>(receivers[r]));
        for (const EmitterGroup& group : groups) {
          const RotatedHalton4 targets(options.seed ^ 0xD1B54A32D192ED03ull,
                                       static_cast<std::uint64_t>(receivers[r]) * 0x9E3779B1u +
                                           static_cast<std::uint64_t>(group.surface));
          const double group_area = group.cumulative_area_m2.back();
          for (int s = 0; s < options.receiver_points; ++s) {
            const auto u = points.rotate(receiver_points[static_cast<std::size_t>(s)]);
            const Eigen::Vector3d x = sample_triangle(receiver.vertices_m[0], receiver.vertices_m[1],
                                                      receiver.vertices_m[2], u[0], u[1]);
            unoccluded.assign(group.slots.size(), 0.0);
            bool any = false;
            for (std::size_t k = 0; k < group.slots.size(); ++k) {
              unoccluded[k] = point_to_triangle_form_factor(x, receiver.normal, scene.patches[emitters[group.slots[k]]]);
              any = any || unoccluded[k] > 0.0;
            }
            if (!any) continue;
            // Visible fraction of the emitter: shadow rays to area-uniform points on it.
            int visible = 0;
            for (int k = 0; k < options.shadow_rays; ++k) {
              const auto v = targets.rotate(target_points[static_cast<std::size_t>(s * options.shadow_rays + k)]);
              const auto pick = std::upper_bound(group.cumulative_area_m2.begin(), group.cumulative_area_m2.end(),
                                                 v[2] * group_area);
              const std::size_t slot = std::min<std::size_t>(pick - group.cumulative_area_m2.begin(), group.slots.size() - 1);
              const Patch& emitter = scene.patches[emitters[group.slots[slot]]];
              const Eigen::Vector3d y = sample_triangle(emitter.vertices_m[0], emitter.vertices_m[1],
                                                        emitter.vertices_m[2], v[0], v[1]);
              if (!caster.occluded(x + receiver.normal * offset, y + emitter.normal * offset)) ++visible;
            }
            const double visible_fraction = static_cast<double>(visible) / options.shadow_rays;
            for (std::size_t k = 0; k < group.slots.size(); ++k)
              F(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(group.slots[k])) +=
                  unoccluded[k] * visible_fraction / options.receiver_points;
          }
        }
      }
    });
  });
  return F;
}

std::vector<int> luminaire_patches(const Scene& scene) {
  std::vector<int> out;
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    if (scene.surfaces[scene.patches[i].surface].is_luminaire) out.push_back(static_cast<int>(i));
  return out;
}

void replace_emitter_columns(const Scene& scene, const RayCaster& caster, std::span<const int> emitters,
                             const DirectLightOptions& options, FormFactorRows& rows, const CheapDirectLight* cheap_rows) {
  if (emitters.empty()) return;
  Eigen::MatrixXd exact;
  if (!cheap_rows) {
    exact = compute_emitter_form_factors(scene, caster, rows.row_patches, emitters, options);
  } else {
    if (cheap_rows->rows.size() != rows.row_patches.size())
      throw std::invalid_argument("replace_emitter_columns: one cheap flag per row");
    std::vector<int> precise, cheap;
    std::vector<Eigen::Index> precise_at, cheap_at;
    for (std::size_t r = 0; r < rows.row_patches.size(); ++r) {
      (cheap_rows->rows[r] ? cheap : precise).push_back(rows.row_patches[r]);
      (cheap_rows->rows[r] ? cheap_at : precise_at).push_back(static_cast<Eigen::Index>(r));
    }
    exact.resize(static_cast<Eigen::Index>(rows.row_patches.size()), static_cast<Eigen::Index>(emitters.size()));
    const Eigen::MatrixXd a = compute_emitter_form_factors(scene, caster, precise, emitters, options);
    const Eigen::MatrixXd b = compute_emitter_form_factors(scene, caster, cheap, emitters, cheap_rows->options);
    for (std::size_t k = 0; k < precise_at.size(); ++k) exact.row(precise_at[k]) = a.row(static_cast<Eigen::Index>(k));
    for (std::size_t k = 0; k < cheap_at.size(); ++k) exact.row(cheap_at[k]) = b.row(static_cast<Eigen::Index>(k));
  }
  std::vector<int> emitter_slot(scene.patches.size(), -1);
  for (std::size_t e = 0; e < emitters.size(); ++e) emitter_slot[emitters[e]] = static_cast<int>(e);
  // Emitter columns in ascending order, so each row is a merge of two sorted lists.
  std::vector<std::size_t> by_column(emitters.size());
  for (std::size_t e = 0; e < by_column.size(); ++e) by_column[e] = e;
  std::sort(by_column.begin(), by_column.end(), [&](std::size_t a, std::size_t b) { return emitters[a] < emitters[b]; });

  SparseRows F(rows.F.rows(), rows.F.cols());
  F.reserve(rows.F.nonZeros() + static_cast<Eigen::Index>((exact.array() > 0.0).count()));
  for (Eigen::Index r = 0; r < rows.F.rows(); ++r) {
    F.startVec(r);
    SparseRows::InnerIterator it(rows.F, r);
    std::size_t k = 0;
    while (it || k < by_column.size()) {
      const int emitter_column = k < by_column.size() ? emitters[by_column[k]] : std::numeric_limits<int>::max();
      if (it && it.col() < emitter_column) {
        if (emitter_slot[it.col()] < 0) F.insertBack(r, it.col()) = it.value();  // gathered hits on emitters are dropped
        ++it;
      } else {
        if (it && it.col() == emitter_column) ++it;
        const double value = exact(r, static_cast<Eigen::Index>(by_column[k]));
        if (value > 0.0) F.insertBack(r, emitter_column) = value;
        ++k;
      }
    }
  }
  F.finalize();
  // The rays that struck an emitter only sampled its solid angle, which the closed
  // form knows: scale the row's other entries so that it loses exactly the
  // closed-form share and keeps its escaped and back-hit shares (see
  // apply_closed_form_loss in sample_operator.cpp, which does the same).
  for (Eigen::Index r = 0; r < F.rows(); ++r) {
    double kept = 0.0, struck = 0.0;
    for (SparseRows::InnerIterator it(rows.F, r); it; ++it) (emitter_slot[it.col()] >= 0 ? struck : kept) += it.value();
    if (!(kept > 0.0)) continue;
    const double scale = std::max(0.0, kept + struck - exact.row(r).sum()) / kept;
    for (SparseRows::InnerIterator it(F, r); it; ++it)
      if (emitter_slot[it.col()] < 0) it.valueRef() *= scale;
  }
  rows.F = std::move(F);
}

}  // namespace ilp
