#include "core/transport/direct_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/transport/row_builder.h"
#include "core/transport/sampling.h"
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

// Lambert's form factor from a differential area at `point` (unit `normal`) to the
// planar polygon `in` (any winding), clipped to the point's hemisphere; the caller
// knows the polygon's emitting side faces the point.
double polygon_form_factor(const std::vector<Eigen::Vector3d>& in, const Eigen::Vector3d& point,
                           const Eigen::Vector3d& normal) {
  const std::vector<Eigen::Vector3d> polygon = clip_to_hemisphere(in, point, normal);
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

}  // namespace

double point_to_triangle_form_factor(const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                     const Patch& emitter) {
  // Behind the emitting side, or in its plane (a coplanar point, the emitter's own
  // patches included, exchanges no light; round-off must not make it see a hemisphere).
  const Eigen::Vector3d from_centroid = point - emitter.centroid_m;
  if (from_centroid.dot(emitter.normal) <= kCoplanarRelTolerance * (from_centroid.norm() + std::sqrt(emitter.area_m2)))
    return 0.0;
  return polygon_form_factor({emitter.vertices_m[0], emitter.vertices_m[1], emitter.vertices_m[2]}, point, normal);
}

namespace {

// Unoccluded light below this share of the brightest luminaire's at a point gets one
// shadow ray: it changes that point's light by less than 0.1 % per luminaire.
constexpr double kNegligibleShare = 1e-3;
// Below this many shadow rays per point (the cheap estimate of cheap_direct_light_options)
// the rays go to stratified points of the opening, all of them cast; from it on, to
// the vertices of a grid over the opening, refined where they disagree (OpeningVisibility).
constexpr int kMinGridRays = 4;
// Levels a cell of that grid whose corners disagree is cut in four before the shadow's
// edge is found on its cells' edges by bisection.
constexpr int kRefineLevels = 1;
// Bisection steps on a leaf cell's edge whose ends disagree: the crossing to 2^-10 of
// the edge, 1/8192 of the opening's side on the default grid (2 cells, 1 level).
constexpr int kCrossingSteps = 9;
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

// The point sources a non-Lambertian opening is cut into for a receiver at x, along its
// length and across: each side cut by its own length (a linear luminaire 1.2 m x 4 cm
// needs several along and one across), at most kSourceSpacingPerDistance of the distance apart.
std::pair<int, int> point_sources(const LuminaireGeometry& g, const Eigen::Vector3d& x) {
  const double spacing = kSourceSpacingPerDistance * std::max((x - g.centre_m).norm(), 1e-9);
  auto sources_along = [&](double side_m) {
    // Clamped in double: a receiver on the opening would make the count overflow an int.
    return static_cast<int>(std::clamp(std::ceil(side_m / spacing), 1.0, static_cast<double>(kMaxSourcesPerSide)));
  };
  int mx = sources_along(g.type->length_m), my = sources_along(g.type->width_m);
  if (g.type->shape == OutlineShape::disc) mx = my = std::max(mx, my);  // the concentric map's cells
  return {mx, my};
}

Unoccluded unoccluded_light(const Scene& scene, const LuminaireGeometry& g, const Eigen::Vector3d& x,
                            const Eigen::Vector3d& n, bool form_factors) {
  Unoccluded out;
  if (form_factors || g.lambertian)
    for (int p : g.patches) out.form_factor += point_to_triangle_form_factor(x, n, scene.patches[static_cast<std::size_t>(p)]);
  if (g.lambertian) {
    out.lux_per_lm = out.form_factor / g.area_m2;  // reciprocity: E = M F(x -> opening), M = 1 lm / A
    return out;
  }
  const auto [mx, my] = point_sources(g, x);
  for (int i = 0; i < mx; ++i)
    for (int j = 0; j < my; ++j)
      out.lux_per_lm += point_source_lux_per_lm(g, opening_point(g, (i + 0.5) / mx, (j + 0.5) / my), x, n);
  out.lux_per_lm /= static_cast<double>(mx) * my;
  return out;
}

// The visible share of the luminaire's light at x from `rays` shadow rays to
// stratified points of the opening (the cheap estimate; one ray for a negligible
// luminaire), each weighted by the light its point on the opening sends to x.
double sampled_share(const RayCaster& caster, const LuminaireGeometry& g, const Eigen::Vector3d& x,
                     const Eigen::Vector3d& n, const RotatedHalton4& targets, const std::array<double, 4>* target_points,
                     int rays, std::uint64_t& cast) {
  const Eigen::Vector3d from = x + n * caster.ray_offset_m();
  double weight = 0.0, visible_weight = 0.0;
  int visible = 0;
  for (int k = 0; k < rays; ++k) {
    const auto v = targets.rotate(target_points[k]);
    const Eigen::Vector3d y = opening_point(g, v[0], v[1]);
    const double w = point_source_lux_per_lm(g, y, x, n);
    const bool seen = !caster.occluded(from, y);
    visible += seen;
    weight += w;
    if (seen) visible_weight += w;
  }
  cast += static_cast<std::uint64_t>(rays);
  // No ray reached a part of the opening that lights x (a sliver in front of x's
  // plane): the plain visible fraction.
  if (!(weight > 0.0)) return static_cast<double>(visible) / rays;
  return visible_weight / weight;
}

// The visible share of the luminaire's light at x by a grid over the opening (u along
// its length, v across, in the unit square): shadow rays to the grid's vertices, its
// corners and rim included, so a part seen or hidden at the rim is always found. A
// cell whose corners disagree is cut in four, kRefineLevels times; a leaf cell whose
// corners still disagree gets the shadow's crossing on each edge whose ends disagree
// by bisection, and its visible part is the polygon of its seen corners and those
// crossings (two diagonal corners seen: the centre's ray says whether they join). An
// occluder's straight edge casts a straight shadow edge on the flat opening, so the
// polygon is exact to the bisection's tolerance. Every part is weighed by the light
// it sends to x: Lambert's closed form for a Lambertian rectangle, else its area
// times the light of its centroid as a point source. All of one pair's rays are
// cast in one fixed order, so the share does not depend on the thread running it.
class OpeningVisibility {
 public:
  OpeningVisibility(const RayCaster& caster, const LuminaireGeometry& g, const Eigen::Vector3d& x,
                    const Eigen::Vector3d& n, int base_cells)
      : caster_(caster), g_(g), x_(x), n_(n), from_(x + n * caster.ray_offset_m()), base_(base_cells),
        lattice_(base_cells << kRefineLevels),
        known_(static_cast<std::size_t>((lattice_ + 1) * (lattice_ + 1)), kUnknown) {}

