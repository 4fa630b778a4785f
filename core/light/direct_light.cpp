#include "core/light/direct_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "core/rays/sampling.h"
#include "core/base/key_hash.h"

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

// Unoccluded light below this share of the brightest luminaire's at a point gets one
// shadow ray: it changes that point's light by less than 0.1 % per luminaire.
constexpr double kNegligibleShare = 1e-3;
// Shadow rays cast first; the rest of options.shadow_rays only where these disagree.
constexpr int kProbeRays = 4;
// Point sources of a non-Lambertian opening are at most this fraction of the
// distance apart: the midpoint rule's error is then below 1 % (tested against the
// closed form for a Lambertian distribution).
constexpr double kSourceSpacingPerDistance = 0.12;
constexpr int kMaxSourcesPerSide = 24;

// One luminaire as the direct light needs it.
struct LuminaireGeometry {
  const LuminaireType* type = nullptr;
  std::vector<int> patches;  // its opening
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();
  Eigen::Matrix3d to_scene = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d to_local = Eigen::Matrix3d::Identity();
  double area_m2 = 0.0;
  double size_m = 0.0;  // longest side
  bool lambertian = true;
  int surface = -1;
};

std::vector<LuminaireGeometry> luminaire_geometry(const Scene& scene, std::span<const int> surfaces) {
  std::vector<LuminaireGeometry> out(surfaces.size());
  std::vector<int> slot(scene.surfaces.size(), -1);
  for (std::size_t l = 0; l < surfaces.size(); ++l) {
    const SceneLuminaire& lum = luminaire_of(scene, surfaces[l]);
    LuminaireGeometry& g = out[l];
    g.type = &lum.type;
    g.centre_m = lum.placement.position_m;
    g.to_scene = luminaire_rotation(lum.placement);
    g.to_local = g.to_scene.transpose();
    g.size_m = std::max(lum.type.length_m, lum.type.width_m);
    g.lambertian = lum.type.lambertian();
    g.surface = surfaces[l];
    slot[static_cast<std::size_t>(surfaces[l])] = static_cast<int>(l);
  }
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    if (const int l = slot[static_cast<std::size_t>(scene.patches[i].surface)]; l >= 0) {
      out[static_cast<std::size_t>(l)].patches.push_back(static_cast<int>(i));
      out[static_cast<std::size_t>(l)].area_m2 += scene.patches[i].area_m2;
    }
  return out;
}

// A point of the opening from (u, v) in the unit square: area-uniform (a disc through
// the concentric map).
Eigen::Vector3d opening_point(const LuminaireGeometry& g, double u, double v) {
  Eigen::Vector3d local;
  if (g.type->shape == OutlineShape::rectangle) {
    local = Eigen::Vector3d((u - 0.5) * g.type->length_m, (v - 0.5) * g.type->width_m, 0.0);
  } else {
    const PolarPoint p = concentric_disk(u, v);
    local = Eigen::Vector3d(0.5 * g.type->length_m * p.r * std::cos(p.phi), 0.5 * g.type->width_m * p.r * std::sin(p.phi), 0.0);
  }
  return g.centre_m + g.to_scene * local;
}

// Illuminance per lumen at x (normal n) from a point source at y carrying the
// luminaire's whole distribution: I(direction) cos(theta_x) / d^2.
double point_source_lux_per_lm(const LuminaireGeometry& g, const Eigen::Vector3d& y, const Eigen::Vector3d& x,
                               const Eigen::Vector3d& n) {
  const Eigen::Vector3d d = x - y;
  const double d2 = d.squaredNorm();
  if (!(d2 > 0.0)) return 0.0;
  const double dist = std::sqrt(d2);
  const double cos_x = -n.dot(d) / dist;
  if (cos_x <= 0.0) return 0.0;
  return g.type->distribution->cd_per_lm(g.to_local * (d / dist)) * cos_x / d2;
}

struct Unoccluded {
  double lux_per_lm = 0.0;
  double form_factor = 0.0;
};

