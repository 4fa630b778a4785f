// Deterministic sample points: a 4-D Halton sequence, randomised per stream by a
// Cranley-Patterson rotation seeded from (seed, stream id), and the maps that turn
// unit-square points into points on a triangle and cosine-weighted directions.
// A stream's points depend only on its seed and id, never on the thread running it.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace ilp {

// SplitMix64: a fast, well-mixed 64-bit hash / generator step.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Uniform double in [0, 1) from the top 53 bits.
inline double to_unit(std::uint64_t x) { return static_cast<double>(x >> 11) * 0x1.0p-53; }

// Radical inverse of i in the given base: the i-th point of van der Corput's sequence.
inline double radical_inverse(std::uint32_t i, std::uint32_t base) {
  const double inv_base = 1.0 / base;
  double inv = inv_base, result = 0.0;
  while (i > 0) {
    const std::uint32_t digit = i % base;
    result += digit * inv;
    i /= base;
    inv *= inv_base;
  }
  return result;
}

// The first n points of the 4-D Halton sequence (bases 2, 3, 5, 7). Every row of a
// form-factor computation uses the same points under its own rotation, so they are
// computed once: the radical inverses would otherwise cost as much as the rays.
inline std::vector<std::array<double, 4>> halton4_points(std::uint32_t n) {
  static constexpr std::uint32_t kBases[4] = {2, 3, 5, 7};
  std::vector<std::array<double, 4>> points(n);
  for (std::uint32_t i = 0; i < n; ++i)
    for (int d = 0; d < 4; ++d) points[i][d] = radical_inverse(i, kBases[d]);
  return points;
}

// A Cranley-Patterson rotation of the Halton sequence, drawn from (seed, stream).
class RotatedHalton4 {
 public:
  RotatedHalton4(std::uint64_t seed, std::uint64_t stream) {
    std::uint64_t state = splitmix64(seed ^ splitmix64(stream + 0x632BE59BD9B4E019ull));
    for (double& s : shift_) {
      state = splitmix64(state);
      s = to_unit(state);
    }
  }
  // The i-th point, each coordinate in [0, 1).
  std::array<double, 4> point(std::uint32_t i) const {
    static constexpr std::uint32_t kBases[4] = {2, 3, 5, 7};
    std::array<double, 4> u;
    for (int d = 0; d < 4; ++d) u[d] = radical_inverse(i, kBases[d]);
    return rotate(u);
  }
  // A precomputed Halton point (halton4_points), rotated: the same as point(i).
  std::array<double, 4> rotate(std::array<double, 4> u) const {
    for (int d = 0; d < 4; ++d) {
      u[d] += shift_[d];
      if (u[d] >= 1.0) u[d] -= 1.0;
    }
    return u;
  }

 private:
  std::array<double, 4> shift_{};
};

// Uniform point on triangle (a, b, c) from (u, v) in the unit square.
inline Eigen::Vector3d sample_triangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c, double u, double v) {
  const double su = std::sqrt(u);
  return a + (b - a) * (su * (1.0 - v)) + (c - a) * (su * v);
}

// Orthonormal basis (t, s) completing unit n (Duff et al. 2017, branchless).
inline void orthonormal_basis(const Eigen::Vector3d& n, Eigen::Vector3d& t, Eigen::Vector3d& s) {
  const double sign = std::copysign(1.0, n.z());
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  t = Eigen::Vector3d(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  s = Eigen::Vector3d(b, sign + n.y() * n.y() * a, -n.y());
}

// Shirley-Chiu concentric map of (u, v) in the unit square to polar (r, phi) on the
// unit disk: area-preserving, so it keeps a point set's stratification.
struct PolarPoint {
  double r = 0.0, phi = 0.0;
};
inline PolarPoint concentric_disk(double u, double v) {
  const double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0;
  PolarPoint p;
  if (a != 0.0 || b != 0.0) {
    constexpr double kQuarterPi = 0.78539816339744830962;
    if (std::abs(a) > std::abs(b)) {
      p.r = a;
      p.phi = kQuarterPi * (b / a);
    } else {
      p.r = b;
      p.phi = 2.0 * kQuarterPi - kQuarterPi * (a / b);
    }
  }
  return p;
}

// Cosine-weighted direction about unit n from (u, v): the concentric disk lifted to
// the hemisphere (Malley), which keeps the point set's stratification.
inline Eigen::Vector3d sample_cosine_hemisphere(const Eigen::Vector3d& n, const Eigen::Vector3d& t,
                                                const Eigen::Vector3d& s, double u, double v) {
  const auto [r, phi] = concentric_disk(u, v);
  // Float trigonometry: directions end up in float rays anyway, and it halves the cost.
  const double x = r * std::cos(static_cast<float>(phi)), y = r * std::sin(static_cast<float>(phi));
  const double z = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
  return t * x + s * y + n * z;
}

}  // namespace ilp