  double share() {
    const int step = 1 << kRefineLevels;
    bool any_seen = false, any_hidden = false;
    for (int j = 0; j <= base_; ++j)
      for (int i = 0; i <= base_; ++i) (seen(i * step, j * step) ? any_seen : any_hidden) = true;
    if (!any_hidden) return 1.0;
    if (!any_seen) return 0.0;
    for (int j = 0; j < base_; ++j)
      for (int i = 0; i < base_; ++i) cell(i * step, j * step, step);
    // No part of the opening in front of x's plane carries weight (a sliver): the
    // plain fraction of the vertices seen.
    if (!(total_ > 0.0)) return vertex_fraction_seen();
    return std::clamp(visible_ / total_, 0.0, 1.0);
  }
  std::uint64_t rays() const { return rays_; }

 private:
  struct UV {
    double u = 0.0, v = 0.0;
  };
  static constexpr signed char kUnknown = -1;

  UV at(int i, int j) const { return {static_cast<double>(i) / lattice_, static_cast<double>(j) / lattice_}; }
  static UV mid(UV a, UV b) { return {0.5 * (a.u + b.u), 0.5 * (a.v + b.v)}; }
  bool cast(UV p) {
    ++rays_;
    return !caster_.occluded(from_, opening_point(g_, p.u, p.v));
  }
  bool seen(int i, int j) {
    signed char& k = known_[static_cast<std::size_t>(j * (lattice_ + 1) + i)];
    if (k == kUnknown) k = cast(at(i, j)) ? 1 : 0;
    return k == 1;
  }
  // The cell [i, i + size] x [j, j + size] of the lattice.
  void cell(int i, int j, int size) {
    const std::array<bool, 4> c{seen(i, j), seen(i + size, j), seen(i + size, j + size), seen(i, j + size)};
    const std::array<UV, 4> corner{at(i, j), at(i + size, j), at(i + size, j + size), at(i, j + size)};
    const int seen_corners = c[0] + c[1] + c[2] + c[3];
    if (seen_corners == 0 || seen_corners == 4) {
      const double w = weight({corner.begin(), corner.end()});
      total_ += w;
      if (seen_corners == 4) visible_ += w;
      return;
    }
    if (size > 1) {
      const int h = size / 2;
      cell(i, j, h);
      cell(i + h, j, h);
      cell(i + h, j + h, h);
      cell(i, j + h, h);
      return;
    }
    std::array<UV, 4> crossing{};
    int crossings = 0;
    for (int k = 0; k < 4; ++k)
      if (c[k] != c[(k + 1) % 4]) {
        crossing[k] = bisect(corner[k], c[k], corner[(k + 1) % 4]);
        ++crossings;
      }
    total_ += weight({corner.begin(), corner.end()});
    if (crossings == 4 && !cast(mid(corner[0], corner[2]))) {  // two seen corners, apart
      for (int k = 0; k < 4; ++k)
        if (c[k]) visible_ += weight({corner[k], crossing[k], crossing[(k + 3) % 4]});
      return;
    }
    std::vector<UV> part;
    for (int k = 0; k < 4; ++k) {
      if (c[k]) part.push_back(corner[k]);
      if (c[k] != c[(k + 1) % 4]) part.push_back(crossing[k]);
    }
    visible_ += weight(part);
  }
  // Where visibility changes between a (seen: a_seen) and b.
  UV bisect(UV a, bool a_seen, UV b) {
    for (int s = 0; s < kCrossingSteps; ++s) {
      const UV m = mid(a, b);
      (cast(m) == a_seen ? a : b) = m;
    }
    return mid(a, b);
  }
  // The light a part of the opening (a polygon in u, v) sends to x, up to a factor
  // common to all parts.
  double weight(const std::vector<UV>& polygon) const {
    if (polygon.size() < 3) return 0.0;
    if (g_.lambertian && g_.type->shape == OutlineShape::rectangle) {
      std::vector<Eigen::Vector3d> corners;
      for (const UV& p : polygon) corners.push_back(opening_point(g_, p.u, p.v));
      return polygon_form_factor(corners, x_, n_);
    }
    double area = 0.0, cu = 0.0, cv = 0.0;  // the shoelace formula and its centroid
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const UV& a = polygon[k];
      const UV& b = polygon[(k + 1) % polygon.size()];
      const double cross = a.u * b.v - b.u * a.v;
      area += cross;
      cu += (a.u + b.u) * cross;
      cv += (a.v + b.v) * cross;
    }
    if (area == 0.0) return 0.0;
    const UV centroid{cu / (3.0 * area), cv / (3.0 * area)};
    return 0.5 * std::abs(area) * point_source_lux_per_lm(g_, opening_point(g_, centroid.u, centroid.v), x_, n_);
  }
  double vertex_fraction_seen() const {
    int seen = 0, known = 0;
    for (const signed char k : known_)
      if (k != kUnknown) {
        ++known;
        seen += k;
      }
    return known ? static_cast<double>(seen) / known : 0.0;
  }

