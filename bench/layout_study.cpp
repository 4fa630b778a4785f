// How good is the layout search, and how good is the model it searches on? On a job
// (configs/office.yaml, or the one given), with the lighting model built once:
//
//  1. prediction: random layouts (positions uniform over the candidates' extent,
//     relative fluxes uniform in the flux range, the flux scale set as the search sets
//     it), each predicted through the model and verified by placing real luminaires
//     and solving exactly: the error of each goal metric and the per-patch RMS error.
//  2. search: global algorithm x local algorithm x evaluation budget, seeds 1-3, without
//     verification: the power found (median), feasibility, evaluations and time.
//
//   ./build/bench/layout_study [CONFIG] [LAYOUTS] [prediction]
//   (defaults: configs/office.yaml, 12 layouts; "prediction": skip the search study)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "job/config.h"
#include "job/plan.h"
#include "job/job_runner.h"

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void prediction_study(const ilp::PreparedJob& prepared, int layouts) {
  const ilp::VariantPlan& plan = prepared.plan;
  const ilp::LightingModel& model = prepared.model;
  const int n = std::min(4, plan.search.layout.count_max);
  std::mt19937_64 rng(12345);
  const Eigen::Vector2d lo = model.grid.lower_m(), hi = model.grid.upper_m();
  const double w_lo = plan.search.luminaire.flux_min_lm / plan.search.luminaire.flux_max_lm;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<double>> errors(plan.search.goals.size());
  std::vector<double> patch_rms, seconds;
  std::printf("## Prediction against verification (%d random layouts of %d luminaires, exact solve %d rays per patch)\n\n",
              layouts, n, plan.verification.settings.rays_per_patch);
  for (int l = 0; l < layouts; ++l) {
    std::vector<Eigen::Vector2d> xy;
    std::vector<double> w;
    for (int j = 0; j < n; ++j) {
      xy.emplace_back(lo.x() + unit(rng) * (hi.x() - lo.x()), lo.y() + unit(rng) * (hi.y() - lo.y()));
      w.push_back(w_lo + unit(rng) * (1.0 - w_lo));
    }
    const ilp::LayoutEvaluation predicted = ilp::evaluate_layout(model, prepared.plan.search, xy, w);
    const auto start = std::chrono::steady_clock::now();
    const ilp::Verification v = ilp::verify_layout(prepared, predicted.luminaires);
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    const Eigen::VectorXd verified = ilp::verified_goal_lux(model, v);
    const std::vector<ilp::GoalJudgement> judged = ilp::judge_goals(model, prepared.plan.search, verified);
    for (std::size_t g = 0; g < judged.size(); ++g)
      errors[g].push_back(predicted.goals[g].value / judged[g].value - 1.0);
    double sum = 0.0, area = 0.0;
    for (std::size_t r = 0; r < model.goal_patches.size(); ++r) {
      const double a = prepared.loaded.scene.patches[static_cast<std::size_t>(model.goal_patches[r])].area_m2;
      const double e = predicted.lux[static_cast<Eigen::Index>(r)] / verified[static_cast<Eigen::Index>(r)] - 1.0;
      sum += a * e * e;
      area += a;
    }
    patch_rms.push_back(std::sqrt(sum / area));
  }
  std::printf("| goal | metric | median error | median abs. error | largest abs. error |\n|---|---|---|---|---|\n");
  for (std::size_t g = 0; g < plan.search.goals.size(); ++g) {
    std::vector<double> abs_err;
    for (double e : errors[g]) abs_err.push_back(std::abs(e));
    std::printf("| %s | %s | %+.2f %% | %.2f %% | %.2f %% |\n", plan.search.goals[g].name.c_str(),
                std::string(ilp::to_string(plan.search.goals[g].metric)).c_str(), 100.0 * median(errors[g]),
                100.0 * median(abs_err), 100.0 * *std::max_element(abs_err.begin(), abs_err.end()));
  }
  std::printf("\nper-patch RMS relative error of total illuminance at the goal patches: median %.2f %%, largest %.2f %%\n",
              100.0 * median(patch_rms), 100.0 * *std::max_element(patch_rms.begin(), patch_rms.end()));
  std::printf("one verification (exact solve): median %.2f s\n\n", median(seconds));
}

void search_study(const ilp::PreparedJob& prepared) {
  std::printf("## Search: power found against algorithm and budget (median of seeds 1-3, no verification)\n\n");
  std::printf("| global | local | global evaluations per count | power W | feasible | evaluations | search s | evaluations/s |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  struct Combo {
    const char* global;
    const char* local;
  };
  for (const Combo c : {Combo{"GN_CRS2_LM", "LN_SBPLX"}, Combo{"GN_CRS2_LM", "LN_COBYLA"}, Combo{"GN_CRS2_LM", "LN_BOBYQA"},
                        Combo{"GN_ISRES", "LN_SBPLX"}, Combo{"GN_ESCH", "LN_SBPLX"}, Combo{"GN_DIRECT_L", "LN_SBPLX"},
                        Combo{"none", "LN_SBPLX"}})
    for (int budget : {1000, 6000, 20000}) {
      if (std::string(c.global) == "none" && budget != 1000) continue;
      std::vector<double> power, evaluations, secs;
      int feasible = 0;
      for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        ilp::SearchSpec spec = prepared.plan.search;
        spec.options.global_algorithm = c.global;
        spec.options.local_algorithm = c.local;
        spec.options.max_evaluations = budget;
        spec.options.max_seconds = 600;
        spec.options.seed = seed;
        const ilp::SearchResult r = ilp::search_layout(prepared.model, spec);
        if (r.best.feasible) {
          ++feasible;
          power.push_back(r.best.power_w);
        }
        evaluations.push_back(r.evaluations);
        secs.push_back(r.seconds);
      }
      std::printf("| %s | %s | %d | %.1f | %d of 3 | %.0f | %.2f | %.0f |\n", c.global, c.local,
                  std::string(c.global) == "none" ? 0 : budget, median(power), feasible, median(evaluations),
                  median(secs), median(evaluations) / median(secs));
      std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const ilp::JobConfig job = ilp::load_job_config(argc > 1 ? argv[1] : ILP_SOURCE_DIR "/configs/office.yaml");
    const int layouts = argc > 2 ? std::stoi(argv[2]) : 12;
    const ilp::PreparedJob prepared = ilp::prepare_job(scene_spec(job), ilp::plan_job(job).variants.front());
    std::printf("# Layout study: %s (%zu patches, %zu goal patches, %zu candidates, k = %d, operator %.2f s)\n\n",
                job.path.c_str(), prepared.loaded.scene.patches.size(), prepared.model.goal_patches.size(),
                prepared.model.grid.size(), prepared.model.sample_size, prepared.model.build_seconds);
    prediction_study(prepared, layouts);
    if (!(argc > 3 && std::string(argv[3]) == "prediction")) search_study(prepared);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
