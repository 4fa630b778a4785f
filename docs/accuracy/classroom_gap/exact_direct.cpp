#include <cstdio>
#include <chrono>
#include "job/config.h"
#include "job/plan.h"
#include "job/job_runner.h"
#include "core/transport/direct_light.h"
using namespace ilp;
// For a layout (result.json's xy, one flux): each work-plane point's predicted total
// (the search's blend), and the same with the blended direct part replaced by the
// direct light of the real luminaires at their positions (area source, shadow rays).
int main(int argc, char** argv) {
  const JobConfig job = load_job_config(argv[1]);
  const int grid = atoi(argv[2]);
  const double flux = atof(argv[3]);
  std::vector<Eigen::Vector2d> lums;
  for (int i = 4; i + 1 < argc; i += 2) lums.emplace_back(atof(argv[i]), atof(argv[i + 1]));
  auto plans = plan_job(job);
  PreparedJob prep = prepare_job(job, plans[0], {}, {}, std::string(getenv("HOME")) + "/.cache/ilp");
  const LightingModel& m = prep.model;
  const SearchLuminaire& sl = prep.plan.search.luminaire;
  const Eigen::Index first = m.grid_first_row[grid];
  const size_t np = m.grids[grid].points.size();
  Scene scene = prep.loaded.scene;
  std::vector<int> surf;
  Eigen::VectorXd bt = Eigen::VectorXd::Zero(np), bd = Eigen::VectorXd::Zero(np);
  for (size_t j = 0; j < lums.size(); ++j) {
    GridPoint g = m.grid.locate(lums[j]);
    surf.push_back(add_luminaire(scene, "L" + std::to_string(j + 1), sl.type, {g.position_m, sl.rotation_deg, sl.tilt_deg}, flux));
    for (size_t q = 0; q < np; ++q)
      for (int k = 0; k < GridPoint::kMaxCandidates; ++k)
        if (int c = g.candidates[k]; c >= 0) {
          bt[q] += g.weights[k] * m.candidate_lux_per_lm(first + q, c) * flux;
          bd[q] += g.weights[k] * m.candidate_direct_lux_per_lm(first + q, c) * flux;
        }
  }
  std::vector<ReceiverPoint> pts(m.grids[grid].points.begin(), m.grids[grid].points.end());
  auto t0 = std::chrono::steady_clock::now();
  LuminaireLight L = compute_luminaire_light_at_points(scene, *prep.caster, pts, surf, job.direct_light);
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Eigen::VectorXd ed = L.lux_per_lm.rowwise().sum() * flux;
  Eigen::VectorXd et = bt - bd + ed;
  Eigen::VectorXd fixed = m.fixed_lux.segment(first, np);
  bt += fixed; et += fixed;
  printf("# point x_m y_m blend_direct_lx exact_direct_lx blend_total_lx exact_direct_total_lx\n");
  for (size_t q = 0; q < np; ++q)
    if (std::abs(bd[q] - ed[q]) > 0.1 * std::max(1.0, ed[q]) || getenv("ALL"))
      printf("%zu %.4f %.4f %.1f %.1f %.1f %.1f\n", q, pts[q].position_m.x(), pts[q].position_m.y(), bd[q], ed[q], bt[q], et[q]);
  printf("blend: Em %.1f Emin %.1f U0 %.3f | exact direct: Em %.1f Emin %.1f U0 %.3f\n", bt.mean(), bt.minCoeff(), bt.minCoeff() / bt.mean(), et.mean(), et.minCoeff(), et.minCoeff() / et.mean());
  printf("exact direct: %zu points x %zu luminaires, %llu shadow rays, %.3f s\n", np, surf.size(), (unsigned long long)L.shadow_rays_cast, s);
}
