// The illuminance colour map: viridis' ends, rising lightness, "#rrggbb" text, and
// scales that end at round numbers without dividing by zero.
#include "output/colour_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace ilp {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::VectorXd values(std::initializer_list<double> v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

// Relative luminance of an sRGB colour (linearised channels, Rec. 709 weights).
double luminance(const Eigen::Vector3d& srgb) {
  const auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
  return 0.2126 * linear(srgb[0]) + 0.7152 * linear(srgb[1]) + 0.0722 * linear(srgb[2]);
}

TEST(ColourMap, EndsAreViridisFirstAndLastColours) {
  EXPECT_TRUE(colour_map(0.0).isApprox(Eigen::Vector3d(0.267004, 0.004874, 0.329415), 1e-12));
  EXPECT_TRUE(colour_map(1.0).isApprox(Eigen::Vector3d(0.993248, 0.906157, 0.143936), 1e-12));
  EXPECT_EQ(svg_colour(colour_map(0.0)), "#440154");
  EXPECT_EQ(svg_colour(colour_map(1.0)), "#fde725");
}

TEST(ColourMap, ClampsOutsideTheUnitIntervalAndGreysNaN) {
  EXPECT_EQ(colour_map(-3.0), colour_map(0.0));
  EXPECT_EQ(colour_map(7.0), colour_map(1.0));
  EXPECT_EQ(colour_map(std::numeric_limits<double>::infinity()), colour_map(1.0));
  EXPECT_EQ(colour_map(kNaN), Eigen::Vector3d::Constant(0.5));
}

TEST(ColourMap, MiddleIsViridisMiddle) {
  // Entries 127 and 128 of the 256-entry table: (0.128729, 0.563265, 0.551229) and
  // (0.127568, 0.566949, 0.550556); the knots lie 17 entries apart, so allow a little.
  EXPECT_TRUE(colour_map(0.5).isApprox(Eigen::Vector3d(0.128149, 0.565107, 0.550893), 0.01))
      << colour_map(0.5).transpose();
}

TEST(ColourMap, LuminanceRisesAlongTheMap) {
  double previous = -1.0;
  for (int i = 0; i <= 1000; ++i) {
    const Eigen::Vector3d c = colour_map(i / 1000.0);
    ASSERT_TRUE((c.array() >= 0.0).all() && (c.array() <= 1.0).all()) << "t = " << i / 1000.0;
    const double y = luminance(c);
    ASSERT_GT(y, previous) << "t = " << i / 1000.0;
    previous = y;
  }
}

TEST(ColourMap, SvgColourRoundsAndClamps) {
  EXPECT_EQ(svg_colour(Eigen::Vector3d(0, 0, 0)), "#000000");
  EXPECT_EQ(svg_colour(Eigen::Vector3d(1, 1, 1)), "#ffffff");
  EXPECT_EQ(svg_colour(Eigen::Vector3d(-0.5, 2.0, 0.5)), "#00ff80");
  EXPECT_EQ(svg_colour(Eigen::Vector3d(kNaN, 0.0627, 1.0 / 255.0)), "#001001");
}

TEST(ColourScale, EndsAtANiceNumberAtOrAboveTheMaximum) {
  const auto top = [](double max) { return colour_scale_for(values({0.5 * max, max})).max_lux; };
  EXPECT_EQ(top(437.0), 500.0);
  EXPECT_EQ(top(0.9), 1.0);
  EXPECT_EQ(top(1.0), 1.0);
  EXPECT_EQ(top(1.2), 2.0);
  EXPECT_EQ(top(2.1), 2.5);
  EXPECT_EQ(top(2.5), 2.5);
  EXPECT_EQ(top(3.0), 4.0);
  EXPECT_EQ(top(4.5), 5.0);
  EXPECT_EQ(top(621.0), 800.0);
  EXPECT_EQ(top(6.0), 6.0);
  EXPECT_EQ(top(8.5), 10.0);
  EXPECT_EQ(top(250.0), 250.0);
  EXPECT_EQ(top(1000.0), 1000.0);
  EXPECT_EQ(top(1001.0), 2000.0);
  EXPECT_EQ(top(500.0 * (1.0 + 1e-12)), 500.0);  // rounding noise does not double the scale
  EXPECT_EQ(top(0.03), 0.04);
  EXPECT_EQ(top(0.0021), 0.0025);
  EXPECT_EQ(top(12345.0), 20000.0);
  EXPECT_EQ(colour_scale_for(values({437.0})).min_lux, 0.0);
}

TEST(ColourScale, IgnoresNaNAndInfinity) {
  const ColourScale s = colour_scale_for(values({kNaN, 120.0, std::numeric_limits<double>::infinity(), 80.0, kNaN}));
  EXPECT_EQ(s.min_lux, 0.0);
  EXPECT_EQ(s.max_lux, 200.0);
}

TEST(ColourScale, NothingToSpanGivesTheUnitRange) {
  for (const Eigen::VectorXd& lux : {Eigen::VectorXd(), values({kNaN, kNaN}), values({0.0, 0.0}), values({-5.0})}) {
    const ColourScale s = colour_scale_for(lux);
    EXPECT_EQ(s.min_lux, 0.0);
    EXPECT_EQ(s.max_lux, 1.0);
    EXPECT_EQ(s.fraction(0.0), 0.0);
  }
}

TEST(ColourScale, FractionClampsKeepsNaNAndSurvivesDegenerateScales) {
  const ColourScale s{0.0, 500.0};
  EXPECT_EQ(s.fraction(250.0), 0.5);
  EXPECT_EQ(s.fraction(500.0), 1.0);
  EXPECT_EQ(s.fraction(900.0), 1.0);
  EXPECT_EQ(s.fraction(-10.0), 0.0);
  EXPECT_TRUE(std::isnan(s.fraction(kNaN)));
  EXPECT_EQ((ColourScale{100.0, 300.0}).fraction(150.0), 0.25);
  EXPECT_EQ((ColourScale{5.0, 5.0}).fraction(7.0), 0.0);
  EXPECT_EQ((ColourScale{5.0, 1.0}).fraction(3.0), 0.0);
  EXPECT_EQ((ColourScale{0.0, kNaN}).fraction(3.0), 0.0);
}

// A scene's scale: a hot patch (a housing under a panel) does not stretch it; the
// quantile is by weight (area), NaN and zero-weight entries count for nothing.
TEST(ColourScale, AQuantileByAreaLeavesAHotPatchOutOfTheScale) {
  Eigen::VectorXd lux(101), area = Eigen::VectorXd::Ones(101);
  for (int i = 0; i < 100; ++i) lux[i] = i + 1.0;  // 1 .. 100 lx
  lux[100] = 14700.0;
  area[100] = 0.001;
  EXPECT_EQ(colour_scale_for(lux).max_lux, 20000.0) << "the largest entry: the hot patch";
  EXPECT_EQ(colour_scale_for(lux, area, 0.99).max_lux, 100.0);
  EXPECT_EQ(colour_scale_for(lux, area, 0.49).max_lux, 50.0) << "49 of 100.001 m2 lie at or below 49 lx";
  area[100] = 1000.0;  // a hot patch that is most of the area is what the scene shows
  EXPECT_EQ(colour_scale_for(lux, area, 0.99).max_lux, 20000.0);
  lux[5] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(colour_scale_for(Eigen::VectorXd::Constant(3, std::numeric_limits<double>::quiet_NaN()),
                             Eigen::VectorXd::Ones(3), 0.99).max_lux, 1.0);
}

}  // namespace
}  // namespace ilp
