#include "optimizer/group_search.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <glpk.h>

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

  PairLight light(const std::vector<const GroupOption*>& pair, const Eigen::VectorXd& s) const {
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


// cost . s as the two-group search always summed it (a Vector2d's dot): the same bits
// for one or two groups as before any number were searched.
double power_of(const Eigen::VectorXd& cost, const Eigen::VectorXd& s) {
  double sum = 0.0;
  for (Eigen::Index g = 0; g < cost.size(); ++g) sum += cost[g] * s[g];
  return sum;
}

// The least cost . s over the box cut by the constraints by GLPK's primal simplex method
// (bounded columns, one row a constraint), the solution clamped into the box.
std::optional<Eigen::VectorXd> least_cost_simplex(const std::vector<OutputConstraintN>& constraints,
                                                  const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                                  const Eigen::VectorXd& cost) {
  const int k = static_cast<int>(lo.size());
  glp_prob* lp = glp_create_prob();
  glp_set_obj_dir(lp, GLP_MIN);
  glp_add_cols(lp, k);
  for (int g = 0; g < k; ++g) {
    glp_set_col_bnds(lp, g + 1, lo[g] < hi[g] ? GLP_DB : GLP_FX, lo[g], hi[g]);
    glp_set_obj_coef(lp, g + 1, cost[g]);
  }
  std::vector<int> ia{0}, ja{0};
  std::vector<double> ar{0.0};
  if (!constraints.empty()) {
    glp_add_rows(lp, static_cast<int>(constraints.size()));
    for (std::size_t r = 0; r < constraints.size(); ++r) {
      const int row = static_cast<int>(r) + 1;
      glp_set_row_bnds(lp, row, GLP_LO, constraints[r].rhs, 0.0);
      for (int g = 0; g < k; ++g)
        if (constraints[r].coeff[g] != 0.0) {
          ia.push_back(row);
          ja.push_back(g + 1);
          ar.push_back(constraints[r].coeff[g]);
        }
    }
    glp_load_matrix(lp, static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());
  }
  glp_smcp parm;
  glp_init_smcp(&parm);
  parm.msg_lev = GLP_MSG_OFF;
  parm.presolve = GLP_ON;  // an infeasible programme then ends at once, with no basis to report
  const int rc = glp_simplex(lp, &parm);
  std::optional<Eigen::VectorXd> out;
  if (rc == 0 && glp_get_status(lp) == GLP_OPT) {
    Eigen::VectorXd s(k);
    for (int g = 0; g < k; ++g) s[g] = glp_get_col_prim(lp, g + 1);
    out = s.cwiseMax(lo).cwiseMin(hi);
  }
  glp_delete_prob(lp);
  return out;
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

namespace {

// linear_goal_constraints in the constraint type C (coefficients Vec: Vector2d for one or
// two groups, VectorXd for any number).
template <class C, class Vec>
std::vector<C> goal_constraints(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                const Eigen::VectorXd& fixed_lux, const std::vector<const Eigen::VectorXd*>& unit_lux,
                                Eigen::Index size) {
  const std::size_t k = unit_lux.size();
  auto coefficients = [&](auto per_group) {
    Vec c = Vec::Zero(size);
    for (std::size_t g = 0; g < k; ++g) c[static_cast<Eigen::Index>(g)] = per_group(*unit_lux[g]);
    return c;
  };
  std::vector<C> out;
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
        const Vec mean = coefficients([&](const Eigen::VectorXd& u) { return weighted_average(area, u); });
        const double fixed_mean = weighted_average(area, fixed_lux);
        for (const Eigen::Index r : area.rows)
          out.push_back({Vec(coefficients([&](const Eigen::VectorXd& u) { return u[r]; }) - t * mean),
                         t * fixed_mean - fixed_lux[r]});
        break;
      }
      case GoalMetric::ugr:  // not linear in the fluxes: judged at the solution
      case GoalMetric::cylindrical_uniformity:
      case GoalMetric::modelling:
        break;
    }
  }
  return out;
}

}  // namespace

std::vector<OutputConstraint> linear_goal_constraints(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                                      const Eigen::VectorXd& fixed_lux,
                                                      const std::vector<const Eigen::VectorXd*>& unit_lux) {
  if (unit_lux.empty() || unit_lux.size() > 2) throw std::invalid_argument("linear_goal_constraints: one or two groups");
  return goal_constraints<OutputConstraint, Eigen::Vector2d>(model, goals, fixed_lux, unit_lux, 2);
}

