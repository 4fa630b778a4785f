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

namespace {

// The search's evaluations and the luminaires of its largest layout (the verification's
// scene), from the plan's layout (counts already capped by constraints.max_luminaires).
void count_search(const SearchSpec& search, CostCounts& c) {
  const LayoutSpec& s = search.layout;
  const int most = s.count_max;
  if (s.family == LayoutFamily::free || s.family == LayoutFamily::array) {
    const int counts = s.family == LayoutFamily::array ? 1 : std::max(1, most - s.count_min + 1);
    c.luminaires = s.family == LayoutFamily::array ? s.array_rows * s.array_columns : most;
    c.evaluations = static_cast<long long>(counts) * (search.options.max_evaluations + search.options.local_max_evaluations);
  } else {  // one evaluation per arrangement; the bays in the zone are not known before the scene
    const RegularLayoutParams& r = s.regular;
    const bool bays = s.family == LayoutFamily::bays;
    constexpr int kBaysAssumed = 256;
    c.luminaires = std::min(most, bays ? kBaysAssumed * r.per_bay.max : r.rows.max * r.columns.max);
    // Each edge ratio tried (every 0.05 of the range) on each axis.
    const long long ratios = 1 + static_cast<long long>(std::ceil((r.edge_ratio_max - r.edge_ratio_min) / 0.05 - 1e-9));
    c.evaluations = bays ? r.per_bay.max - r.per_bay.min + 1
                         : static_cast<long long>(r.rows.max - r.rows.min + 1) * (r.columns.max - r.columns.min + 1) *
                               ratios * ratios;
  }
  c.search_max_seconds = search.options.max_seconds;
}

}  // namespace

CostCounts job_cost_counts(const VariantPlan& plan, const Scene& job_scene, const LightingModel& geometry,
                           std::optional<double> budget, const std::vector<CalcGridSize>* grids) {
  const ModelSpec& model = plan.model;
  const SampleOperatorOptions& op = model.operator_options;
  const SampleSizeRule& sample = model.sample_size;
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
    c.reflected_sources =
        candidate_reflected_blend(geometry.grid, c.sources - geometry.grid.size(), model.reflected_stride).computed.size();
  c.channels = job_scene.channels;
  c.rays_per_patch = op.form_factors.rays_per_patch;
  c.exact_second_bounce = op.indirect == IndirectMethod::exact_second_bounce;
  c.direct_rays = op.direct_light.receiver_points * op.direct_light.shadow_rays;
  c.direct_points = op.direct_light.receiver_points;
  c.point_sources = mean_point_sources(geometry.scene, population, luminaire_surfaces(geometry.scene));
  c.point_direct_rays = op.direct_light.shadow_rays;
  if (c.population > 0) {
    if (sample.target_error) {
      c.pilot_builds = sample.error_samples;
      c.pilot_size = static_cast<std::size_t>(std::min<double>(
          static_cast<double>(c.population), std::max(2.0, std::round(sample.pilot_fraction * c.population))));
      c.sample_size = static_cast<std::size_t>(std::min<double>(static_cast<double>(c.population), sample.max_size));
    } else {
      c.sample_size =
          static_cast<std::size_t>(std::min<double>(static_cast<double>(c.population), sample.size_for(c.population)));
    }
  }
  count_search(plan.search, c);
  const VerificationSettings& verification = plan.verification.settings;
  const VerificationPlan verify =
      plan_verification(verification, c.patches + 2 * static_cast<std::size_t>(c.luminaires), c.population,
                        c.goal_patches, c.luminaires, budget);
  c.verify = verify.method == VerificationMethod::exact    ? CostCounts::Verify::exact
             : verify.method == VerificationMethod::sample ? CostCounts::Verify::sample
                                                           : CostCounts::Verify::none;
  c.verify_rays = verification.rays_per_patch;
  c.verify_indirect_rays = verification.indirect_rays_per_patch;
  c.verify_first_indirect_rays = verification.first_indirect_rays;
  c.verify_decisive_rays = verification.decisive_rays;
  c.verify_sample_size = static_cast<std::size_t>(verify.sample_size);
  c.verify_rounds = verify.method == VerificationMethod::none ? 1 : verification.rounds;
  c.output_patches = plan.outputs.patch_files ? c.patches : 0;
  c.output_renders = plan.outputs.renders;
  if (plan.outputs.plan_render)  // the plan's outline: the mounting surface, else every patch (plan_svg.h)
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

MachineCosts job_machine_costs(int worker_threads, const RunOptions& run) {
  return machine_costs(run.machine.speed, usable_threads(worker_threads));
}

CostedGeometry costed_geometry(const VariantPlan& plan, const Scene& job_scene,
                               const std::optional<MemoryBudget>& budget, const MachineCosts& costs,
                               const RayCaster* caster) {
  const ModelSpec& spec = plan.model;
  const std::optional<double> bytes = budget ? std::optional<double>(budget->bytes) : std::nullopt;
  auto before_grids = [&](const LightingModel& partial, const std::vector<CalcGridSize>& grids) {
    if (grids.empty()) return;
    CostedGeometry c;
    c.counts = job_cost_counts(plan, job_scene, partial, bytes, &grids);
    c.counts.photometric = !spec.candidates.type.lambertian();
    c.counts.shares = spec.operator_options.share.count;
    c.counts.hit_block_patches = static_cast<std::size_t>(spec.operator_options.hit_block_patches);
    c.estimate = estimate_job_cost(c.counts, costs);
    c.refusal = refusal_of(c.estimate, budget, plan.source);
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
  out.counts = job_cost_counts(plan, job_scene, out.model, bytes);
  out.counts.photometric = !spec.candidates.type.lambertian();
  out.counts.shares = spec.operator_options.share.count;
  out.counts.hit_block_patches = static_cast<std::size_t>(spec.operator_options.hit_block_patches);
  out.estimate = estimate_job_cost(out.counts, costs);
  out.refusal = refusal_of(out.estimate, budget, plan.source);
  return out;
}

double whole_run_seconds(Objective objective, const std::vector<CostEstimate>& variants) {
  double seconds = 0.0;
  for (std::size_t v = 0; v < variants.size(); ++v)
    for (const PhaseEstimate& p : variants[v].phases) {
      if (v > 0 && (p.name == kOutputPhase || p.name == kScenePhase)) continue;
      const bool later_verification = v > 0 && p.name.starts_with("verification");
      seconds += later_verification && objective_rule(objective).minimises_power ? 0.5 * p.seconds : p.seconds;
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
