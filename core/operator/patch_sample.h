// The random sample P of patches behind the sample-based inverse (METHOD section 3).
// Three ways to draw it, compared in docs/accuracy.md:
//   uniform     k distinct patches, each equally likely (the paper's choice);
//   area        k independent draws with probability proportional to area, with
//               replacement (a patch drawn twice counts twice);
//   stratified  systematic sampling over the patches ordered by surface and mesh
//               order: every patch has probability k/n, every surface gets its
//               share of k to within one patch, spread evenly over it.
// The gather estimate needs each sample patch's weight 1/pi_p (pi_p: how likely the
// draw makes it), up to a common factor: that is `weight`.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "core/scene/scene.h"

namespace ilp {

enum class SampleStrategy { uniform, area, stratified };

std::string_view to_string(SampleStrategy strategy);
std::optional<SampleStrategy> parse_sample_strategy(std::string_view text);

struct PatchSample {
  std::vector<int> patches;  // distinct patch indices, ascending
  Eigen::VectorXd weight;    // per entry of `patches`: multiplicity / inclusion probability, up to a common factor
  bool census = false;       // every patch of the population (k >= population): all weights 1, no sampling error
};

// Draws from `population` (distinct patch indices). k >= population size gives the
// census. Deterministic for a seed. Throws std::invalid_argument when k < 1 or the
// population is empty.
PatchSample draw_patch_sample(const Scene& scene, std::span<const int> population, int k, SampleStrategy strategy,
                              std::uint64_t seed);

}  // namespace ilp
