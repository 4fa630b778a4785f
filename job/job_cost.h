// The cost model (core/cost/cost_model.h) applied to an inverse job: its counts from the
// job and the model's geometry (goal patches, candidates), and the verification
// method `auto` resolves to on this machine (exact when its sparse rows fit in
// memory, else a sample whose dense k x k solve fits and stays quick).
#pragma once

#include <optional>
#include <string>

#include "job/verification_spec.h"
#include "job/plan.h"
#include "core/cost/cost_model.h"
#include "core/scene/scene.h"
#include "optimizer/lighting_model.h"

namespace ilp {

struct VerificationPlan {
  VerificationMethod method = VerificationMethod::none;  // exact, sample or none (never automatic)
  int sample_size = 0;                                    // sample: k
  std::string reason;                                     // for the run log
};

// The largest k the automatic verification uses (a dense LU of 4000 per channel takes about 3 s here).
inline constexpr int kAutoVerificationMaxSample = 4000;

// What verify_layout does for `job` on a scene of `patches` patches (`population` of
// them reflecting) with `luminaires` placed, within `budget_bytes` (none: no limit).
VerificationPlan plan_verification(const VerificationSettings& settings, std::size_t patches, std::size_t population,
                                   std::size_t goal_patches, int luminaires, std::optional<double> budget_bytes);

// Counts for the cost model. `sample_size`: k of the operator (0 when not known: the
// configured size, or with solver.target_error the largest k it may choose). The
// grids' points are geometry's (goal_points) unless `grids` gives their sizes (before
// they are laid: the cells, the most points they can have).
CostCounts job_cost_counts(const VariantPlan& plan, const Scene& job_scene, const LightingModel& geometry,
                           std::optional<double> budget_bytes, const std::vector<CalcGridSize>* grids = nullptr);

// One variant's model geometry with what `ilp run` costs: the estimate is made before
// the grids are laid, from their cells, and a job that cannot fit is refused then (no
// grid point is laid); else the grids are laid and the estimate made again from their
// points. What prepare_job logs and refuses, and what `ilp inspect` prints. `caster`:
// the scene's BVH, to lay the grids with (none: one is built for them).
struct CostedGeometry {
  LightingModel model;   // without grids and areas when refused
  CostEstimate estimate;
  CostCounts counts;
  std::string refusal;   // require_fits's message; empty when the job fits
};
CostedGeometry costed_geometry(const VariantPlan& plan, const Scene& job_scene,
                               const std::optional<MemoryBudget>& budget, const MachineCosts& costs,
                               const RayCaster* caster = nullptr);

// The cost model's constants for this job on this machine: run.machine's speed at the
// job's worker threads.
MachineCosts job_machine_costs(int worker_threads, const RunOptions& run);

// The whole run's time before any work: the sum of its variants' estimates (each
// variant builds its own operator; the first verifies its layout in full, each later one
// half of it on average, as min_power skips a variant predicted to lose; the scene and
// its BVH are read, and the outputs written, once), from each variant's estimate in
// plan order. What `ilp inspect` and `ilp run` print for a job of several variants.
double whole_run_seconds(Objective objective, const std::vector<CostEstimate>& variants);
// A job of luminaire groups (job.groups), each group's variants' estimates: every
// group's variants are built and searched, but the run reads the model and writes its
// outputs once and verifies the groups' layouts together once (the largest verification
// of any variant counted).
double groups_run_seconds(const std::vector<std::vector<CostEstimate>>& groups);

}  // namespace ilp
