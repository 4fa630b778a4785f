#include "core/operator/patch_sample.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/transport/sampling.h"

namespace ilp {
namespace {

// A seeded stream of uniform doubles in [0, 1).
class UnitStream {
 public:
  explicit UnitStream(std::uint64_t seed) : state_(splitmix64(seed ^ 0x5A3C9E17F00DBA11ull)) {}
  double next() {
    state_ = splitmix64(state_);
    return to_unit(state_);
  }

 private:
  std::uint64_t state_;
};

PatchSample from_counts(const std::map<int, int>& multiplicity, const Scene& scene, bool area_weighted) {
  PatchSample out;
  out.weight.resize(static_cast<Eigen::Index>(multiplicity.size()));
  for (const auto& [patch, count] : multiplicity) {
    out.weight[static_cast<Eigen::Index>(out.patches.size())] =
        area_weighted ? count / scene.patches[patch].area_m2 : static_cast<double>(count);
    out.patches.push_back(patch);
  }
  return out;
}

}  // namespace

std::string_view to_string(SampleStrategy strategy) {
  switch (strategy) {
    case SampleStrategy::uniform: return "uniform";
    case SampleStrategy::area: return "area";
    case SampleStrategy::stratified: return "stratified";
  }
  return "?";
}

std::optional<SampleStrategy> parse_sample_strategy(std::string_view text) {
  for (SampleStrategy s : {SampleStrategy::uniform, SampleStrategy::area, SampleStrategy::stratified})
    if (text == to_string(s)) return s;
  return std::nullopt;
}

PatchSample draw_patch_sample(const Scene& scene, std::span<const int> population, int k, SampleStrategy strategy,
                              std::uint64_t seed) {
  if (population.empty()) throw std::invalid_argument("draw_patch_sample: empty population");
  if (k < 1) throw std::invalid_argument("draw_patch_sample: k = " + std::to_string(k) + ": must be >= 1");
  const std::size_t n = population.size();
  if (static_cast<std::size_t>(k) >= n) {
    PatchSample census;
    census.patches.assign(population.begin(), population.end());
    std::sort(census.patches.begin(), census.patches.end());
    census.weight = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(n));
    census.census = true;
    return census;
  }
  UnitStream random(seed);
  std::map<int, int> multiplicity;
  switch (strategy) {
    case SampleStrategy::uniform: {
      // Partial Fisher-Yates: the first k entries become a simple random sample.
      std::vector<int> pool(population.begin(), population.end());
      for (std::size_t m = 0; m < static_cast<std::size_t>(k); ++m) {
        const std::size_t pick = m + std::min(n - m - 1, static_cast<std::size_t>(random.next() * (n - m)));
        std::swap(pool[m], pool[pick]);
        multiplicity[pool[m]] = 1;
      }
      return from_counts(multiplicity, scene, false);
    }
    case SampleStrategy::area: {
      std::vector<double> cumulative(n);
      double total = 0.0;
      for (std::size_t m = 0; m < n; ++m) cumulative[m] = total += scene.patches[population[m]].area_m2;
      for (int draw = 0; draw < k; ++draw) {
        const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), random.next() * total);
        ++multiplicity[population[std::min<std::size_t>(static_cast<std::size_t>(it - cumulative.begin()), n - 1)]];
      }
      return from_counts(multiplicity, scene, true);
    }
    case SampleStrategy::stratified: {
      std::vector<int> ordered(population.begin(), population.end());
      std::stable_sort(ordered.begin(), ordered.end(), [&](int a, int b) {
        const int sa = scene.patches[a].surface, sb = scene.patches[b].surface;
        return sa != sb ? sa < sb : a < b;
      });
      // Every (n / k)-th patch from a random start: k distinct patches, each with probability k / n.
      const double step = static_cast<double>(n) / k, start = random.next() * step;
      for (int m = 0; m < k; ++m)
        multiplicity[ordered[std::min<std::size_t>(static_cast<std::size_t>(start + m * step), n - 1)]] = 1;
      return from_counts(multiplicity, scene, false);
    }
  }
  throw std::invalid_argument("draw_patch_sample: unknown strategy");
}

}  // namespace ilp
