#include "core/exact/exact_solver.h"

#include <chrono>
#include <algorithm>
#include <iomanip>
#include <iterator>
#include <ostream>

#include "core/transport/ray_caster.h"
#include "core/transport/row_builder.h"

namespace ilp {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Fills emitted, absorbed and lost flux. Light leaving a reflecting patch is lost in
// the fraction of its gathered rays that struck a back face or escaped; a
// luminaire's light travels through its closed-form column, so what it loses is its
// flux minus what its column delivers (sum over receivers of A_i F_il E_l).
void account_flux(const Scene& scene, const FormFactorRows& rows, const RadiositySolution& solution,
                  ExactSolveSummary& s) {
  const Eigen::Index n = static_cast<Eigen::Index>(scene.patches.size());
  Eigen::VectorXd delivered_by_luminaire = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (SparseRows::InnerIterator it(rows.F, i); it; ++it)
      if (scene.surfaces[scene.patches[it.col()].surface].is_luminaire())
        delivered_by_luminaire[it.col()] += scene.patches[i].area_m2 * it.value();
  Eigen::RowVectorXd absorbed = Eigen::RowVectorXd::Zero(scene.channels), lost = absorbed;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Patch& p = scene.patches[i];
    s.emitted_lm += p.area_m2 * p.exitance_lm_per_m2;
    for (int c = 0; c < scene.channels; ++c) {
      absorbed[c] += p.area_m2 * (1.0 - p.reflectance[c]) * solution.illuminance_lux(i, c);
      if (scene.surfaces[p.surface].is_luminaire())
        lost[c] += p.exitance_lm_per_m2 * (p.area_m2 - delivered_by_luminaire[i]);
      else
        lost[c] += p.area_m2 * solution.radiosity_lm_per_m2(i, c) * (rows.back_hit_fraction[i] + rows.escaped_fraction[i]);
    }
  }
  s.absorbed_lm = photometric(absorbed);
  s.lost_lm = photometric(lost);
}

// Each refinement's rays follow their own stream.
constexpr std::uint64_t kRefinementSeedSalt = 0x9E3779B97F4A7C15ull;
// The rows made precise after the first solve (make_precise) have theirs.
constexpr std::uint64_t kPreciseSeedSalt = 0xD1B54A32D192ED03ull;

// The rows of `base` (every patch, in scene order) with the rows of `more` (the patches `others`,
// ascending) merged in: (n_base x base + n_more x more) / (n_base + n_more).
void merge_rows(FormFactorRows& base, const FormFactorRows& more, const std::vector<int>& others, int n_base,
                int n_more, int threads) {
  const Eigen::Index n = base.F.rows();
  const double w_old = static_cast<double>(n_base) / (n_base + n_more), w_new = 1.0 - w_old;
  std::vector<Eigen::Index> row_in_more(static_cast<std::size_t>(n), -1);
  for (std::size_t r = 0; r < others.size(); ++r)
    row_in_more[static_cast<std::size_t>(others[r])] = static_cast<Eigen::Index>(r);
  // Row i: as it was, or (i = others[r]) w_old x its entries + w_new x more's row r, the
  // union of both rows' columns.
  const SparseRows& old = base.F;
  base.F = build_rows(n, old.cols(), threads, [&](Eigen::Index i, const auto& emit) {
    const Eigen::Index m = row_in_more[static_cast<std::size_t>(i)];
    SparseRows::InnerIterator a(old, i);
    if (m < 0) {
      for (; a; ++a) emit(a.index(), a.value());
      return;
    }
    SparseRows::InnerIterator b(more.F, m);
    while (a || b) {
      if (a && (!b || a.index() < b.index())) {
        emit(a.index(), w_old * a.value());
        ++a;
      } else if (b && (!a || b.index() < a.index())) {
        emit(b.index(), w_new * b.value());
        ++b;
      } else {
        emit(a.index(), w_old * a.value() + w_new * b.value());
        ++a;
        ++b;
      }
    }
  });
  for (std::size_t r = 0; r < others.size(); ++r) {
    const auto i = static_cast<Eigen::Index>(others[r]), k = static_cast<Eigen::Index>(r);
    base.escaped_fraction[i] = w_old * base.escaped_fraction[i] + w_new * more.escaped_fraction[k];
    base.back_hit_fraction[i] = w_old * base.back_hit_fraction[i] + w_new * more.back_hit_fraction[k];
  }
  base.rays_cast += more.rays_cast;
  base.seconds += more.seconds;
}

}  // namespace

