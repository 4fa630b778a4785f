// Gather rows from receiver points (grid points, which are not patches): the
// fraction of a point's cosine-weighted rays reaching each patch, F(point, :), as
// compute_form_factor_rows gives for patches. A point is a differential area: its
// row is the indirect light it receives, H = F B, from the radiosity B of the patches.
#pragma once

#include <span>

#include "core/transport/direct_light.h"
#include "core/transport/form_factors.h"

namespace ilp {

// One row per point, in order (row_patches holds -1 - point index). Rays leave the
// point pushed ray_offset_m along its normal; back hits and escapes are counted as for
// patch rows. Deterministic for options.seed whatever the thread count.
FormFactorRows compute_point_rows(const Scene& scene, const RayCaster& caster, std::span<const ReceiverPoint> points,
                                  const FormFactorOptions& options, const ProgressCallback& progress = {});

}  // namespace ilp
