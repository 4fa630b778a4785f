#include "core/light/opening_axis.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace ilp {
namespace {

constexpr double kStepCDeg = 5.0, kStepGammaDeg = 2.5;
// A rectangle this much longer than wide is a linear luminaire, whose curves tell its
// length (a 2 x 4 ft troffer or high-bay need not: overhead.ies has its narrower curve
// across its length).
constexpr double kElongated = 3.0;
// Mirror asymmetry (share of the light) below which a luminaire counts as symmetric
// end to end, and above which it counts as throwing its light to one side.
constexpr double kSymmetric = 0.02, kAsymmetric = 0.05;
// One plane's spread this much below the other's marks it as the longitudinal plane.
constexpr double kNarrower = 0.95;

double sin_deg(double a) { return std::sin(a * std::numbers::pi / 180.0); }

// sum |I(C) - I(mirror(C))| / sum (I(C) + I(mirror(C))), weighted by sin(gamma).
template <class Mirror>
double mirror_asymmetry(const Photometry& p, const Mirror& mirror) {
  double diff = 0.0, sum = 0.0;
  for (double c = 0.0; c < 360.0; c += kStepCDeg)
    for (double g = 0.0; g <= 180.0; g += kStepGammaDeg) {
      const double a = p.intensity_cd(c, g), b = p.intensity_cd(mirror(c), g), w = std::abs(sin_deg(g)) + 1e-3;
      diff += w * std::abs(a - b);
      sum += w * (a + b);
    }
  return sum > 0.0 ? diff / sum : 0.0;
}

// Intensity-weighted mean |sin gamma| over the half-planes c and c + 180 (trapezoid
// rule in gamma).
double plane_spread(const Photometry& p, double c) {
  constexpr int kSteps = static_cast<int>(180.0 / kStepGammaDeg);
  double weighted = 0.0, total = 0.0;
  for (double half : {c, c + 180.0})
    for (int k = 0; k <= kSteps; ++k) {
      const double g = k * kStepGammaDeg;
      const double i = p.intensity_cd(half, g) * (k == 0 || k == kSteps ? 0.5 : 1.0);
      weighted += i * std::abs(sin_deg(g));
      total += i;
    }
  return total > 0.0 ? weighted / total : 0.0;
}

std::string format(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v;
  return os.str();
}

// The C angle (0 or 90) of the long side of an elongated EULUMDAT opening, from its
// curves; NaN when they do not tell. `why` says what decided.
double long_axis_from_curves(const CurveEvidence& e, std::string& why) {
  const std::string figures = "(asymmetry along C0 " + format(e.asymmetry_along_c0) + ", along C90 " +
                              format(e.asymmetry_along_c90) + "; spread C0-C180 " + format(e.spread_c0_c180) +
                              ", C90-C270 " + format(e.spread_c90_c270) + ")";
  if (e.asymmetry_along_c0 >= kAsymmetric && e.asymmetry_along_c90 <= kSymmetric) {
    why = "the curves are symmetric end to end only along C90-C270 (a linear luminaire throws to one side, never "
          "to one end) " + figures;
    return 90.0;
  }
  if (e.asymmetry_along_c90 >= kAsymmetric && e.asymmetry_along_c0 <= kSymmetric) {
    why = "the curves are symmetric end to end only along C0-C180 " + figures;
    return 0.0;
  }
  if (e.spread_c0_c180 < kNarrower * e.spread_c90_c270) {
    why = "the C0-C180 curve is the narrower one (the plane along a linear luminaire's length) " + figures;
    return 0.0;
  }
  if (e.spread_c90_c270 < kNarrower * e.spread_c0_c180) {
    why = "the C90-C270 curve is the narrower one (the plane along a linear luminaire's length) " + figures;
    return 90.0;
  }
  why = "the curves do not tell " + figures;
  return std::numeric_limits<double>::quiet_NaN();
}

PhotometricOpening laid(const LuminousOpening& o, double length_axis_c_deg, std::string reason) {
  PhotometricOpening out;
  out.length_axis_c_deg = length_axis_c_deg;
  out.along_c0_m = length_axis_c_deg == 0.0 ? o.length_m : o.width_m;
  out.along_c90_m = length_axis_c_deg == 0.0 ? o.width_m : o.length_m;
  out.reason = std::move(reason);
  return out;
}

}  // namespace

CurveEvidence curve_evidence(const Photometry& p) {
  CurveEvidence e;
  e.asymmetry_along_c0 = mirror_asymmetry(p, [](double c) { return 180.0 - c; });
  e.asymmetry_along_c90 = mirror_asymmetry(p, [](double c) { return 360.0 - c; });
  e.spread_c0_c180 = plane_spread(p, 0.0);
  e.spread_c90_c270 = plane_spread(p, 90.0);
  return e;
}

PhotometricOpening photometric_opening(const Photometry& p, std::optional<double> length_axis_c_deg) {
  const LuminousOpening& o = p.opening;
  if (length_axis_c_deg) {
    if (*length_axis_c_deg != 0.0 && *length_axis_c_deg != 90.0)
      throw std::invalid_argument("the C-plane of a luminous opening's length must be 0 or 90 degrees, not " +
                                  format(*length_axis_c_deg));
    return laid(o, *length_axis_c_deg, "the product says the length runs along C" + format(*length_axis_c_deg));
  }
  if (p.format == PhotometryFormat::ies)
    return laid(o, 0.0, "IES LM-63: the length runs along the 0-180 degree plane, the width along 90-270");
  const double long_m = std::max(o.length_m, o.width_m), short_m = std::min(o.length_m, o.width_m);
  if (o.shape != OpeningShape::rectangle || !(short_m > 0.0) || long_m < kElongated * short_m)
    return laid(o, 0.0, "EULUMDAT, not a linear opening (round, or less than " + format(kElongated) +
                            " times longer than wide): the length along C0, where it changes little");
  std::string why;
  const double long_axis = long_axis_from_curves(curve_evidence(p), why);
  if (std::isnan(long_axis))
    return laid(o, 0.0, "EULUMDAT does not say which plane the length runs along and " + why + ": the length along C0");
  const double length_axis = o.length_m >= o.width_m ? long_axis : 90.0 - long_axis;
  return laid(o, length_axis, "EULUMDAT does not say which plane the length runs along; " + why);
}

}  // namespace ilp
