#include <cstdio>
#include "job/config.h"
#include "job/plan.h"
#include "job/job_runner.h"
#include "core/transport/direct_light.h"
using namespace ilp;
// direct lux at a grid point from one real luminaire swept along y at fixed x, vs the search's blend
int main(int argc, char** argv) {
  const JobConfig job = load_job_config(argv[1]);
  double px = atof(argv[2]), py = atof(argv[3]), lx = atof(argv[4]), flux = atof(argv[5]);
  double y0 = atof(argv[6]), y1 = atof(argv[7]); int n = atoi(argv[8]);
  auto plans = plan_job(job);
  PreparedJob prep = prepare_job(job, plans[0], {}, {}, std::string(getenv("HOME")) + "/.cache/ilp");
  const LightingModel& m = prep.model;
  int q = -1; double best = 1e9;
  for (size_t k = 0; k < m.goal_points.size(); ++k) {
    double d = (m.goal_points[k].position_m.head<2>() - Eigen::Vector2d(px, py)).norm();
    if (d < best) { best = d; q = (int)k; }
  }
  const Eigen::Index row = (Eigen::Index)m.goal_patches.size() + q;
  const SearchLuminaire& sl = prep.plan.search.luminaire;
  printf("# point %d (%.4f %.4f) luminaire x %.3f rotation %.0f, flux %.1f lm\n# y_m blend_direct_lux real_direct_lux\n", q, m.goal_points[q].position_m.x(), m.goal_points[q].position_m.y(), lx, sl.rotation_deg, flux);
  for (int i = 0; i <= n; ++i) {
    double y = y0 + (y1 - y0) * i / n;
    GridPoint g = m.grid.locate({lx, y});
    double d = 0;
    for (int k = 0; k < GridPoint::kMaxCandidates; ++k) if (g.candidates[k] >= 0) d += g.weights[k] * m.candidate_direct_lux_per_lm(row, g.candidates[k]);
    Scene scene = prep.loaded.scene;
    int s = add_luminaire(scene, "L", sl.type, {g.position_m, sl.rotation_deg, sl.tilt_deg}, flux);
    std::vector<int> surf{s};
    std::vector<ReceiverPoint> pts{m.goal_points[q]};
    LuminaireLight L = compute_luminaire_light_at_points(scene, *prep.caster, pts, surf, job.direct_light);
    printf("%.3f %.1f %.1f\n", y, std::max(0.0, d) * flux, L.lux_per_lm(0, 0) * flux);
  }
}
