// Marching squares against closed forms: circles of r^2, straight lines of a ramp,
// missing nodes, saddles and the input checks.
#include "output/contours.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace ilp {
namespace {

using V2 = Eigen::Vector2d;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// nx x ny nodes at `spacing` from `origin`, valued f(x, y).
template <class F>
LatticeField sampled(int nx, int ny, V2 origin, double spacing, F f) {
  LatticeField field{nx, ny, origin, V2::Constant(spacing), {}};
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) field.values.push_back(f(field.node_m(i, j)));
  return field;
}

TEST(Contours, RadialSquareFieldGivesClosedCirclesAtTheLevelsRadius) {
  // r^2 interpolated linearly along an edge of length h overshoots by at most h^2/4
  // (the chord's sagitta of a parabola of curvature 2), so a point lies within
  // h^2 / (8 R) of radius R (first order in the level error over dr^2/dr = 2R).
  const double h = 0.1;
  const LatticeField field = sampled(61, 61, V2(-3.0, -3.0), h, [](const V2& p) { return p.squaredNorm(); });
  for (double radius : {0.5, 1.0, 2.2}) {
    const std::vector<ContourLine> lines = contour_lines(field, radius * radius);
    ASSERT_EQ(lines.size(), 1u) << "radius " << radius;
    const ContourLine& line = lines.front();
    EXPECT_TRUE(line.closed);
    EXPECT_DOUBLE_EQ(line.level, radius * radius);
    const double tolerance = h * h / (8.0 * radius) + 1e-12;
    double length = 0.0;
    for (std::size_t k = 0; k < line.points_m.size(); ++k) {
      const V2& p = line.points_m[k];
      EXPECT_NEAR(p.norm(), radius, tolerance) << "radius " << radius << " point " << k;
      EXPECT_LE(p.norm(), radius + 1e-12) << "a chord of r^2 overshoots, so points lie on or inside the circle";
      length += (line.points_m[(k + 1) % line.points_m.size()] - p).norm();
    }
    // The polygon's perimeter is a little under the circle's (inscribed).
    EXPECT_NEAR(length, 2.0 * M_PI * radius, 0.02 * 2.0 * M_PI * radius) << "radius " << radius;
    EXPECT_LT(length, 2.0 * M_PI * radius);
  }
}

TEST(Contours, LinearRampGivesAStraightOpenLineAtTheRightX) {
  // v = 3 x + 1 (lux): the level 7.3 lies at x = 2.1, exactly, on every row.
  const LatticeField field = sampled(11, 7, V2(0.0, 0.0), 0.5, [](const V2& p) { return 3.0 * p.x() + 1.0; });
  const std::vector<ContourLine> lines = contour_lines(field, 7.3);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_FALSE(lines[0].closed);
  ASSERT_EQ(lines[0].points_m.size(), 7u);  // one point per row of nodes
  for (const V2& p : lines[0].points_m) EXPECT_NEAR(p.x(), 2.1, 1e-12);
  // From one edge of the lattice to the other, in order.
  const double y0 = lines[0].points_m.front().y(), y1 = lines[0].points_m.back().y();
  EXPECT_NEAR(std::min(y0, y1), 0.0, 1e-12);
  EXPECT_NEAR(std::max(y0, y1), 3.0, 1e-12);
  for (std::size_t k = 1; k < lines[0].points_m.size(); ++k)
    EXPECT_NEAR(std::abs(lines[0].points_m[k].y() - lines[0].points_m[k - 1].y()), 0.5, 1e-12);
}

TEST(Contours, DiagonalRampsLineHasTheRightSlope) {
  // v = x + 2 y: the level 3 is the line x + 2 y = 3.
  const LatticeField field = sampled(9, 9, V2(-1.0, -1.0), 0.37, [](const V2& p) { return p.x() + 2.0 * p.y(); });
  const std::vector<ContourLine> lines = contour_lines(field, 3.0);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_GE(lines[0].points_m.size(), 5u);
  for (const V2& p : lines[0].points_m) EXPECT_NEAR(p.x() + 2.0 * p.y(), 3.0, 1e-12);
}

TEST(Contours, LevelOutsideTheRangeGivesNoLine) {
  const LatticeField field = sampled(5, 5, V2(0.0, 0.0), 1.0, [](const V2& p) { return p.x(); });
  EXPECT_TRUE(contour_lines(field, -1.0).empty());
  EXPECT_TRUE(contour_lines(field, 4.5).empty());
}

TEST(Contours, NoLinePassesThroughASquareWithAMissingNode) {
  // A ramp in x with one missing node in the middle: the line at x = 2.25 is cut where
  // the four squares round node (2, 3)... the node at x = 2 sits left of the line, so the two
  // squares right of it (those spanning x 2..2.5) lose their segment.
  LatticeField field = sampled(9, 7, V2(0.0, 0.0), 0.5, [](const V2& p) { return p.x(); });
  const int i = 4, j = 3;  // x = 2.0, y = 1.5
  field.values[j * field.nx + i] = kNaN;
  const std::vector<ContourLine> lines = contour_lines(field, 2.25);
  ASSERT_EQ(lines.size(), 2u);
  for (const ContourLine& line : lines) {
    EXPECT_FALSE(line.closed);
    for (const V2& p : line.points_m) {
      EXPECT_NEAR(p.x(), 2.25, 1e-12);
      // Rows 2 and 4 (y = 1.0, 2.0) are still crossed, but not the row of the missing node
      // (y = 1.5): the segments either side of it are gone.
      EXPECT_GT(std::abs(p.y() - 1.5), 0.49);
    }
  }
  // Every node's value NaN: nothing.
  std::fill(field.values.begin(), field.values.end(), kNaN);
  EXPECT_TRUE(contour_lines(field, 2.25).empty());
}

