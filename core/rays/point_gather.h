// Gather rows from receiver points (grid points, which are not patches): the
// fraction of a point's cosine-weighted rays reaching each patch, F(point, :), as
// compute_form_factor_rows gives for patches. A point is a differential area: its
// row is the indirect light it receives, H = F B, from the radiosity B of the patches.
#pragma once

#include <span>

#include "core/rays/form_factors.h"
#include "core/light/direct_light.h"
#include "core/exact/radiosity.h"

namespace ilp {

// One row per point, in order (row_patches holds -1 - point index). Rays leave the
// point pushed ray_offset_m along its normal; back hits and escapes are counted as for
// patch rows. Deterministic for options.seed whatever the thread count.
FormFactorRows compute_point_rows(const Scene& scene, const RayCaster& caster, std::span<const ReceiverPoint> points,
                                  const FormFactorOptions& options, const ProgressCallback& progress = {});

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
  std::uint64_t rays_cast = 0;
  double seconds = 0.0;
};
PointIlluminance exact_point_illuminance(const Scene& scene, const RayCaster& caster, const RadiositySolution& solution,
                                         std::span<const ReceiverPoint> points, const FormFactorOptions& rows,
                                         const DirectLightOptions& direct, const ProgressCallback& progress = {});

}  // namespace ilp
