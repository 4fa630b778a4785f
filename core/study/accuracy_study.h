// What accuracy costs in time (issue 3): the sample-based operator built for a range
// of sample sizes, rays per row, strategies and seeds, each measured against one
// exact reference solved with more rays and an independent ray seed, next to the
// error predicted from eta pilot samples without the reference. `ilp accuracy`
// prints, plots and saves it; docs/accuracy.md records the office study.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "core/transport/direct_light.h"
#include "core/exact/exact_solver.h"
#include "core/base/progress.h"
#include "core/operator/sample_error.h"
#include "core/operator/sample_operator.h"
#include "core/scene/scene.h"

namespace ilp {

struct AccuracyStudyOptions {
  std::vector<double> sample_fractions{0.01, 0.02, 0.05, 0.10, 0.25, 1.0};  // of the reflecting patches;
                                                                            // those giving the same k run once
  int seeds = 3;                                 // samples per size (the census needs one)
  std::vector<int> rays_per_row{256};
  std::vector<SampleStrategy> strategies{SampleStrategy::stratified};
  std::vector<IndirectMethod> methods{IndirectMethod::exact_second_bounce};
  int reference_rays = 1024;                     // rays per patch of the exact reference
  std::uint64_t reference_seed = 1'000'003;      // independent of the operator's rays
  int error_samples = 4;                         // eta, for the predicted error
  double pilot_fraction = 0.02;                  // k0 of the prediction, of the reflecting patches
  int evaluation_repeats = 2000;                 // T phi products timed per measurement
  SampleOperatorOptions base;                    // ray seed, threads, direct-light settings
};

// A calculation grid's points measured with the goal patches (rows after them in T).
struct AccuracyGrid {
  std::string name;
  std::vector<ReceiverPoint> points;
};

// Relative error of total illuminance at points, each point weighted equally:
// RMS and maximum of |value - reference| / reference over points whose reference is > 0.
struct PointError {
  double rms_relative_total = 0.0;
  double max_relative_total = 0.0;
};
PointError compare_point_illuminance(const Eigen::VectorXd& total_lux, const Eigen::VectorXd& reference_total_lux);

struct AccuracyRow {
  SampleStrategy strategy = SampleStrategy::stratified;
  IndirectMethod method = IndirectMethod::sample_gather;
  double sample_fraction = 0.0;     // k / reflecting patches
  int sample_size = 0;              // k requested
  std::size_t sample_patches = 0;   // distinct patches drawn
  int rays_per_row = 0;
  std::uint64_t sample_seed = 0;
  double build_seconds = 0.0;       // goal rows + sample rows + direct + solve + T
  double evaluation_microseconds = 0.0;  // one T phi, median
  IlluminanceError error;           // over the goal patches (NaN without goal patches)
  std::vector<PointError> grids;    // per AccuracyGrid, in order
  double predicted_rms_error_total = 0.0;
  std::size_t goal_fallback_rows = 0;
  double condition_estimate = 0.0;
};

struct StudyPrediction {
  SampleStrategy strategy = SampleStrategy::stratified;
  IndirectMethod method = IndirectMethod::exact_second_bounce;
  int rays_per_row = 0;
  ErrorPrediction prediction;
};

struct AccuracyStudy {
  std::size_t patches = 0, population = 0, goal_patches = 0, goal_points = 0;
  std::vector<std::string> grids;             // the grids' names, as AccuracyRow::grids
  ExactSolveSummary reference;
  std::vector<StudyPrediction> predictions;   // one per (strategy, method, rays)
  std::vector<AccuracyRow> rows;
};

// Light sources: every luminaire and emitting surface at its configured flux.
AccuracyStudy run_accuracy_study(const Scene& scene, std::span<const int> goal_patches,
                                 const AccuracyStudyOptions& options, const ProgressCallback& progress = {});
// The same with calculation grids: the reference at their points is each point's gather
// over the reference radiosity with reference_rays rays and its direct light
// (exact_point_illuminance, as `ilp run`'s verification), the operator's the rows
// after the goal patches. Goal patches may then be empty.
AccuracyStudy run_accuracy_study(const Scene& scene, std::span<const int> goal_patches,
                                 std::span<const AccuracyGrid> grids, const AccuracyStudyOptions& options,
                                 const ProgressCallback& progress = {});

// Median time of one T phi product, microseconds.
double time_evaluation_microseconds(const SampleOperator& op, const Eigen::VectorXd& flux_lm, int repeats);

}  // namespace ilp