ProgressiveExactSolve::ProgressiveExactSolve(const Scene& scene, const ExactSolveOptions& options,
                                             int first_other_rays, const ProgressCallback& progress)
    : scene_(scene), options_(options), progress_(progress) {
  ExactSolveSummary& s = solution_.summary;
  s.patches = scene.patches.size();
  auto start = std::chrono::steady_clock::now();
  caster_ = std::make_unique<RayCaster>(options.base_caster, scene, options.form_factors.threads);
  s.bvh_seconds = seconds_since(start);
  s.ray_offset_m = caster_->ray_offset_m();
  const int full = options.form_factors.rays_per_patch;
  const bool split = options.precise_patches && options.other_rays_per_patch > 0;
  options_.other_rays_per_patch = split ? std::min(options.other_rays_per_patch, full) : 0;
  other_rays_ = split ? std::clamp(first_other_rays, 1, options_.other_rays_per_patch) : full;
  std::vector<int> rays(scene.patches.size(), split ? other_rays_ : full);
  std::vector<bool> precise(scene.patches.size(), !split);
  if (split)
    for (int p : *options.precise_patches) {
      rays.at(static_cast<std::size_t>(p)) = full;
      precise[static_cast<std::size_t>(p)] = true;
    }
  for (std::size_t i = 0; i < precise.size(); ++i)
    if (!precise[i]) others_.push_back(static_cast<int>(i));
  precise_ = precise;
  raw_ = compute_form_factor_rows(scene, *caster_, scene.all_patches(), rays, options.form_factors, progress);
  start = std::chrono::steady_clock::now();
  if (progress) progress("direct light", 0, 1);
  if (!options.precise_patches) {
    emitter_ = emitter_light(scene, *caster_, options.direct_light, raw_);
  } else {
    CheapDirectLight cheap{std::vector<bool>(scene.patches.size(), true), options.other_direct_light};
    cheap.options.seed = options.direct_light.seed;
    cheap.options.threads = options.direct_light.threads;
    for (int p : *options.precise_patches) cheap.rows.at(static_cast<std::size_t>(p)) = false;
    emitter_ = emitter_light(scene, *caster_, options.direct_light, raw_, &cheap);
  }
  if (progress) progress("direct light", 1, 1);
  s.direct_light_seconds = seconds_since(start);
  s.shadow_rays = emitter_.light.shadow_rays_cast;
  solve();
}

ProgressiveExactSolve::~ProgressiveExactSolve() = default;

bool ProgressiveExactSolve::can_refine() const {
  return options_.other_rays_per_patch > 0 && other_rays_ < options_.other_rays_per_patch && !others_.empty();
}

void ProgressiveExactSolve::refine() {
  if (!can_refine()) return;
  const int more = std::min(other_rays_, options_.other_rays_per_patch - other_rays_);
  FormFactorOptions step = options_.form_factors;
  step.rays_per_patch = more;
  step.seed = options_.form_factors.seed ^ (kRefinementSeedSalt * static_cast<std::uint64_t>(++level_));
  const FormFactorRows added = compute_form_factor_rows(scene_, *caster_, others_, step, progress_);
  merge_rows(raw_, added, others_, other_rays_, more, options_.form_factors.threads);
  other_rays_ += more;
  solve();
}

std::size_t ProgressiveExactSolve::precise_count() const {
  return static_cast<std::size_t>(std::count(precise_.begin(), precise_.end(), true));
}

std::size_t ProgressiveExactSolve::make_precise(const std::vector<int>& patches, int rays) {
  std::vector<int> add;
  for (int p : patches)
    if (!precise_.at(static_cast<std::size_t>(p))) {
      precise_[static_cast<std::size_t>(p)] = true;
      add.push_back(p);
    }
  if (add.empty()) return 0;
  std::sort(add.begin(), add.end());
  FormFactorOptions cast = options_.form_factors;
  cast.rays_per_patch = std::max(1, rays);
  cast.seed = options_.form_factors.seed ^ kPreciseSeedSalt;
  const FormFactorRows fresh = compute_form_factor_rows(scene_, *caster_, add, cast, progress_);
  merge_rows(raw_, fresh, add, 0, 1, options_.form_factors.threads);  // replaced: the old rows weigh nothing
  if (!emitter_.surfaces.empty()) {
    const auto start = std::chrono::steady_clock::now();
    const LuminaireLight light = compute_luminaire_light(scene_, *caster_, add, emitter_.surfaces, options_.direct_light);
    for (std::size_t r = 0; r < add.size(); ++r) {  // the emitter's rows are the patches, in scene order
      emitter_.light.lux_per_lm.row(add[r]) = light.lux_per_lm.row(static_cast<Eigen::Index>(r));
      emitter_.light.form_factor.row(add[r]) = light.form_factor.row(static_cast<Eigen::Index>(r));
    }
    solution_.summary.shadow_rays += light.shadow_rays_cast;
    solution_.summary.direct_light_seconds += seconds_since(start);
  }
  std::vector<int> rest;
  rest.reserve(others_.size());
  std::set_difference(others_.begin(), others_.end(), add.begin(), add.end(), std::back_inserter(rest));
  others_ = std::move(rest);
  solve();
  return add.size();
}

void ProgressiveExactSolve::set_relative_residual(double relative_residual) {
  options_.radiosity.relative_residual = relative_residual;
}

