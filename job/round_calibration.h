// Between verification rounds: a goal met as predicted but missed as verified is
// searched for again with its target moved by how far the prediction overshot the
// verified value (a defect correction; job/job_runner.h runs the rounds).
#pragma once

#include <optional>
#include <string>

#include "job/plan.h"

namespace ilp {

// The next search's target (in the job's terms: maintained lux, or the U0 ratio) for a
// goal whose job target is real_target, searched this round for current_target, and
// judged `predicted` through the operator and `verified` by the verification solve:
// real_target x predicted / verified, just past it (0.2 %), never easier than
// current_target, and a uniformity no higher than 1. std::nullopt when the target
// stays as it is, or the values give no ratio (one of them 0).
std::optional<double> next_search_target(GoalMetric metric, double real_target, double current_target,
                                         double predicted, double verified);

// The run log's line for it, e.g. "round 2: floor minimum predicted 137.2 lx, verified
// 106.3 lx (initial, for 125 lx); the next search aims at 129.4 lx for 100 lx": lux
// values are initial and targets maintained, so the initial target is given where a
// maintenance factor makes them differ. `round` counts from 0.
std::string calibration_line(int round, double maintenance_factor, const GoalLine& goal, double predicted,
                             double verified, double next_target);

}  // namespace ilp
