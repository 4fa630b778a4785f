// Cylindrical illuminance Ez at a point (vertical axis): the mean of the vertical illuminance
// over all horizontal directions, i.e. the flux on a small upright cylinder's curved side over
// its area. From light arriving along a direction at angle theta from the vertical with
// illuminance E_n on a plane facing it (E_n = I / d^2 for a point source), a vertical plane
// at azimuth phi to the light gets E_n sin(theta) max(0, cos phi), whose mean over phi is
// E_n sin(theta) / pi: Ez = I sin(theta) / (pi d^2). The horizontal illuminance is
// Eh = E_n cos(theta) for light from above. Modelling (EN 12464-1) = Ez / Eh.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "core/glare/ugr.h"

namespace ilp {

// Light arriving at a point: the unit direction from the point toward where it comes from,
// and its illuminance on a plane normal to that direction.
struct IncidentLight {
  Eigen::Vector3d toward_source = Eigen::Vector3d::UnitZ();
  double normal_illuminance_lx = 0.0;
};

// A point source of `intensity_cd` toward the point, at source_m.
IncidentLight incident_from_point(const Eigen::Vector3d& point_m, const Eigen::Vector3d& source_m, double intensity_cd);
// A luminaire taken as a point at its opening's centre (its intensity toward the point; no shading).
IncidentLight incident_from_luminaire(const Eigen::Vector3d& point_m, const GlareSource& luminaire);

double cylindrical_illuminance_lx(const std::vector<IncidentLight>& light);
// On the horizontal plane facing up (light from below counts 0).
double horizontal_illuminance_lx(const std::vector<IncidentLight>& light);
// On the vertical plane whose normal points along the horizontal `facing` (e.g. at the eye).
double vertical_illuminance_lx(const std::vector<IncidentLight>& light, const Eigen::Vector3d& facing);
// Ez / Eh; 0 when Eh is 0.
double modelling_ratio(const std::vector<IncidentLight>& light);

}  // namespace ilp
