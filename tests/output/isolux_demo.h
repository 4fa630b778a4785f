// A realistic grid for the isolux plan's tests and demo: a 6 x 4 m office, a work
// plane at 0.80 m with a 0.5 m band and 0.2 m spacing, four luminaires 2.0 m above it
// (isotropic point sources: E = I cos^3(theta) / h^2 each), a desk-sized solid whose
// points are missing, maintenance factor 0.8.
#pragma once

#include <array>
#include <cmath>
#include <limits>

#include "output/isolux_plan.h"
#include "output/svg_text.h"

namespace ilp::test {

inline IsoluxGridView office_isolux_view(double intensity_cd = 1650.0, double spacing_m = 0.2) {
  IsoluxGridView v;
  v.name = "work plane";
  v.title = "office, 0.80 m above the floor, 0.5 m band";
  v.spacing_m = Eigen::Vector2d::Constant(spacing_m);
  const Eigen::Vector2d lo(0.5, 0.5), hi(5.5, 3.5);  // the task area: the room less the band
  v.nx = static_cast<int>(std::lround((hi.x() - lo.x()) / spacing_m));
  v.ny = static_cast<int>(std::lround((hi.y() - lo.y()) / spacing_m));
  v.origin_m = lo + 0.5 * v.spacing_m;
  v.room_outline_m = {{{0.0, 0.0}, {6.0, 0.0}, {6.0, 4.0}, {0.0, 4.0}}};
  const double h = 2.0, mf = 0.8;
  const std::array<Eigen::Vector2d, 4> at = {Eigen::Vector2d(1.5, 1.0), Eigen::Vector2d(4.5, 1.0),
                                              Eigen::Vector2d(1.5, 3.0), Eigen::Vector2d(4.5, 3.0)};
  for (int k = 0; k < 4; ++k)
    v.luminaires.push_back({svg::cat("L", std::to_string(k + 1)), "panel 1200", at[k], 1.2, 0.3, 0.0, false});
  for (int j = 0; j < v.ny; ++j)
    for (int i = 0; i < v.nx; ++i) {
      const Eigen::Vector2d p = v.origin_m + Eigen::Vector2d(i * spacing_m, j * spacing_m);
      double e = 0.0;
      for (const Eigen::Vector2d& c : at) {
        const double d2 = (p - c).squaredNorm() + h * h;
        e += intensity_cd * std::pow(h / std::sqrt(d2), 3) / (h * h);
      }
      const bool in_solid = p.x() > 2.4 && p.x() < 3.6 && p.y() > 1.6 && p.y() < 2.4;  // a cabinet
      v.maintained_lux.push_back(in_solid ? std::numeric_limits<double>::quiet_NaN() : mf * e);
    }
  v.target_lux = 500.0;
  v.maintenance_factor = mf;
  v.north_deg = 30.0;
  return v;
}

}  // namespace ilp::test
