// Direct light from luminaires without gather noise. A gather row of 256 rays sees
// a 0.6 m luminaire 3 m away only a few times, so its F_il would be noise; here the
// luminaire's light at a receiver comes from its type (core/light/luminaire.h): the
// unoccluded illuminance in closed form or by point sources, times the visible
// share from shadow rays.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/rays/form_factors.h"
#include "core/base/progress.h"
#include "core/rays/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

struct DirectLightOptions {
  int receiver_points = 8;  // points on each receiver patch (low-discrepancy)
  int shadow_rays = 8;      // at most, from each point to a luminaire it sees partly (4 first)
  std::uint64_t seed = 1;
  int threads = 0;          // 0: all cores
  // Called from worker threads as blocks of receivers finish (may be empty): a long
  // phase (100K goal patches x candidates) says how far it is.
  ProgressCallback progress;
  std::string progress_label = "direct light";
};

// The operator cache's key (core/base/key_hash.h): every field but threads, progress
// and progress_label, which never change the light.
void hash_fields(KeyWriter& k, const DirectLightOptions& o);

// The cheap estimate where direct light matters little: 1 point, 2 shadow rays.
inline DirectLightOptions cheap_direct_light_options() {
  DirectLightOptions o;
  o.receiver_points = 1;
  o.shadow_rays = 2;
  return o;
}

// Unoccluded form factor from a differential area at `point` with unit `normal`
// to the triangle `emitter` (which emits from the side its normal faces); 0 when
// either faces away. Exact for the triangle as clipped to the point's hemisphere.
double point_to_triangle_form_factor(const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                                     const Patch& emitter);

// A point that receives light: position and unit normal (the side it receives on).
struct ReceiverPoint {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

// The luminaires' direct light at receivers, one column per luminaire surface:
// - lux_per_lm: illuminance per lumen the luminaire emits, with its shadows;
// - form_factor: the share of light leaving the receiver diffusely that strikes the
//   luminaire's opening where it is visible (what the luminaire absorbs of the
//   receiver's light). For a Lambertian opening it is lux_per_lm x opening area
//   (reciprocity); for any other distribution the two differ.
//
// How (see the .cpp): the unoccluded light is exact for a Lambertian opening
// (Lambert's closed form, clipped to the receiver's hemisphere), else the opening is
// cut into point sources that each carry the distribution, finer the nearer the
// receiver (one point in the far field), so that the quadrature error stays below
// 1 %. Shadows: shadow rays to points on the opening, each weighted by its share of
// the unoccluded light (a ray toward a part of the opening behind the receiver's
// plane or beyond the beam counts for nothing); 4 rays first, all
// options.shadow_rays only where those disagree (a penumbra). Pairs whose
// unoccluded light is below 1e-3 of the brightest luminaire at that point get one
// shadow ray.
struct LuminaireLight {
  Eigen::MatrixXd lux_per_lm;   // receivers x luminaire surfaces
  Eigen::MatrixXd form_factor;  // receivers x luminaire surfaces
};

// Receivers are patches, each averaged over options.receiver_points points on it.
LuminaireLight compute_luminaire_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                       std::span<const int> luminaire_surfaces, const DirectLightOptions& options);
// Receivers are points (a calculation grid): one point each, with receiver_points x
// shadow_rays rays where a luminaire is partly hidden (a patch's whole budget).
LuminaireLight compute_luminaire_light_at_points(const Scene& scene, const RayCaster& caster,
                                                 std::span<const ReceiverPoint> points,
                                                 std::span<const int> luminaire_surfaces,
                                                 const DirectLightOptions& options);

// The scene's luminaire surfaces, in surface order.
std::vector<int> luminaire_surfaces(const Scene& scene);

// Replaces the columns of F (rows: rows.row_patches) that belong to the scene's
// luminaires with their direct light: a luminaire patch's column holds
// lux_per_lm x the patch's area, so that F B (B = exitance = flux / opening area)
// gives the luminaire's illuminance whatever its distribution. Rays that hit
// luminaires are dropped from the gathered entries, and the row's other entries are
// scaled so that the row sum stays 1 - escaped - back-hit fraction - the luminaires'
// form_factor: the share they absorb is the closed form's, not the ray count's.
//
// With `cheap_rows`, the rows it marks (by row, not patch) use `cheap` options
// instead; each receiver's points and rays depend only on its patch and the options,
// so the other rows are exactly what they would be without the split.
struct CheapDirectLight {
  std::vector<bool> rows;  // one per row of FormFactorRows
  DirectLightOptions options;
};
void replace_emitter_columns(const Scene& scene, const RayCaster& caster, const DirectLightOptions& options,
                             FormFactorRows& rows,
                             const CheapDirectLight* cheap_rows = nullptr);

}  // namespace ilp
