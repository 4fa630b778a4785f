#include "optimizer/group_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "optimizer/goal_metrics.h"

namespace ilp {
namespace {

using Polygon = std::vector<Eigen::Vector2d>;

// The part of a convex polygon where c.coeff . s >= c.rhs (Sutherland-Hodgman with
// one half-plane), with a round-off slack relative to the constraint's terms.
Polygon clip(const Polygon& polygon, const OutputConstraint& c, double extent) {
  const double slack = 1e-10 * (std::abs(c.rhs) + c.coeff.cwiseAbs().sum() * extent);
  auto margin = [&](const Eigen::Vector2d& p) { return c.coeff.dot(p) - c.rhs; };
  Polygon out;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d& p = polygon[i];
    const Eigen::Vector2d& q = polygon[(i + 1) % polygon.size()];
    const double mp = margin(p), mq = margin(q);
    const bool p_in = mp + slack >= 0.0, q_in = mq + slack >= 0.0;
    if (p_in) out.push_back(p);
    if (p_in != q_in && mp != mq) out.push_back(p + std::clamp(mp / (mp - mq), 0.0, 1.0) * (q - p));  // on the line itself
  }
  return out;
}

double weighted_average(const GoalArea& area, const Eigen::VectorXd& v) {
  double sum = 0.0;
  for (std::size_t r = 0; r < area.rows.size(); ++r) sum += area.area_weights[static_cast<Eigen::Index>(r)] * v[area.rows[r]];
  return sum;
}

const GoalArea& area_of(const LightingModel& model, const GoalSpec& goal) {
  const int a = find_goal_area(model, goal.name, metric_rule(goal.metric).area);
  if (a < 0) throw std::invalid_argument("goal '" + goal.name + "' is not in the lighting model");
  return model.areas[static_cast<std::size_t>(a)];
}

// The pair's light at fluxes s, as GoalLight wants it.
struct PairLight {
  Eigen::VectorXd lux, eye_indirect_lux, glare;
};

class PairEvaluator {
 public:
  PairEvaluator(const LightingModel& model, const GroupSearchSpec& spec) : model_(model) {
    search_.goals = spec.goals;
    search_.objective = Objective::min_power;
    const auto n_obs = static_cast<Eigen::Index>(model.observer_rows.size());
    fixed_eye_.resize(n_obs);
    for (Eigen::Index o = 0; o < n_obs; ++o) {
      const Eigen::Index r = model.observer_rows[static_cast<std::size_t>(o)];
      fixed_eye_[o] = model.fixed_lux[r] - model.fixed_direct_lux[r];
    }
  }

  PairLight light(const std::vector<const GroupOption*>& pair, const Eigen::Vector2d& s) const {
    PairLight out{model_.fixed_lux, fixed_eye_, model_.fixed_glare};
    for (std::size_t g = 0; g < pair.size(); ++g) {
      const ArrangementLight& a = *pair[g]->light;
      const double flux = s[static_cast<Eigen::Index>(g)];
      out.lux += flux * a.lux_per_lm;
      if (out.glare.size() > 0) {
        out.eye_indirect_lux += flux * a.eye_indirect_per_lm;
        out.glare += flux * flux * a.glare_per_lm2;
      }
    }
    return out;
  }

  // Judged as the single-group search judges: every goal within its tolerance.
  std::vector<GoalJudgement> judge(const PairLight& l) const {
    return judge_goals(model_, search_, GoalLight{l.lux, l.eye_indirect_lux, l.glare});
  }

  static bool all_met(const std::vector<GoalJudgement>& goals) {
    return std::all_of(goals.begin(), goals.end(), [](const GoalJudgement& g) {
      return g.violation <= goal_tolerance(Objective::min_power, g.metric) + 1e-9;
    });
  }

  static double missed(const std::vector<GoalJudgement>& goals) {
    double sum = 0.0;
    for (const GoalJudgement& g : goals) sum += g.violation;
    return sum;
  }

 private:
  const LightingModel& model_;
  SearchSpec search_;
  Eigen::VectorXd fixed_eye_;
};

// A lower bound on a pair's power: each group at least its minimum output, and for each
// average goal short of its target the cheapest fluxes that close the gap on the
// average alone (a fractional knapsack: the best lux per watt first). Infinite when an
// average goal cannot be reached at full output.
double least_pair_power_w(const std::vector<const GroupOption*>& pair, const std::vector<Eigen::VectorXd>& gains,
                          const Eigen::VectorXd& deficits) {
  const std::size_t k = pair.size();
  std::vector<double> cost(k);
  double floor_w = 0.0;
  for (std::size_t g = 0; g < k; ++g) {
    cost[g] = pair[g]->count() / pair[g]->efficacy_lm_per_w;
    floor_w += cost[g] * pair[g]->flux_min_lm;
  }
  double least_w = floor_w;
  for (Eigen::Index a = 0; a < deficits.size(); ++a) {
    double short_lux = deficits[a], power_w = floor_w;
    std::vector<std::size_t> order(k);
    std::iota(order.begin(), order.end(), 0);
    auto gain = [&](std::size_t g) { return gains[g][a]; };
    for (std::size_t g = 0; g < k; ++g) short_lux -= gain(g) * pair[g]->flux_min_lm;
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return gain(x) / cost[x] > gain(y) / cost[y]; });
    for (const std::size_t g : order) {
      if (short_lux <= 0.0 || gain(g) <= 0.0) break;
      const double room_lm = pair[g]->flux_max_lm - pair[g]->flux_min_lm;
      const double take_lm = std::min(room_lm, short_lux / gain(g));
      power_w += cost[g] * take_lm;
      short_lux -= gain(g) * take_lm;
    }
    if (short_lux > 1e-9 * std::max(1.0, deficits[a])) return std::numeric_limits<double>::infinity();
    least_w = std::max(least_w, power_w);
  }
  return least_w;
}

}  // namespace

