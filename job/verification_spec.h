// What the verification of a layout is given: the verification section as the job states
// it (VerificationSettings, read by the loader), and the plan's VerificationSpec with the
// solver options of its solves (plan_job fills it; the verification reads nothing else).
#pragma once

#include <cstddef>
#include <cstdint>

#include "core/exact/exact_solver.h"
#include "core/operator/sample_operator.h"

namespace ilp {

enum class VerificationMethod { automatic, exact, sample, none };

// verification: the layout found, placed as real luminaires and solved again.
struct VerificationSettings {
  VerificationMethod method = VerificationMethod::automatic;  // auto: exact up to max_exact_patches, else sample
  int rays_per_patch = 1024;          // rows of goal patches and each grid point's gather
  // Rows of the other patches, whose light is read only through reflections (smooth):
  // at most this many rays (exact method); direct light there is the cheap estimate.
  int indirect_rays_per_patch = 128;
  // Those rows start at this many rays and are doubled, with new rays, until every goal
  // moves by less than its margin allows (job/verification_margin.h): the indirect
  // light is smooth, so a few rays per patch often decide it. = indirect_rays_per_patch:
  // one step.
  int first_indirect_rays = 16;
  // Exact: the grid points that decide a minimum, uniformity or maximum goal (within 5 %
  // of the lowest or highest, or within 3 of their own standard errors) gather again with
  // this many rays (at least rays_per_patch), and the patches each gathers at least
  // 0.2 % of its reflected light from get precise direct light and rows of a sixteenth
  // as many (at least rays_per_patch): a minimum is one point, whose gather and few
  // nearby patches' cheap light and rows would otherwise be its error. 0: off.
  int decisive_rays = 16384;
  // Searches at most: when a goal fails only on verification, the search runs again
  // with that goal's target scaled by predicted / verified (a defect correction).
  int rounds = 3;
  std::size_t max_exact_patches = 30000;
  double sample_fraction = 0.25;  // method sample: k as a fraction of the reflecting patches
  // The least margin (relative) the flux correction keeps above the target of each goal
  // it scales (average, minimum), for the error the verification does not estimate
  // (job/verification_margin.h).
  double margin = 0.005;
};

// The verification's inputs in a plan: its settings, and the options of the solves it runs
// (the job's solver options at the run's threads; the seeds before the verification's salt).
struct VerificationSpec {
  VerificationSettings settings;
  ExactSolveOptions exact;        // form factors, direct light, radiosity at the run's threads
  SampleOperatorOptions sample;   // the sample method's operator (sample_size set when used)
  int threads = 0;                // worker threads
};

}  // namespace ilp
