// The exact reference at receiver points (grid points, which are not patches): each
// point's gather row (core/transport/point_gather.h) over the solved radiosity, with
// the luminaires' direct light in closed form; what the verification reads at goal points.
#pragma once

#include <span>

#include "core/exact/radiosity.h"
#include "core/transport/direct_light.h"
#include "core/transport/point_gather.h"

namespace ilp {

// The exact solver's illuminance at points (verification): luminaires' direct light by
// compute_luminaire_light_at_points at their flux, and each point's gather over the solved
// radiosity of the patches its row hits (luminaire hits dropped, the row's other entries
// scaled so that it loses the closed-form share to luminaires, as patch rows do).
struct PointIlluminance {
  Eigen::VectorXd total_lux;   // photometric
  Eigen::VectorXd direct_lux;  // luminaires and emitting surfaces, straight
  // The statistical error of each point's gather (lux, one standard error): the spread of
  // its rays' values over sqrt(rays), as if they were independent (they are a stratified
  // low-discrepancy set, whose error is smaller: an upper estimate). It leaves out the
  // error of the radiosity gathered and of the direct light's shadow rays.
  Eigen::VectorXd indirect_standard_error_lux;
  FormFactorRows rows;  // each point's gather row (row q: point q), as cast
  std::uint64_t rays_cast = 0;
  double seconds = 0.0;
};
PointIlluminance exact_point_illuminance(const Scene& scene, const RayCaster& caster, const RadiositySolution& solution,
                                         std::span<const ReceiverPoint> points, const FormFactorOptions& rows,
                                         const DirectLightOptions& direct, const ProgressCallback& progress = {});

// The patches a point gathers most of its reflected light from: for each point q of
// `which`, the patches j whose share F(q, j) B_j of its gathered light (photometric,
// luminaires left out) is at least `share`; ascending, each once. Those patches' rows
// are where the noise of that point's value comes from (its own gather's is its standard
// error).
std::vector<int> dominant_patches(const Scene& scene, const FormFactorRows& point_rows,
                                  const RadiositySolution& solution, std::span<const int> which, double share);

}  // namespace ilp
