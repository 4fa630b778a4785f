// The whole exact reference pipeline for one scene: BVH, every form-factor row by
// ray casting, luminaire columns from the closed-form direct term, then the
// Gauss-Seidel radiosity solve. Timings and ray counts come back in the summary.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <vector>

#include "core/transport/direct_light.h"
#include "core/transport/form_factors.h"
#include "core/transport/ray_caster.h"
#include "core/base/progress.h"
#include "core/exact/radiosity.h"
#include "core/scene/scene.h"

namespace ilp {

struct ExactSolveOptions {
  FormFactorOptions form_factors;
  DirectLightOptions direct_light;
  RadiosityOptions radiosity;
  // When given, only these patches (maybe none) get `direct_light` and rows of
  // form_factors.rays_per_patch rays; the others get `other_direct_light`, a cheaper
  // estimate, and rows of other_rays_per_patch rays (when > 0): what they receive is
  // read only through reflections, and indirect light is smooth (for verifying a
  // layout, whose goals are a few patches and points). Not given: every patch precise.
  std::optional<std::vector<int>> precise_patches;
  DirectLightOptions other_direct_light = cheap_direct_light_options();
  int other_rays_per_patch = 0;
  // A BVH built on the scene's first patches (the job scene, a layout's luminaires
  // appended after them): reused, only the rest get a BVH (RayCaster's second constructor).
  std::shared_ptr<const RayCaster> base_caster;
};

struct ExactSolveSummary {
  std::size_t patches = 0;
  double bvh_seconds = 0.0;
  double ray_offset_m = 0.0;             // how far ray origins are pushed off their patch
  double form_factor_seconds = 0.0;
  double direct_light_seconds = 0.0;
  std::uint64_t shadow_rays = 0;         // cast for the luminaires' direct light
  double solve_seconds = 0.0;
  std::uint64_t rays_cast = 0;           // form-factor rays (not counting shadow rays)
  double rays_per_second = 0.0;          // form-factor rays / form_factor_seconds
  double mean_escaped_fraction = 0.0;    // area-weighted: light leaving the scene
  double mean_back_hit_fraction = 0.0;   // area-weighted: light absorbed by back faces
  int iterations = 0;
  double relative_residual = 0.0;
  // Where the light goes (photometric lm): emitted = absorbed + lost up to ray noise.
  double emitted_lm = 0.0;
  double absorbed_lm = 0.0;              // sum A_i (1 - rho_i) H_i
  double lost_lm = 0.0;                  // struck back faces or left the scene
};

struct ExactSolution {
  RadiositySolution radiosity;
  ExactSolveSummary summary;
};

ExactSolution solve_exact(const Scene& scene, const ExactSolveOptions& options, const ProgressCallback& progress = {});

// The exact solve refined in steps, for a verification that stops when its goals are
// decided: the rows of the patches outside options.precise_patches start at
// `first_other_rays` rays and each refine() adds as many new rays again (an independent
// stream: another seed), up to options.other_rays_per_patch; the merged row of 2n rays
// is the mean of its two n-ray rows, an unbiased estimate like one row of 2n rays. The
// precise rows and the luminaires' direct light are computed once; each step solves the
// radiosity again. Without precise_patches or other_rays_per_patch, every row is cast
// at once (like solve_exact) and there is nothing to refine.
class ProgressiveExactSolve {
 public:
  ProgressiveExactSolve(const Scene& scene, const ExactSolveOptions& options, int first_other_rays,
                        const ProgressCallback& progress = {});
  ~ProgressiveExactSolve();
  ProgressiveExactSolve(const ProgressiveExactSolve&) = delete;
  ProgressiveExactSolve& operator=(const ProgressiveExactSolve&) = delete;

  const ExactSolution& solution() const { return solution_; }
  const RayCaster& caster() const { return *caster_; }
  int other_rays() const { return other_rays_; }  // rays per row outside the precise patches, so far
  bool can_refine() const;
  void refine();  // doubles other_rays() (capped at options.other_rays_per_patch) and solves again
  // Makes `patches` precise, as options.precise_patches are: their rows are cast again at
  // `rays` rays (a stream of their own, replacing the rows they had; never refined after)
  // and they get options.direct_light instead of the cheap estimate; then solves again.
  // For the patches a decisive goal point gathers most of its light from, whose rows'
  // noise would otherwise be that point's error. Returns how many became precise
  // (patches already precise are left as they are).
  std::size_t make_precise(const std::vector<int>& patches, int rays);
  std::size_t precise_count() const;
  // The Gauss-Seidel tolerance of the solves from now on (options.radiosity's at first):
  // steps whose solution only decides the next step can stop sooner, the last one not.
  void set_relative_residual(double relative_residual);
  // Solves again from the last solution when its residual is above the tolerance now
  // set (a step solved loosely turned out to be the last); returns whether it did.
  bool tighten();
  // The radiosity of `lit`, a scene of the same patches with other exitances (another
  // lighting state: some luminaires dimmed or off), on the rows solved so far: the same
  // form factors and luminaire columns (per unit exitance), solved from E.
  RadiositySolution solve_lit(const Scene& lit) const;

 private:
  void solve();
  const Scene& scene_;
  ExactSolveOptions options_;
  ProgressCallback progress_;
  std::unique_ptr<RayCaster> caster_;
  std::vector<int> others_;    // patches refined, ascending
  std::vector<bool> precise_;  // per patch: rows and direct light at the precise settings
  FormFactorRows raw_;         // every row, luminaire columns as cast
  EmitterLight emitter_;
  int other_rays_ = 0;
  int level_ = 0;
  ExactSolution solution_;
};

std::ostream& operator<<(std::ostream& os, const ExactSolveSummary& summary);

}  // namespace ilp
