// The data sheet's polar curve (output/polar_curve.h): sampled values are the file's
// intensities per 1000 lm, and the drawn curve of a cosine distribution is the circle
// its polar plot must be (r = I0 cos gamma is a circle through the centre).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "output/polar_curve.h"

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// An IES file: C 0, 90, 180, 270; gamma 0..90 every 5 degrees; I = i0 cos(gamma) x
// (1 + asym where C = 0) so that the planes differ.
ilp::Photometry cosine_file(double i0, double c0_boost = 0.0) {
  std::ostringstream os;
  os.precision(17);
  os << "IESNA:LM-63-2002\n[TEST] cosine\n[MANUFAC] test\nTILT=NONE\n";
  os << "1 1000 1 19 4 1 2 0.6 0.6 0\n1.0 1.0 30\n";
  for (int g = 0; g <= 90; g += 5) os << g << ' ';
  os << "\n0 90 180 270\n";
  for (int c = 0; c < 360; c += 90) {
    for (int g = 0; g <= 90; g += 5) os << i0 * std::cos(g * kDeg) * (c == 0 ? 1.0 + c0_boost : 1.0) << ' ';
    os << '\n';
  }
  return ilp::parse_ies(os.str(), "cosine.ies");
}

TEST(PolarCurve, SamplesAreTheFilesIntensityPerKilolumen) {
  const ilp::Photometry p = cosine_file(300.0, 0.5);
  const ilp::PolarCurve c = ilp::polar_curve(p, 5.0);
  const double per_klm = 1000.0 / p.luminaire_flux_lm;
  ASSERT_EQ(c.c0_c180.gamma_deg.size(), 37u);  // 0, 5, ..., 180
  for (std::size_t k = 0; k < c.c0_c180.gamma_deg.size(); ++k) {
    const double g = c.c0_c180.gamma_deg[k];
    EXPECT_NEAR(c.c0_c180.cd_per_klm[k], p.intensity_cd(0.0, g) * per_klm, 1e-9) << g;
    EXPECT_NEAR(c.c0_c180.cd_per_klm_opposite[k], p.intensity_cd(180.0, g) * per_klm, 1e-9) << g;
    EXPECT_NEAR(c.c90_c270.cd_per_klm[k], p.intensity_cd(90.0, g) * per_klm, 1e-9) << g;
    EXPECT_NEAR(c.c90_c270.cd_per_klm_opposite[k], p.intensity_cd(270.0, g) * per_klm, 1e-9) << g;
  }
  // Nadir of C0 is the file's 450 cd, above the horizontal nothing.
  EXPECT_NEAR(c.c0_c180.cd_per_klm[0], 450.0 * per_klm, 1e-9);
  EXPECT_EQ(c.c0_c180.cd_per_klm.back(), 0.0);
  EXPECT_NEAR(c.max_cd_per_klm, 450.0 * per_klm, 1e-9);
  // A 1-2-5 step with at most 5 rings up to the maximum.
  const double step = c.ring_step_cd_per_klm;
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
  EXPECT_TRUE(std::abs(mantissa - 1.0) < 1e-9 || std::abs(mantissa - 2.0) < 1e-9 || std::abs(mantissa - 5.0) < 1e-9) << step;
  EXPECT_LE(c.max_cd_per_klm / step, 5.0);
  EXPECT_GT(c.max_cd_per_klm / step, 2.0);
}

// The C90-C270 polyline of I0 cos(gamma) (the same in both planes) must lie on the
// circle through the centre of diameter I0 x scale below it: x² + (y - R)² = R².
TEST(PolarCurve, DrawsACosineDistributionAsACircle) {
  const ilp::PolarCurve c = ilp::polar_curve(cosine_file(300.0), 2.5);
  const std::string svg = ilp::polar_curve_svg(c, 360.0);
  const std::regex line("class=\"c90_c270\"[^>]*points=\"([^\"]*)\"");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, line)) << svg;
  std::istringstream points(m[1].str());
  std::vector<std::pair<double, double>> xy;
  for (std::string pair; points >> pair;) {
    const auto comma = pair.find(',');
    xy.emplace_back(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)));
  }
  ASSERT_EQ(xy.size(), 2u * c.c90_c270.gamma_deg.size());
  const double cx = 180.0, cy = 180.0;  // size / 2
  const double radius_px = 180.0 - 24.0;
  const int rings = static_cast<int>(std::ceil(c.max_cd_per_klm / c.ring_step_cd_per_klm - 1e-9));
  const double big_r = c.max_cd_per_klm * radius_px / (rings * c.ring_step_cd_per_klm) / 2.0;
  // At the file's gamma nodes (every 5 degrees) the curve is the file's value: on the
  // circle to the SVG's 0.01 px rounding; between them the interpolant (PCHIP) departs
  // from the cosine by up to ~3e-4 of the value: 1e-3 of the diameter.
  const std::size_t n = c.c90_c270.gamma_deg.size();
  for (std::size_t k = 0; k < xy.size(); ++k) {
    const double g = c.c90_c270.gamma_deg[k < n ? k : 2 * n - 1 - k];
    const bool node = std::abs(std::remainder(g, 5.0)) < 1e-9;
    const auto [x, y] = xy[k];
    EXPECT_NEAR(std::hypot(x - cx, y - (cy + big_r)), big_r, node ? 0.01 : 2e-3 * big_r) << "gamma " << g;
  }
  // The nadir point is straight below the centre, at the full radius.
  EXPECT_NEAR(xy.front().first, cx, 1e-9);
  EXPECT_NEAR(xy.front().second, cy + 2.0 * big_r, 0.01);
}

TEST(PolarCurve, RefusesABadStepOrAFileWithoutFlux) {
  const ilp::Photometry p = cosine_file(300.0);
  EXPECT_THROW((void)ilp::polar_curve(p, 0.0), std::invalid_argument);
  EXPECT_THROW((void)ilp::polar_curve(p, 50.0), std::invalid_argument);
  ilp::Photometry dark = p;
  dark.luminaire_flux_lm = 0.0;
  EXPECT_THROW((void)ilp::polar_curve(dark), std::invalid_argument);
}

}  // namespace
