#include "optimizer/layout_search.h"

#include "core/base/setting.h"
#include <nlopt.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <numeric>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/base/error.h"
#include "optimizer/goal_metrics.h"
#include "optimizer/regular_layout.h"

namespace ilp {
namespace {

constexpr double kPenaltyWeight = 10.0;
// A constraint counts as met up to this relative violation (round-off of the closed-form scale).
constexpr double kConstraintTolerance = 1e-4;
// closest_to_target: an average goal within this of its target counts as met.
constexpr double kTargetTolerance = 0.05;

using Clock = std::chrono::steady_clock;

std::vector<int> goal_areas(const LightingModel& model, const SearchSpec& spec) {
  std::vector<int> out;
  for (const GoalSpec& g : spec.goals) {
    const int a = find_goal_area(model, g.name, metric_rule(g.metric).area);
    if (a < 0) throw std::invalid_argument("goal '" + g.name + "' (" + std::string(metric_rule(g.metric).name) +
                                           ") is not in the lighting model");
    out.push_back(a);
  }
  return out;
}

double area_average(const GoalArea& area, const Eigen::VectorXd& lux) {
  double sum = 0.0;
  for (std::size_t r = 0; r < area.rows.size(); ++r) sum += area.area_weights[static_cast<Eigen::Index>(r)] * lux[area.rows[r]];
  return sum;
}

std::vector<GoalJudgement> judge_goals(const LightingModel& model, const SearchSpec& spec, const std::vector<int>& areas,
                                       const GoalLight& light);

// One search variable layout: how a point x of the search space becomes positions
// and relative fluxes.
class LayoutCoding {
 public:
  LayoutCoding(const LightingModel& model, const SearchSpec& spec, int luminaires) : family_(spec.layout.family), n_(luminaires) {
    const SearchLuminaire& s = spec.luminaire;
    const LayoutSpec& layout = spec.layout;
    lo_ = model.grid.lower_m();
    hi_ = model.grid.upper_m();
    if (family_ == LayoutFamily::free) {
      // One output for all (a product) or a fixed package: positions only; else a
      // relative flux each (a zero-width flux range would stall NLopt's local stage).
      const bool own_flux = !s.uniform_output && s.flux_min_lm < s.flux_max_lm;
      per_luminaire_ = own_flux ? 3 : 2;
      const double w_lo = s.flux_max_lm > 0.0 ? s.flux_min_lm / s.flux_max_lm : 0.0;
      for (int j = 0; j < n_; ++j) {
        lower_.insert(lower_.end(), {lo_.x(), lo_.y(), w_lo});
        upper_.insert(upper_.end(), {hi_.x(), hi_.y(), 1.0});
        if (!own_flux) {
          lower_.pop_back();
          upper_.pop_back();
        }
      }
      // Start: spread evenly over the surface in a near-square arrangement.
      const Eigen::Vector2d extent = hi_ - lo_ + Eigen::Vector2d::Constant(1e-9);
      int columns = std::clamp(static_cast<int>(std::lround(std::sqrt(n_ * extent.x() / extent.y()))), 1, n_);
      const int rows = (n_ + columns - 1) / columns;
      for (int j = 0; j < n_; ++j) {
        const int c = j % columns, r = j / columns;
        const int in_row = std::min(columns, n_ - r * columns);
        initial_.insert(initial_.end(), {lo_.x() + (c + 0.5) / in_row * (hi_.x() - lo_.x()),
                                         lo_.y() + (r + 0.5) / rows * (hi_.y() - lo_.y()), 1.0});
        if (!own_flux) initial_.pop_back();
      }
      return;
    }
    // Array: per axis an offset (first centre) and a spacing, each fixed or searched.
    const Eigen::Vector2d surface_min = lo_ - s.type.half_footprint_m(s.rotation_deg, s.tilt_deg);
    const int counts[2] = {layout.array_columns, layout.array_rows};
    for (int axis = 0; axis < 2; ++axis) {
      Axis& a = axes_[axis];
      a.count = counts[axis];
      a.lo = lo_[axis];
      a.hi = hi_[axis];
      if (layout.array_offset_m) a.offset = surface_min[axis] + (*layout.array_offset_m)[axis];
      if (layout.array_spacing_m) a.spacing = (*layout.array_spacing_m)[axis];
      const double tolerance = 1e-9 * (1.0 + std::abs(a.hi));
      if (a.offset && (*a.offset < a.lo - tolerance || *a.offset > a.hi + tolerance))
        throw ConfigError(located(layout.loc, setting_name(Setting::array_offset) + ": the first luminaire would not lie wholly on '" +
                                                    layout.mounting_surface + "'"));
      const double reach = a.spacing ? *a.spacing * (a.count - 1) : 0.0;
      if (a.offset && a.spacing && *a.offset + reach > a.hi + tolerance)
        throw ConfigError(located(layout.loc, setting_name(Setting::array) + ": the array does not fit on '" + layout.mounting_surface + "'"));
      if (a.spacing && !a.offset && a.lo + reach > a.hi + tolerance)
        throw ConfigError(located(layout.loc, setting_name(Setting::array_spacing) + ": the array is wider than '" +
                                                    layout.mounting_surface + "'"));
      const double even = (a.hi - a.lo) / a.count;
      if (!a.offset) {
        a.offset_var = static_cast<int>(lower_.size());
        lower_.push_back(a.lo);
        upper_.push_back(a.spacing ? a.hi - reach : a.hi);
        initial_.push_back(std::min(upper_.back(), a.lo + 0.5 * even));
      }
      if (!a.spacing && a.count > 1) {
        a.spread_var = static_cast<int>(lower_.size());
        lower_.push_back(0.0);
        upper_.push_back(1.0);
        const double first = a.offset ? *a.offset : initial_[static_cast<std::size_t>(a.offset_var)];
        initial_.push_back(a.hi > first ? std::clamp(even * (a.count - 1) / (a.hi - first), 0.0, 1.0) : 0.0);
      }
    }
  }

  int dimension() const { return static_cast<int>(lower_.size()); }
  const std::vector<double>& lower() const { return lower_; }
  const std::vector<double>& upper() const { return upper_; }
  const std::vector<double>& initial() const { return initial_; }