TEST(Contours, SaddleIsResolvedByTheCentreValue) {
  // One square, diagonal corners high: corner values 1 (lower left), 0, 1 (upper right), 0.
  LatticeField field{2, 2, V2(0.0, 0.0), V2(1.0, 1.0), {1.0, 0.0, 0.0, 1.0}};
  field.values = {1.0, 0.0, 0.0, 1.0};  // (0,0)=1 (1,0)=0 (0,1)=0 (1,1)=1
  // Centre mean 0.5. Level 0.4: the centre is above, so the high corners join through
  // it and the two lines cut off the low corners (1,0) and (0,1).
  {
    const std::vector<ContourLine> lines = contour_lines(field, 0.4);
    ASSERT_EQ(lines.size(), 2u);
    for (const ContourLine& line : lines) {
      ASSERT_EQ(line.points_m.size(), 2u);
      const V2 mid = 0.5 * (line.points_m[0] + line.points_m[1]);
      // Around (1, 0) or (0, 1): the midpoint is nearer that low corner than the high ones.
      const double to_low = std::min((mid - V2(1, 0)).norm(), (mid - V2(0, 1)).norm());
      const double to_high = std::min((mid - V2(0, 0)).norm(), (mid - V2(1, 1)).norm());
      EXPECT_LT(to_low, to_high);
    }
  }
  // Level 0.6: the centre is below, so the lines cut off the high corners instead.
  {
    const std::vector<ContourLine> lines = contour_lines(field, 0.6);
    ASSERT_EQ(lines.size(), 2u);
    for (const ContourLine& line : lines) {
      const V2 mid = 0.5 * (line.points_m[0] + line.points_m[1]);
      const double to_low = std::min((mid - V2(1, 0)).norm(), (mid - V2(0, 1)).norm());
      const double to_high = std::min((mid - V2(0, 0)).norm(), (mid - V2(1, 1)).norm());
      EXPECT_GT(to_low, to_high);
    }
  }
}

TEST(Contours, SaddleChoiceIsConsistentAcrossNeighbours) {
  // A checkerboard of 0 and 1 at level 0.4 (centres 0.5, above): the high nodes join
  // diagonally everywhere, so every low interior node is ringed by one closed loop
  // (4 edge points) and no line ends inside the lattice.
  const int n = 6;
  LatticeField field{n, n, V2::Zero(), V2::Ones(), {}};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) field.values.push_back((i + j) % 2 == 0 ? 1.0 : 0.0);
  const std::vector<ContourLine> lines = contour_lines(field, 0.4);
  int closed = 0;
  for (const ContourLine& line : lines) {
    if (line.closed) {
      ++closed;
      EXPECT_EQ(line.points_m.size(), 4u);
    } else {
      // An open line starts and ends on the lattice's border.
      for (const V2& p : {line.points_m.front(), line.points_m.back()})
        EXPECT_TRUE(p.x() < 1e-12 || p.y() < 1e-12 || p.x() > n - 1 - 1e-12 || p.y() > n - 1 - 1e-12)
            << p.transpose();
    }
  }
  // Low interior nodes (i + j odd, 1 <= i, j <= 4): 8 of the 16.
  EXPECT_EQ(closed, 8);
}

TEST(Contours, TwoHillsGiveTwoClosedLoops) {
  const LatticeField field = sampled(41, 21, V2(0.0, 0.0), 0.1, [](const V2& p) {
    return std::exp(-(p - V2(1.0, 1.0)).squaredNorm() / 0.1) + std::exp(-(p - V2(3.0, 1.0)).squaredNorm() / 0.1);
  });
  const std::vector<ContourLine> lines = contour_lines(field, 0.5);
  ASSERT_EQ(lines.size(), 2u);
  for (const ContourLine& line : lines) EXPECT_TRUE(line.closed);
}

TEST(Contours, BadInputIsRejected) {
  LatticeField field{2, 2, V2::Zero(), V2::Ones(), {1.0, 2.0, 3.0}};
  EXPECT_THROW(contour_lines(field, 1.5), std::invalid_argument);
  field.values.push_back(4.0);
  EXPECT_NO_THROW(contour_lines(field, 1.5));
  EXPECT_THROW(contour_lines(field, kNaN), std::invalid_argument);
  field.spacing_m = V2(0.0, 1.0);
  EXPECT_THROW(contour_lines(field, 1.5), std::invalid_argument);
  field.spacing_m = V2(1.0, 1.0);
  field.nx = -2;
  field.ny = -2;
  EXPECT_THROW(contour_lines(field, 1.5), std::invalid_argument);
  // An empty lattice has no lines.
  EXPECT_TRUE(contour_lines(LatticeField{0, 0, V2::Zero(), V2::Ones(), {}}, 1.0).empty());
}

}  // namespace
}  // namespace ilp
