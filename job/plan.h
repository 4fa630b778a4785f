// From the job file to what each stage is given: the translation happens here, once,
// and core/ and optimizer/ see only these stage inputs (options structs, specs), never
// the schema. One plan per product variant: the luminaire it places (the plain panel
// of the flux_lm/efficacy keys is a product too), the lighting model's spec, the
// search's spec (goal targets already initial for the variant's maintenance factor).
#pragma once

#include <optional>
#include <vector>

#include "core/exact/exact_solver.h"
#include "core/light/luminaire_product.h"
#include "core/cost/machine_speed.h"
#include "core/operator/sample_operator.h"
#include "job/config.h"
#include "optimizer/lighting_model.h"
#include "optimizer/scenario_spec.h"
#include "optimizer/search_spec.h"

namespace ilp {

// What a command's options add to a job: not from the file, never written into it.
struct RunOptions {
  std::optional<int> threads;               // --threads: replaces solver.threads (0: every core)
  std::optional<double> max_memory_bytes;   // --max-memory: a budget below the machine's
  // Under mpirun, a single-room job's operator builds split over the ranks (the lighting
  // model's only: the verification's operator stays whole on rank 0). Default: one process.
  WorkShare operator_share;
  // This machine's speed against the cost model's reference (core/cost/machine_speed.h),
  // for the estimates alone: the reference's own by default.
  MachineCalibration machine;
};

// Worker threads: --threads, else solver.threads.
int worker_threads(const JobConfig& job, const RunOptions& run);
// The solver section as the operator's options (sample_size still unset) and the exact solver's.
SampleOperatorOptions operator_options(const JobConfig& job, const RunOptions& run);
ExactSolveOptions exact_options(const JobConfig& job, const RunOptions& run);

struct VariantPlan {
  ProductVariant product;        // what the search places; the plain panel as a product
  bool listed = false;           // one of luminaires.products (else the plain panel)
  double maintenance_factor = 1.0;  // the product's own, else the job's
  ModelSpec model;
  SearchSpec search;
  std::vector<ScenarioSpec> scenarios;  // the job's other lighting states, goals at initial targets
};

// Every variant the job searches: each product at each rotation, or the plain panel.
// Throws ConfigError for a job that places no luminaires (no mounting surface or no
// goals), or a product whose photometric file cannot be used.
std::vector<VariantPlan> plan_job(const JobConfig& job, const RunOptions& run = {});

// The goal lines at initial targets for a maintenance factor (a sweep point's job
// after set_goal_parameter gives new targets for the same plan).
std::vector<GoalSpec> goal_specs(const JobConfig& job, double maintenance_factor);

}  // namespace ilp
