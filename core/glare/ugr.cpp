#include "core/glare/ugr.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "core/base/error.h"
#include "core/light/luminaire_product.h"

namespace ilp {
namespace {

constexpr double kPointOpeningDiameterM = 0.1;

Eigen::Vector3d horizontal_unit(const Eigen::Vector3d& v) {
  const Eigen::Vector3d h(v.x(), v.y(), 0.0);
  if (!(h.norm() > 0.0)) throw IlpError("UGR observer: the view direction has no horizontal part");
  return h.normalized();
}

}  // namespace

GlareOpening glare_opening(const LuminaireType& type) {
  return GlareOpening{type.shape, type.length_m, type.width_m, 0.0};
}

GlareOpening glare_opening(const LuminousOpening& o) {
  GlareOpening g;
  switch (o.shape) {
    case OpeningShape::point:
      return GlareOpening{OutlineShape::disc, kPointOpeningDiameterM, kPointOpeningDiameterM, 0.0};
    case OpeningShape::rectangle:
      return GlareOpening{OutlineShape::rectangle, o.length_m, o.width_m, o.height_m};
    case OpeningShape::line:  // a thin rectangle along its one size, as the scene meshes it
      return GlareOpening{OutlineShape::rectangle, o.length_m > 0.0 ? o.length_m : kLineSourceWidthM,
                          o.width_m > 0.0 ? o.width_m : kLineSourceWidthM, o.height_m};
    case OpeningShape::disc:
    case OpeningShape::cylinder:
      g.shape = OutlineShape::disc;
      g.length_m = g.width_m = std::max(o.length_m, o.width_m);
      g.height_m = o.shape == OpeningShape::cylinder ? o.height_m : 0.0;
      return g;
  }
  return g;
}

double projected_area_m2(const GlareOpening& o, const Eigen::Vector3d& toward_eye_local) {
  const double n = toward_eye_local.norm();
  if (!(n > 0.0)) return 0.0;
  const Eigen::Vector3d d = toward_eye_local / n;
  const double below = std::max(0.0, -d.z());  // the bottom faces -z
  if (o.shape == OutlineShape::disc) {
    const double diameter = o.length_m;
    return std::numbers::pi / 4.0 * diameter * diameter * below + diameter * o.height_m * std::hypot(d.x(), d.y());
  }
  return o.length_m * o.width_m * below +
         o.height_m * (o.length_m * std::abs(d.y()) + o.width_m * std::abs(d.x()));
}

GlareSource glare_source(const LuminaireType& type, const LuminairePlacement& at, double flux_lm) {
  return GlareSource{glare_opening(type), type.distribution, at, flux_lm};
}

GlareView glare_view(const GlareSource& s, const UgrObserver& obs, PositionIndexMethod method) {
  GlareView v;
  const Eigen::Vector3d forward = horizontal_unit(obs.view_direction);
  const Eigen::Vector3d left(-forward.y(), forward.x(), 0.0);  // z x forward
  const Eigen::Vector3d d = s.placement.position_m - obs.position_m;  // eye to source
  v.r_m = d.dot(forward);
  v.t_m = d.dot(left);
  v.h_m = d.z();
  v.distance_m = d.norm();
  const Eigen::Vector3d toward_eye_local =
      luminaire_rotation(s.placement).transpose() * (-d).normalized();  // distributions want unit vectors
  v.intensity_cd = s.distribution ? s.distribution->cd_per_lm(toward_eye_local) * s.flux_lm : 0.0;
  v.projected_area_m2 = projected_area_m2(s.opening, toward_eye_local);
  if (!(v.projected_area_m2 > 0.0) || !(v.distance_m > 0.0)) return v;
  v.luminance_cd_m2 = v.intensity_cd / v.projected_area_m2;
  v.solid_angle_sr = v.projected_area_m2 / (v.distance_m * v.distance_m);
  if (v.h_m > 0.0) v.position_index = guth_position_index(v.r_m, v.t_m, v.h_m, method);
  if (v.position_index)
    v.term = v.luminance_cd_m2 * v.luminance_cd_m2 * v.solid_angle_sr / (*v.position_index * *v.position_index);
  return v;
}

double glare_term(const GlareSource& source, const UgrObserver& observer, PositionIndexMethod method) {
  return glare_view(source, observer, method).term;
}

double glare_term_per_lm2(const GlareSource& source, const UgrObserver& observer, PositionIndexMethod method) {
  GlareSource unit = source;
  unit.flux_lm = 1.0;
  return glare_view(unit, observer, method).term;
}

double ugr_from_terms(double sum_of_terms, double background_luminance_cd_m2) {
  if (!(background_luminance_cd_m2 > 0.0))
    throw IlpError("UGR: the background luminance must be > 0 cd/m2 (got " +
                   std::to_string(background_luminance_cd_m2) + ")");
  if (!(sum_of_terms > 0.0)) return -std::numeric_limits<double>::infinity();
  return 8.0 * std::log10(0.25 / background_luminance_cd_m2 * sum_of_terms);
}

double ugr(const std::vector<GlareSource>& sources, const UgrObserver& observer, double background_luminance_cd_m2,
           PositionIndexMethod method) {
  double sum = 0.0;
  for (const GlareSource& s : sources) sum += glare_term(s, observer, method);
  return ugr_from_terms(sum, background_luminance_cd_m2);
}

double ugr(const std::vector<GlareSource>& sources, const UgrObserver& observer,
           const std::function<double(const UgrObserver&)>& indirect_vertical_illuminance_lx,
           PositionIndexMethod method) {
  return ugr(sources, observer, indirect_vertical_illuminance_lx(observer) / std::numbers::pi, method);
}

std::vector<UgrObserver> default_ugr_observers(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, double floor_z_m,
                                               double eye_height_m, double wall_offset_m) {
  const Eigen::Vector2d mid = 0.5 * (lo + hi);
  const double z = floor_z_m + eye_height_m, o = wall_offset_m;
  return {
      {{mid.x(), lo.y() + o, z}, Eigen::Vector3d::UnitY()},
      {{hi.x() - o, mid.y(), z}, -Eigen::Vector3d::UnitX()},
      {{mid.x(), hi.y() - o, z}, -Eigen::Vector3d::UnitY()},
      {{lo.x() + o, mid.y(), z}, Eigen::Vector3d::UnitX()},
  };
}

}  // namespace ilp