  void decode(const double* x, std::vector<Eigen::Vector2d>& xy, std::vector<double>& w) const {
    xy.resize(static_cast<std::size_t>(n_));
    w.resize(static_cast<std::size_t>(n_));
    if (family_ == LayoutFamily::free) {
      const int k = per_luminaire_;
      for (int j = 0; j < n_; ++j) {
        xy[static_cast<std::size_t>(j)] = Eigen::Vector2d(x[k * j], x[k * j + 1]);
        w[static_cast<std::size_t>(j)] = k == 3 ? x[k * j + 2] : 1.0;
      }
      return;
    }
    double first[2], step[2];
    for (int axis = 0; axis < 2; ++axis) {
      const Axis& a = axes_[axis];
      first[axis] = a.offset ? *a.offset : x[a.offset_var];
      step[axis] = a.spacing ? *a.spacing
                   : a.count > 1 ? x[a.spread_var] * std::max(0.0, a.hi - first[axis]) / (a.count - 1)
                                 : 0.0;
    }
    int j = 0;
    for (int r = 0; r < axes_[1].count; ++r)
      for (int c = 0; c < axes_[0].count; ++c, ++j) {
        xy[static_cast<std::size_t>(j)] = Eigen::Vector2d(first[0] + c * step[0], first[1] + r * step[1]);
        w[static_cast<std::size_t>(j)] = 1.0;  // one flux for the whole array
      }
  }

 private:
  struct Axis {
    int count = 1;
    double lo = 0.0, hi = 0.0;
    std::optional<double> offset, spacing;
    int offset_var = -1, spread_var = -1;  // spacing = spread * (hi - offset) / (count - 1)
  };
  LayoutFamily family_;
  int n_ = 0;
  int per_luminaire_ = 3;  // free layout: variables per luminaire (x, y and, unless uniform, w)
  Eigen::Vector2d lo_, hi_;
  Axis axes_[2];
  std::vector<double> lower_, upper_, initial_;
};

// How far two outlines of one footprint (extent_m: the rotated outline's box) overlap
// with centres delta apart, as a share of the footprint (0 apart on both axes: 1), or
// 0 when they do not: outlines of a layout never overlap, whatever min_distance_m says.
double outline_overlap(const Eigen::Vector2d& delta, const Eigen::Vector2d& extent_m) {
  const Eigen::Vector2d gap = delta.cwiseAbs();
  if (!(gap.x() < extent_m.x() && gap.y() < extent_m.y())) return 0.0;
  return std::min((extent_m.x() - gap.x()) / extent_m.x(), (extent_m.y() - gap.y()) / extent_m.y());
}

class Evaluator {
 public:
  Evaluator(const LightingModel& model, const SearchSpec& spec)
      : model_(model),
        spec_(spec),
        areas_(goal_areas(model, spec)),
        candidates_(model.candidate_lux_per_lm.cast<float>()),
        arena_(std::make_unique<tbb::task_arena>(arena_threads(spec.options.threads))),
        column_weight_(static_cast<std::size_t>(candidates_.cols())),
        column_used_(static_cast<std::size_t>(candidates_.cols())) {
    // The indirect light at each observer's eye (T minus D at its row), per candidate and fixed.
    const auto n_obs = static_cast<Eigen::Index>(model.observer_rows.size());
    eye_indirect_.resize(n_obs, model.candidate_lux_per_lm.cols());
    fixed_eye_indirect_.resize(n_obs);
    for (Eigen::Index o = 0; o < n_obs; ++o) {
      const Eigen::Index r = model.observer_rows[static_cast<std::size_t>(o)];
      eye_indirect_.row(o) = model.candidate_lux_per_lm.row(r) - model.candidate_direct_lux_per_lm.row(r);
      fixed_eye_indirect_[o] = model.fixed_lux[r] - model.fixed_direct_lux[r];
    }
  }

  // The light of the luminaires at xy with relative fluxes w at scale 1 (at the goal
  // rows, without the fixed sources): out.luminaires get their blends and positions,
  // terms_ the blended candidate columns.
  Eigen::VectorXd blend(const std::vector<Eigen::Vector2d>& xy, const std::vector<double>& w, LayoutEvaluation& out) const {
    const std::size_t n = xy.size();
    out.luminaires.resize(n);
    // Each candidate column's weight, summed over the luminaires whose blends share it:
    // neighbouring luminaires blend the same columns, so there are at most as many
    // terms as candidates, whatever the count. In column order, a fixed order.
    std::vector<double>& column_weight = column_weight_;
    std::fill(column_weight.begin(), column_weight.end(), 0.0);
    std::vector<char>& used = column_used_;
    std::fill(used.begin(), used.end(), 0);
    for (std::size_t j = 0; j < n; ++j) {
      PlacedLuminaire& lum = out.luminaires[j];
      lum.blend = model_.grid.locate(xy[j]);
      lum.position_m = lum.blend.position_m;
      for (int k = 0; k < GridPoint::kMaxCandidates; ++k) {
        const int c = lum.blend.candidates[k];
        if (c < 0) continue;
        column_weight[static_cast<std::size_t>(c)] += w[j] * lum.blend.weights[k];
        used[static_cast<std::size_t>(c)] = 1;
      }
    }
    std::vector<std::pair<Eigen::Index, double>>& terms = terms_;  // (candidate column, weight)
    terms.clear();
    for (std::size_t c = 0; c < column_weight.size(); ++c)
      if (used[c]) terms.emplace_back(static_cast<Eigen::Index>(c), column_weight[c]);
    // a = sum of weight x column. Blocks of rows in parallel; each row adds its terms in
    // the same order whatever the threads, so the result is bit for bit the same.
    const Eigen::Index rows = candidates_.rows();
    Eigen::VectorXf a_float = Eigen::VectorXf::Zero(rows);
    auto accumulate = [&](Eigen::Index begin, Eigen::Index end) {
      for (const auto& [column, weight] : terms)
        a_float.segment(begin, end - begin).noalias() +=
            static_cast<float>(weight) * candidates_.col(column).segment(begin, end - begin);
    };
    if (rows < 2 * kRowBlock) {
      accumulate(0, rows);
    } else {
      arena_->execute([&] {
        tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, rows, kRowBlock),
                          [&](const tbb::blocked_range<Eigen::Index>& r) { accumulate(r.begin(), r.end()); });
      });
    }
    // Catmull-Rom weights can be negative: at a sharp shadow edge the blend may dip below 0.
    return a_float.cast<double>().cwiseMax(0.0);
  }

