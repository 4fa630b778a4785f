#include "job/job_cost.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/base/error.h"
#include "core/transport/direct_light.h"
#include "core/operator/sample_operator.h"

namespace ilp {

VerificationPlan plan_verification(const VerificationSettings& s, std::size_t patches, std::size_t population,
                                   std::size_t goal_patches, int luminaires, std::optional<double> budget) {
  VerificationPlan plan;
  plan.method = s.method;
  const int configured_k =
      std::max(1, static_cast<int>(std::lround(s.sample_fraction * static_cast<double>(population))));
  if (s.method == VerificationMethod::none) return plan;
  if (s.method == VerificationMethod::exact) {
    plan.reason = "verification.method: exact";
    return plan;
  }
  if (s.method == VerificationMethod::sample) {
    plan.sample_size = configured_k;
    plan.reason = "verification.method: sample";
    return plan;
  }
  // auto: exact up to max_exact_patches, or beyond while its sparse rows fit in half
  // the budget; else a sample that fits and stays quick.
  const double exact_bytes = exact_verification_bytes(patches, s.rays_per_patch);
  std::ostringstream why;
  if (patches <= s.max_exact_patches) {
    plan.method = VerificationMethod::exact;
    why << "auto: exact (" << patches << " patches <= verification.max_exact_patches " << s.max_exact_patches << ")";
  } else if (!budget || exact_bytes <= 0.5 * *budget) {
    plan.method = VerificationMethod::exact;
    why << "auto: exact (" << patches << " sparse rows at " << s.rays_per_patch << " rays, about "
        << format_bytes(exact_bytes) << ", fit in memory)";
  } else {
    plan.method = VerificationMethod::sample;
    int k = std::min(configured_k, kAutoVerificationMaxSample);
    while (k > 1 && budget &&
           sample_verification_bytes(static_cast<std::size_t>(k), goal_patches, static_cast<std::size_t>(luminaires) + 1,
                                    s.rays_per_patch) > 0.5 * *budget)
      k = k * 3 / 4;
    plan.sample_size = std::max(1, k);
    why << "auto: sample of k = " << plan.sample_size << " (exact rows would need " << format_bytes(exact_bytes)
        << "; k capped at " << kAutoVerificationMaxSample << " and by memory, verification.sample_fraction asks "
        << configured_k << ")";
  }
  plan.reason = why.str();
  return plan;
}

CostCounts job_cost_counts(const JobConfig& job, const Scene& job_scene, const LightingModel& geometry,
                           std::optional<double> budget, const std::vector<CalcGridSize>* grids) {
  CostCounts c;
  c.patches = job_scene.patches.size();
  const std::vector<int> population = reflecting_patches(job_scene);
  c.population = population.size();
  std::vector<double> areas;
  areas.reserve(population.size());
  for (int p : population) areas.push_back(job_scene.patches[static_cast<std::size_t>(p)].area_m2);
  c.area_shares = area_share_bins(areas);
  c.goal_patches = geometry.goal_patches.size();
  c.grid_points = geometry.goal_points.size();
  if (grids) {
    c.grid_points = 0;
    for (const CalcGridSize& g : *grids) {
      c.grid_points += g.cells;
      c.grid_outline_tests += g.cells * g.outline_parts;
    }
  }
  c.sources = scene_light_sources(geometry.scene).size();
  // The candidates' reflected light at every n-th node (compute_lighting_operator's blend).
  if (geometry.grid.size() > 0 && geometry.grid.size() <= c.sources)
    c.reflected_sources = candidate_reflected_blend(geometry.grid, c.sources - geometry.grid.size(),
                                                    job.sample.reflected_stride).computed.size();
  c.channels = job_scene.channels;
  c.rays_per_patch = job.form_factors.rays_per_patch;
  c.exact_second_bounce = job.sample.indirect == IndirectMethod::exact_second_bounce;
  c.direct_rays = job.direct_light.receiver_points * job.direct_light.shadow_rays;
  c.direct_points = job.direct_light.receiver_points;
  c.point_sources = mean_point_sources(geometry.scene, population, luminaire_surfaces(geometry.scene));
  c.point_direct_rays = job.direct_light.shadow_rays;
  if (c.population > 0) {
    if (job.sample.target_error) {
      c.pilot_builds = job.sample.error_samples;
      c.pilot_size = static_cast<std::size_t>(std::min<double>(
          static_cast<double>(c.population), std::max(2.0, std::round(job.sample.pilot_fraction * c.population))));
      c.sample_size = static_cast<std::size_t>(std::min<double>(static_cast<double>(c.population),
                                                                job.sample.max_size_for_target));
    } else {
      c.sample_size = static_cast<std::size_t>(std::min<double>(static_cast<double>(c.population),
                                                                job.sample.size_for(c.population)));
    }
  }
  if (job.search) {
    const LuminaireSearch& s = *job.search;
    const int most = job.constraints.max_luminaires ? std::min(s.count_max, *job.constraints.max_luminaires) : s.count_max;
    if (s.layout == LayoutFamily::free || s.layout == LayoutFamily::array) {
      const int counts = s.layout == LayoutFamily::array ? 1 : std::max(1, most - s.count_min + 1);
      c.luminaires = s.layout == LayoutFamily::array ? s.array_rows * s.array_columns : most;
      c.evaluations = static_cast<long long>(counts) *
                      (job.optimizer.max_evaluations + job.optimizer.local_max_evaluations);
    } else {  // one evaluation per arrangement; the bays in the zone are not known before the scene
      const RegularLayoutParams& r = s.regular;
      const bool bays = s.layout == LayoutFamily::bays;
      constexpr int kBaysAssumed = 256;
      c.luminaires = std::min(most, bays ? kBaysAssumed * r.per_bay.max : r.rows.max * r.columns.max);
      // Each edge ratio tried (every 0.05 of the range) on each axis.
      const long long ratios = 1 + static_cast<long long>(std::ceil((r.edge_ratio_max - r.edge_ratio_min) / 0.05 - 1e-9));
      c.evaluations = bays ? r.per_bay.max - r.per_bay.min + 1
                           : static_cast<long long>(r.rows.max - r.rows.min + 1) * (r.columns.max - r.columns.min + 1) *
                                 ratios * ratios;
    }
    c.search_max_seconds = job.optimizer.max_seconds;
  }
  const VerificationPlan plan =
      plan_verification(job.verification, c.patches + 2 * static_cast<std::size_t>(c.luminaires), c.population, c.goal_patches,
                        c.luminaires, budget);
  c.verify = plan.method == VerificationMethod::exact    ? CostCounts::Verify::exact
             : plan.method == VerificationMethod::sample ? CostCounts::Verify::sample
                                                         : CostCounts::Verify::none;
  c.verify_rays = job.verification.rays_per_patch;
  c.verify_indirect_rays = job.verification.indirect_rays_per_patch;
  c.verify_first_indirect_rays = job.verification.first_indirect_rays;
  c.verify_decisive_rays = job.verification.decisive_rays;
  c.verify_sample_size = static_cast<std::size_t>(plan.sample_size);
  c.verify_rounds = plan.method == VerificationMethod::none ? 1 : job.verification.rounds;
  c.output_patches = job.output.ply || job.output.csv ? c.patches : 0;
  c.output_renders = job.output.plan_png || job.output.isolux_png || job.output.pdf;
  if (job.output.plan_png || job.output.pdf)  // the plan's outline: the mounting surface, else every patch (plan_svg.h)
    c.plan_patches = geometry.grid.mounting_patches().empty() ? c.patches : geometry.grid.mounting_patches().size();
  return c;
}

namespace {

// The estimate of `counts` and, when it exceeds the budget, require_fits's message.
std::string refusal_of(const CostEstimate& estimate, const std::optional<MemoryBudget>& budget, const std::string& where) {
  try {
    require_fits(estimate, budget, where);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return {};
}

// Thrown by the check before the grids, to stop lighting_model_geometry there.
struct RefusedBeforeGrids {
  CostedGeometry costed;
};

}  // namespace

MachineCosts job_machine_costs(const JobConfig& job, const RunOptions& run) {
  return machine_costs(run.machine.speed, usable_threads(worker_threads(job, run)));
}

CostedGeometry costed_geometry(const JobConfig& job, const Scene& job_scene, const ModelSpec& spec,
                               const std::optional<MemoryBudget>& budget, const MachineCosts& costs,
                               const RayCaster* caster) {
  const std::optional<double> bytes = budget ? std::optional<double>(budget->bytes) : std::nullopt;
  auto before_grids = [&](const LightingModel& partial, const std::vector<CalcGridSize>& grids) {
    if (grids.empty()) return;
    CostedGeometry c;
    c.counts = job_cost_counts(job, job_scene, partial, bytes, &grids);
    c.counts.photometric = !spec.candidates.type.lambertian();
    c.counts.shares = spec.operator_options.share.count;
    c.counts.hit_block_patches = static_cast<std::size_t>(spec.operator_options.hit_block_patches);
    c.estimate = estimate_job_cost(c.counts, costs);
    c.refusal = refusal_of(c.estimate, budget, job.path);
    if (!c.refusal.empty()) {
      c.model = partial;
      throw RefusedBeforeGrids{std::move(c)};
    }
  };
  CostedGeometry out;
  try {
    out.model = lighting_model_geometry(job_scene, spec, caster, before_grids);
  } catch (RefusedBeforeGrids& refused) {
    return std::move(refused.costed);
  }
  out.counts = job_cost_counts(job, job_scene, out.model, bytes);
  out.counts.photometric = !spec.candidates.type.lambertian();
  out.counts.shares = spec.operator_options.share.count;
  out.counts.hit_block_patches = static_cast<std::size_t>(spec.operator_options.hit_block_patches);
  out.estimate = estimate_job_cost(out.counts, costs);
  out.refusal = refusal_of(out.estimate, budget, job.path);
  return out;
}

double whole_run_seconds(const JobConfig& job, const std::vector<CostEstimate>& variants) {
  double seconds = 0.0;
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (const PhaseEstimate& p : variants[v].phases) {
      if (v > 0 && (p.name == kOutputPhase || p.name == kScenePhase)) continue;
      const bool later_verification = v > 0 && p.name.starts_with("verification");
      seconds += later_verification && objective_rule(job.objective).minimises_power ? 0.5 * p.seconds : p.seconds;
    }
  return seconds;
}

double groups_run_seconds(const std::vector<std::vector<CostEstimate>>& groups) {
  double seconds = 0.0, verification = 0.0;
  bool first = true;
  for (const std::vector<CostEstimate>& variants : groups)
    for (const CostEstimate& e : variants) {
      for (const PhaseEstimate& p : e.phases) {
        if (p.name.starts_with("verification")) {
          verification = std::max(verification, p.seconds);
        } else if (first || (p.name != kOutputPhase && p.name != kScenePhase)) {
          seconds += p.seconds;
        }
      }
      first = false;
    }
  return seconds + verification;
}

}  // namespace ilp