  const RayCaster& caster_;
  const LuminaireGeometry& g_;
  Eigen::Vector3d x_, n_, from_;
  int base_, lattice_;
  std::vector<signed char> known_;  // per lattice vertex: kUnknown, 0 hidden, 1 seen
  double visible_ = 0.0, total_ = 0.0;
  std::uint64_t rays_ = 0;
};

// Cells per side of the opening's grid for `shadow_rays` per point: (cells + 1)^2 rays
// at its vertices, about shadow_rays and at least 9.
int grid_cells(int shadow_rays) {
  return std::max(2, static_cast<int>(std::lround(std::sqrt(static_cast<double>(shadow_rays)))) - 1);
}

// The shared loop: receiver r has `points_per_receiver` points (point_of(r, s) gives
// one) and its own stream of shadow-ray targets, stream_of(r), so that its light
// does not depend on which other receivers are computed with it.
template <class PointOf, class StreamOf>
LuminaireLight luminaire_light(const Scene& scene, const RayCaster& caster, std::size_t receivers,
                               int points_per_receiver, std::span<const int> luminaire_surfaces,
                               const DirectLightOptions& options, const StreamOf& stream_of, const PointOf& point_of,
                               std::span<const int> computed = {}, const BrightestOverAll* over_all = nullptr) {
  // Columns: the luminaires `computed` names (indices into luminaire_surfaces), or every
  // one. The others are still seen (brightest, which decides what is negligible, is over
  // every luminaire), so a luminaire's column has the same bits whichever are computed.
  std::vector<int> columns(computed.begin(), computed.end());
  if (computed.empty() && !over_all)
    for (std::size_t l = 0; l < luminaire_surfaces.size(); ++l) columns.push_back(static_cast<int>(l));
  for (int l : columns)
    if (l < 0 || l >= static_cast<int>(luminaire_surfaces.size()))
      throw std::invalid_argument("compute_luminaire_light: luminaire " + std::to_string(l) + " is not in the list");
  const auto R = static_cast<Eigen::Index>(receivers);
  const auto L = static_cast<Eigen::Index>(columns.size());
  LuminaireLight out{Eigen::MatrixXd::Zero(R, L), Eigen::MatrixXd::Zero(R, L), 0};
  // Split over processes (over_all): every one takes part in the exchange, columns or none.
  if (R == 0 || (L == 0 && !over_all)) return out;
  const std::vector<LuminaireGeometry> geometry = luminaire_geometry(scene, luminaire_surfaces);
  const int rays = std::max(1, options.shadow_rays);
  const bool grid = rays >= kMinGridRays;
  const int cells = grid_cells(rays);
  const auto target_points = halton4_points(static_cast<std::uint32_t>(points_per_receiver * rays));
  std::atomic<std::uint64_t> rays_cast{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  std::atomic<std::size_t> done{0};
  // Split (over_all): the unoccluded light of this process's columns only, kept, and
  // each point's brightest over every process's columns (the largest of the largest:
  // the very value one process finds over every luminaire) before any shadow ray.
  const std::size_t points = receivers * static_cast<std::size_t>(points_per_receiver);
  std::vector<Unoccluded> kept;
  std::vector<double> brightest_of;
  if (over_all) {
    kept.resize(points * columns.size());
    brightest_of.assign(points, 0.0);
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers, 16), [&](const auto& range) {
        for (std::size_t r = range.begin(); r != range.end(); ++r)
          for (int s = 0; s < points_per_receiver; ++s) {
            const ReceiverPoint point = point_of(r, s);
            const std::size_t at = r * static_cast<std::size_t>(points_per_receiver) + static_cast<std::size_t>(s);
            double brightest = 0.0;
            for (std::size_t c = 0; c < columns.size(); ++c) {
              const Unoccluded u = unoccluded_light(scene, geometry[static_cast<std::size_t>(columns[c])], point.position_m,
                                                    point.normal, options.form_factors);
              kept[at * columns.size() + c] = u;
              brightest = std::max(brightest, u.lux_per_lm);
            }
            brightest_of[at] = brightest;
          }
      });
    });
    brightest_of = (*over_all)(std::move(brightest_of));
    if (brightest_of.size() != points)
      throw std::logic_error("compute_luminaire_light: " + std::to_string(brightest_of.size()) + " brightest values for " +
                             std::to_string(points) + " points");
    if (L == 0) return out;
  }
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, receivers, 16), [&](const auto& range) {
      const auto ray_modes = RayCaster::prepare_thread();
      std::vector<Unoccluded> unoccluded(geometry.size());
      std::uint64_t cast = 0;
      for (std::size_t r = range.begin(); r != range.end(); ++r) {
        const auto row = static_cast<Eigen::Index>(r);
        for (int s = 0; s < points_per_receiver; ++s) {
          const ReceiverPoint point = point_of(r, s);
          double brightest = 0.0;
          if (over_all) {
            const std::size_t at = r * static_cast<std::size_t>(points_per_receiver) + static_cast<std::size_t>(s);
            for (std::size_t c = 0; c < columns.size(); ++c)
              unoccluded[static_cast<std::size_t>(columns[c])] = kept[at * columns.size() + c];
            brightest = brightest_of[at];
          } else {
            for (std::size_t l = 0; l < geometry.size(); ++l) {
              unoccluded[l] = unoccluded_light(scene, geometry[l], point.position_m, point.normal, options.form_factors);
              brightest = std::max(brightest, unoccluded[l].lux_per_lm);
            }
          }
          for (std::size_t c = 0; c < columns.size(); ++c) {
            const auto l = static_cast<std::size_t>(columns[c]);
            if (unoccluded[l].lux_per_lm <= 0.0 && unoccluded[l].form_factor <= 0.0) continue;
            const RotatedHalton4 targets(options.seed ^ 0xD1B54A32D192ED03ull,
                                         stream_of(r) * 0x9E3779B1u +
                                             static_cast<std::uint64_t>(geometry[l].surface));
            const bool negligible = unoccluded[l].lux_per_lm < kNegligibleShare * brightest;
            // This point's slice of the target set.
            const std::array<double, 4>* slice = target_points.data() + static_cast<std::ptrdiff_t>(s) * rays;
            double share = 0.0;
            if (grid && !negligible) {
              OpeningVisibility visibility(caster, geometry[l], point.position_m, point.normal, cells);
              share = visibility.share();
              cast += visibility.rays();
            } else {
              share = sampled_share(caster, geometry[l], point.position_m, point.normal, targets, slice,
                                    negligible ? 1 : rays, cast);
            }
            const auto col = static_cast<Eigen::Index>(c);
            out.lux_per_lm(row, col) += unoccluded[l].lux_per_lm * share / points_per_receiver;
            out.form_factor(row, col) += unoccluded[l].form_factor * share / points_per_receiver;
          }
        }
      }
      rays_cast += cast;
      const std::size_t now = done.fetch_add(range.size()) + range.size();
      if (options.progress) options.progress(options.progress_label, now, receivers);
    });
  });
  out.shadow_rays_cast = rays_cast.load();
  return out;
}

}  // namespace