std::vector<OutputConstraintN> linear_goal_constraints_n(const LightingModel& model, const std::vector<GoalSpec>& goals,
                                                         const Eigen::VectorXd& fixed_lux,
                                                         const std::vector<const Eigen::VectorXd*>& unit_lux) {
  if (unit_lux.empty() || unit_lux.size() > static_cast<std::size_t>(kMaxSearchedGroups))
    throw std::invalid_argument("linear_goal_constraints_n: 1 to " + std::to_string(kMaxSearchedGroups) + " groups");
  return goal_constraints<OutputConstraintN, Eigen::VectorXd>(model, goals, fixed_lux, unit_lux,
                                                              static_cast<Eigen::Index>(unit_lux.size()));
}

namespace {

// A vector of one or two groups' values in the plane (zero beyond them), as the exact
// enumeration takes it.
Eigen::Vector2d in_plane(const Eigen::VectorXd& v) {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  p.head(v.size()) = v;
  return p;
}

}  // namespace

std::optional<Eigen::VectorXd> least_cost_outputs_n(const std::vector<OutputConstraintN>& constraints,
                                                    const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                                    const Eigen::VectorXd& cost) {
  const Eigen::Index k = lo.size();
  if (k <= 2) {  // the exact vertex enumeration of the plane
    std::vector<OutputConstraint> flat;
    for (const OutputConstraintN& c : constraints) flat.push_back({in_plane(c.coeff), c.rhs});
    const std::optional<Eigen::Vector2d> s = least_cost_outputs(flat, in_plane(lo), in_plane(hi), in_plane(cost));
    if (!s) return std::nullopt;
    return Eigen::VectorXd(s->head(k));
  }
  return least_cost_simplex(constraints, lo, hi, cost);
}

namespace {

// Every combination of arrangements (one per group: k indices into the groups' options,
// flat), the first group's index varying slowest, each with its lower bound on the power.
struct Combinations {
  std::size_t k = 0;
  std::vector<int> picks;      // combination c: picks[c * k .. c * k + k)
  std::vector<double> bound_w;
  int pick(std::size_t c, std::size_t g) const { return picks[c * k + g]; }
};

Combinations combinations(const std::vector<GroupChoices>& groups, const std::vector<std::vector<Eigen::VectorXd>>& gains,
                          const Eigen::VectorXd& deficits) {
  const std::size_t k = groups.size();
  double count = 1.0;
  for (const GroupChoices& g : groups) count *= static_cast<double>(g.options.size());
  if (k > 2 && count > kMaxGroupCombinations)  // (pairs are as many as two groups have)
    throw std::invalid_argument("search_groups: " + std::to_string(static_cast<long long>(count)) +
                                " combinations of arrangements (at most " +
                                std::to_string(static_cast<long long>(kMaxGroupCombinations)) + ")");
  Combinations out;
  out.k = k;
  out.picks.reserve(static_cast<std::size_t>(count) * k);
  out.bound_w.reserve(static_cast<std::size_t>(count));
  std::vector<int> at(k, 0);
  std::vector<const GroupOption*> members(k);
  std::vector<Eigen::VectorXd> g(k);
  while (true) {
    for (std::size_t i = 0; i < k; ++i) {
      members[i] = &groups[i].options[static_cast<std::size_t>(at[i])];
      g[i] = gains[i][static_cast<std::size_t>(at[i])];
    }
    out.picks.insert(out.picks.end(), at.begin(), at.end());
    out.bound_w.push_back(least_pair_power_w(members, g, deficits));
    std::size_t i = k;  // the last group's index varies fastest
    while (i > 0 && ++at[i - 1] == static_cast<int>(groups[i - 1].options.size())) at[--i] = 0;
    if (i == 0) break;
  }
  return out;
}

// The least-power outputs of one combination: the plane's exact enumeration for one or two
// groups (as before any number were searched), GLPK's simplex for more.
std::optional<Eigen::VectorXd> combination_outputs(const LightingModel& model, const GroupSearchSpec& spec,
                                                   const std::vector<const Eigen::VectorXd*>& units,
                                                   const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                                   const Eigen::VectorXd& cost) {
  const Eigen::Index k = lo.size();
  if (k > 2) {
    std::vector<OutputConstraintN> constraints = linear_goal_constraints_n(model, spec.goals, model.fixed_lux, units);
    if (std::isfinite(spec.max_power_w)) constraints.push_back({-cost, -spec.max_power_w});
    return least_cost_outputs_n(constraints, lo, hi, cost);
  }
  std::vector<OutputConstraint> constraints = linear_goal_constraints(model, spec.goals, model.fixed_lux, units);
  if (std::isfinite(spec.max_power_w)) constraints.push_back({-in_plane(cost), -spec.max_power_w});
  const std::optional<Eigen::Vector2d> s = least_cost_outputs(constraints, in_plane(lo), in_plane(hi), in_plane(cost));
  if (!s) return std::nullopt;
  return Eigen::VectorXd(s->head(k));
}

bool any_collide(const std::vector<const GroupOption*>& members) {
  for (std::size_t a = 0; a < members.size(); ++a)
    for (std::size_t b = a + 1; b < members.size(); ++b)
      if (groups_collide(*members[a], *members[b])) return true;
  return false;
}

}  // namespace