Unoccluded unoccluded_light(const Scene& scene, const LuminaireGeometry& g, const Eigen::Vector3d& x,
                            const Eigen::Vector3d& n) {
  Unoccluded out;
  for (int p : g.patches) out.form_factor += point_to_triangle_form_factor(x, n, scene.patches[static_cast<std::size_t>(p)]);
  if (g.lambertian) {
    out.lux_per_lm = out.form_factor / g.area_m2;  // reciprocity: E = M F(x -> opening), M = 1 lm / A
    return out;
  }
  // Point sources per side of the opening, each side cut by its own length (a linear
  // luminaire 1.2 m x 4 cm needs several along and one across).
  const double spacing = kSourceSpacingPerDistance * std::max((x - g.centre_m).norm(), 1e-9);
  auto sources_along = [&](double side_m) {
    // Clamped in double: a receiver on the opening would make the count overflow an int.
    return static_cast<int>(std::clamp(std::ceil(side_m / spacing), 1.0, static_cast<double>(kMaxSourcesPerSide)));
  };
  int mx = sources_along(g.type->length_m), my = sources_along(g.type->width_m);
  if (g.type->shape == OutlineShape::disc) mx = my = std::max(mx, my);  // the concentric map's cells
  for (int i = 0; i < mx; ++i)
    for (int j = 0; j < my; ++j)
      out.lux_per_lm += point_source_lux_per_lm(g, opening_point(g, (i + 0.5) / mx, (j + 0.5) / my), x, n);
  out.lux_per_lm /= static_cast<double>(mx) * my;
  return out;
}

// The visible share of the luminaire's light at x, each shadow ray weighted by the
// light its point on the opening sends to x. `rays` at most; kProbeRays first.
double visible_share(const RayCaster& caster, const LuminaireGeometry& g, const Eigen::Vector3d& x,
                     const Eigen::Vector3d& n, const RotatedHalton4& targets, const std::array<double, 4>* target_points,
                     int rays) {
  const Eigen::Vector3d from = x + n * caster.ray_offset_m();
  double weight = 0.0, visible_weight = 0.0;
  int cast = 0, visible = 0, weighted_seen = 0, weighted_visible = 0;
  auto cast_ray = [&](int k) {
    const auto v = targets.rotate(target_points[k]);
    const Eigen::Vector3d y = opening_point(g, v[0], v[1]);
    const double w = point_source_lux_per_lm(g, y, x, n);
    const bool seen = !caster.occluded(from, y);
    ++cast;
    visible += seen;
    weight += w;
    if (seen) visible_weight += w;
    if (w > 0.0) {
      ++weighted_seen;
      weighted_visible += seen;
    }
  };
  const int probe = std::min(kProbeRays, rays);
  for (int k = 0; k < probe; ++k) cast_ray(k);
  const bool unanimous = weighted_seen > 0 && (weighted_visible == 0 || weighted_visible == weighted_seen);
  if (!unanimous)
    for (int k = probe; k < rays; ++k) cast_ray(k);
  // No ray reached a part of the opening that lights x (a sliver in front of x's
  // plane): the plain visible fraction.
  if (!(weight > 0.0)) return static_cast<double>(visible) / cast;
  return visible_weight / weight;
}

// The shared loop: receiver r has `points_per_receiver` points (point_of(r, s) gives
// one) and its own stream of shadow-ray targets, stream_of(r), so that its light
// does not depend on which other receivers are computed with it.
template <class PointOf, class StreamOf>
LuminaireLight luminaire_light(const Scene& scene, const RayCaster& caster, std::size_t receivers,
                               int points_per_receiver, std::span<const int> luminaire_surfaces,
                               const DirectLightOptions& options, const StreamOf& stream_of, const PointOf& point_of) {
  const auto R = static_cast<Eigen::Index>(receivers);
  const auto L = static_cast<Eigen::Index>(luminaire_surfaces.size());
  LuminaireLight out{Eigen::MatrixXd::Zero(R, L), Eigen::MatrixXd::Zero(R, L)};
  if (R == 0 || L == 0) return out;
  const std::vector<LuminaireGeometry> geometry = luminaire_geometry(scene, luminaire_surfaces);
  const int rays = std::max(1, options.shadow_rays);
  const auto target_points = halton4_points(static_cast<std::uint32_t>(points_per_receiver * rays));
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  std::atomic<std::size_t> done{0};
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers, 16), [&](const auto& range) {
      RayCaster::prepare_thread();
      std::vector<Unoccluded> unoccluded(geometry.size());
      for (std::size_t r = range.begin(); r != range.end(); ++r) {
        const auto row = static_cast<Eigen::Index>(r);
        for (int s = 0; s < points_per_receiver; ++s) {
          const ReceiverPoint point = point_of(r, s);
          double brightest = 0.0;
          for (std::size_t l = 0; l < geometry.size(); ++l) {
            unoccluded[l] = unoccluded_light(scene, geometry[l], point.position_m, point.normal);
            brightest = std::max(brightest, unoccluded[l].lux_per_lm);
          }
          for (std::size_t l = 0; l < geometry.size(); ++l) {
            if (unoccluded[l].lux_per_lm <= 0.0 && unoccluded[l].form_factor <= 0.0) continue;
            const RotatedHalton4 targets(options.seed ^ 0xD1B54A32D192ED03ull,
                                         stream_of(r) * 0x9E3779B1u +
                                             static_cast<std::uint64_t>(geometry[l].surface));
            const bool negligible = unoccluded[l].lux_per_lm < kNegligibleShare * brightest;
            // This point's slice of the target set.
            const std::array<double, 4>* slice = target_points.data() + static_cast<std::ptrdiff_t>(s) * rays;
            const double share = visible_share(caster, geometry[l], point.position_m, point.normal, targets, slice,
                                               negligible ? 1 : rays);
            const auto col = static_cast<Eigen::Index>(l);
            out.lux_per_lm(row, col) += unoccluded[l].lux_per_lm * share / points_per_receiver;
            out.form_factor(row, col) += unoccluded[l].form_factor * share / points_per_receiver;
          }
        }
      }
      const std::size_t now = done.fetch_add(range.size()) + range.size();
      if (options.progress) options.progress(options.progress_label, now, receivers);
    });
  });
  return out;
}

}  // namespace

