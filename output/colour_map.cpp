#include "output/colour_map.h"

#include <algorithm>
#include <utility>
#include <vector>
#include <array>
#include <cmath>

namespace ilp {
namespace {

// Viridis (van der Walt and Smith, matplotlib's _viridis_data) at every 17th of its
// 256 entries, i.e. exactly at t = k / 15. Linear interpolation between these stays
// within 7/255 per channel of the full table.
constexpr int kKnots = 16;
constexpr std::array<std::array<double, 3>, kKnots> kViridis = {{
    {0.267004, 0.004874, 0.329415},  // entry 0
    {0.282656, 0.100196, 0.422160},  // 17
    {0.277134, 0.185228, 0.489898},  // 34
    {0.253935, 0.265254, 0.529983},  // 51
    {0.221989, 0.339161, 0.548752},  // 68
    {0.190631, 0.407061, 0.556089},  // 85
    {0.163625, 0.471133, 0.558148},  // 102
    {0.139147, 0.533812, 0.555298},  // 119
    {0.120565, 0.596422, 0.543611},  // 136
    {0.134692, 0.658636, 0.517649},  // 153
    {0.208030, 0.718701, 0.472873},  // 170
    {0.327796, 0.773980, 0.406640},  // 187
    {0.477504, 0.821444, 0.318195},  // 204
    {0.647257, 0.858400, 0.209861},  // 221
    {0.824940, 0.884720, 0.106217},  // 238
    {0.993248, 0.906157, 0.143936},  // 255
}};

// The smallest of 1, 2, 2.5, 4, 5, 6, 8 x 10^n that is >= v > 0 (to a relative 1e-9, so that
// a maximum of 500 plus rounding noise stays 500).
double nice_ceiling(double v) {
  const int exponent = static_cast<int>(std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 2.5, 4.0, 5.0, 6.0, 8.0, 10.0}) {
    // Dividing by 10^-n for negative n gives 0.25 rather than 2.5 * 0.1 = 0.25000000000000006.
    const double nice = exponent >= 0 ? m * std::pow(10.0, exponent) : m / std::pow(10.0, -exponent);
    if (nice >= v * (1.0 - 1e-9)) return std::isfinite(nice) ? nice : v;
  }
  return v;  // not reached: 10^(n+1) > v
}

}  // namespace

Eigen::Vector3d colour_map(double t) {
  if (std::isnan(t)) return Eigen::Vector3d::Constant(0.5);
  const double x = std::clamp(t, 0.0, 1.0) * (kKnots - 1);
  const int k = std::min(static_cast<int>(x), kKnots - 2);
  const double f = x - k;
  const auto& a = kViridis[k];
  const auto& b = kViridis[k + 1];
  return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

std::string svg_colour(const Eigen::Vector3d& rgb) {
  constexpr char kHex[] = "0123456789abcdef";
  std::string s = "#";
  for (int c = 0; c < 3; ++c) {
    const double v = std::isnan(rgb[c]) ? 0.0 : std::clamp(rgb[c], 0.0, 1.0);
    const int byte = static_cast<int>(std::lround(v * 255.0));
    s += kHex[byte / 16];
    s += kHex[byte % 16];
  }
  return s;
}

double ColourScale::fraction(double lux) const {
  if (std::isnan(lux)) return lux;
  if (!std::isfinite(min_lux) || !std::isfinite(max_lux) || !(max_lux > min_lux)) return 0.0;
  return std::clamp((lux - min_lux) / (max_lux - min_lux), 0.0, 1.0);
}

ColourScale colour_scale_for(const Eigen::VectorXd& lux) {
  double largest = 0.0;
  for (Eigen::Index i = 0; i < lux.size(); ++i)
    if (std::isfinite(lux[i])) largest = std::max(largest, lux[i]);
  if (!(largest > 0.0)) return {0.0, 1.0};  // all NaN, zero or negative: nothing to span
  return {0.0, nice_ceiling(largest)};
}

ColourScale colour_scale_for(const Eigen::VectorXd& lux, const Eigen::VectorXd& weights, double quantile) {
  std::vector<std::pair<double, double>> finite;  // value, weight
  double total = 0.0;
  for (Eigen::Index i = 0; i < lux.size(); ++i)
    if (std::isfinite(lux[i]) && weights[i] > 0.0) {
      finite.emplace_back(lux[i], weights[i]);
      total += weights[i];
    }
  if (finite.empty()) return {0.0, 1.0};
  std::sort(finite.begin(), finite.end());
  double below = 0.0, at = finite.back().first;
  for (const auto& [value, weight] : finite) {
    below += weight;
    if (below >= quantile * total) {
      at = value;
      break;
    }
  }
  if (!(at > 0.0)) return {0.0, 1.0};
  return {0.0, nice_ceiling(at)};
}

}  // namespace ilp
