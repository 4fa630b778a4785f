// A synthetic photometric web every C-plane of which differs, with its closed form, for
// tests of turned and tilted luminaires against I(C, gamma) cos / d² (tests/core,
// tests/optimizer).
#pragma once

#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include "core/light/photometry.h"

namespace ilp::test {

// I(C, gamma) = 1000 cos(gamma) (1 + 0.5 sin(gamma) cos C + 0.25 sin(gamma) sin 2C) cd
// below the horizontal, 0 above: the two lobes make every C differ.
inline double asymmetric_web_cd(double c_deg, double gamma_deg) {
  if (gamma_deg >= 90.0) return 0.0;
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double c = c_deg * kDeg, g = gamma_deg * kDeg;
  return 1000.0 * std::cos(g) * (1.0 + 0.5 * std::sin(g) * std::cos(c) + 0.25 * std::sin(g) * std::sin(2.0 * c));
}

// That web as an IES LM-63-2002 file with a point opening (absolute photometry), at
// 2.5 deg in gamma and 5 deg in C.
inline std::shared_ptr<const Photometry> asymmetric_point_web() {
  std::ostringstream os;
  os.precision(17);
  os << "IESNA:LM-63-2002\n[TEST] synthetic\n[MANUFAC] test\nTILT=NONE\n1 -1 1 37 73 1 2 0 0 0\n1 1 10\n";
  for (int g = 0; g <= 36; ++g) os << 2.5 * g << ' ';
  os << '\n';
  for (int c = 0; c <= 72; ++c) os << 5.0 * c << ' ';
  os << '\n';
  for (int c = 0; c <= 72; ++c) {
    for (int g = 0; g <= 36; ++g) os << asymmetric_web_cd(5.0 * c, 2.5 * g) << ' ';
    os << '\n';
  }
  return std::make_shared<const Photometry>(parse_ies(os.str(), "synthetic.ies"));
}

}  // namespace ilp::test