LuminaireLight compute_luminaire_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                       std::span<const int> luminaire_surfaces, const DirectLightOptions& options) {
  const auto receiver_points = halton4_points(static_cast<std::uint32_t>(options.receiver_points));
  return luminaire_light(scene, caster, receivers.size(), options.receiver_points, luminaire_surfaces, options,
                         [&](std::size_t r) { return static_cast<std::uint64_t>(receivers[r]); },
                         [&](std::size_t r, int s) {
                           const Patch& p = scene.patches[static_cast<std::size_t>(receivers[r])];
                           const RotatedHalton4 points(options.seed, static_cast<std::uint64_t>(receivers[r]));
                           const auto u = points.rotate(receiver_points[static_cast<std::size_t>(s)]);
                           return ReceiverPoint{sample_triangle(p.vertices_m[0], p.vertices_m[1], p.vertices_m[2], u[0], u[1]),
                                                p.normal};
                         });
}

LuminaireLight compute_luminaire_light_at_points(const Scene& scene, const RayCaster& caster,
                                                 std::span<const ReceiverPoint> points,
                                                 std::span<const int> luminaire_surfaces,
                                                 const DirectLightOptions& options) {
  // A point has no area to average its visibility over: it gets the shadow rays a
  // patch spends on all its receiver points (in a penumbra; 4 decide elsewhere).
  DirectLightOptions point_options = options;
  point_options.shadow_rays = options.shadow_rays * std::max(1, options.receiver_points);
  return luminaire_light(scene, caster, points.size(), 1, luminaire_surfaces, point_options,
                         [](std::size_t r) { return static_cast<std::uint64_t>(r) ^ 0x5851F42D4C957F2Dull; },
                         [&](std::size_t r, int) { return points[r]; });
}

std::vector<int> luminaire_surfaces(const Scene& scene) {
  std::vector<int> out;
  for (std::size_t s = 0; s < scene.surfaces.size(); ++s)
    if (scene.surfaces[s].is_luminaire()) out.push_back(static_cast<int>(s));
  return out;
}

