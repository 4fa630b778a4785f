// Drawing the patch sample: sizes, determinism, and inclusion probabilities against
// what each strategy promises (frequencies over many seeds).
#include "core/operator/patch_sample.h"

#include <gtest/gtest.h>

#include <map>

#include "core/scene/reference_scenes.h"

namespace ilp {
namespace {

using V = Eigen::Vector3d;

// Two surfaces whose patches differ 9-fold in area. Meshing at 0.75 m cuts the
// 1 m square "big" (triangle edges up to 1.41 m, m = 2) into 8 patches of 0.125 m2
// and the 4 x 0.25 m strip "thin" (edges up to 4.01 m, m = 6) into 72 of 0.0139 m2.
Scene two_sizes() {
  const V rho = V::Constant(0.5);
  return reference::make_quad_scene({{"big", V(0, 0, 0), V(1, 0, 0), V(1, 1, 0), V(0, 1, 0), rho},
                                     {"thin", V(2, 0, 0), V(6, 0, 0), V(6, 0.25, 0), V(2, 0.25, 0), rho}},
                                    0.75);
}

TEST(PatchSample, FixtureHasTwoPatchSizes) {
  const Scene scene = two_sizes();
  ASSERT_EQ(scene.patches.size(), 80u);
  EXPECT_NEAR(scene.patches.front().area_m2, 0.125, 1e-12);
  EXPECT_NEAR(scene.patches.back().area_m2, 0.5 / 36, 1e-12);
}

std::vector<int> all(const Scene& scene) { return scene.all_patches(); }

TEST(PatchSample, CensusWhenKReachesThePopulation) {
  const Scene scene = two_sizes();
  const std::vector<int> population = all(scene);
  for (SampleStrategy s : {SampleStrategy::uniform, SampleStrategy::area, SampleStrategy::stratified}) {
    const PatchSample sample = draw_patch_sample(scene, population, static_cast<int>(population.size()) + 3, s, 7);
    EXPECT_TRUE(sample.census);
    EXPECT_EQ(sample.patches, population);
    EXPECT_EQ(sample.weight, Eigen::VectorXd::Ones(static_cast<Eigen::Index>(population.size())));
  }
}

TEST(PatchSample, DistinctSortedDeterministicAndSeedDependent) {
  const Scene scene = two_sizes();
  for (SampleStrategy s : {SampleStrategy::uniform, SampleStrategy::area, SampleStrategy::stratified}) {
    const PatchSample a = draw_patch_sample(scene, all(scene), 6, s, 11);
    const PatchSample b = draw_patch_sample(scene, all(scene), 6, s, 11);
    EXPECT_EQ(a.patches, b.patches) << to_string(s);
    EXPECT_TRUE(std::is_sorted(a.patches.begin(), a.patches.end()));
    EXPECT_EQ(std::adjacent_find(a.patches.begin(), a.patches.end()), a.patches.end()) << "duplicates";
    EXPECT_FALSE(a.census);
    if (s != SampleStrategy::area) {
      EXPECT_EQ(a.patches.size(), 6u) << to_string(s);
    }
    bool differs = false;
    for (std::uint64_t seed = 12; seed < 20 && !differs; ++seed)
      differs = draw_patch_sample(scene, all(scene), 6, s, seed).patches != a.patches;
    EXPECT_TRUE(differs) << to_string(s) << ": the seed changes nothing";
  }
}

// Empirical inclusion frequency (uniform, stratified) or expected multiplicity
// (area) of each patch over many seeds.
std::map<int, double> frequencies(const Scene& scene, int k, SampleStrategy s, int draws, bool multiplicity) {
  std::map<int, double> f;
  for (int seed = 0; seed < draws; ++seed) {
    const PatchSample sample = draw_patch_sample(scene, all(scene), k, s, static_cast<std::uint64_t>(seed));
    for (std::size_t m = 0; m < sample.patches.size(); ++m) {
      const int p = sample.patches[m];
      // For area draws weight = multiplicity / area.
      f[p] += multiplicity ? sample.weight[static_cast<Eigen::Index>(m)] * scene.patches[p].area_m2 : 1.0;
    }
  }
  for (auto& [p, v] : f) v /= draws;
  return f;
}

TEST(PatchSample, UniformAndStratifiedGiveEveryPatchProbabilityKOverN) {
  const Scene scene = two_sizes();
  const double n = static_cast<double>(scene.patches.size());
  const int k = 5, draws = 20000;
  for (SampleStrategy s : {SampleStrategy::uniform, SampleStrategy::stratified}) {
    const auto f = frequencies(scene, k, s, draws, false);
    const double expected = k / n, sigma = std::sqrt(expected * (1 - expected) / draws);
    for (int p : all(scene)) {
      const double got = f.count(p) ? f.at(p) : 0.0;
      EXPECT_NEAR(got, expected, 5 * sigma) << to_string(s) << " patch " << p;
    }
  }
}

TEST(PatchSample, AreaDrawsPatchesInProportionToArea) {
  const Scene scene = two_sizes();
  const int k = 5, draws = 20000;
  const auto f = frequencies(scene, k, SampleStrategy::area, draws, true);
  const double total = scene.total_area_m2();
  for (int p : all(scene)) {
    const double expected = k * scene.patches[p].area_m2 / total;  // expected draws of p
    const double sigma = std::sqrt(expected / draws);               // Poisson-ish
    EXPECT_NEAR(f.count(p) ? f.at(p) : 0.0, expected, 5 * sigma + 1e-3) << "patch " << p;
  }
  // Weights are multiplicity / area: a big patch drawn once weighs less than a small one.
  const PatchSample sample = draw_patch_sample(scene, all(scene), 30, SampleStrategy::area, 3);
  for (std::size_t m = 0; m < sample.patches.size(); ++m) {
    const double multiplicity = sample.weight[static_cast<Eigen::Index>(m)] * scene.patches[sample.patches[m]].area_m2;
    EXPECT_NEAR(multiplicity, std::round(multiplicity), 1e-9);
    EXPECT_GE(multiplicity, 1.0);
  }
}

TEST(PatchSample, StratifiedGivesEachSurfaceItsShare) {
  const Scene scene = two_sizes();
  const int big = scene.find_surface("big");
  const double n = static_cast<double>(scene.patches.size());
  double big_patches = 0.0;
  for (const Patch& p : scene.patches) big_patches += p.surface == big;
  for (int k : {3, 7, 11}) {
    const double share = k * big_patches / n;
    for (std::uint64_t seed = 0; seed < 50; ++seed) {
      const PatchSample sample = draw_patch_sample(scene, all(scene), k, SampleStrategy::stratified, seed);
      int on_big = 0;
      for (int p : sample.patches) on_big += scene.patches[p].surface == big;
      EXPECT_LE(std::abs(on_big - share), 1.0) << "k " << k << " seed " << seed;
    }
  }
}

TEST(PatchSample, RejectsEmptyPopulationAndBadK) {
  const Scene scene = two_sizes();
  EXPECT_THROW(draw_patch_sample(scene, {}, 3, SampleStrategy::uniform, 1), std::invalid_argument);
  EXPECT_THROW(draw_patch_sample(scene, all(scene), 0, SampleStrategy::uniform, 1), std::invalid_argument);
}

TEST(PatchSample, StrategyNamesRoundTrip) {
  for (SampleStrategy s : {SampleStrategy::uniform, SampleStrategy::area, SampleStrategy::stratified})
    EXPECT_EQ(parse_sample_strategy(to_string(s)), s);
  EXPECT_FALSE(parse_sample_strategy("random"));
}

}  // namespace
}  // namespace ilp
