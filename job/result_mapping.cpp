#include "job/result_mapping.h"

#include "optimizer/goal_metrics.h"

namespace ilp {

// Product x count, watts each and in all.
std::vector<BillLine> bill_of_materials(const VariantPlan& plan, const JobOutcome& outcome) {
  if (outcome.luminaires.empty()) return {};
  const ProductVariant& p = plan.product;
  const SearchLuminaire& s = plan.search.luminaire;
  BillLine line;
  line.count = static_cast<int>(outcome.luminaires.size());
  line.total_power_w = outcome.power_w;
  line.product = p.product;
  line.source = p.source;
  line.rated_flux_lm = p.rated_flux_lm;
  line.unit_power_w = p.power_w;
  line.output_fraction = s.uniform_output ? outcome.luminaires.front().flux_lm / p.rated_flux_lm : 1.0;
  if (!s.uniform_output) line.product += " (each at its own flux)";
  return {line};
}

ResultRecord make_record(const std::string& program_version, const PreparedJob& prepared, const JobConfig& job, const JobOutcome& outcome,
                         const std::vector<GridRecord>& grids, const std::vector<std::pair<std::string, double>>& timings) {
  const SearchLuminaire& luminaire = prepared.plan.search.luminaire;
  ResultRecord r;
  r.program_version = program_version;
  r.config = job.path;
  r.objective = std::string(objective_rule(job.objective).key);
  r.layout_family = std::string(layout_family_key(prepared.plan.search.layout.family));
  r.arrangement = outcome.search.best.arrangement;
  r.spacing_x_m = outcome.search.best.spacing_m.x();
  r.spacing_y_m = outcome.search.best.spacing_m.y();
  for (std::size_t j = 0; j < outcome.luminaires.size(); ++j) {
    const PlacedLuminaire& l = outcome.luminaires[j];
    const std::optional<double> floor_z = prepared.model.floor_z_m;
    r.luminaires.push_back({luminaire_name(j), l.position_m.x(), l.position_m.y(), l.position_m.z(), l.flux_lm, l.power_w,
                            luminaire.product, luminaire.rotation_deg,
                            floor_z ? std::optional<double>(l.position_m.z() - *floor_z) : std::nullopt});
  }
  for (std::size_t g = 0; g < outcome.goals.size(); ++g) {
    const GoalOutcome& o = outcome.goals[g];
    GoalRecord rec;
    rec.name = o.predicted.name;
    rec.surfaces = job.goals[g].surfaces;
    rec.grid = job.goals[g].grid;
    rec.metric = std::string(to_string(o.predicted.metric));
    rec.unit = std::string(metric_rule(o.predicted.metric).unit);
    // The report shows maintained values, as the job states its targets.
    const double mf = metric_rule(o.predicted.metric).lux ? outcome.maintenance_factor : 1.0;
    rec.target = job.goals[g].target;
    rec.predicted = o.predicted.value * mf;
    if (o.verified) rec.verified = o.verified->value * mf;
    rec.met = o.met;
    rec.fails_only_on_verification = o.fails_only_on_verification;
    rec.tolerance = o.tolerance;
    r.goals.push_back(rec);
  }
  r.power_w = outcome.power_w;
  r.mounting_area_m2 = outcome.mounting_area_m2;
  r.power_density_w_per_m2 = outcome.power_density_w_per_m2;
  r.floor_area_m2 = outcome.floor_area_m2;
  r.floor_area_source = outcome.floor_area_source;
  r.power_density_w_per_m2_per_100_lx = outcome.power_density_w_per_m2_per_100_lx;
  r.maintenance_factor = outcome.maintenance_factor;
  r.grids = grids;
  r.fixed_flux_lm = outcome.fixed_flux_lm;
  r.feasible = outcome.feasible;
  r.all_met = outcome.all_met;
  r.flux_correction = outcome.flux_correction;
  r.flux_correction_limited = outcome.flux_correction_limited;
  r.verification = outcome.verification.method;
  r.verification_rays_per_patch = outcome.verification.rays_per_patch;
  r.sample_size = prepared.model.sample_size;
  r.population = static_cast<int>(prepared.model.stats.population);
  r.patches = static_cast<int>(prepared.loaded.scene.patches.size());
  r.candidates = static_cast<int>(prepared.model.grid.size());
  r.seed = job.form_factors.seed;
  r.optimizer_seed = job.optimizer.seed;
  r.evaluations = outcome.search.evaluations;
  r.searches = outcome.searches;
  r.calibration = outcome.calibration;
  r.time_limited = outcome.search.time_limited;
  r.search_max_seconds = job.optimizer.max_seconds;
  r.timings_s = timings;
  for (const CountAttempt& a : outcome.search.attempts)
    r.attempts.push_back(
        {a.luminaires, a.evaluations, a.seconds, a.feasible, a.power_w, a.global_stop, a.local_stop, a.arrangement});
  return r;
}

}  // namespace ilp
