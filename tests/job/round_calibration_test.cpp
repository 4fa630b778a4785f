// The defect correction between verification rounds, against the ratios worked by hand.
#include "job/config.h"
#include "job/round_calibration.h"

#include <gtest/gtest.h>

namespace ilp {
namespace {

TEST(RoundCalibration, AMinimumOverPredictedIsAimedHigherByTheRatio) {
  // 137.2 predicted, 106.3 verified: aim at 100 x 137.2 / 106.3, 0.2 % past it.
  const auto next = next_search_target(GoalMetric::minimum, 100.0, 100.0, 137.2, 106.3);
  ASSERT_TRUE(next);
  EXPECT_NEAR(*next, 100.0 * 137.2 / 106.3 * 1.002, 1e-9);
  // A later round never eases a target an earlier one raised.
  EXPECT_FALSE(next_search_target(GoalMetric::minimum, 100.0, 135.0, 137.2, 106.3));
  const auto higher = next_search_target(GoalMetric::average, 500.0, 510.0, 560.0, 500.0);
  ASSERT_TRUE(higher);
  EXPECT_NEAR(*higher, 500.0 * 1.12 * 1.002, 1e-9);
}

TEST(RoundCalibration, AMaximumUnderPredictedIsAimedLower) {
  const auto next = next_search_target(GoalMetric::maximum, 1000.0, 1000.0, 900.0, 1100.0);
  ASSERT_TRUE(next);
  EXPECT_NEAR(*next, 1000.0 * 900.0 / 1100.0 * 0.998, 1e-9);
  EXPECT_FALSE(next_search_target(GoalMetric::maximum, 1000.0, 700.0, 900.0, 1100.0)) << "already lower";
}

TEST(RoundCalibration, UniformityStopsAtOneAndZeroValuesGiveNoRatio) {
  const auto capped = next_search_target(GoalMetric::uniformity, 0.95, 0.95, 0.99, 0.9);
  ASSERT_TRUE(capped);
  EXPECT_EQ(*capped, 1.0);
  EXPECT_FALSE(next_search_target(GoalMetric::uniformity, 0.95, 1.0, 0.99, 0.9)) << "1 already: no new round for it";
  EXPECT_FALSE(next_search_target(GoalMetric::minimum, 100.0, 100.0, 120.0, 0.0));
  EXPECT_FALSE(next_search_target(GoalMetric::minimum, 100.0, 100.0, 0.0, 80.0));
}

TEST(RoundCalibration, TheLineSaysLuxAreInitialWhereAMaintenanceFactorApplies) {
  JobConfig job;
  GoalLine floor;
  floor.name = "floor";
  floor.metric = GoalMetric::minimum;
  floor.target = 100.0;
  job.maintenance_factor = 0.8;
  const std::string line = calibration_line(1, job.maintenance_factor, floor, 137.2, 106.3, 129.4);
  EXPECT_EQ(line, "round 2: floor minimum predicted 137.2 lx, verified 106.3 lx (initial, for 125 lx); "
                  "the next search aims at 129.4 lx for 100 lx");
  job.maintenance_factor = 1.0;
  EXPECT_EQ(calibration_line(0, job.maintenance_factor, floor, 137.2, 106.3, 129.4),
            "round 1: floor minimum predicted 137.2 lx, verified 106.3 lx; the next search aims at 129.4 lx for 100 lx");
  GoalLine u0;
  u0.name = "work_plane";
  u0.metric = GoalMetric::uniformity;
  u0.target = 0.6;
  job.maintenance_factor = 0.8;
  EXPECT_EQ(calibration_line(0, job.maintenance_factor, u0, 0.6005, 0.5927, 0.609),
            "round 1: work_plane uniformity predicted 0.6005, verified 0.5927; the next search aims at 0.609 for 0.6");
}

}  // namespace
}  // namespace ilp
