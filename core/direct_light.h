// Direct light from small emitters (the square luminaires) without gather noise.
// A gather row of 256 rays sees a 0.6 m luminaire 3 m away only a few times, so
// its F_il would be noise; here F_il is the closed-form point-to-polygon form
// factor (Lambert's contour integral, clipped to the receiver's hemisphere)
// integrated over receiver points on patch i, times the unoccluded fraction of
// shadow rays from each point to points on l.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "core/form_factors.h"
#include "core/ray_caster.h"
#include "core/scene.h"

namespace ilp {

struct DirectLightOptions {
  int receiver_points = 8;  // points on each receiver patch (low-discrepancy)
  int shadow_rays = 8;      // visibility rays from each point to the emitter
  std::uint64_t seed = 1;
  int threads = 0;          // 0: all cores
};

// Unoccluded form factor from a differential area at `point` with unit `normal`
// to the triangle `emitter` (which emits from the side its normal faces); 0 when
// either faces away. Exact for the triangle as clipped to the point's hemisphere.
double point_to_triangle_form_factor(const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                     const Patch& emitter);

// F(i, l) for every receiver i in `receivers` and emitter l in `emitters`:
// #receivers by #emitters, each entry the fraction of light leaving i diffusely
// that reaches l directly (reciprocity gives l's light arriving at i: A_l F_li / A_i).
// The patches of one surface share their shadow rays (one visible fraction per
// receiver point and surface), which suits emitters small against their distance
// to the receivers, as luminaires are.
Eigen::MatrixXd compute_emitter_form_factors(const Scene& scene, const RayCaster& caster,
                                             std::span<const int> receivers, std::span<const int> emitters,
                                             const DirectLightOptions& options);

// Patches of luminaire surfaces: the emitters whose columns should not be gathered.
std::vector<int> luminaire_patches(const Scene& scene);

// Replaces the columns of F (rows: rows.row_patches) that belong to `emitters`
// with compute_emitter_form_factors values. Rays that hit those emitters are
// dropped from the gathered entries, and the row's other entries are scaled so that
// the row sum stays 1 - escaped - back-hit fraction: the share lost to emitters is
// the closed form's, not the ray count's.
//
// With `cheap_rows`, the rows it marks (by row, not patch) use `cheap` options
// instead; each receiver's points and rays depend only on its patch and the options,
// so the other rows are exactly what they would be without the split.
struct CheapDirectLight {
  std::vector<bool> rows;  // one per row of FormFactorRows
  DirectLightOptions options;
};
void replace_emitter_columns(const Scene& scene, const RayCaster& caster, std::span<const int> emitters,
                             const DirectLightOptions& options, FormFactorRows& rows,
                             const CheapDirectLight* cheap_rows = nullptr);

}  // namespace ilp