bool groups_collide(const GroupOption& a, const GroupOption& b) {
  constexpr double kTouchM = 1e-3;
  const Eigen::Vector2d reach = 0.5 * (a.extent_m + b.extent_m) - Eigen::Vector2d::Constant(kTouchM);
  for (const PlacedLuminaire& p : a.light->luminaires)
    for (const PlacedLuminaire& q : b.light->luminaires) {
      const Eigen::Vector3d d = (p.position_m - q.position_m).cwiseAbs();
      if (d.x() < reach.x() && d.y() < reach.y() && d.z() < kGroupClearanceM) return true;
    }
  return false;
}

std::optional<Eigen::Vector2d> least_cost_outputs(const std::vector<OutputConstraint>& constraints,
                                                  const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                                                  const Eigen::Vector2d& cost) {
  Polygon polygon{lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  const double extent = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  for (const OutputConstraint& c : constraints) {
    polygon = clip(polygon, c, extent);
    if (polygon.empty()) return std::nullopt;
  }
  Eigen::Vector2d best = polygon.front();
  for (const Eigen::Vector2d& p : polygon)
    if (cost.dot(p) < cost.dot(best)) best = p;
  return best.cwiseMax(lo).cwiseMin(hi);  // the slack may leave a vertex a hair outside
}

std::vector<OutputConstraint> linear_goal_constraints(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                                      const Eigen::VectorXd& fixed_lux,
                                                      const std::vector<const Eigen::VectorXd*>& unit_lux) {
  if (unit_lux.empty() || unit_lux.size() > static_cast<std::size_t>(kMaxSearchedGroups))
    throw std::invalid_argument("linear_goal_constraints: one or two groups");
  const std::size_t k = unit_lux.size();
  auto coefficients = [&](auto per_group) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (std::size_t g = 0; g < k; ++g) c[static_cast<Eigen::Index>(g)] = per_group(*unit_lux[g]);
    return c;
  };
  std::vector<OutputConstraint> out;
  for (const GoalSpec& goal : goals) {
    const GoalArea& area = area_of(model, goal);
    const double t = goal.target;
    switch (goal.metric) {
      case GoalMetric::average:
      case GoalMetric::cylindrical:
        out.push_back({coefficients([&](const Eigen::VectorXd& u) { return weighted_average(area, u); }),
                       t - weighted_average(area, fixed_lux)});
        break;
      case GoalMetric::minimum:
        for (const Eigen::Index r : area.rows)
          out.push_back({coefficients([&](const Eigen::VectorXd& u) { return u[r]; }), t - fixed_lux[r]});
        break;
      case GoalMetric::maximum:
        for (const Eigen::Index r : area.rows)
          out.push_back({coefficients([&](const Eigen::VectorXd& u) { return -u[r]; }), fixed_lux[r] - t});
        break;
      case GoalMetric::uniformity: {  // E_r >= t x average, for every row
        const Eigen::Vector2d mean = coefficients([&](const Eigen::VectorXd& u) { return weighted_average(area, u); });
        const double fixed_mean = weighted_average(area, fixed_lux);
        for (const Eigen::Index r : area.rows)
          out.push_back({coefficients([&](const Eigen::VectorXd& u) { return u[r]; }) - t * mean,
                         t * fixed_mean - fixed_lux[r]});
        break;
      }
      default:  // not linear in the fluxes: judged at the solution
        break;
    }
  }
  return out;
}

