// Regular layouts (fields, rows, bays) against positions worked out by hand.
#include "optimizer/regular_layout.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ilp {
namespace {

ArrangementFrame room_frame(double x, double y, Eigen::Vector2d extent = Eigen::Vector2d(0.6, 0.6)) {
  ArrangementFrame f;
  f.zone_m = Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(x, y));
  f.luminaire_extent_m = extent;
  return f;
}

LayoutSpec regular(LayoutFamily family, CountRange rows, CountRange columns) {
  LayoutSpec l;
  l.family = family;
  l.count_min = 1;
  l.count_max = 1000;
  l.regular.rows = rows;
  l.regular.columns = columns;
  return l;
}

Arrangement only(const std::vector<Arrangement>& a) {
  EXPECT_EQ(a.size(), 1u);
  return a.front();
}

TEST(RegularLayout, EvenPositionsPutTheOuterOnesAnEdgeRatioOfASpacingFromTheEnds) {
  EXPECT_EQ(even_positions(0, 6, 3, 0.5), (std::vector<double>{1, 3, 5}));
  EXPECT_EQ(even_positions(0, 6, 1, 0.5), (std::vector<double>{3}));
  // s = 6 / (1 + 2 x 0.25) = 4: at 1 and 5.
  const std::vector<double> two = even_positions(0, 6, 2, 0.25);
  EXPECT_NEAR(two[0], 1.0, 1e-12);
  EXPECT_NEAR(two[1], 5.0, 1e-12);
}

TEST(RegularLayout, AFieldIsCentredWithEqualSpacingPerAxis) {
  const Arrangement a = only(regular_arrangements(regular(LayoutFamily::field, {2, 2}, {3, 3}), room_frame(6, 4)));
  EXPECT_EQ(a.label, "3 x 2 field");
  ASSERT_EQ(a.xy_m.size(), 6u);
  // Columns at 1, 3, 5 (spacing 2); rows at 1, 3 (spacing 2).
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(a.xy_m[static_cast<std::size_t>(r * 3 + c)].x(), 1.0 + 2.0 * c, 1e-12);
      EXPECT_NEAR(a.xy_m[static_cast<std::size_t>(r * 3 + c)].y(), 1.0 + 2.0 * r, 1e-12);
    }
  EXPECT_EQ(a.spacing_m, Eigen::Vector2d(2, 2));
}

TEST(RegularLayout, FieldsKeepCountsAndSpacingRatiosInRange) {
  LayoutSpec l = regular(LayoutFamily::field, {1, 4}, {1, 6});
  l.count_min = 4;
  l.count_max = 9;
  const std::vector<Arrangement> all = regular_arrangements(l, room_frame(6, 4));
  ASSERT_FALSE(all.empty());
  for (const Arrangement& a : all) {
    EXPECT_GE(a.xy_m.size(), 4u);
    EXPECT_LE(a.xy_m.size(), 9u);
  }
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_LE(all[i - 1].xy_m.size(), all[i].xy_m.size()) << "fewest first";
  // 6 x 1 in 6 x 4 m: spacings 1 and 4, a ratio of 4 > 2: left out; 3 x 2 (2 and 2) kept.
  bool six_by_one = false, three_by_two = false;
  for (const Arrangement& a : all) {
    six_by_one = six_by_one || a.label == "6 x 1 field";
    three_by_two = three_by_two || a.label == "3 x 2 field";
  }
  EXPECT_FALSE(six_by_one);
  EXPECT_TRUE(three_by_two);
}

TEST(RegularLayout, AnEdgeRatioRangeTriesEveryRatioPerAxis) {
  LayoutSpec l = regular(LayoutFamily::field, {2, 2}, {2, 2});
  l.regular.edge_ratio_min = 0.3;
  l.regular.edge_ratio_max = 0.5;
  const std::vector<Arrangement> all = regular_arrangements(l, room_frame(6, 4));
  ASSERT_EQ(all.size(), 25u) << "0.5, 0.45, 0.4, 0.35, 0.3 on each axis";
  // 0.3 on x: s = 6 / 1.6 = 3.75, the first at 1.125.
  bool found = false;
  for (const Arrangement& a : all)
    if (std::abs(a.xy_m[0].x() - 1.125) < 1e-9) found = true;
  EXPECT_TRUE(found);
}

