// The sample-based operator against the exact solve, conservation and its own shortcuts.
#include "core/sample_operator.h"

#include <gtest/gtest.h>

#include "core/config.h"
#include "core/error.h"
#include "core/exact_solver.h"
#include "core/job.h"
#include "core/reference_scenes.h"

namespace ilp {
namespace {

// The shipped office, meshed coarsely (about 1,900 patches) so that k = n stays cheap.
Scene coarse_office(double max_edge_m = 0.6) {
  JobConfig job = load_job_config(ILP_SOURCE_DIR "/configs/office.yaml");
  job.scene.max_patch_edge_m = max_edge_m;
  return load_job_scene(job).scene;
}

std::vector<int> patches_of_surfaces(const Scene& scene, std::initializer_list<const char*> names) {
  std::vector<int> out;
  for (std::size_t i = 0; i < scene.patches.size(); ++i)
    for (const char* name : names)
      if (scene.surfaces[scene.patches[i].surface].name == name) out.push_back(static_cast<int>(i));
  return out;
}

SampleOperatorOptions options_with(int k, int rays = 256) {
  SampleOperatorOptions o;
  o.sample_size = k;
  o.form_factors.rays_per_patch = rays;
  return o;
}

SampleOperator build(const Scene& scene, std::span<const int> goals, const SampleOperatorOptions& o) {
  const RayCaster caster(scene);
  const GoalRows rows = compute_goal_rows(scene, caster, goals, scene_light_sources(scene), o);
  return build_sample_operator(scene, caster, rows, o);
}

TEST(SampleOperator, CensusReproducesTheExactSolve) {
  const Scene scene = coarse_office();
  const std::vector<int> goals = patches_of_surfaces(scene, {"desk_1", "desk_2", "floor", "walls"});
  for (IndirectMethod method : {IndirectMethod::sample_gather, IndirectMethod::exact_second_bounce}) {
    SampleOperatorOptions o = options_with(static_cast<int>(scene.patches.size()));
    o.indirect = method;
    const SampleOperator op = build(scene, goals, o);
    ASSERT_TRUE(op.stats.census);
    ExactSolveOptions exact;
    exact.radiosity.relative_residual = 1e-12;
    const ExactSolution reference = solve_exact(scene, exact);
    const Eigen::VectorXd H = op.illuminance_lux(source_flux_lm(scene, op.sources));
    const Eigen::VectorXd direct = op.direct_lux(source_flux_lm(scene, op.sources));
    for (std::size_t g = 0; g < goals.size(); ++g) {
      const Eigen::Index i = goals[g];
      ASSERT_NEAR(direct[g], reference.radiosity.direct_lux[i], 1e-9 * reference.radiosity.direct_lux[i] + 1e-12)
          << "patch " << i;
      ASSERT_NEAR(H[g], reference.radiosity.total_lux[i], 1e-8 * reference.radiosity.total_lux[i])
          << "patch " << i << " with " << to_string(method);
    }
  }
}

}  // namespace
}  // namespace ilp
