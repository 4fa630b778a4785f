// A RayCaster that reuses a base caster's BVH for the scene's first patches (the job
// scene) and builds one only for the patches appended after them (a layout's
// luminaires) answers every query as a BVH of the whole scene does; a base built on
// another scene is not reused.
#include "core/transport/ray_caster.h"

#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

Scene room() { return reference::make_closed_box(V::Zero(), V(4.0, 3.0, 2.5), 0.5, 0.5); }

// The room with two panels hanging 0.4 m below its ceiling and one lying on its floor
// (its opening 1 cm above the floor's patches).
Scene room_with_panels() {
  Scene scene = room();
  add_square_luminaire(scene, "a", V(1.2, 1.0, 2.1), 0.6, 1000.0);
  add_square_luminaire(scene, "b", V(2.8, 2.0, 2.1), 0.6, 1000.0);
  add_square_luminaire(scene, "c", V(2.0, 1.5, 0.01), 0.6, 1000.0);
  return scene;
}

V random_direction(std::mt19937_64& random) {
  std::normal_distribution<double> normal;
  V d;
  do d = V(normal(random), normal(random), normal(random));
  while (d.norm() < 1e-6);
  return d.normalized();
}

TEST(RayCaster, ReusingTheJobScenesBvhGivesEveryHitOfTheWholeScenesBvh) {
  const auto base = std::make_shared<const RayCaster>(room(), 1);
  const Scene scene = room_with_panels();
  const RayCaster whole(scene, 1);
  const RayCaster reused(base, scene, 1);
  ASSERT_TRUE(reused.reuses_base());
  EXPECT_EQ(reused.ray_offset_m(), whole.ray_offset_m());
  const int first_luminaire_patch = static_cast<int>(room().patches.size());
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> inside(0.05, 0.95);
  int luminaire_hits = 0, occluded = 0;
  for (int k = 0; k < 20000; ++k) {
    const V origin(4.0 * inside(random), 3.0 * inside(random), 2.5 * inside(random));
    const V direction = random_direction(random);
    const RayHit a = whole.first_hit(origin, direction), b = reused.first_hit(origin, direction);
    ASSERT_EQ(a.patch, b.patch) << "ray " << k;
    ASSERT_EQ(a.t, b.t) << "ray " << k;
    ASSERT_EQ(a.front, b.front) << "ray " << k;
    luminaire_hits += a.patch >= first_luminaire_patch;
    const V to(4.0 * inside(random), 3.0 * inside(random), 2.5 * inside(random));
    ASSERT_EQ(whole.occluded(origin, to), reused.occluded(origin, to)) << "segment " << k;
    occluded += whole.occluded(origin, to);
  }
  // The test sees both kinds of hit and both answers of the shadow query.
  EXPECT_GT(luminaire_hits, 200);
  EXPECT_GT(occluded, 200);
  EXPECT_LT(occluded, 19800);
}

TEST(RayCaster, ABaseOfAnotherSceneIsNotReusedAndTheWholeSceneIsStillHit) {
  Scene other = room();
  other.patches[3].vertices_m[1].z() += 1e-3;  // one vertex moved: not the same patches
  const auto base = std::make_shared<const RayCaster>(other, 1);
  const Scene scene = room_with_panels();
  const RayCaster reused(base, scene, 1), whole(scene, 1);
  EXPECT_FALSE(reused.reuses_base());
  EXPECT_FALSE(RayCaster(nullptr, scene, 1).reuses_base());
  // A base with more patches than the scene is not its first patches either.
  EXPECT_FALSE(RayCaster(std::make_shared<const RayCaster>(scene, 1), room(), 1).reuses_base());
  std::mt19937_64 random(11);
  for (int k = 0; k < 2000; ++k) {
    const V origin(2.0, 1.5, 1.2), direction = random_direction(random);
    ASSERT_EQ(whole.first_hit(origin, direction).patch, reused.first_hit(origin, direction).patch);
  }
}

// A scene with nothing appended: every query answered by the base's BVH alone.
TEST(RayCaster, ReusingABaseWithNothingAppendedAnswersAsTheBase) {
  const Scene scene = room();
  const auto base = std::make_shared<const RayCaster>(scene, 1);
  const RayCaster reused(base, scene, 1);
  ASSERT_TRUE(reused.reuses_base());
  const RayHit hit = reused.first_hit(V(2.0, 1.5, 1.0), V(0.0, 0.0, -1.0));
  EXPECT_EQ(hit.patch, base->first_hit(V(2.0, 1.5, 1.0), V(0.0, 0.0, -1.0)).patch);
  EXPECT_NEAR(hit.t, 1.0, 1e-6);
  EXPECT_TRUE(hit.front);
  EXPECT_FALSE(reused.occluded(V(1.0, 1.0, 1.0), V(3.0, 2.0, 2.0)));
  EXPECT_TRUE(reused.occluded(V(2.0, 1.5, 1.0), V(2.0, 1.5, 3.0)));  // through the ceiling
}

}  // namespace
}  // namespace ilp