  // A fixed arrangement's light at 1 lm per luminaire (ArrangementLight).
  ArrangementLight unit_light(const std::vector<Eigen::Vector2d>& xy) const {
    LayoutEvaluation placed;
    ArrangementLight out;
    out.lux_per_lm = blend(xy, std::vector<double>(xy.size(), 1.0), placed);
    out.luminaires = std::move(placed.luminaires);
    for (PlacedLuminaire& l : out.luminaires) l.flux_lm = 1.0;
    const auto n_obs = static_cast<Eigen::Index>(model_.observers.size());
    out.eye_indirect_per_lm = Eigen::VectorXd::Zero(n_obs);
    out.glare_per_lm2 = Eigen::VectorXd::Zero(n_obs);
    if (n_obs == 0) return out;
    for (const auto& [column, weight] : terms_) out.eye_indirect_per_lm += weight * eye_indirect_.col(column);
    out.eye_indirect_per_lm = out.eye_indirect_per_lm.cwiseMax(0.0);
    for (const PlacedLuminaire& l : out.luminaires)
      for (int k = 0; k < GridPoint::kMaxCandidates; ++k)
        if (l.blend.candidates[k] >= 0)
          out.glare_per_lm2 += l.blend.weights[k] * model_.candidate_glare_per_lm2.col(l.blend.candidates[k]);
    out.glare_per_lm2 = out.glare_per_lm2.cwiseMax(0.0);
    return out;
  }

  LayoutEvaluation operator()(const std::vector<Eigen::Vector2d>& xy, const std::vector<double>& w) const {
    LayoutEvaluation out;
    const Eigen::VectorXd a = blend(xy, w, out);
    judge_light(a, w, out);
    return out;
  }

  // The same with the luminaires' own direct light at the goal points (exact_point_direct,
  // lux at relative fluxes w, one per goal point) in place of the blend of the candidates'
  // direct columns; out.direct_correction_lux holds the difference at the chosen scale.
  LayoutEvaluation with_point_direct(const std::vector<Eigen::Vector2d>& xy, const std::vector<double>& w,
                                     const Eigen::VectorXd& exact_point_direct) const {
    LayoutEvaluation out;
    Eigen::VectorXd a = blend(xy, w, out);
    const Eigen::Index Q = exact_point_direct.size();
    Eigen::VectorXd blended_direct = Eigen::VectorXd::Zero(Q);
    for (const auto& [column, weight] : terms_)
      blended_direct += weight * model_.candidate_direct_lux_per_lm.col(column).tail(Q);
    Eigen::VectorXd unit_correction = Eigen::VectorXd::Zero(a.size());
    unit_correction.tail(Q) = exact_point_direct - blended_direct.cwiseMax(0.0);
    a = (a + unit_correction).cwiseMax(0.0);
    judge_light(a, w, out);
    out.direct_correction_lux = unit_correction * out.flux_scale;
    return out;
  }

