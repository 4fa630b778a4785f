// From the job file to what each stage is given: the translation happens here, once,
// and the stages (job/'s runners, core/ and optimizer/) see only the plan and its stage
// inputs (options structs, specs), never the schema. A JobPlan holds the scene's spec,
// the goals and one plan per product variant: the luminaire it places (the plain panel
// of the flux_lm/efficacy keys is a product too), the lighting model's spec, the
// search's spec (goal targets already initial for the variant's maintenance factor); a
// job of luminaire groups holds each group's variants.
#pragma once

#include <optional>
#include <vector>

#include "core/exact/exact_solver.h"
#include "core/light/luminaire_product.h"
#include "core/cost/machine_speed.h"
#include "core/operator/sample_operator.h"
#include "job/scene_spec.h"
#include "job/verification_spec.h"
#include "optimizer/lighting_model.h"
#include "optimizer/scenario_spec.h"
#include "optimizer/search_spec.h"

namespace ilp {

struct JobConfig;  // job/config.h: plan_job is its only reader on the way to the stages

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

// One goal line as the job states it: a metric over a named area at its maintained
// target (lux metrics; U0 as given), and where the area is (for the records).
struct GoalLine {
  std::string name;
  GoalMetric metric = GoalMetric::average;
  double target = 0.0;                // maintained, as the job states it
  std::vector<std::string> surfaces;  // empty for a grid goal
  std::string grid;                   // the calculation grid, or "" for surfaces
};

// What a solve is judged against: the job's goal lines, its objective and its power
// density cap. A sweep point and each verification round edit a copy of this, never the
// config.
struct JobGoals {
  std::vector<GoalLine> lines;
  Objective objective = Objective::min_power;
  std::optional<double> max_power_density_w_per_m2;
};

// The target a goal is searched and verified at: initial = maintained / maintenance
// factor for lux metrics, the target itself for ratios (U0) and UGR.
double initial_target(GoalMetric metric, double maintained, double maintenance_factor);
// Sets the target of the line `key` names ("goals.NAME.average_lux", ".min_lux",
// ".max_lux", ".uniformity", ...) to `value`, checked as the job file is; throws
// ConfigError "--set KEY ..." naming the key or the rule broken.
void set_goal_target(JobGoals& goals, const std::string& key, double value);

// What the run's outputs cost (the cost model's output phase), from output.formats.
struct OutputWork {
  bool patch_files = false;  // per-patch files (scene.ply, illuminance.csv)
  bool renders = false;      // PNG or PDF renders (plan.png, isolux_*.png, report.pdf)
  bool plan_render = false;  // the plan rendered (plan.png, report.pdf): its outline's triangles
};

struct VariantPlan {
  ProductVariant product;        // what the search places; the plain panel as a product
  bool listed = false;           // one of luminaires.products (else the plain panel)
  double maintenance_factor = 1.0;  // the product's own, else the job's
  ModelSpec model;
  SearchSpec search;             // its goals: `goals` at initial targets for maintenance_factor
  JobGoals goals;                // the job's goal lines, maintained
  VerificationSpec verification;  // how the layout found is verified
  OutputWork outputs;            // what its outputs cost
  std::string source;            // the job file, for messages
  std::vector<ScenarioSpec> scenarios;  // the job's other lighting states, goals at initial targets
};

// The variant's search at the targets of `goals` (the plan's, a sweep point's or a
// verification round's): every line at its initial target for the variant's
// maintenance factor (GoalSpec, as the search and the verification judge), the goals'
// objective. The one place maintained lines become the search's.
SearchSpec search_at(const VariantPlan& variant, const JobGoals& goals);

// One luminaire group of a job of groups (luminaires.groups[g]): its name, where the
// job gives it, the surfaces its search needs of the mesh, and its variants.
struct GroupPlan {
  std::string name;
  FileLoc loc;
  SearchSurfaces surfaces;
  std::vector<VariantPlan> variants;
};

// The whole job as the stages take it.
struct JobPlan {
  std::string source;                 // the job file, for messages
  SceneSpec scene;                    // what the scene stage reads (group 0's search surfaces for groups)
  int threads = 0;                    // worker threads (0: every core)
  JobGoals goals;                     // the job's goal lines, maintained
  std::vector<VariantPlan> variants;  // a single search: each product at each rotation (empty with groups)
  std::vector<GroupPlan> groups;      // luminaires.groups, searched together (then no variants)
};

// The scene stage's input of a job (the whole of it for `ilp solve`, `inspect`, `accuracy`).
SceneSpec scene_spec(const JobConfig& job);

// Every variant the job searches, each product at each rotation or the plain panel; or
// every group's. Throws ConfigError for a job that places no luminaires (no mounting
// surface or no goals), or a product whose photometric file cannot be used.
JobPlan plan_job(const JobConfig& job, const RunOptions& run = {});


}  // namespace ilp