namespace {

// compute_luminaire_light for the rows' patches, the rows `cheap_rows` marks with its options.
LuminaireLight row_light(const Scene& scene, const RayCaster& caster, std::span<const int> surfaces,
                         const DirectLightOptions& options, const FormFactorRows& rows,
                         const CheapDirectLight* cheap_rows) {
  if (!cheap_rows) return compute_luminaire_light(scene, caster, rows.row_patches, surfaces, options);
  if (cheap_rows->rows.size() != rows.row_patches.size())
    throw std::invalid_argument("replace_emitter_columns: one cheap flag per row");
  std::vector<int> precise, cheap;
  std::vector<Eigen::Index> precise_at, cheap_at;
  for (std::size_t r = 0; r < rows.row_patches.size(); ++r) {
    (cheap_rows->rows[r] ? cheap : precise).push_back(rows.row_patches[r]);
    (cheap_rows->rows[r] ? cheap_at : precise_at).push_back(static_cast<Eigen::Index>(r));
  }
  const auto R = static_cast<Eigen::Index>(rows.row_patches.size()), L = static_cast<Eigen::Index>(surfaces.size());
  LuminaireLight out{Eigen::MatrixXd(R, L), Eigen::MatrixXd(R, L)};
  const LuminaireLight a = compute_luminaire_light(scene, caster, precise, surfaces, options);
  const LuminaireLight b = compute_luminaire_light(scene, caster, cheap, surfaces, cheap_rows->options);
  for (std::size_t k = 0; k < precise_at.size(); ++k) {
    out.lux_per_lm.row(precise_at[k]) = a.lux_per_lm.row(static_cast<Eigen::Index>(k));
    out.form_factor.row(precise_at[k]) = a.form_factor.row(static_cast<Eigen::Index>(k));
  }
  for (std::size_t k = 0; k < cheap_at.size(); ++k) {
    out.lux_per_lm.row(cheap_at[k]) = b.lux_per_lm.row(static_cast<Eigen::Index>(k));
    out.form_factor.row(cheap_at[k]) = b.form_factor.row(static_cast<Eigen::Index>(k));
  }
  return out;
}

}  // namespace

void replace_emitter_columns(const Scene& scene, const RayCaster& caster, const DirectLightOptions& options,
                             FormFactorRows& rows, const CheapDirectLight* cheap_rows) {
  const std::vector<int> surfaces = luminaire_surfaces(scene);
  if (surfaces.empty()) return;
  const LuminaireLight light = row_light(scene, caster, surfaces, options, rows, cheap_rows);
  // One column per opening patch: lux per lm x the patch's area, so F B = illuminance.
  std::vector<int> emitters, emitter_luminaire;
  std::vector<int> slot_of_surface(scene.surfaces.size(), -1);
  for (std::size_t l = 0; l < surfaces.size(); ++l) slot_of_surface[static_cast<std::size_t>(surfaces[l])] = static_cast<int>(l);
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    if (const int l = slot_of_surface[static_cast<std::size_t>(scene.patches[i].surface)]; l >= 0) {
      emitters.push_back(static_cast<int>(i));
      emitter_luminaire.push_back(l);
    }
  Eigen::MatrixXd exact(light.lux_per_lm.rows(), static_cast<Eigen::Index>(emitters.size()));
  for (std::size_t e = 0; e < emitters.size(); ++e)
    exact.col(static_cast<Eigen::Index>(e)) =
        light.lux_per_lm.col(emitter_luminaire[e]) * scene.patches[static_cast<std::size_t>(emitters[e])].area_m2;
  // What the real (not virtual) luminaires absorb of each row's light.
  Eigen::VectorXd absorbed = Eigen::VectorXd::Zero(light.form_factor.rows());
  for (std::size_t l = 0; l < surfaces.size(); ++l)
    if (!scene.surfaces[static_cast<std::size_t>(surfaces[l])].is_virtual) absorbed += light.form_factor.col(static_cast<Eigen::Index>(l));
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
  // The rays that struck a luminaire only sampled its solid angle, which the closed
  // form knows: scale the row's other entries so that it loses exactly the
  // closed-form share and keeps its escaped and back-hit shares (see
  // apply_closed_form_loss in core/operator/sample_rows.cpp, which does the same).
  for (Eigen::Index r = 0; r < F.rows(); ++r) {
    double kept = 0.0, struck = 0.0;
    for (SparseRows::InnerIterator it(rows.F, r); it; ++it) (emitter_slot[it.col()] >= 0 ? struck : kept) += it.value();
    if (!(kept > 0.0)) continue;
    const double scale = std::max(0.0, kept + struck - absorbed[r]) / kept;
    for (SparseRows::InnerIterator it(F, r); it; ++it)
      if (emitter_slot[it.col()] < 0) it.valueRef() *= scale;
  }
  rows.F = std::move(F);
}

static_assert(field_count<DirectLightOptions>() == 6, "DirectLightOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const DirectLightOptions& o) {
  k.field("receiver_points", o.receiver_points).field("shadow_rays", o.shadow_rays).field("seed", o.seed);
  // Not threads, progress or progress_label: the same light for any of them.
}

}  // namespace ilp