 private:
  // Sets the flux scale for the light a at relative fluxes w, judges the goals and
  // constraints there, and the objective.
  void judge_light(const Eigen::VectorXd& a, const std::vector<double>& w, LayoutEvaluation& out) const {
    const SearchLuminaire& s = spec_.luminaire;
    const std::size_t n = w.size();
    const Eigen::VectorXd& f = model_.fixed_lux;
    const double w_max = n ? *std::max_element(w.begin(), w.end()) : 0.0;
    const double w_min = n ? *std::min_element(w.begin(), w.end()) : 0.0;
    double scale_hi = w_max > 0.0 ? s.flux_max_lm / w_max : 0.0;
    const double w_sum = std::accumulate(w.begin(), w.end(), 0.0);
    const double max_power_w = spec_.layout.max_power_w;
    // closest_to_target: the fit is held to the power cap (power is linear in the scale).
    if (!objective_rule(spec_.objective).minimises_power && std::isfinite(max_power_w) && w_sum > 0.0)
      scale_hi = std::min(scale_hi, max_power_w * s.efficacy_lm_per_w / w_sum);
    const double scale_lo = w_min > 0.0 ? std::min(scale_hi, s.flux_min_lm / w_min) : 0.0;
    double scale = 0.0;
    if (objective_rule(spec_.objective).minimises_power) {
      for (std::size_t g = 0; g < spec_.goals.size(); ++g) {
        const GoalSpec& goal = spec_.goals[g];
        const GoalArea& area = model_.areas[static_cast<std::size_t>(areas_[g])];
        if (metric_rule(goal.metric).scale_closed_form)
          scale = std::max(scale, least_flux_scale(goal.metric, area, f, a, goal.target));
      }
    } else {
      double num = 0.0, den = 0.0;
      for (std::size_t g = 0; g < spec_.goals.size(); ++g) {
        const GoalSpec& goal = spec_.goals[g];
        if (goal.metric != GoalMetric::average) continue;
        const GoalArea& area = model_.areas[static_cast<std::size_t>(areas_[g])];
        const double target = goal.target;
        const double t2 = target * target, gain = area_average(area, a);
        num += (target - area_average(area, f)) * gain / t2;
        den += gain * gain / t2;
      }
      scale = den > 0.0 ? std::max(0.0, num / den) : scale_hi;
    }
    scale = std::clamp(scale, scale_lo, scale_hi);

    out.flux_scale = scale;
    out.lux = f + scale * a;
    glare_at_eyes(out, terms_, scale, w);
    out.goals = judge_goals(model_, spec_, areas_, {out.lux, out.eye_indirect_lux, out.glare});
    for (std::size_t j = 0; j < n; ++j) {
      out.luminaires[j].flux_lm = scale * w[j];
      out.luminaires[j].power_w = out.luminaires[j].flux_lm / s.efficacy_lm_per_w;
      out.power_w += out.luminaires[j].power_w;
    }
    const double d_min = spec_.layout.min_distance_m;
    const Eigen::Vector2d extent_m = 2.0 * s.type.half_footprint_m(s.rotation_deg, s.tilt_deg);
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t k = j + 1; k < n; ++k) {
        const Eigen::Vector2d delta = (out.luminaires[j].position_m - out.luminaires[k].position_m).head<2>();
        const double d = delta.norm();
        if (d < d_min) out.distance_violation += (d_min - d) / d_min;
        out.distance_violation += outline_overlap(delta, extent_m);  // whatever min_distance_m says
      }
    double penalty = out.distance_violation, deviation = 0.0;
    out.feasible = out.distance_violation <= kConstraintTolerance;
    // Over the power cap: infeasible, by the relative excess (min_power keeps the scale
    // the goals want, so the closest layout shows what the goals cost).
    if (std::isfinite(max_power_w) && out.power_w > max_power_w) {
      const double excess = (out.power_w - max_power_w) / std::max(max_power_w, 1e-300);
      penalty += excess;
      out.feasible = out.feasible && excess <= kConstraintTolerance;
    }
    for (const GoalJudgement& g : out.goals) {
      if (is_target_goal(spec_.objective, g.metric)) {
        deviation += g.violation * g.violation;
        continue;
      }
      penalty += g.violation;
      out.feasible = out.feasible && g.violation <= kConstraintTolerance;
    }
    const double reference_power_w = std::max(1e-300, static_cast<double>(n) * s.flux_max_lm / s.efficacy_lm_per_w);
    out.objective = (objective_rule(spec_.objective).minimises_power ? out.power_w / reference_power_w : deviation) +
                    kPenaltyWeight * penalty;
  }

  // By value: binding tbb::task_arena::automatic to make_unique's reference would need
  // its address, which the shared TBB library does not give a position-independent binary.
  static int arena_threads(int threads) {
    const int automatic = tbb::task_arena::automatic;
    return threads > 0 ? threads : automatic;
  }
  // Per observer: the indirect illuminance at the eye (the blended columns, linear in
  // the flux) and the glare terms (each luminaire's flux squared times the blend of its
  // candidates' terms per lm^2). Nothing without observers.
  void glare_at_eyes(LayoutEvaluation& out, const std::vector<std::pair<Eigen::Index, double>>& terms, double scale,
                     const std::vector<double>& w) const {
    if (model_.observers.empty()) return;
    out.eye_indirect_lux = fixed_eye_indirect_;
    for (const auto& [column, weight] : terms) out.eye_indirect_lux += (scale * weight) * eye_indirect_.col(column);
    out.eye_indirect_lux = out.eye_indirect_lux.cwiseMax(0.0);
    out.glare = model_.fixed_glare;
    for (std::size_t j = 0; j < out.luminaires.size(); ++j) {
      const GridPoint& blend = out.luminaires[j].blend;
      const double flux2 = scale * w[j] * scale * w[j];
      for (int k = 0; k < GridPoint::kMaxCandidates; ++k)
        if (blend.candidates[k] >= 0)
          out.glare += (flux2 * blend.weights[k]) * model_.candidate_glare_per_lm2.col(blend.candidates[k]);
    }
    out.glare = out.glare.cwiseMax(0.0);  // Catmull-Rom weights can be negative
  }
  // Rows per parallel block: large enough that a block's work outweighs scheduling it.
  static constexpr Eigen::Index kRowBlock = 512;
  Eigen::MatrixXd eye_indirect_;        // observers x candidates: indirect lux per lm at the eye
  Eigen::VectorXd fixed_eye_indirect_;  // per observer, from the fixed sources
  const LightingModel& model_;
  const SearchSpec spec_;  // a copy: an evaluator may outlive the spec it was made from
  std::vector<int> areas_;
  // T's candidate columns in single precision: the blend streams them through memory
  // once per evaluation, and float halves the bytes. A lux value is good to about
  // 1e-6 of itself, far below the operator's own error.
  Eigen::MatrixXf candidates_;
  std::unique_ptr<tbb::task_arena> arena_;
  // Scratch of one evaluation, kept to spare an allocation each (an Evaluator is used
  // by one search at a time).
  mutable std::vector<double> column_weight_;
  mutable std::vector<char> column_used_;
  mutable std::vector<std::pair<Eigen::Index, double>> terms_;
};

std::string stop_reason(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS: return "converged";
    case nlopt::STOPVAL_REACHED: return "stop value reached";
    case nlopt::FTOL_REACHED: return "objective tolerance reached";
    case nlopt::XTOL_REACHED: return "step tolerance reached";
    case nlopt::MAXEVAL_REACHED: return "evaluation budget used";
    case nlopt::MAXTIME_REACHED: return "time budget used";
    default: return "stopped (" + std::to_string(static_cast<int>(r)) + ")";
  }
}

// Is a better than b (possibly with another luminaire count)? Feasible first; then
// power (min_power) or the objective; infeasible ones by the objective, which their
// penalty dominates.
bool better(const LayoutEvaluation& a, const LayoutEvaluation& b, Objective objective) {
  if (a.feasible != b.feasible) return a.feasible;
  if (a.feasible && objective_rule(objective).minimises_power) return a.power_w < b.power_w;
  return a.objective < b.objective;
}

struct Stage {
  std::string stop;
  bool time_limited = false;
};

// Catmull-Rom blends can overshoot the best candidate column a little; 1.25 leaves a
// wide margin, so that no count that could reach a target is skipped.
constexpr double kBlendOvershootMargin = 1.25;

// The least total flux (lm) that can bring every average goal up to its target: over
// the average goals still short with the fixed light alone, the shortfall over what
// one lumen adds to the goal's average at the best candidate (times the blend's
// margin). 0 when no average goal is short; infinite when one is short and no
// candidate lights it.
double least_total_flux_lm(const LightingModel& model, const SearchSpec& spec) {
  double flux_lm = 0.0;
  for (const GoalSpec& goal : spec.goals) {
    if (goal.metric != GoalMetric::average) continue;
    const int a = find_goal_area(model, goal.name);
    if (a < 0) continue;
    const GoalArea& area = model.areas[static_cast<std::size_t>(a)];
    const double deficit = goal.target - area_average(area, model.fixed_lux);
    if (!(deficit > 0.0)) continue;
    double best_gain = 0.0;
    for (Eigen::Index c = 0; c < model.candidate_lux_per_lm.cols(); ++c)
      best_gain = std::max(best_gain, area_average(area, model.candidate_lux_per_lm.col(c)));
    const double gain = kBlendOvershootMargin * best_gain;
    flux_lm = std::max(flux_lm, gain > 0.0 ? deficit / gain : std::numeric_limits<double>::infinity());
  }
  return flux_lm;
}

