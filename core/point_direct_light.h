// Direct light from luminaires at receiver points that are not patches (the points of
// a calculation grid). A point has a position and a normal but no area: it neither
// shades nor reflects. Today's luminaires are square Lambertian panels, so the
// illuminance per lumen is the closed-form point-to-polygon form factor over the
// luminaire's patches, times the visible fraction of shadow rays, over its area.
// The integrator replaces the body with the photometric model; the signature stays.
#pragma once

#include <Eigen/Core>
#include <span>

#include "core/direct_light.h"
#include "core/ray_caster.h"
#include "core/scene.h"

namespace ilp {

struct ReceiverPoint {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit: the side the point receives on
};

// Illuminance per lumen at each point from each luminaire source (a Surface with is_luminaire):
// #points x luminaire_surfaces.size(), lux/lm, shadow rays through the caster (virtual candidates
// are not in the caster: they shade nothing). options.shadow_rays rays per point and luminaire
// (receiver_points is not used: a point is one point). Throws std::invalid_argument for a surface
// that is not a luminaire or has no area.
Eigen::MatrixXd luminaire_lux_per_lm_at_points(const Scene& scene, const RayCaster& caster,
                                               std::span<const ReceiverPoint> points,
                                               std::span<const int> luminaire_surfaces,
                                               const DirectLightOptions& options);

}  // namespace ilp
