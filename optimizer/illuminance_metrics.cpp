#include "optimizer/illuminance_metrics.h"

#include <algorithm>
#include <iomanip>
#include <limits>
#include <ostream>
#include <stdexcept>

namespace ilp {

SurfaceIlluminance surface_illuminance(const Scene& scene, const Eigen::VectorXd& lux, int surface) {
  if (lux.size() != static_cast<Eigen::Index>(scene.patches.size()))
    throw std::invalid_argument("surface_illuminance: " + std::to_string(lux.size()) + " values for " +
                                std::to_string(scene.patches.size()) + " patches");
  if (surface < 0 || surface >= static_cast<int>(scene.surfaces.size()))
    throw std::invalid_argument("surface_illuminance: no surface " + std::to_string(surface));
  SurfaceIlluminance out;
  out.surface = scene.surfaces[surface].name;
  out.min_lux = std::numeric_limits<double>::infinity();
  out.max_lux = -std::numeric_limits<double>::infinity();
  double weighted = 0.0;
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const Patch& p = scene.patches[i];
    if (p.surface != surface) continue;
    const double e = lux[static_cast<Eigen::Index>(i)];
    ++out.patches;
    out.area_m2 += p.area_m2;
    weighted += p.area_m2 * e;
    out.min_lux = std::min(out.min_lux, e);
    out.max_lux = std::max(out.max_lux, e);
  }
  if (out.patches == 0) {
    out.min_lux = out.max_lux = 0.0;
    return out;
  }
  out.average_lux = weighted / out.area_m2;
  out.uniformity = out.average_lux > 0.0 ? out.min_lux / out.average_lux : 0.0;
  return out;
}

std::vector<SurfaceIlluminance> surface_illuminance_table(const Scene& scene, const Eigen::VectorXd& lux,
                                                          const std::vector<std::string>& surfaces) {
  std::vector<SurfaceIlluminance> rows;
  if (surfaces.empty()) {
    for (std::size_t s = 0; s < scene.surfaces.size(); ++s)
      rows.push_back(surface_illuminance(scene, lux, static_cast<int>(s)));
  } else {
    for (const std::string& name : surfaces) {
      const int s = scene.find_surface(name);
      if (s < 0) throw std::invalid_argument("surface_illuminance_table: unknown surface '" + name + "'");
      rows.push_back(surface_illuminance(scene, lux, s));
    }
  }
  return rows;
}

void print_illuminance_table(std::ostream& os, const std::vector<SurfaceIlluminance>& rows) {
  std::size_t width = 7;
  for (const auto& r : rows) width = std::max(width, r.surface.size());
  const auto flags = os.flags();
  os << std::left << std::setw(static_cast<int>(width)) << "surface" << std::right << std::setw(9) << "patches"
     << std::setw(10) << "area m2" << std::setw(11) << "Eavg lux" << std::setw(11) << "Emin lux" << std::setw(11)
     << "Emax lux" << std::setw(7) << "U0" << "\n";
  os << std::fixed;
  for (const auto& r : rows) {
    os << std::left << std::setw(static_cast<int>(width)) << r.surface << std::right << std::setw(9) << r.patches
       << std::setprecision(2) << std::setw(10) << r.area_m2 << std::setprecision(1) << std::setw(11)
       << r.average_lux << std::setw(11) << r.min_lux << std::setw(11) << r.max_lux << std::setprecision(2)
       << std::setw(7) << r.uniformity << "\n";
  }
  os.flags(flags);
}

}  // namespace ilp