// What the search knows of n luminaires before searching them: can they reach every
// average target at full output, and the least electric power they can draw doing so
// (each at least its minimum output, together at least least_total_flux_lm).
struct CountBound {
  bool reaches_averages = true;
  double least_power_w = 0.0;
};

CountBound count_bound(const SearchLuminaire& s, int n, double least_flux_lm) {
  const double most_flux_lm = n * s.flux_max_lm;
  return {most_flux_lm >= least_flux_lm, std::max(n * s.flux_min_lm, least_flux_lm) / s.efficacy_lm_per_w};
}

std::vector<int> searched_counts(const LayoutSpec& layout) {
  std::vector<int> counts;
  if (layout.family == LayoutFamily::array) {
    counts.push_back(layout.array_rows * layout.array_columns);
  } else {
    for (int n = layout.count_min; n <= layout.count_max; ++n) counts.push_back(n);
  }
  if (counts.empty()) throw std::invalid_argument("no luminaire count is allowed by " + setting_name(Setting::count) + " and " +
                                                    setting_name(Setting::max_luminaires));
  return counts;
}

std::string watts(double w) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1) << w << " W";
  return out.str();
}

// The earlier round's attempt at n luminaires, if it searched that count.
const CountAttempt* easier_attempt(const SearchBounds& bounds, int n) {
  for (const CountAttempt& a : bounds.easier)
    if (a.luminaires == n) return &a;
  return nullptr;
}

// The counts in the order they are searched: for min_power, those an earlier round
// found feasible, least power first (the likeliest best, whose power then bounds the
// rest), then the others; else, and among the others, from the fewest luminaires up.
std::vector<int> search_order(const std::vector<int>& counts, const SearchBounds& bounds, Objective objective) {
  if (!objective_rule(objective).minimises_power) return counts;
  auto earlier_power_w = [&](int n) {
    const CountAttempt* a = easier_attempt(bounds, n);
    return a && a->feasible ? a->power_w : kNoPowerToBeat;
  };
  std::vector<int> order = counts;
  std::ranges::stable_sort(order, [&](int a, int b) { return earlier_power_w(a) < earlier_power_w(b); });
  return order;
}

// Why n luminaires are not searched (min_power), or empty: to_beat is the least power
// of a layout already found with every goal met (here or given).
std::string skip_reason(int n, const std::vector<int>& counts, const CountBound& bound, const SearchBounds& bounds,
                        double to_beat) {
  // A count whose luminaires, all at full output where each lights the goal best,
  // cannot reach an average target is not searched (the largest count always is,
  // unless a power to beat is given) ...
  const bool may_skip = n != counts.back() || bounds.power_to_beat_w < kNoPowerToBeat;
  if (!bound.reaches_averages && may_skip) return "not searched: cannot reach an average target at full output";
  const CountAttempt* easier = easier_attempt(bounds, n);
  if (easier && !easier->feasible && may_skip)
    return "not searched: infeasible as searched at the easier targets of an earlier round";
  // ... nor one that cannot draw less than a layout already found, nor one that drew
  // no less at the easier targets of an earlier round.
  if (to_beat < kNoPowerToBeat && bound.least_power_w >= to_beat)  // (inf >= inf: nothing to beat yet)
    return "not searched: needs at least " + watts(bound.least_power_w) + ", no less than the " + watts(to_beat) +
           " of a layout already found";
  if (easier && easier->feasible && easier->power_w >= to_beat)
    return "not searched: drew " + watts(easier->power_w) + " at the easier targets of an earlier round, no less than the " +
           watts(to_beat) + " of a layout already found";
  return {};
}

}  // namespace

double goal_tolerance(Objective objective, GoalMetric metric) {
  return is_target_goal(objective, metric) ? kTargetTolerance
                                                                                         : kConstraintTolerance;
}

std::vector<GoalJudgement> judge_goals(const LightingModel& model, const SearchSpec& spec, const GoalLight& light) {
  return judge_goals(model, spec, goal_areas(model, spec), light);
}

std::vector<GoalJudgement> judge_goals(const LightingModel& model, const SearchSpec& spec, const Eigen::VectorXd& lux) {
  const Eigen::VectorXd none;
  return judge_goals(model, spec, goal_areas(model, spec), {lux, none, none});
}

namespace {

std::vector<GoalJudgement> judge_goals(const LightingModel& model, const SearchSpec& spec, const std::vector<int>& areas,
                                       const GoalLight& light) {
  std::vector<GoalJudgement> out;
  for (std::size_t g = 0; g < spec.goals.size(); ++g) {
    const GoalSpec& goal = spec.goals[g];
    const GoalArea& area = model.areas[static_cast<std::size_t>(areas[g])];
    const double target = goal.target;  // initial, as the values are
    GoalJudgement j{goal.name, goal.metric, target, 0.0, 0.0};
    if (goal.metric == GoalMetric::ugr && light.glare.size() != static_cast<Eigen::Index>(model.observers.size()))
      throw std::logic_error("judge_goals: goal '" + goal.name + "' rates glare, and no glare terms were given");
    j.value = goal_value(goal.metric, area, light);
    j.violation = relative_violation(goal.metric, j.value, target, objective_rule(spec.objective).averages_are_targets);
    out.push_back(j);
  }
  return out;
}

}  // namespace

struct LayoutEvaluator::Impl {
  Evaluator evaluate;
};

LayoutEvaluator::LayoutEvaluator(const LightingModel& model, const SearchSpec& spec) {
  impl_ = std::make_unique<Impl>(Impl{Evaluator(model, spec)});
}

LayoutEvaluator::~LayoutEvaluator() = default;

LayoutEvaluation LayoutEvaluator::operator()(const std::vector<Eigen::Vector2d>& xy_m,
                                             const std::vector<double>& relative_flux) const {
  if (xy_m.size() != relative_flux.size()) throw std::invalid_argument("evaluate_layout: one flux per position");
  return impl_->evaluate(xy_m, relative_flux);
}

