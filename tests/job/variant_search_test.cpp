// A job's product variants share the scene and its BVH (job/variant_search.h,
// load_shared_scene): read once, the same for every variant, and each variant's
// operator exactly the one it gets when prepared alone.
#include "job/variant_search.h"

#include <gtest/gtest.h>

#include <vector>

#include "core/base/error.h"
#include "job/config.h"
#include "job/group_runner.h"
#include "tests/test_support.h"
#include "job/plan.h"

namespace ilp {
namespace {

// A shipped job with small operators: what the tests compare is that they are shared or the same.
JobConfig small_job(const char* path) {
  JobConfig job = load_job_config(path);
  job.sample.fraction = 0.02;
  job.form_factors.rays_per_patch = 16;
  job.direct_light.receiver_points = 1;
  job.direct_light.shadow_rays = 4;
  return job;
}

TEST(PrepareVariants, TheVariantsShareOneSceneAndBvhAndEachOperatorIsItsOwnAlone) {
  const JobConfig job = small_job(ILP_SOURCE_DIR "/configs/office_products.yaml");
  JobPlan plan = plan_job(job);
  std::vector<VariantPlan>& plans = plan.variants;
  ASSERT_GE(plans.size(), 2u);
  plans.resize(2);
  std::vector<std::string> log;
  const std::vector<PreparedJob> prepared =
      prepare_variants(plan, {}, {}, "", [&](const std::string& line) { log.push_back(line); });
  ASSERT_EQ(prepared.size(), 2u);
  // One BVH, one reading of the model (its lines logged once, its time on the first variant).
  EXPECT_EQ(prepared[0].caster.get(), prepared[1].caster.get());
  EXPECT_GT(prepared[0].scene_seconds, 0.0);
  EXPECT_EQ(prepared[1].scene_seconds, 0.0);
  EXPECT_EQ(prepared[1].bvh_seconds, 0.0);
  std::size_t mesh_lines = 0;
  for (const std::string& line : log) mesh_lines += line.starts_with("mesh ");
  EXPECT_EQ(mesh_lines, 1u);
  for (std::size_t v = 0; v < 2; ++v) {
    const PreparedJob alone = prepare_job(scene_spec(job), plans[v]);
    EXPECT_EQ(prepared[v].loaded.scene.patches.size(), alone.loaded.scene.patches.size());
    EXPECT_EQ(prepared[v].model.grid.size(), alone.model.grid.size());
    EXPECT_EQ(prepared[v].model.goal_points.size(), alone.model.goal_points.size());
    ASSERT_EQ(prepared[v].model.candidate_lux_per_lm.rows(), alone.model.candidate_lux_per_lm.rows());
    ASSERT_EQ(prepared[v].model.candidate_lux_per_lm.cols(), alone.model.candidate_lux_per_lm.cols());
    EXPECT_TRUE(prepared[v].model.candidate_lux_per_lm == alone.model.candidate_lux_per_lm) << "variant " << v;
  }
}

// A job of luminaire groups reads the model once for all its groups (it read it once a
// group before), and prints the whole run's estimate before the first group's operator.
TEST(PrepareVariants, TheGroupsShareOneSceneAndBvhAndTheWholeRunIsEstimatedFirst) {
  const JobConfig job = small_job(ILP_SOURCE_DIR "/configs/office_two_groups.yaml");
  ASSERT_EQ(job.groups.size(), 2u);
  std::vector<std::string> log;
  const PreparedGroups groups = prepare_groups(plan_job(job), {}, {}, "", [&](const std::string& line) { log.push_back(line); });
  ASSERT_GE(groups.prepared.size(), 2u);
  for (const PreparedJob& p : groups.prepared) EXPECT_EQ(p.caster.get(), groups.prepared.front().caster.get());
  std::size_t mesh_lines = 0, whole = 0, first_group = log.size();
  for (std::size_t k = 0; k < log.size(); ++k) {
    mesh_lines += log[k].starts_with("mesh ");
    if (log[k].starts_with("estimate: the whole run")) whole = k;
    if (log[k].starts_with("group '") && first_group == log.size()) first_group = k;
  }
  EXPECT_EQ(mesh_lines, 1u);
  EXPECT_LT(whole, first_group) << "the whole run's estimate comes before the first group";
  for (const std::string& line : log) EXPECT_FALSE(line.starts_with("warning: nothing emits light")) << line;
}

// Each group's search surfaces are checked on the shared scene, not only the first's.
TEST(PrepareVariants, AGroupsUnknownMountingSurfaceIsALocatedError) {
  JobConfig job = small_job(ILP_SOURCE_DIR "/configs/office_two_groups.yaml");
  ASSERT_EQ(job.groups.size(), 2u);
  job.groups[1].search.mounting_surface = "no_such_surface";
  job.groups[1].search.suspended_height_m.reset();
  const std::string message = test::error_of<ConfigError>([&] { prepare_groups(plan_job(job), {}, {}, "", {}); }, "prepare_groups");
  EXPECT_TRUE(test::Contains(message, "office_two_groups.yaml:"));
  EXPECT_TRUE(test::Contains(message, "luminaires.mounting_surface: unknown surface 'no_such_surface'"));
}

}  // namespace
}  // namespace ilp