LuminaireLight compute_luminaire_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                       std::span<const int> luminaire_surfaces, const DirectLightOptions& options) {
  return compute_luminaire_light(scene, caster, receivers, luminaire_surfaces, {}, options);
}

LuminaireLight compute_luminaire_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                       std::span<const int> luminaire_surfaces, std::span<const int> computed,
                                       const DirectLightOptions& options, const BrightestOverAll& over_all) {
  const auto receiver_points = halton4_points(static_cast<std::uint32_t>(options.receiver_points));
  return luminaire_light(scene, caster, receivers.size(), options.receiver_points, luminaire_surfaces, options,
                         [&](std::size_t r) { return static_cast<std::uint64_t>(receivers[r]); },
                         [&](std::size_t r, int s) {
                           const Patch& p = scene.patches[static_cast<std::size_t>(receivers[r])];
                           const RotatedHalton4 points(options.seed, static_cast<std::uint64_t>(receivers[r]));
                           const auto u = points.rotate(receiver_points[static_cast<std::size_t>(s)]);
                           return ReceiverPoint{sample_triangle(p.vertices_m[0], p.vertices_m[1], p.vertices_m[2], u[0], u[1]),
                                                p.normal};
                         },
                         computed, over_all ? &over_all : nullptr);
}

LuminaireLight compute_luminaire_light_at_points(const Scene& scene, const RayCaster& caster,
                                                 std::span<const ReceiverPoint> points,
                                                 std::span<const int> luminaire_surfaces,
                                                 const DirectLightOptions& options) {
  // A point's visibility is found as each of a patch's receiver points' is: the
  // opening's grid refined where it disagrees finds the shadow's edge on it.
  return luminaire_light(scene, caster, points.size(), 1, luminaire_surfaces, options,
                         [](std::size_t r) { return static_cast<std::uint64_t>(r) ^ 0x5851F42D4C957F2Dull; },
                         [&](std::size_t r, int) { return points[r]; });
}