LayoutEvaluation evaluate_layout(const LightingModel& model, const SearchSpec& spec,
                                 const std::vector<Eigen::Vector2d>& xy_m, const std::vector<double>& relative_flux) {
  return LayoutEvaluator(model, spec)(xy_m, relative_flux);
}

double least_layout_power_w(const LightingModel& model, const SearchSpec& spec) {
  const double least_flux_lm = least_total_flux_lm(model, spec);
  double least = kNoPowerToBeat;
  for (const int n : searched_counts(spec.layout)) {
    const CountBound bound = count_bound(spec.luminaire, n, least_flux_lm);
    if (bound.reaches_averages) least = std::min(least, bound.least_power_w);
  }
  return least;
}

namespace {

struct CountSearch {
  CountAttempt record;
  LayoutEvaluation found;
  bool time_limited = false;
};

// NLopt's global stage, then its local stage from the best point, over the layouts of
// n luminaires; every evaluation counts, so the best point is kept even when NLopt
// stops on an exception or returns a point it did not evaluate last.
CountSearch search_count(const LightingModel& model, const SearchSpec& spec, const Evaluator& evaluate, int n,
                         std::optional<Clock::time_point> deadline, const ProgressCallback& progress) {
  const SearchOptions& opt = spec.options;
  const LayoutCoding coding(model, spec, n);
  const auto start = Clock::now();
  std::vector<Eigen::Vector2d> xy;
  std::vector<double> w;
  std::vector<double> best_x = coding.initial();
  double best_f = std::numeric_limits<double>::infinity();
  int evaluations = 0;
  auto objective = [&](const double* x) {
    coding.decode(x, xy, w);
    const double f = evaluate(xy, w).objective;
    ++evaluations;
    if (f < best_f) {
      best_f = f;
      best_x.assign(x, x + coding.dimension());
    }
    if (progress && evaluations % 256 == 0)
      progress("search " + std::to_string(n) + " luminaires", static_cast<std::size_t>(evaluations),
               static_cast<std::size_t>(opt.max_evaluations + opt.local_max_evaluations));
    return f;
  };
  CountSearch out;
  out.record.luminaires = n;
  if (coding.dimension() == 0) {
    objective(nullptr);
    out.record.global_stop = out.record.local_stop = "nothing to search (layout fixed)";
  } else {
    auto run_stage = [&](const std::string& algorithm, int budget, bool local) -> Stage {
      if (algorithm == "none") return {"skipped", false};
      // Without a deadline (the default) only the evaluation budget ends a stage.
      const double remaining =
          deadline ? std::chrono::duration<double>(*deadline - Clock::now()).count() : 0.0;
      if (deadline && remaining <= 0.0) return {"no time left", true};
      nlopt::opt stage(algorithm.c_str(), static_cast<unsigned>(coding.dimension()));
      stage.set_lower_bounds(coding.lower());
      stage.set_upper_bounds(coding.upper());
      auto trampoline = [](unsigned, const double* x, double*, void* data) {
        return (*static_cast<decltype(objective)*>(data))(x);
      };
      stage.set_min_objective(trampoline, &objective);
      stage.set_maxeval(budget);
      if (deadline) stage.set_maxtime(remaining);
      if (local) {
        stage.set_xtol_rel(1e-7);
        stage.set_ftol_rel(1e-10);
        std::vector<double> step(static_cast<std::size_t>(coding.dimension()));
        for (std::size_t i = 0; i < step.size(); ++i) step[i] = 0.05 * (coding.upper()[i] - coding.lower()[i]);
        stage.set_initial_step(step);
      }
      std::vector<double> x = best_x;
      double f = 0.0;
      try {
        const nlopt::result r = stage.optimize(x, f);
        return {stop_reason(r), r == nlopt::MAXTIME_REACHED};
      } catch (const nlopt::roundoff_limited&) {
        return {"round-off limited", false};
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("optimizer: NLopt rejected " + algorithm + ": " + e.what());
      }
    };
    // NLopt's stochastic algorithms draw from one global generator: seeding it
    // before each stage makes the layout a function of the seed alone.
    nlopt::srand(opt.seed * 1000003ull + static_cast<unsigned long>(n));
    objective(coding.initial().data());
    const Stage global = run_stage(opt.global_algorithm, opt.max_evaluations, false);
    nlopt::srand(opt.seed * 1000003ull + static_cast<unsigned long>(n) + 7919ull);
    const Stage local = run_stage(opt.local_algorithm, opt.local_max_evaluations, true);
    out.record.global_stop = global.stop;
    out.record.local_stop = local.stop;
    out.time_limited = global.time_limited || local.time_limited;
  }
  coding.decode(best_x.data(), xy, w);
  if (spec.layout.ceiling_module_m > 0.0)  // the module's cell centres (the grid's nodes)
    for (Eigen::Vector2d& p : xy) p = model.grid.nearest_candidate_m(p);
  out.found = evaluate(xy, w);
  out.record.evaluations = evaluations;
  out.record.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  out.record.feasible = out.found.feasible;
  out.record.power_w = out.found.power_w;
  out.record.objective = out.found.objective;
  return out;
}

// What a regular layout is laid in: the mounting zone within the mounting surface's
// extent, the luminaire's outline as placed, the ceiling module's lattice.
ArrangementFrame arrangement_frame(const LightingModel& model, const SearchSpec& spec) {
  ArrangementFrame frame;
  frame.zone_m = model.zone_m.isEmpty() ? model.grid.surface_box_m() : model.zone_m.intersection(model.grid.surface_box_m());
  frame.luminaire_extent_m = 2.0 * spec.luminaire.type.half_footprint_m(spec.luminaire.rotation_deg, spec.luminaire.tilt_deg);
  frame.module_m = spec.layout.ceiling_module_m;
  frame.module_origin_m = model.grid.lower_m();
  return frame;
}

std::string metres(const Eigen::Vector2d& xy) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << "(" << xy.x() << ", " << xy.y() << ") m";
  return out.str();
}