GroupSearchResult search_groups(const LightingModel& model, const GroupSearchSpec& spec,
                                const std::vector<GroupChoices>& groups) {
  const auto start = std::chrono::steady_clock::now();
  if (groups.empty() || groups.size() > static_cast<std::size_t>(kMaxSearchedGroups))
    throw std::invalid_argument("search_groups: " + std::to_string(groups.size()) + " groups (1 to " +
                                std::to_string(kMaxSearchedGroups) + " are searched)");
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
  // Every combination with its bound, least bound first.
  const Combinations all = combinations(groups, gains, deficits);
  std::vector<std::size_t> order(all.bound_w.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all.bound_w[a] < all.bound_w[b]; });

  const PairEvaluator evaluator(model, spec);
  GroupSearchResult best;
  best.pairs = static_cast<long>(order.size());
  double best_missed = std::numeric_limits<double>::infinity();
  auto keep = [&](const std::vector<const GroupOption*>& members, std::size_t c, const Eigen::VectorXd& s,
                  PairLight&& light, std::vector<GoalJudgement>&& goals, bool feasible) {
    best.feasible = feasible;
    best.groups.clear();
    best.power_w = 0.0;
    for (std::size_t g = 0; g < k; ++g) {
      const double flux = s[static_cast<Eigen::Index>(g)];
      const double power_w = flux * members[g]->count() / members[g]->efficacy_lm_per_w;
      best.groups.push_back({all.pick(c, g), flux, power_w});
      best.power_w += power_w;
    }
    best.goals = std::move(goals);
    best.lux = std::move(light.lux);
    best.eye_indirect_lux = std::move(light.eye_indirect_lux);
    best.glare = std::move(light.glare);
  };
  const auto dims = static_cast<Eigen::Index>(k);
  for (std::size_t n = 0; n < order.size(); ++n) {
    const std::size_t c = order[n];
    if (best.feasible && all.bound_w[c] >= best.power_w) {
      best.pruned = static_cast<long>(order.size() - n);
      break;
    }
    std::vector<const GroupOption*> members;
    for (std::size_t g = 0; g < k; ++g) members.push_back(&groups[g].options[static_cast<std::size_t>(all.pick(c, g))]);
    if (any_collide(members)) {
      ++best.colliding;
      continue;
    }
    Eigen::VectorXd lo(dims), hi(dims), cost(dims);
    std::vector<const Eigen::VectorXd*> units;
    for (std::size_t g = 0; g < k; ++g) {
      const auto e = static_cast<Eigen::Index>(g);
      lo[e] = members[g]->flux_min_lm;
      hi[e] = members[g]->flux_max_lm;
      cost[e] = members[g]->count() / members[g]->efficacy_lm_per_w;
      units.push_back(&members[g]->light->lux_per_lm);
    }
    ++best.solved;
    const std::optional<Eigen::VectorXd> s = combination_outputs(model, spec, units, lo, hi, cost);
    if (s) {
      PairLight light = evaluator.light(members, *s);
      std::vector<GoalJudgement> goals = evaluator.judge(light);
      if (PairEvaluator::all_met(goals)) {
        if (!best.feasible || power_of(cost, *s) < best.power_w) keep(members, c, *s, std::move(light), std::move(goals), true);
        continue;
      }
    }
    if (best.feasible) continue;
    // No feasible combination yet: keep the one that misses least at full output, to report.
    PairLight light = evaluator.light(members, hi);
    std::vector<GoalJudgement> goals = evaluator.judge(light);
    const double missed = PairEvaluator::missed(goals);
    if (missed < best_missed) {
      best_missed = missed;
      keep(members, c, hi, std::move(light), std::move(goals), false);
    }
  }
  best.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return best;
}

}  // namespace ilp