GroupSearchResult search_groups(const LightingModel& model, const GroupSearchSpec& spec,
                                const std::vector<GroupChoices>& groups) {
  const auto start = std::chrono::steady_clock::now();
  if (groups.empty() || groups.size() > static_cast<std::size_t>(kMaxSearchedGroups))
    throw std::invalid_argument("search_groups: " + std::to_string(groups.size()) + " groups (one or two are searched)");
  for (const GroupChoices& g : groups)
    if (g.options.empty()) throw std::invalid_argument("search_groups: group '" + g.name + "' has no arrangement");
  const std::size_t k = groups.size();
  // Per option its average gain on each average goal; each goal's deficit from the fixed light.
  std::vector<const GoalSpec*> averages;
  for (const GoalSpec& goal : spec.goals)
    if (goal.metric == GoalMetric::average || goal.metric == GoalMetric::cylindrical) averages.push_back(&goal);
  Eigen::VectorXd deficits(static_cast<Eigen::Index>(averages.size()));
  for (std::size_t a = 0; a < averages.size(); ++a)
    deficits[static_cast<Eigen::Index>(a)] = averages[a]->target - weighted_average(area_of(model, *averages[a]), model.fixed_lux);
  std::vector<std::vector<Eigen::VectorXd>> gains(k);
  for (std::size_t g = 0; g < k; ++g)
    for (const GroupOption& o : groups[g].options) {
      Eigen::VectorXd v(deficits.size());
      for (std::size_t a = 0; a < averages.size(); ++a)
        v[static_cast<Eigen::Index>(a)] = weighted_average(area_of(model, *averages[a]), o.light->lux_per_lm);
      gains[g].push_back(std::move(v));
    }
  // Every pair (index i of group 0, j of group 1), with its bound, least bound first.
  struct Pair {
    int i = 0, j = 0;
    double bound_w = 0.0;
  };
  std::vector<Pair> pairs;
  const int second = k == 2 ? static_cast<int>(groups[1].options.size()) : 1;
  for (int i = 0; i < static_cast<int>(groups[0].options.size()); ++i)
    for (int j = 0; j < second; ++j) {
      std::vector<const GroupOption*> pair{&groups[0].options[static_cast<std::size_t>(i)]};
      std::vector<Eigen::VectorXd> g{gains[0][static_cast<std::size_t>(i)]};
      if (k == 2) {
        pair.push_back(&groups[1].options[static_cast<std::size_t>(j)]);
        g.push_back(gains[1][static_cast<std::size_t>(j)]);
      }
      pairs.push_back({i, j, least_pair_power_w(pair, g, deficits)});
    }
  std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& a, const Pair& b) { return a.bound_w < b.bound_w; });

  const PairEvaluator evaluator(model, spec);
  GroupSearchResult best;
  best.pairs = static_cast<long>(pairs.size());
  double best_missed = std::numeric_limits<double>::infinity();
  auto keep = [&](const std::vector<const GroupOption*>& pair, const Pair& p, const Eigen::Vector2d& s,
                  PairLight&& light, std::vector<GoalJudgement>&& goals, bool feasible) {
    best.feasible = feasible;
    best.groups.clear();
    best.power_w = 0.0;
    for (std::size_t g = 0; g < k; ++g) {
      const double flux = s[static_cast<Eigen::Index>(g)];
      const double power_w = flux * pair[g]->count() / pair[g]->efficacy_lm_per_w;
      best.groups.push_back({g == 0 ? p.i : p.j, flux, power_w});
      best.power_w += power_w;
    }
    best.goals = std::move(goals);
    best.lux = std::move(light.lux);
    best.eye_indirect_lux = std::move(light.eye_indirect_lux);
    best.glare = std::move(light.glare);
  };
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    const Pair& p = pairs[n];
    if (best.feasible && p.bound_w >= best.power_w) {
      best.pruned = static_cast<long>(pairs.size() - n);
      break;
    }
    std::vector<const GroupOption*> pair{&groups[0].options[static_cast<std::size_t>(p.i)]};
    if (k == 2) pair.push_back(&groups[1].options[static_cast<std::size_t>(p.j)]);
    if (k == 2 && groups_collide(*pair[0], *pair[1])) {
      ++best.colliding;
      continue;
    }
    Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Zero(), cost = Eigen::Vector2d::Zero();
    std::vector<const Eigen::VectorXd*> units;
    for (std::size_t g = 0; g < k; ++g) {
      const auto e = static_cast<Eigen::Index>(g);
      lo[e] = pair[g]->flux_min_lm;
      hi[e] = pair[g]->flux_max_lm;
      cost[e] = pair[g]->count() / pair[g]->efficacy_lm_per_w;
      units.push_back(&pair[g]->light->lux_per_lm);
    }
    std::vector<OutputConstraint> constraints = linear_goal_constraints(model, spec.goals, model.fixed_lux, units);
    if (std::isfinite(spec.max_power_w)) constraints.push_back({-cost, -spec.max_power_w});
    ++best.solved;
    const std::optional<Eigen::Vector2d> s = least_cost_outputs(constraints, lo, hi, cost);
    if (s) {
      PairLight light = evaluator.light(pair, *s);
      std::vector<GoalJudgement> goals = evaluator.judge(light);
      if (PairEvaluator::all_met(goals)) {
        if (!best.feasible || cost.dot(*s) < best.power_w) keep(pair, p, *s, std::move(light), std::move(goals), true);
        continue;
      }
    }
    if (best.feasible) continue;
    // No feasible pair yet: keep the pair that misses least at full output, to report.
    PairLight light = evaluator.light(pair, hi);
    std::vector<GoalJudgement> goals = evaluator.judge(light);
    const double missed = PairEvaluator::missed(goals);
    if (missed < best_missed) {
      best_missed = missed;
      keep(pair, p, hi, std::move(light), std::move(goals), false);
    }
  }
  best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return best;
}

}  // namespace ilp