double mean_point_sources(const Scene& scene, std::span<const int> receivers, std::span<const int> luminaire_surfaces,
                          std::size_t samples) {
  if (receivers.empty() || luminaire_surfaces.empty() || samples == 0) return 0.0;
  const std::vector<LuminaireGeometry> geometry = luminaire_geometry(scene, luminaire_surfaces);
  const std::size_t n = std::min(samples, receivers.size() * geometry.size());
  std::uint64_t state = 0x9E3779B97F4A7C15ull;  // a fixed stream: the same count every run
  auto next = [&state] {                        // splitmix64
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t r = next() % receivers.size(), l = next() % geometry.size();
    const LuminaireGeometry& g = geometry[l];
    if (g.lambertian) continue;
    const Patch& p = scene.patches[static_cast<std::size_t>(receivers[r])];
    const auto [mx, my] = point_sources(g, (p.vertices_m[0] + p.vertices_m[1] + p.vertices_m[2]) / 3.0);
    sum += static_cast<double>(mx) * my;
  }
  return sum / static_cast<double>(n);
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
  const LuminaireLight a = compute_luminaire_light(scene, caster, precise, surfaces, options);
  const LuminaireLight b = compute_luminaire_light(scene, caster, cheap, surfaces, cheap_rows->options);
  LuminaireLight out{Eigen::MatrixXd(R, L), Eigen::MatrixXd(R, L), a.shadow_rays_cast + b.shadow_rays_cast};
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

EmitterLight emitter_light(const Scene& scene, const RayCaster& caster, const DirectLightOptions& options,
                           const FormFactorRows& rows, const CheapDirectLight* cheap_rows) {
  EmitterLight out;
  out.row_patches = rows.row_patches;
  out.surfaces = luminaire_surfaces(scene);
  if (!out.surfaces.empty()) out.light = row_light(scene, caster, out.surfaces, options, rows, cheap_rows);
  return out;
}

std::uint64_t replace_emitter_columns(const Scene& scene, const RayCaster& caster, const DirectLightOptions& options,
                                      FormFactorRows& rows, const CheapDirectLight* cheap_rows) {
  return apply_emitter_columns(scene, emitter_light(scene, caster, options, rows, cheap_rows), rows);
}

std::uint64_t apply_emitter_columns(const Scene& scene, const EmitterLight& emitter, FormFactorRows& rows) {
  if (emitter.row_patches != rows.row_patches)
    throw std::invalid_argument("apply_emitter_columns: the light was computed for other rows");
  if (emitter.surfaces.empty()) return 0;
  rows.F = with_emitter_columns(scene, emitter, rows);
  return emitter.light.shadow_rays_cast;
}

SparseRows with_emitter_columns(const Scene& scene, const EmitterLight& emitter, const FormFactorRows& rows,
                                int threads) {
  if (emitter.row_patches != rows.row_patches)
    throw std::invalid_argument("with_emitter_columns: the light was computed for other rows");
  const std::vector<int>& surfaces = emitter.surfaces;
  if (surfaces.empty()) return rows.F;
  const LuminaireLight& light = emitter.light;
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

  // The rays that struck a luminaire only sampled its solid angle, which the closed
  // form knows: scale the row's other entries so that it loses exactly the
  // closed-form share and keeps its escaped and back-hit shares (see
  // apply_closed_form_loss in core/operator/sample_rows.cpp, which does the same).
  // Each row is a merge of its entries and the emitter columns, both ascending.
  return build_rows(rows.F.rows(), rows.F.cols(), threads, [&](Eigen::Index r, const auto& emit) {
    double kept = 0.0, struck = 0.0;
    for (SparseRows::InnerIterator it(rows.F, r); it; ++it) (emitter_slot[it.col()] >= 0 ? struck : kept) += it.value();
    const double scale = kept > 0.0 ? std::max(0.0, kept + struck - absorbed[r]) / kept : 1.0;
    SparseRows::InnerIterator it(rows.F, r);
    std::size_t k = 0;
    while (it || k < by_column.size()) {
      const int emitter_column = k < by_column.size() ? emitters[by_column[k]] : std::numeric_limits<int>::max();
      if (it && it.col() < emitter_column) {
        // Gathered hits on emitters are dropped (scale is 1 for a row that kept nothing).
        if (emitter_slot[it.col()] < 0) emit(it.col(), it.value() * scale);
        ++it;
      } else {
        if (it && it.col() == emitter_column) ++it;
        const double value = exact(r, static_cast<Eigen::Index>(by_column[k]));
        if (value > 0.0) emit(emitter_column, value);
        ++k;
      }
    }
  });
}

static_assert(field_count<DirectLightOptions>() == 7, "DirectLightOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const DirectLightOptions& o) {
  k.field("receiver_points", o.receiver_points).field("shadow_rays", o.shadow_rays).field("seed", o.seed);
  // Not threads, progress or progress_label: the same light for any of them.
}

}  // namespace ilp
