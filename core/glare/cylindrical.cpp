#include "core/glare/cylindrical.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/base/error.h"

namespace ilp {

IncidentLight incident_from_point(const Eigen::Vector3d& point_m, const Eigen::Vector3d& source_m, double intensity_cd) {
  const Eigen::Vector3d d = source_m - point_m;
  const double d2 = d.squaredNorm();
  if (!(d2 > 0.0)) throw IlpError("incident light: the source sits on the point");
  return IncidentLight{d / std::sqrt(d2), intensity_cd / d2};
}

IncidentLight incident_from_luminaire(const Eigen::Vector3d& point_m, const GlareSource& l) {
  const Eigen::Vector3d toward_point_local =
      luminaire_rotation(l.placement.rotation_deg).transpose() * (point_m - l.placement.position_m).normalized();
  const double intensity_cd = l.distribution ? l.distribution->cd_per_lm(toward_point_local) * l.flux_lm : 0.0;
  return incident_from_point(point_m, l.placement.position_m, intensity_cd);
}

double cylindrical_illuminance_lx(const std::vector<IncidentLight>& light) {
  double ez = 0.0;
  for (const IncidentLight& l : light)
    ez += l.normal_illuminance_lx * std::hypot(l.toward_source.x(), l.toward_source.y()) / std::numbers::pi;
  return ez;
}

double horizontal_illuminance_lx(const std::vector<IncidentLight>& light) {
  double eh = 0.0;
  for (const IncidentLight& l : light) eh += l.normal_illuminance_lx * std::max(0.0, l.toward_source.z());
  return eh;
}

double vertical_illuminance_lx(const std::vector<IncidentLight>& light, const Eigen::Vector3d& facing) {
  const Eigen::Vector3d n = Eigen::Vector3d(facing.x(), facing.y(), 0.0).normalized();
  double ev = 0.0;
  for (const IncidentLight& l : light) ev += l.normal_illuminance_lx * std::max(0.0, l.toward_source.dot(n));
  return ev;
}

double modelling_ratio(const std::vector<IncidentLight>& light) {
  const double eh = horizontal_illuminance_lx(light);
  return eh > 0.0 ? cylindrical_illuminance_lx(light) / eh : 0.0;
}

}  // namespace ilp