// Why an arrangement cannot be built (its first member without a legal mounting
// point within the tolerance), or empty.
std::string unmountable_member(const LightingModel& model, const LayoutSpec& layout, const Arrangement& a) {
  for (const Eigen::Vector2d& xy : a.xy_m) {
    const double d = model.grid.mount_distance_m(xy);
    if (d <= layout.regular.position_tolerance_m) continue;
    std::ostringstream out;
    out << std::fixed << std::setprecision(2) << "infeasible: the member at " << metres(xy)
        << " has no mounting point on '" << layout.mounting_surface << "' within " << layout.regular.position_tolerance_m
        << " m (the nearest is " << d << " m away)";
    return out.str();
  }
  return {};
}

// Why an arrangement cannot be built as it stands: two members closer than
// layout.min_distance_m, or whose outlines (the luminaire's footprint in plan at its
// rotation and tilt) overlap by more than 1 mm; empty when none are.
std::string crowded_members(const SearchSpec& spec, const Arrangement& a) {
  const Eigen::Vector2d half = spec.luminaire.type.half_footprint_m(spec.luminaire.rotation_deg, spec.luminaire.tilt_deg);
  constexpr double kTouchM = 1e-3;  // outlines end to end (continuous rows) touch, they do not overlap
  for (std::size_t i = 0; i < a.xy_m.size(); ++i)
    for (std::size_t j = i + 1; j < a.xy_m.size(); ++j) {
      const Eigen::Vector2d d = (a.xy_m[i] - a.xy_m[j]).cwiseAbs();
      std::ostringstream out;
      out << std::fixed << std::setprecision(2);
      if (d.norm() < spec.layout.min_distance_m - kTouchM) {
        out << "infeasible: the members at " << metres(a.xy_m[i]) << " and " << metres(a.xy_m[j]) << " are " << d.norm()
            << " m apart, closer than " << setting_name(Setting::min_distance) << " = " << spec.layout.min_distance_m << " m";
        return out.str();
      }
      if (d.x() < 2.0 * half.x() - kTouchM && d.y() < 2.0 * half.y() - kTouchM) {
        out << "infeasible: the members at " << metres(a.xy_m[i]) << " and " << metres(a.xy_m[j])
            << " overlap (outlines " << 2.0 * half.x() << " x " << 2.0 * half.y() << " m in plan)";
        return out.str();
      }
    }
  return {};
}

// The regular layout's arrangements in the mounting zone; a layout too wide to enumerate
// or with none in its count range is refused at luminaires.layout.
std::vector<Arrangement> layout_arrangements(const LightingModel& model, const SearchSpec& spec) {
  std::vector<Arrangement> arrangements;
  try {
    arrangements = regular_arrangements(spec.layout, arrangement_frame(model, spec));
  } catch (const std::length_error& e) {
    throw ConfigError(located(spec.layout.loc, setting_name(Setting::layout) + ": " + e.what()));
  }
  if (arrangements.empty())
    throw ConfigError(located(spec.layout.loc, setting_name(Setting::layout) + ": no arrangement of this layout has a luminaire count in [" + std::to_string(spec.layout.count_min) + ", " +
                                               std::to_string(spec.layout.count_max) + "] in the mounting zone"));
  return arrangements;
}

// min_power with a power to beat: a best layout that draws no less, or misses a goal, as
// predicted is not worth verifying (SearchResult::beaten_note).
void beaten_by_power(const SearchSpec& spec, const SearchBounds& bounds, SearchResult& result) {
  if (result.beaten || !objective_rule(spec.objective).minimises_power || !std::isfinite(bounds.power_to_beat_w)) return;
  const LayoutEvaluation& best = result.best;
  if (best.feasible && best.power_w < bounds.power_to_beat_w) return;
  result.beaten = true;
  result.beaten_note = best.feasible ? "its best layout as predicted draws " + watts(best.power_w) +
                                           ", no less than the " + watts(bounds.power_to_beat_w) + " already found"
                                     : "no layout meets every goal as predicted, and " + watts(bounds.power_to_beat_w) +
                                           " were already found";
}

// Regular searches check at most this many of their best arrangements against the
// luminaires' own direct light at the goal points.
constexpr int kMaxDirectChecks = 64;

// The best arrangements as predicted, best first, re-judged with the luminaires' own
// direct light at the goal points until one meets its goals and is at least as good as
// the next one's prediction. Returns the checked best (feasible if any check was).
LayoutEvaluation check_direct_light(const Evaluator& evaluate, const std::vector<Arrangement>& arrangements,
                                    std::vector<std::pair<LayoutEvaluation, std::size_t>> feasible,
                                    const SearchSpec& spec, const PointDirectLight& point_direct, SearchResult& result) {
  std::ranges::stable_sort(feasible, [&](const auto& a, const auto& b) { return better(a.first, b.first, spec.objective); });
  std::optional<LayoutEvaluation> checked;
  std::string first_missed;
  for (std::size_t k = 0; k < feasible.size() && result.direct_checks < kMaxDirectChecks; ++k) {
    if (checked && checked->feasible && !better(feasible[k].first, *checked, spec.objective)) break;
    const Arrangement& a = arrangements[feasible[k].second];
    const std::vector<double> unit(a.xy_m.size(), 1.0);
    std::vector<PlacedLuminaire> placed = feasible[k].first.luminaires;
    for (PlacedLuminaire& l : placed) l.flux_lm = 1.0;
    LayoutEvaluation c = evaluate.with_point_direct(a.xy_m, unit, point_direct(placed));
    c.arrangement = a.label;
    c.spacing_m = a.spacing_m;
    ++result.direct_checks;
    if (!c.feasible && first_missed.empty()) {
      for (const GoalJudgement& g : c.goals)
        if (!is_target_goal(spec.objective, g.metric) && g.violation > kConstraintTolerance) {
          std::ostringstream line;
          line << a.label << ": " << g.name << " " << to_string(g.metric) << " " << std::setprecision(4) << g.value
               << " with the luminaires' own direct light (predicted "
               << feasible[k].first.goals[static_cast<std::size_t>(&g - c.goals.data())].value << ")";
          first_missed = line.str();
          break;
        }
    }
    if (!checked || better(c, *checked, spec.objective)) checked = std::move(c);
  }
  result.direct_check_note = first_missed;
  return std::move(*checked);
}

