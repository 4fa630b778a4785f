// Illuminance statistics over a named surface: the quantities lighting goals are
// stated in (EN 12464-1): area-weighted average, minimum, maximum and uniformity
// U0 = Emin / Eavg. Patches are weighted by area so meshing does not bias them.
#pragma once

#include <Eigen/Core>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/scene/scene.h"

namespace ilp {

struct SurfaceIlluminance {
  std::string surface;
  std::size_t patches = 0;
  double area_m2 = 0.0;
  double average_lux = 0.0;  // sum A_i E_i / sum A_i
  double min_lux = 0.0;
  double max_lux = 0.0;
  double uniformity = 0.0;   // U0 = min / average; 0 when the average is 0
};

// lux: one value per scene patch. Throws std::invalid_argument on a size mismatch
// or an unknown surface index.
SurfaceIlluminance surface_illuminance(const Scene& scene, const Eigen::VectorXd& lux, int surface);

// One entry per surface, in scene order (all surfaces when `surfaces` is empty).
std::vector<SurfaceIlluminance> surface_illuminance_table(const Scene& scene, const Eigen::VectorXd& lux,
                                                          const std::vector<std::string>& surfaces = {});

// Fixed-width table: surface, patches, area m2, Eavg lux, Emin lux, Emax lux, U0.
void print_illuminance_table(std::ostream& os, const std::vector<SurfaceIlluminance>& rows);

}  // namespace ilp