TEST(RegularLayout, ACeilingModuleMakesWholeModulesAndCellCentres) {
  ArrangementFrame f = room_frame(6, 4);
  f.module_m = 0.6;
  f.module_origin_m = Eigen::Vector2d(0.3, 0.3);  // cell centres at 0.3 + 0.6 k
  const Arrangement a = only(regular_arrangements(regular(LayoutFamily::field, {1, 1}, {3, 3}), f));
  // Ideal 1, 3, 5: spacing 2 -> 3 modules (1.8), first 3 - 1.8 = 1.2 -> the cell centre 1.5.
  ASSERT_EQ(a.xy_m.size(), 3u);
  EXPECT_NEAR(a.xy_m[0].x(), 1.5, 1e-12);
  EXPECT_NEAR(a.xy_m[1].x(), 3.3, 1e-12);
  EXPECT_NEAR(a.xy_m[2].x(), 5.1, 1e-12);
  EXPECT_NEAR(a.xy_m[0].y(), 2.1, 1e-12) << "the single row's 2.0 on the nearest cell centre";
}

TEST(RegularLayout, RowsRunAlongTheLuminairesLengthEndToEndOrSpaced) {
  // 1.2 x 0.1 m luminaires: rows along x.
  LayoutSpec l = regular(LayoutFamily::rows, {2, 2}, {3, 3});
  l.regular.continuous = true;
  const Arrangement a = only(regular_arrangements(l, room_frame(6, 4, Eigen::Vector2d(1.2, 0.1))));
  EXPECT_EQ(a.label, "2 rows of 3 end to end along x");
  const double xs[] = {1.8, 3.0, 4.2}, ys[] = {1.0, 3.0};
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(a.xy_m[static_cast<std::size_t>(r * 3 + c)].x(), xs[c], 1e-12);
      EXPECT_NEAR(a.xy_m[static_cast<std::size_t>(r * 3 + c)].y(), ys[r], 1e-12);
    }
  // Turned (0.1 x 1.2): rows along y, luminaires at 1/6, 1/2, 5/6 of 4 m when spaced.
  l.regular.continuous = false;
  const Arrangement b = only(regular_arrangements(l, room_frame(6, 4, Eigen::Vector2d(0.1, 1.2))));
  EXPECT_EQ(b.label, "2 rows of 3 along y");
  EXPECT_NEAR(b.xy_m[0].x(), 1.5, 1e-12);
  EXPECT_NEAR(b.xy_m[1].x(), 4.5, 1e-12);
  EXPECT_NEAR(b.xy_m[0].y(), 4.0 / 6.0, 1e-12);
  EXPECT_NEAR(b.xy_m[2].y(), 2.0, 1e-12);
}

TEST(RegularLayout, BaysTakeTheirLuminairesAlongTheirLongerSide) {
  LayoutSpec l;
  l.family = LayoutFamily::bays;
  l.count_max = 1000;
  l.regular.bay_module_m = Eigen::Vector2d(3, 2);
  l.regular.bay_origin_m = Eigen::Vector2d(0, 0);
  l.regular.per_bay = {2, 2};
  // Bays [0, 3] and [3, 6] x [0, 2] and [2, 4]; a zone [0, 6] x [0, 2.8] holds the
  // centres y = 1 only (3 is outside).
  ArrangementFrame f = room_frame(6, 2.8);
  const Arrangement a = only(regular_arrangements(l, f));
  EXPECT_EQ(a.label, "2 per bay, 2 bays of 3 x 2 m");
  ASSERT_EQ(a.xy_m.size(), 4u);
  const double xs[] = {0.75, 2.25, 3.75, 5.25};
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(a.xy_m[static_cast<std::size_t>(i)].x(), xs[i], 1e-12);
    EXPECT_NEAR(a.xy_m[static_cast<std::size_t>(i)].y(), 1.0, 1e-12);
  }
}

TEST(RegularLayout, RangesTooWideToEnumerateAreRefused) {
  LayoutSpec l = regular(LayoutFamily::field, {1, 100}, {1, 100});
  l.count_max = 10000;
  l.regular.max_spacing_ratio = 100;
  l.regular.edge_ratio_min = 0.05;
  l.regular.edge_ratio_max = 1.0;
  EXPECT_THROW(regular_arrangements(l, room_frame(60, 40)), std::length_error);
}

TEST(RegularLayout, OtherFamiliesAndEmptyZonesAreRefused) {
  EXPECT_THROW(regular_arrangements(regular(LayoutFamily::free, {1, 1}, {1, 1}), room_frame(6, 4)), std::invalid_argument);
  ArrangementFrame empty;
  EXPECT_THROW(regular_arrangements(regular(LayoutFamily::field, {1, 1}, {1, 1}), empty), std::invalid_argument);
}

}  // namespace
}  // namespace ilp
