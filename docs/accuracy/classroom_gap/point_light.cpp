#include <cstdio>
#include <iostream>
#include "job/config.h"
#include "job/plan.h"
#include "job/job_runner.h"
#include "core/transport/direct_light.h"
#include "core/transport/ray_caster.h"
using namespace ilp;
int main(int argc, char** argv) {
  const std::string cfg = argv[1];
  double px = atof(argv[2]), py = atof(argv[3]);
  double flux = atof(argv[4]);
  // luminaire xy pairs after
  std::vector<Eigen::Vector2d> lums;
  for (int i = 5; i + 1 < argc; i += 2) lums.emplace_back(atof(argv[i]), atof(argv[i + 1]));
  const JobConfig job = load_job_config(cfg);
  auto plans = plan_job(job);
  std::string cache = std::string(getenv("HOME")) + "/.cache/ilp";
  PreparedJob prep = prepare_job(job, plans[0], {}, {}, cache);
  const LightingModel& m = prep.model;
  int q = -1; double best = 1e9;
  for (size_t k = 0; k < m.goal_points.size(); ++k) {
    double d = (m.goal_points[k].position_m.head<2>() - Eigen::Vector2d(px, py)).norm();
    if (d < best) { best = d; q = (int)k; }
  }
  const ReceiverPoint P = m.goal_points[q];
  const Eigen::Index row = (Eigen::Index)m.goal_patches.size() + q;
  printf("point %d at (%.4f %.4f %.4f) n=(%.2f %.2f %.2f)\n", q, P.position_m.x(), P.position_m.y(), P.position_m.z(), P.normal.x(), P.normal.y(), P.normal.z());
  const SearchLuminaire& sl = prep.plan.search.luminaire;
  printf("rotation %.1f tilt %.1f length %.3f width %.3f\n", sl.rotation_deg, sl.tilt_deg, sl.type.length_m, sl.type.width_m);
  // prediction per luminaire
  double pred_total = 0, pred_direct = 0;
  std::vector<Eigen::Vector3d> pos3;
  for (size_t j = 0; j < lums.size(); ++j) {
    GridPoint g = m.grid.locate(lums[j]);
    pos3.push_back(g.position_m);
    double d = 0, t = 0;
    for (int k = 0; k < GridPoint::kMaxCandidates; ++k) {
      int c = g.candidates[k]; if (c < 0) continue;
      d += g.weights[k] * m.candidate_direct_lux_per_lm(row, c);
      t += g.weights[k] * m.candidate_lux_per_lm(row, c);
    }
    pred_total += t * flux; pred_direct += d * flux;
    printf("L%zu (%.3f %.3f %.3f): predicted direct %.1f lx total %.1f lx\n", j + 1, g.position_m.x(), g.position_m.y(), g.position_m.z(), d * flux, t * flux);
    if (getenv("SHOWC"))
      for (int k = 0; k < GridPoint::kMaxCandidates; ++k) {
        int c = g.candidates[k]; if (c < 0) continue;
        auto cp = m.grid.positions_m()[c];
        printf("    cand %d (%.3f %.3f) w %.3f direct %.1f\n", c, cp.x(), cp.y(), g.weights[k], m.candidate_direct_lux_per_lm(row, c) * flux);
      }
  }
  printf("predicted: direct %.1f total %.1f (fixed %.1f)\n", pred_direct, pred_total, m.fixed_lux[row]);
  // verification-like: real luminaires in job scene
  Scene scene = prep.loaded.scene;
  std::vector<int> surf;
  for (size_t j = 0; j < pos3.size(); ++j)
    surf.push_back(add_luminaire(scene, "L" + std::to_string(j + 1), sl.type, {pos3[j], sl.rotation_deg, sl.tilt_deg}, flux));
  RayCaster caster(scene);
  DirectLightOptions o = job.direct_light;
  std::vector<ReceiverPoint> pts{P};
  LuminaireLight L = compute_luminaire_light_at_points(scene, caster, pts, surf, o);
  double sum = 0;
  for (size_t j = 0; j < surf.size(); ++j) { printf("L%zu real: direct %.1f lx\n", j + 1, L.lux_per_lm(0, j) * flux); sum += L.lux_per_lm(0, j) * flux; }
  printf("real direct sum %.1f\n", sum);
  // the same with a caster on the job scene only (no luminaire bodies)
  RayCaster caster0(prep.loaded.scene);
  LuminaireLight L0 = compute_luminaire_light_at_points(scene, caster0, pts, surf, o);
  sum = 0;
  for (size_t j = 0; j < surf.size(); ++j) { printf("L%zu real, luminaires not occluding: direct %.1f lx\n", j + 1, L0.lux_per_lm(0, j) * flux); sum += L0.lux_per_lm(0, j) * flux; }
  printf("sum %.1f\n", sum);
  // rays from point to the nearest luminaire's opening
  int jn = 0; double dn = 1e9;
  for (size_t j = 0; j < pos3.size(); ++j) { double d = (pos3[j] - P.position_m).norm(); if (d < dn) { dn = d; jn = (int)j; } }
  Eigen::Matrix3d R = luminaire_rotation(sl.rotation_deg, sl.tilt_deg);
  printf("rays to L%d:\n", jn + 1);
  for (int i = 0; i <= 6; ++i) for (int k = 0; k <= 2; ++k) {
    Eigen::Vector3d local((i / 6.0 - 0.5) * sl.type.length_m, (k / 2.0 - 0.5) * sl.type.width_m, 0);
    Eigen::Vector3d y = pos3[jn] + R * local;
    Eigen::Vector3d d = y - P.position_m; double len = d.norm(); d /= len;
    RayHit h = caster.first_hit(P.position_m + d * caster.ray_offset_m(), d, len);
    std::string nm = h.patch >= 0 ? scene.surfaces[scene.patches[h.patch].surface].name : "-";
    printf("  u %.2f v %.2f target (%.3f %.3f %.3f): hit %s t %.3f of %.3f", i/6.0, k/2.0, y.x(), y.y(), y.z(), nm.c_str(), h.t, len);
    if (h.patch >= 0) { auto hp = P.position_m + d * (h.t + caster.ray_offset_m()); printf(" at (%.3f %.3f %.3f)", hp.x(), hp.y(), hp.z()); }
    printf("\n");
  }
}