// Field, rows and bays: every arrangement judged at its one output (no NLopt: nothing
// moves). Min_power skips an arrangement that cannot draw less than a layout already found.
SearchResult search_regular(const LightingModel& model, const SearchSpec& spec, const ProgressCallback& progress,
                            const SearchBounds& bounds, const PointDirectLight& point_direct) {
  const auto start = Clock::now();
  const std::vector<Arrangement> arrangements = layout_arrangements(model, spec);
  const Evaluator evaluate(model, spec);
  const double least_flux_lm = least_total_flux_lm(model, spec);
  const bool min_power = objective_rule(spec.objective).minimises_power;
  SearchResult result;
  std::optional<LayoutEvaluation> best;
  std::vector<std::pair<LayoutEvaluation, std::size_t>> feasible;  // with their arrangement, for the direct check
  std::string first_refusal;
  bool skipped_for_power = false;
  const std::string phase = "search " + std::to_string(arrangements.size()) + " arrangements";
  for (std::size_t i = 0; i < arrangements.size(); ++i) {
    const Arrangement& a = arrangements[i];
    const int n = static_cast<int>(a.xy_m.size());
    CountAttempt attempt;
    attempt.luminaires = n;
    attempt.arrangement = a.label;
    const double to_beat = std::min(bounds.power_to_beat_w, best && best->feasible ? best->power_w : kNoPowerToBeat);
    const double least_w = count_bound(spec.luminaire, n, least_flux_lm).least_power_w;
    std::string stop = unmountable_member(model, spec.layout, a);
    if (stop.empty()) stop = crowded_members(spec, a);
    if (stop.empty() && min_power && least_w >= to_beat) {
      stop = "not searched: needs at least " + watts(least_w) + ", no less than the " + watts(to_beat) +
             " of a layout already found";
      skipped_for_power = true;
    } else if (first_refusal.empty() && !stop.empty()) {
      first_refusal = a.label + ": " + stop;
    }
    if (stop.empty()) {
      LayoutEvaluation e = evaluate(a.xy_m, std::vector<double>(a.xy_m.size(), 1.0));
      e.arrangement = a.label;
      e.spacing_m = a.spacing_m;
      attempt.evaluations = 1;
      attempt.feasible = e.feasible;
      attempt.power_w = e.power_w;
      attempt.objective = e.objective;
      stop = "evaluated (the arrangement is fixed)";
      ++result.evaluations;
      if (e.feasible && point_direct) {  // kept without its light vectors: the check recomputes them
        LayoutEvaluation kept = e;
        kept.lux.resize(0);
        kept.eye_indirect_lux.resize(0);
        kept.glare.resize(0);
        feasible.emplace_back(std::move(kept), i);
      }
      if (!best || better(e, *best, spec.objective)) best = std::move(e);
    }
    attempt.global_stop = attempt.local_stop = stop;
    result.attempts.push_back(attempt);
    // One phase for the whole list (a phase per arrangement printed a line each: 1,668
    // lines for the classroom's fields).
    if (progress) progress(phase, i + 1, arrangements.size());
  }
  if (!feasible.empty() && !model.goal_points.empty())
    best = check_direct_light(evaluate, arrangements, std::move(feasible), spec, point_direct, result);
  if (!best && !skipped_for_power) result.refused = "no arrangement can be mounted or built; " + first_refusal;
  result.beaten = !best;
  if (best) result.best = std::move(*best);
  beaten_by_power(spec, bounds, result);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace

SearchResult search_layout(const LightingModel& model, const SearchSpec& spec, const ProgressCallback& progress,
                           const SearchBounds& bounds, const PointDirectLight& point_direct) {
  if (spec.layout.family != LayoutFamily::free && spec.layout.family != LayoutFamily::array)
    return search_regular(model, spec, progress, bounds, point_direct);
  const auto start = Clock::now();
  const std::optional<Clock::time_point> deadline =
      spec.options.max_seconds > 0.0
          ? std::optional(start + std::chrono::duration_cast<Clock::duration>(
                                      std::chrono::duration<double>(spec.options.max_seconds)))
          : std::nullopt;
  const std::vector<int> counts = searched_counts(spec.layout);
  const Evaluator evaluate(model, spec);
  const double least_flux_lm = least_total_flux_lm(model, spec);
  SearchResult result;
  std::optional<LayoutEvaluation> best;
  for (const int n : search_order(counts, bounds, spec.objective)) {
    const double to_beat = std::min(bounds.power_to_beat_w, best && best->feasible ? best->power_w : kNoPowerToBeat);
    const std::string skip = objective_rule(spec.objective).minimises_power
                                 ? skip_reason(n, counts, count_bound(spec.luminaire, n, least_flux_lm), bounds, to_beat)
                                 : std::string();
    if (!skip.empty()) {
      CountAttempt skipped;
      skipped.luminaires = n;
      skipped.global_stop = skipped.local_stop = skip;
      result.attempts.push_back(skipped);
      continue;
    }
    CountSearch searched = search_count(model, spec, evaluate, n, deadline, progress);
    result.attempts.push_back(searched.record);
    result.evaluations += searched.record.evaluations;
    result.time_limited = result.time_limited || searched.time_limited;
    if (!best || better(searched.found, *best, spec.objective)) best = std::move(searched.found);
  }
  std::ranges::stable_sort(result.attempts, {}, &CountAttempt::luminaires);
  result.beaten = !best;
  if (best) result.best = std::move(*best);
  beaten_by_power(spec, bounds, result);
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

RegularLights regular_arrangement_lights(const LightingModel& model, const SearchSpec& spec) {
  if (spec.layout.family == LayoutFamily::free || spec.layout.family == LayoutFamily::array)
    throw std::invalid_argument("regular_arrangement_lights: free and array layouts have no fixed arrangements");
  const std::vector<Arrangement> arrangements = layout_arrangements(model, spec);
  const Evaluator evaluate(model, spec);
  RegularLights out;
  for (const Arrangement& a : arrangements) {
    std::string stop = unmountable_member(model, spec.layout, a);
    if (stop.empty()) stop = crowded_members(spec, a);
    if (!stop.empty()) {
      if (out.refused++ == 0) out.first_refusal = a.label + ": " + stop;
      continue;
    }
    ArrangementLight light = evaluate.unit_light(a.xy_m);
    light.label = a.label;
    light.spacing_m = a.spacing_m;
    out.arrangements.push_back(std::move(light));
  }
  return out;
}

}  // namespace ilp