bool ProgressiveExactSolve::tighten() {
  if (!(solution_.summary.relative_residual > options_.radiosity.relative_residual)) return false;
  solve();
  return true;
}

void ProgressiveExactSolve::solve() {
  ExactSolveSummary& s = solution_.summary;
  // The luminaires' columns from raw_ as it is (no copy of its F first).
  const FormFactorRows rows{raw_.row_patches, with_emitter_columns(scene_, emitter_, raw_, options_.form_factors.threads),
                            raw_.escaped_fraction, raw_.back_hit_fraction, raw_.rays_cast, raw_.seconds};
  s.form_factor_seconds = raw_.seconds;
  s.rays_cast = raw_.rays_cast;
  s.rays_per_second = raw_.seconds > 0.0 ? static_cast<double>(raw_.rays_cast) / raw_.seconds : 0.0;
  double area = 0.0;
  s.mean_escaped_fraction = s.mean_back_hit_fraction = 0.0;
  for (std::size_t i = 0; i < scene_.patches.size(); ++i) {
    const double a = scene_.patches[i].area_m2;
    area += a;
    s.mean_escaped_fraction += a * rows.escaped_fraction[static_cast<Eigen::Index>(i)];
    s.mean_back_hit_fraction += a * rows.back_hit_fraction[static_cast<Eigen::Index>(i)];
  }
  s.mean_escaped_fraction /= area;
  s.mean_back_hit_fraction /= area;
  if (progress_) progress_("radiosity solve (Gauss-Seidel)", 0, 1);
  // After the first solve, from the last one: the rows changed a little (a doubling, a
  // few patches made precise), so Gauss-Seidel needs fewer sweeps to the same residual.
  const bool warm = solution_.radiosity.radiosity_lm_per_m2.rows() > 0;
  const Eigen::MatrixXd last = warm ? solution_.radiosity.radiosity_lm_per_m2 : Eigen::MatrixXd();
  solution_.radiosity = solve_radiosity(scene_, rows.F, options_.radiosity, warm ? &last : nullptr);
  if (progress_) progress_("radiosity solve (Gauss-Seidel)", 1, 1);
  s.solve_seconds += solution_.radiosity.seconds;
  s.iterations = solution_.radiosity.iterations;
  s.relative_residual = solution_.radiosity.relative_residual;
  s.emitted_lm = s.absorbed_lm = s.lost_lm = 0.0;
  account_flux(scene_, rows, solution_.radiosity, s);
}

RadiositySolution ProgressiveExactSolve::solve_lit(const Scene& lit) const {
  if (lit.patches.size() != scene_.patches.size())
    throw std::invalid_argument("ProgressiveExactSolve::solve_lit: not a scene of the same patches");
  const SparseRows F = with_emitter_columns(scene_, emitter_, raw_, options_.form_factors.threads);
  return solve_radiosity(lit, F, options_.radiosity);
}

ExactSolution solve_exact(const Scene& scene, const ExactSolveOptions& options, const ProgressCallback& progress) {
  // Every row at its final ray count at once: nothing to refine.
  ProgressiveExactSolve solve(scene, options, options.other_rays_per_patch, progress);
  return solve.solution();
}

std::ostream& operator<<(std::ostream& os, const ExactSolveSummary& s) {
  const auto flags = os.flags();
  const auto precision = os.precision();
  os << std::fixed << std::setprecision(3);
  os << "BVH: " << s.patches << " patches in " << s.bvh_seconds << " s, ray offset " << std::setprecision(1)
     << s.ray_offset_m * 1e6 << " um\n"
     << std::setprecision(3)
     << "form factors: " << s.rays_cast << " rays in " << s.form_factor_seconds << " s ("
     << std::setprecision(2) << s.rays_per_second / 1e6 << " M rays/s)\n"
     << std::setprecision(3) << "direct light (luminaires): " << s.direct_light_seconds << " s, " << s.shadow_rays
     << " shadow rays\n"
     << "Gauss-Seidel: " << s.iterations << " sweeps in " << s.solve_seconds << " s, relative residual "
     << std::scientific << std::setprecision(1) << s.relative_residual << "\n"
     << std::fixed << std::setprecision(4) << "light escaping the scene: " << 100.0 * s.mean_escaped_fraction
     << " %, absorbed by back faces: " << 100.0 * s.mean_back_hit_fraction << " % (area-weighted)\n"
     << std::setprecision(1) << "flux: emitted " << s.emitted_lm << " lm, absorbed " << s.absorbed_lm
     << " lm, lost on back faces or escaping " << s.lost_lm << " lm";
  if (s.emitted_lm > 0.0)
    os << ": balance " << std::showpos << std::setprecision(3)
       << 100.0 * (s.absorbed_lm + s.lost_lm - s.emitted_lm) / s.emitted_lm << std::noshowpos << " % (ray noise)";
  os.flags(flags);
  os.precision(precision);
  return os;
}

}  // namespace ilp
