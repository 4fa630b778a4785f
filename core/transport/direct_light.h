// Direct light from luminaires without gather noise. A gather row of 256 rays sees
// a 0.6 m luminaire 3 m away only a few times, so its F_il would be noise; here the
// luminaire's light at a receiver comes from its type (core/light/luminaire.h): the
// unoccluded illuminance in closed form or by point sources, times the visible
// share from shadow rays.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "core/transport/form_factors.h"
#include "core/base/progress.h"
#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

struct DirectLightOptions {
  int receiver_points = 8;  // points on each receiver patch (low-discrepancy)
  // From each point to each luminaire: from 4 on, the vertices of a grid of c x c cells
  // over the opening, (c + 1)^2 about this and at least 9 rays (c >= 2), and more where
  // they disagree (a penumbra: see compute_luminaire_light); below 4, this many rays to
  // stratified points of the opening (the cheap estimate).
  int shadow_rays = 8;
  std::uint64_t seed = 1;
  // The luminaires' form factors from the receiver (what they absorb of its light):
  // off where only the light is read (the patches the operator's rows hit), which
  // spares a photometric opening's polygon form factors; a Lambertian opening's light
  // comes from its form factor, so it always has them. Not in the cache key: the light
  // is the same.
  bool form_factors = true;
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
// 1 %. Shadows: shadow rays to the vertices of a grid over the opening (its corners
// and rim included: a part seen or hidden at the rim is always found); where they
// disagree the cells are cut in four and the shadow's edge is found on the cells'
// edges by bisection, so a point seeing 5 % of a panel, or missing 5 % of it, gets
// that part's light within 1 % (tested against the closed form). Each part is
// weighted by the light it sends to the receiver (a part behind the receiver's plane
// or beyond the beam counts for nothing). A shadow smaller than a grid cell that
// touches no vertex (a thin rod across the middle of a panel) is not seen. Pairs whose
// unoccluded light is below 1e-3 of the brightest luminaire at that point get one
// shadow ray. Every pair's rays are cast in a fixed order: the light does not depend
// on the thread count.
struct LuminaireLight {
  Eigen::MatrixXd lux_per_lm;   // receivers x luminaire surfaces
  Eigen::MatrixXd form_factor;  // receivers x luminaire surfaces
  std::uint64_t shadow_rays_cast = 0;  // in all, for the cost of a phase
};

// Receivers are patches, each averaged over options.receiver_points points on it.
LuminaireLight compute_luminaire_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                       std::span<const int> luminaire_surfaces, const DirectLightOptions& options);
// Each receiver point's brightest unoccluded light over this process's luminaires in,
// the largest over every process's out (a split operator build: core/operator/work_share.h).
using BrightestOverAll = std::function<std::vector<double>(std::vector<double>)>;

// The columns of the luminaires `computed` names (indices into luminaire_surfaces, in
// that order) only, each with the bits it has when every luminaire is computed (a split
// operator build computes its share of the sources). What is negligible at a point is
// judged against its brightest luminaire: without `over_all`, every luminaire's
// unoccluded light is computed to find it; with it, only the computed ones', and
// over_all gives the largest over every process, which must all call it alike (one
// exchange per call, even a process with no column; `computed` empty then means none).
LuminaireLight compute_luminaire_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                       std::span<const int> luminaire_surfaces, std::span<const int> computed,
                                       const DirectLightOptions& options, const BrightestOverAll& over_all = {});
// Receivers are points (a calculation grid): one point each, with the shadow rays of
// one of a patch's receiver points (receiver_points does not apply).
LuminaireLight compute_luminaire_light_at_points(const Scene& scene, const RayCaster& caster,
                                                 std::span<const ReceiverPoint> points,
                                                 std::span<const int> luminaire_surfaces,
                                                 const DirectLightOptions& options);

// The scene's luminaire surfaces, in surface order.
std::vector<int> luminaire_surfaces(const Scene& scene);

// The point sources a receiver's unoccluded light evaluates per photometric luminaire
// (a Lambertian opening's closed form has none: 0), averaged over up to `samples` pairs
// of `receivers` (at their centroids) and `luminaire_surfaces` drawn from a fixed
// stream: more where the receivers are near a long opening. For the cost model.
double mean_point_sources(const Scene& scene, std::span<const int> receivers, std::span<const int> luminaire_surfaces,
                          std::size_t samples = 4096);

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
// Returns the shadow rays cast.
//
// In two steps, for rows refined by more rays while the luminaires stay (the exact
// solve's progressive refinement): emitter_light computes the light once, and
// apply_emitter_columns applies it to rows of the same patches in the same order.
struct EmitterLight {
  std::vector<int> row_patches;  // the rows it was computed for
  std::vector<int> surfaces;     // luminaire_surfaces(scene)
  LuminaireLight light;
};
EmitterLight emitter_light(const Scene& scene, const RayCaster& caster, const DirectLightOptions& options,
                           const FormFactorRows& rows, const CheapDirectLight* cheap_rows = nullptr);
std::uint64_t apply_emitter_columns(const Scene& scene, const EmitterLight& emitter, FormFactorRows& rows);
// The F apply_emitter_columns gives `rows`, built from them left as they are (no copy of
// their F first: a solve that keeps its raw rows), on `threads` threads (0: every core;
// the same F for any count).
SparseRows with_emitter_columns(const Scene& scene, const EmitterLight& emitter, const FormFactorRows& rows,
                                int threads = 0);
std::uint64_t replace_emitter_columns(const Scene& scene, const RayCaster& caster, const DirectLightOptions& options,
                                      FormFactorRows& rows, const CheapDirectLight* cheap_rows = nullptr);

}  // namespace ilp
