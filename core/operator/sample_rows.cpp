// How the rows behind the sample operator are cast and read: the goal rows (once per
// set of goals), the sample's rows, their sums split by what the rays struck, and the
// direct light at goal, sample and hit patches with the closed-form luminaire loss.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "core/transport/direct_light.h"
#include "core/operator/sample_operator.h"
#include "core/operator/sample_operator_stages.h"
#include "core/operator/work_share.h"
#include "core/transport/point_gather.h"

namespace ilp {
namespace detail {

SourceTable make_source_table(const Scene& scene, std::span<const LightSource> sources) {
  SourceTable t;
  std::vector<int> source_of_surface(scene.surfaces.size(), -1);
  for (std::size_t l = 0; l < sources.size(); ++l) {
    const int s = sources[l].surface;
    if (s < 0 || s >= static_cast<int>(scene.surfaces.size()))
      throw std::invalid_argument("light source '" + sources[l].name + "': surface " + std::to_string(s) +
                                  " is not in the scene");
    if (source_of_surface[s] >= 0)
      throw std::invalid_argument("light source '" + sources[l].name + "': surface listed twice");
    source_of_surface[s] = static_cast<int>(l);
    const bool luminaire = scene.surfaces[s].is_luminaire();
    t.emitting_index.push_back(luminaire ? -1 : static_cast<int>(t.gathered.size()));
    t.absorbs.push_back(luminaire && !scene.surfaces[s].is_virtual);
    if (!luminaire) t.gathered.push_back(static_cast<int>(l));
    if (luminaire) {
      t.luminaire_surfaces.push_back(s);
      t.luminaire_source.push_back(static_cast<int>(l));
    }
  }
  t.area_m2.assign(sources.size(), 0.0);
  t.gathered_of_patch.assign(scene.patches.size(), -1);
  for (std::size_t i = 0; i < scene.patches.size(); ++i) {
    const int l = source_of_surface[scene.patches[i].surface];
    if (l < 0) continue;
    t.area_m2[l] += scene.patches[i].area_m2;
    if (t.emitting_index[l] < 0) {
      t.luminaire_patches.push_back(static_cast<int>(i));
    } else {
      t.gathered_of_patch[i] = t.emitting_index[l];
    }
  }
  return t;
}

namespace {

std::vector<bool> source_luminaire_mask(const Scene& scene, const SourceTable& sources) {
  std::vector<bool> mask(scene.patches.size(), false);
  for (int p : sources.luminaire_patches) mask[static_cast<std::size_t>(p)] = true;
  return mask;
}

RowSums row_sums_from_rows(const Scene& scene, const SparseRows& F, const SourceTable& sources) {
  const Eigen::Index rows = F.rows();
  RowSums out{Eigen::VectorXd::Zero(rows), Eigen::MatrixXd::Zero(rows, static_cast<Eigen::Index>(sources.gathered.size())),
              Eigen::VectorXd::Zero(rows), Eigen::VectorXd::Zero(rows)};
  const std::vector<bool> luminaire = source_luminaire_mask(scene, sources);
  for (Eigen::Index r = 0; r < rows; ++r)
    for (SparseRows::InnerIterator it(F, r); it; ++it) {
      if (luminaire[static_cast<std::size_t>(it.col())]) {
        out.luminaire[r] += it.value();
        continue;
      }
      out.kept[r] += it.value();
      if (is_reflecting(scene, scene.patches[it.col()])) out.reflecting[r] += it.value();
      if (const int e = sources.gathered_of_patch[it.col()]; e >= 0) out.gathered(r, e) += it.value();
    }
  return out;
}

// The same sums by counting rays only: bin 0 reflecting, 1 + e gathered source e,
// 1 + m + e both (a reflecting emitter), 1 + 2m luminaires.
RowSums row_sums_by_counting(const Scene& scene, const RayCaster& caster, std::span<const int> patches,
                             const SourceTable& sources, const FormFactorOptions& options,
                             const ProgressCallback& progress) {
  const int m = static_cast<int>(sources.gathered.size());
  const std::vector<bool> luminaire = source_luminaire_mask(scene, sources);
  std::vector<int> bin(scene.patches.size(), -1);
  for (std::size_t j = 0; j < scene.patches.size(); ++j) {
    const bool reflecting = is_reflecting(scene, scene.patches[j]);
    const int e = sources.gathered_of_patch[j];
    bin[j] = luminaire[j] ? 1 + 2 * m : e >= 0 ? (reflecting ? 1 + m + e : 1 + e) : (reflecting ? 0 : -1);
  }
  const int bins = 2 + 2 * m;
  const Eigen::MatrixXd f = compute_row_bin_fractions(scene, caster, patches, bin, bins, options, progress);
  RowSums out{f.col(0), Eigen::MatrixXd::Zero(f.rows(), m), f.col(1 + 2 * m), Eigen::VectorXd()};
  for (int e = 0; e < m; ++e) {
    out.reflecting += f.col(1 + m + e);
    out.gathered.col(e) = f.col(1 + e) + f.col(1 + m + e);
  }
  // Columns bins and bins + 1 are the escaped and back-hit fractions.
  out.kept = Eigen::VectorXd::Ones(f.rows()) - f.col(bins) - f.col(bins + 1) - out.luminaire;
  return out;
}

// Rays that strike a luminaire only sample its solid angle, which the closed form
// knows exactly. Each row's other entries are scaled by (kept + hits - closed) / kept
// so that the row loses exactly the closed-form share to luminaires and keeps its
// escaped and back-hit shares. Without this, a room of rho 0.999 whose only loss is
// its luminaires gets that loss from 0 to 3 ray hits per row, and interreflection
// multiplies the noise by 1 / (1 - rho s). `absorbed`: the rows' form factors to the
// luminaires that absorb (DirectRows). Applies the scale to the sums and to D's
// gathered columns.
Eigen::VectorXd apply_closed_form_loss(RowSums& sums, Eigen::MatrixXd& D, const Eigen::MatrixXd& absorbed,
                                       const SourceTable& sources) {
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(sums.kept.size());
  for (Eigen::Index r = 0; r < scale.size(); ++r) {
    const double closed = absorbed.row(r).sum();
    if (sums.kept[r] > 0.0) scale[r] = std::max(0.0, sums.kept[r] + sums.luminaire[r] - closed) / sums.kept[r];
  }
  sums.reflecting.array() *= scale.array();
  for (Eigen::Index e = 0; e < sums.gathered.cols(); ++e) sums.gathered.col(e).array() *= scale.array();
  for (int l : sources.gathered) D.col(l).array() *= scale.array();
  return scale;
}

// D(R,:): illuminance at each receiver per lumen of each source, and the receivers'
// form factors to the luminaires that absorb (columns of the other sources are 0).
struct DirectRows {
  Eigen::MatrixXd D;
  Eigen::MatrixXd absorbed;
};

// A split build's exchange of each receiver point's brightest luminaire (none in one process).
BrightestOverAll brightest_over_shares(const WorkShare& share) {
  if (share.count == 1) return {};
  return [&share](std::vector<double> mine) { return max_over_shares(share, std::move(mine)); };
}

// The columns [first, last) of the sources only (a split build's share of them,
// WorkShare::column_range), each with the bits it has when every column is computed.
DirectRows direct_light_columns(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                const SourceTable& sources, const Eigen::MatrixXd& gathered,
                                const DirectLightOptions& options, std::size_t first, std::size_t last,
                                const BrightestOverAll& over_all = {}) {
  const auto R = static_cast<Eigen::Index>(receivers.size()), L = static_cast<Eigen::Index>(last - first);
  const auto mine = [&](int l) { return static_cast<std::size_t>(l) >= first && static_cast<std::size_t>(l) < last; };
  const auto col = [&](int l) { return static_cast<Eigen::Index>(static_cast<std::size_t>(l) - first); };
  DirectRows out{Eigen::MatrixXd::Zero(R, L), Eigen::MatrixXd::Zero(R, L)};
  std::vector<int> computed;  // indices into luminaire_surfaces of this share's luminaires
  for (std::size_t e = 0; e < sources.luminaire_surfaces.size(); ++e)
    if (mine(sources.luminaire_source[e])) computed.push_back(static_cast<int>(e));
  if ((!computed.empty() || over_all) && R > 0) {
    const LuminaireLight light =
        compute_luminaire_light(scene, caster, receivers, sources.luminaire_surfaces, computed, options, over_all);
    for (std::size_t c = 0; c < computed.size(); ++c) {
      const int l = sources.luminaire_source[static_cast<std::size_t>(computed[c])];
      out.D.col(col(l)) = light.lux_per_lm.col(static_cast<Eigen::Index>(c));
      if (sources.absorbs[static_cast<std::size_t>(l)]) out.absorbed.col(col(l)) = light.form_factor.col(static_cast<Eigen::Index>(c));
    }
  }
  for (std::size_t e = 0; e < sources.gathered.size(); ++e) {
    const int l = sources.gathered[e];
    if (mine(l) && sources.area_m2[l] > 0.0) out.D.col(col(l)) = gathered.col(static_cast<Eigen::Index>(e)) / sources.area_m2[l];
  }
  return out;
}

DirectRows direct_light(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                        std::size_t source_count, const SourceTable& sources, const Eigen::MatrixXd& gathered,
                        const DirectLightOptions& options) {
  return direct_light_columns(scene, caster, receivers, sources, gathered, options, 0, source_count);
}

// D(Q,:) at goal points and their form factors to the absorbing luminaires, as
// direct_light gives them for patches: luminaires through compute_luminaire_light_at_points,
// gathered sources from the points' own rows (fraction of rays reaching the source / its area).
DirectRows point_direct_light(const Scene& scene, const RayCaster& caster, std::span<const ReceiverPoint> points,
                              std::size_t source_count, const SourceTable& table, const Eigen::MatrixXd& gathered,
                              const DirectLightOptions& options) {
  const auto Q = static_cast<Eigen::Index>(points.size()), L = static_cast<Eigen::Index>(source_count);
  DirectRows out{Eigen::MatrixXd::Zero(Q, L), Eigen::MatrixXd::Zero(Q, L)};
  if (!table.luminaire_surfaces.empty() && Q > 0) {
    const LuminaireLight light =
        compute_luminaire_light_at_points(scene, caster, points, table.luminaire_surfaces, options);
    for (std::size_t e = 0; e < table.luminaire_surfaces.size(); ++e) {
      const int l = table.luminaire_source[e];
      out.D.col(l) = light.lux_per_lm.col(static_cast<Eigen::Index>(e));
      if (table.absorbs[static_cast<std::size_t>(l)]) out.absorbed.col(l) = light.form_factor.col(static_cast<Eigen::Index>(e));
    }
  }
  for (std::size_t e = 0; e < table.gathered.size(); ++e) {
    const int l = table.gathered[e];
    if (table.area_m2[l] > 0.0 && gathered.rows() > 0) out.D.col(l) = gathered.col(static_cast<Eigen::Index>(e)) / table.area_m2[l];
  }
  return out;
}

// direct_light at the goal patches in blocks of options.hit_block_patches receivers,
// each block computed by the share that owns it (options.share) and every block's rows
// gathered on every share. A receiver's light depends on its patch alone (its random
// points are seeded by the patch), so the rows have the same bits whatever the split.
DirectRows direct_light_in_blocks(const Scene& scene, const RayCaster& caster, std::span<const int> receivers,
                                  std::size_t source_count, const SourceTable& sources, const Eigen::MatrixXd& gathered,
                                  DirectLightOptions light, const SampleOperatorOptions& options) {
  const WorkShare& share = options.share;
  if (share.count == 1) return direct_light(scene, caster, receivers, source_count, sources, gathered, light);
  const std::size_t block_size = static_cast<std::size_t>(std::max(1, options.hit_block_patches));
  const std::size_t blocks = (receivers.size() + block_size - 1) / block_size;
  const auto L = static_cast<Eigen::Index>(source_count);
  const ProgressCallback progress = light.progress;
  std::size_t mine = 0, done = 0;
  for (std::size_t b = static_cast<std::size_t>(share.index); b < blocks; b += static_cast<std::size_t>(share.count))
    mine += std::min(receivers.size(), (b + 1) * block_size) - b * block_size;
  if (progress)
    light.progress = [&](std::string_view label, std::size_t now, std::size_t) { progress(label, done + now, mine); };
  const std::vector<double> all = gather_blocks(blocks, share, [&](std::size_t b) {
    const std::size_t first = b * block_size, count = std::min(receivers.size(), first + block_size) - first;
    const DirectRows rows = direct_light(scene, caster, receivers.subspan(first, count), source_count, sources,
                                         gathered.middleRows(static_cast<Eigen::Index>(first), static_cast<Eigen::Index>(count)),
                                         light);
    done += count;
    std::vector<double> out(2 * count * static_cast<std::size_t>(L));
    Eigen::Map<RowMajorMatrix>(out.data(), static_cast<Eigen::Index>(count), L) = rows.D;
    Eigen::Map<RowMajorMatrix>(out.data() + count * static_cast<std::size_t>(L), static_cast<Eigen::Index>(count), L) = rows.absorbed;
    return out;
  });
  const auto R = static_cast<Eigen::Index>(receivers.size());
  if (all.size() != 2 * receivers.size() * static_cast<std::size_t>(L))
    throw std::logic_error("direct light in blocks: " + std::to_string(all.size()) + " values gathered, expected " +
                           std::to_string(2 * receivers.size() * static_cast<std::size_t>(L)));
  DirectRows out{Eigen::MatrixXd(R, L), Eigen::MatrixXd(R, L)};
  std::size_t at = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t first = b * block_size, count = std::min(receivers.size(), first + block_size) - first;
    const auto rows = static_cast<Eigen::Index>(count);
    out.D.middleRows(static_cast<Eigen::Index>(first), rows) = Eigen::Map<const RowMajorMatrix>(all.data() + at, rows, L);
    out.absorbed.middleRows(static_cast<Eigen::Index>(first), rows) =
        Eigen::Map<const RowMajorMatrix>(all.data() + at + count * static_cast<std::size_t>(L), rows, L);
    at += 2 * count * static_cast<std::size_t>(L);
  }
  return out;
}

}  // namespace

SampleRows cast_sample_rows(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                            const PatchSample& sample, const SourceTable& table, const SampleOperatorOptions& options,
                            const ProgressCallback& progress, SampleOperatorStats& st) {
  const std::vector<int>& P = sample.patches;
  FormFactorRows rows = compute_form_factor_rows(scene, caster, P, options.form_factors, progress);
  st.sample_row_seconds = rows.seconds;
  st.rays_cast += rows.rays_cast;
  RowSums sums = row_sums_from_rows(scene, rows.F, table);
  std::vector<int> goal_slot(scene.patches.size(), -1), sample_slot(scene.patches.size(), -1);
  for (std::size_t g = 0; g < goals.patches.size(); ++g) goal_slot[goals.patches[g]] = static_cast<int>(g);
  for (std::size_t b = 0; b < P.size(); ++b) sample_slot[P[b]] = static_cast<int>(b);
  return {std::move(rows), std::move(sums), std::move(sample_slot), std::move(goal_slot)};
}

namespace {

// direct_light_at_sample for a split build: this share's columns of D(P,:) only (the
// k x #sources matrices are what a large room holds most of). A row's closed-form loss
// needs its form factors to every absorbing luminaire: those outside the share's columns
// are computed too (form factors only kept), and each row's sum runs over a full-width
// row in column order, the expression apply_closed_form_loss sums, so the scale has the
// single process's bits.
SampleDirect direct_light_at_sample_columns(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                            const std::vector<int>& P, const std::vector<int>& goal_slot,
                                            const std::vector<int>& need_direct,
                                            const std::vector<Eigen::Index>& need_direct_row,
                                            const Eigen::MatrixXd& gathered_needed, SampleRows& rows,
                                            const SourceTable& table, const DirectLightOptions& sample_light,
                                            const WorkShare& share, SampleOperatorStats& st) {
  const std::span<const LightSource> sources = goals.sources;
  const Eigen::Index k = static_cast<Eigen::Index>(P.size());
  const Eigen::Index L = static_cast<Eigen::Index>(sources.size());
  const auto [c0, c1] = share.column_range(sources.size());
  const Eigen::Index first = static_cast<Eigen::Index>(c0), Ls = static_cast<Eigen::Index>(c1 - c0);
  // One call (one exchange of the points' brightest): this share's luminaires, then the
  // absorbing luminaires outside its columns (their form factors only are read).
  std::vector<int> computed;                 // indices into luminaire_surfaces
  std::vector<Eigen::Index> computed_source;  // their source (column of T)
  for (std::size_t e = 0; e < table.luminaire_surfaces.size(); ++e)
    if (const auto l = static_cast<std::size_t>(table.luminaire_source[e]); l >= c0 && l < c1) {
      computed.push_back(static_cast<int>(e));
      computed_source.push_back(static_cast<Eigen::Index>(l));
    }
  const std::size_t own = computed.size();
  for (std::size_t e = 0; e < table.luminaire_surfaces.size(); ++e)
    if (const auto l = static_cast<std::size_t>(table.luminaire_source[e]); table.absorbs[l] && (l < c0 || l >= c1)) {
      computed.push_back(static_cast<int>(e));
      computed_source.push_back(static_cast<Eigen::Index>(l));
    }
  const LuminaireLight light = compute_luminaire_light(scene, caster, need_direct, table.luminaire_surfaces, computed,
                                                       sample_light, brightest_over_shares(share));
  DirectRows mine{Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(need_direct.size()), Ls),
                  Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(need_direct.size()), Ls)};
  for (std::size_t c = 0; c < own && !need_direct.empty(); ++c) {
    const Eigen::Index col = computed_source[c] - first;
    mine.D.col(col) = light.lux_per_lm.col(static_cast<Eigen::Index>(c));
    if (table.absorbs[static_cast<std::size_t>(computed_source[c])]) mine.absorbed.col(col) = light.form_factor.col(static_cast<Eigen::Index>(c));
  }
  for (std::size_t e = 0; e < table.gathered.size(); ++e)
    if (const auto l = static_cast<std::size_t>(table.gathered[e]); l >= c0 && l < c1 && table.area_m2[l] > 0.0)
      mine.D.col(static_cast<Eigen::Index>(l - c0)) = gathered_needed.col(static_cast<Eigen::Index>(e)) / table.area_m2[l];
  std::vector<Eigen::Index> row_of(static_cast<std::size_t>(k), -1);  // a computed row's index in need_direct
  for (std::size_t m = 0; m < need_direct_row.size(); ++m) row_of[static_cast<std::size_t>(need_direct_row[m])] = static_cast<Eigen::Index>(m);
  SampleDirect out;
  Eigen::MatrixXd& D_P = out.D_P;
  D_P.resize(k, Ls);
  Eigen::VectorXd closed(k);
  Eigen::MatrixXd full(1, L);  // one row's form factors to every source (0 but absorbing luminaires)
  for (Eigen::Index b = 0; b < k; ++b) {
    if (const int g = goal_slot[static_cast<std::size_t>(P[static_cast<std::size_t>(b)])]; g >= 0) {
      D_P.row(b) = goals.direct_lux_per_lm.row(g).segment(first, Ls);
      full.row(0) = goals.luminaire_form_factor.row(g);
    } else {
      const Eigen::Index m = row_of[static_cast<std::size_t>(b)];
      D_P.row(b) = mine.D.row(m);
      full.setZero();
      full.row(0).segment(first, Ls) = mine.absorbed.row(m);
      for (std::size_t j = own; j < computed.size(); ++j) full(0, computed_source[j]) = light.form_factor(m, static_cast<Eigen::Index>(j));
    }
    closed[b] = full.row(0).sum();
  }
  st.direct_rows += need_direct.size();
  // apply_closed_form_loss's scale, from the rows' sums; the gathered sources' columns
  // of the computed rows scaled (rows copied from the goals are scaled already).
  RowSums& sums = rows.sums;
  Eigen::VectorXd scale = Eigen::VectorXd::Ones(k);
  for (Eigen::Index r = 0; r < k; ++r)
    if (sums.kept[r] > 0.0) scale[r] = std::max(0.0, sums.kept[r] + sums.luminaire[r] - closed[r]) / sums.kept[r];
  sums.reflecting.array() *= scale.array();
  for (Eigen::Index e = 0; e < sums.gathered.cols(); ++e) sums.gathered.col(e).array() *= scale.array();
  for (int l : table.gathered)
    if (static_cast<std::size_t>(l) >= c0 && static_cast<std::size_t>(l) < c1)
      for (Eigen::Index r : need_direct_row) D_P(r, l - first) *= scale[r];
  out.kept_scale = std::move(scale);
  require_finite(D_P, "direct light", scene, P, sources.subspan(c0, c1 - c0));
  return out;
}

}  // namespace

// Direct light at the sample patches. A census (every patch its own stratum) takes the
// goals' precise estimate, copied where a sample patch is a goal; a sample takes
// options.sample_direct_light at every sample patch, goal or not, so that the sample's
// emission does not depend on which patches are goals.
SampleDirect direct_light_at_sample(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                    const PatchSample& sample, SampleRows& rows, const SourceTable& table,
                                    const SampleOperatorOptions& options, const ProgressCallback& progress,
                                    SampleOperatorStats& st) {
  const std::span<const LightSource> sources = goals.sources;
  const std::vector<int>& P = sample.patches;
  const Eigen::Index k = static_cast<Eigen::Index>(P.size());
  const Eigen::Index L = static_cast<Eigen::Index>(sources.size());
  const bool census = sample.census;
  std::vector<int> goal_slot = rows.goal_slot;
  if (!census) std::fill(goal_slot.begin(), goal_slot.end(), -1);
  std::vector<int> need_direct;
  std::vector<Eigen::Index> need_direct_row;
  for (Eigen::Index b = 0; b < k; ++b)
    if (goal_slot[P[b]] < 0) {
      need_direct.push_back(P[b]);
      need_direct_row.push_back(b);
    }
  Eigen::MatrixXd gathered_needed(static_cast<Eigen::Index>(need_direct.size()), rows.sums.gathered.cols());
  for (std::size_t m = 0; m < need_direct.size(); ++m)
    gathered_needed.row(static_cast<Eigen::Index>(m)) = rows.sums.gathered.row(need_direct_row[m]);
  DirectLightOptions sample_light = census ? options.direct_light : options.sample_direct_light;
  sample_light.seed = options.direct_light.seed;
  sample_light.threads = options.direct_light.threads;
  sample_light.progress = progress;
  sample_light.progress_label = "direct light (sample)";
  if (options.share.count > 1)
    return direct_light_at_sample_columns(scene, caster, goals, P, goal_slot, need_direct, need_direct_row, gathered_needed,
                                          rows, table, sample_light, options.share, st);
  const DirectRows D_new = direct_light(scene, caster, need_direct, sources.size(), table, gathered_needed, sample_light);
  SampleDirect out;
  Eigen::MatrixXd& D_P = out.D_P;
  D_P.resize(k, L);
  Eigen::MatrixXd absorbed_P(k, L);
  for (Eigen::Index b = 0; b < k; ++b)
    if (goal_slot[P[b]] >= 0) {
      D_P.row(b) = goals.direct_lux_per_lm.row(goal_slot[P[b]]);
      absorbed_P.row(b) = goals.luminaire_form_factor.row(goal_slot[P[b]]);
    }
  for (std::size_t m = 0; m < need_direct.size(); ++m) {
    D_P.row(need_direct_row[m]) = D_new.D.row(static_cast<Eigen::Index>(m));
    absorbed_P.row(need_direct_row[m]) = D_new.absorbed.row(static_cast<Eigen::Index>(m));
  }
  st.direct_rows += need_direct.size();
  // Rows copied from the goals are scaled already (same patch, same rays, same scale).
  Eigen::MatrixXd D_scaled = D_P;
  out.kept_scale = apply_closed_form_loss(rows.sums, D_scaled, absorbed_P, table);
  for (std::size_t m = 0; m < need_direct.size(); ++m) D_P.row(need_direct_row[m]) = D_scaled.row(need_direct_row[m]);
  require_finite(D_P, "direct light", scene, P, sources);
  return out;
}

namespace {

// Adds F(rows,:) B1 over the hits in slots [first, first + D.rows()) to `out` (rows by
// #sources), B1_j = rho_j(channel) D(slot j - first,:). Rows are split among threads;
// each row's sum is its own, in the row's column order, so the split changes nothing.
void gather_block(const Scene& scene, const SparseRows& F, const std::vector<int>& slot, int first,
                  const RowMajorMatrix& D, int channel, Eigen::Map<RowMajorMatrix> out) {
  const int last = first + static_cast<int>(D.rows());
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, F.rows(), 64), [&](const tbb::blocked_range<Eigen::Index>& r) {
    for (Eigen::Index row = r.begin(); row < r.end(); ++row)
      for (SparseRows::InnerIterator it(F, row); it; ++it)
        if (const int s = slot[it.col()]; s >= first && s < last)
          out.row(row) += it.value() * scene.reflectance(static_cast<int>(it.col()), channel) * D.row(s - first);
  });
}

}  // namespace

// Refinement: direct light at every reflecting patch the sample and goal rows hit.
// Goal and sample patches reuse theirs; the others are only ever read through a
// row's average over its hits, so a cheaper estimate (hit_direct_light) serves.
FirstReflection first_reflection_at_rows(const Scene& scene, const RayCaster& caster, const GoalRows& goals,
                                         const SampleRows& rows, const SampleDirect& direct, const SourceTable& table,
                                         const SampleOperatorOptions& options, const ProgressCallback& progress,
                                         SampleOperatorStats& st) {
  if (options.hit_block_patches < 1)
    throw std::invalid_argument("hit_block_patches = " + std::to_string(options.hit_block_patches) + ": must be >= 1");
  const std::span<const LightSource> sources = goals.sources;
  std::vector<int> hit_slot(scene.patches.size(), -1);
  std::vector<int> hit;
  auto collect = [&](const SparseRows& F) {
    for (Eigen::Index r = 0; r < F.rows(); ++r)
      for (SparseRows::InnerIterator it(F, r); it; ++it)
        if (hit_slot[it.col()] < 0 && is_reflecting(scene, scene.patches[it.col()])) {
          hit_slot[it.col()] = static_cast<int>(hit.size());
          hit.push_back(static_cast<int>(it.col()));
        }
  };
  collect(rows.rows.F);
  collect(goals.rows->F);
  if (goals.point_rows) collect(goals.point_rows->F);
  auto is_cheap = [&](int patch) { return rows.sample_slot[patch] < 0 && rows.goal_slot[patch] < 0; };
  st.cheap_direct_rows = static_cast<std::size_t>(std::count_if(hit.begin(), hit.end(), is_cheap));

  // Gathered sources keep the plain form (their direct light is known only where rows were cast).
  DirectLightOptions cheap_options = options.hit_direct_light;
  cheap_options.seed = options.direct_light.seed;
  cheap_options.threads = options.direct_light.threads;
  cheap_options.form_factors = false;  // only D is read here
  cheap_options.progress_label = "direct light (patches the rows hit)";
  const std::size_t block_size = static_cast<std::size_t>(options.hit_block_patches);
  const std::size_t blocks = (hit.size() + block_size - 1) / block_size;
  // A split build computes its share's columns (sources) of every block: no exchange here.
  if (std::string error; !options.share.is_valid(&error)) throw std::invalid_argument(error);
  // Plain names, not a structured binding: the lambda below captures them (clang 14 refuses a binding).
  const auto range = options.share.column_range(sources.size());
  const std::size_t c0 = range.first, c1 = range.second;
  const auto first_col = static_cast<Eigen::Index>(c0), Ls = static_cast<Eigen::Index>(c1 - c0);
  const std::span<const LightSource> my_sources = sources.subspan(c0, c1 - c0);
  const std::size_t cheap_total = st.cheap_direct_rows;
  std::size_t done = 0;
  if (progress)
    cheap_options.progress = [&](std::string_view label, std::size_t now, std::size_t) { progress(label, done + now, cheap_total); };

  const Eigen::Index k = rows.rows.F.rows(), G = goals.rows->F.rows();
  const Eigen::Index Q = goals.point_rows ? goals.point_rows->F.rows() : 0;
  const int channels = scene.channels;
  const std::size_t per_channel = static_cast<std::size_t>((k + G + Q) * Ls);
  if (direct.D_P.cols() != Ls)
    throw std::logic_error("first_reflection_at_rows: the sample's direct light has " + std::to_string(direct.D_P.cols()) +
                           " columns, this share computes " + std::to_string(Ls));
  // Block b's partial sums: per channel, the sample's, goals' and points' rows (row-major),
  // this share's columns; added in block order, as every path adds them.
  auto partial = [&](std::size_t b) {
    const std::size_t first = b * block_size, last = std::min(hit.size(), first + block_size);
    RowMajorMatrix D(static_cast<Eigen::Index>(last - first), Ls);
    std::vector<int> cheap;
    std::vector<Eigen::Index> cheap_row;
    for (std::size_t h = first; h < last; ++h) {
      const auto row = static_cast<Eigen::Index>(h - first);
      if (rows.sample_slot[hit[h]] >= 0) D.row(row) = direct.D_P.row(rows.sample_slot[hit[h]]);
      else if (rows.goal_slot[hit[h]] >= 0) D.row(row) = goals.direct_lux_per_lm.row(rows.goal_slot[hit[h]]).segment(first_col, Ls);
      else {
        cheap.push_back(hit[h]);
        cheap_row.push_back(row);
      }
    }
    {
      const Eigen::MatrixXd D_cheap = direct_light_columns(
          scene, caster, cheap, table,
          Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(cheap.size()), static_cast<Eigen::Index>(table.gathered.size())),
          cheap_options, c0, c1, brightest_over_shares(options.share)).D;
      done += cheap.size();
      for (std::size_t m = 0; m < cheap.size(); ++m) D.row(cheap_row[m]) = D_cheap.row(static_cast<Eigen::Index>(m));
    }
    for (std::size_t e = 0; e < table.gathered.size(); ++e)
      if (const auto l = static_cast<std::size_t>(table.gathered[e]); l >= c0 && l < c1) D.col(static_cast<Eigen::Index>(l - c0)).setZero();
    const std::vector<int> labels(hit.begin() + static_cast<std::ptrdiff_t>(first), hit.begin() + static_cast<std::ptrdiff_t>(last));
    require_finite(Eigen::MatrixXd(D), "direct light", scene, labels, my_sources);
    std::vector<double> out(per_channel * static_cast<std::size_t>(channels), 0.0);
    for (int c = 0; c < channels; ++c) {
      double* at = out.data() + per_channel * static_cast<std::size_t>(c);
      gather_block(scene, rows.rows.F, hit_slot, static_cast<int>(first), D, c, Eigen::Map<RowMajorMatrix>(at, k, Ls));
      gather_block(scene, goals.rows->F, hit_slot, static_cast<int>(first), D, c, Eigen::Map<RowMajorMatrix>(at + k * Ls, G, Ls));
      if (Q > 0)
        gather_block(scene, goals.point_rows->F, hit_slot, static_cast<int>(first), D, c,
                     Eigen::Map<RowMajorMatrix>(at + (k + G) * Ls, Q, Ls));
    }
    return out;
  };
  // Every block on this process (its columns), in block order.
  std::vector<double> total = reduce_blocks(blocks, WorkShare{}, partial);
  if (total.empty()) total.assign(per_channel * static_cast<std::size_t>(channels), 0.0);  // no hit at all
  if (total.size() != per_channel * static_cast<std::size_t>(channels))
    throw std::logic_error("first_reflection_at_rows: " + std::to_string(total.size()) + " values reduced, expected " +
                           std::to_string(per_channel * static_cast<std::size_t>(channels)));
  FirstReflection out;
  for (int c = 0; c < channels; ++c) {
    const double* at = total.data() + per_channel * static_cast<std::size_t>(c);
    out.at_sample.push_back(Eigen::Map<const RowMajorMatrix>(at, k, Ls));
    out.at_goals.push_back(Eigen::Map<const RowMajorMatrix>(at + k * Ls, G, Ls));
    if (goals.point_rows) out.at_points.push_back(Eigen::Map<const RowMajorMatrix>(at + (k + G) * Ls, Q, Ls));
  }
  return out;
}

}  // namespace detail

using namespace detail;

GoalRows compute_goal_rows(const Scene& scene, const RayCaster& caster, std::span<const int> goal_patches,
                           std::span<const LightSource> sources, const SampleOperatorOptions& options,
                           const ProgressCallback& progress) {
  return compute_goal_rows(scene, caster, goal_patches, {}, sources, options, progress);
}

GoalRows compute_goal_rows(const Scene& scene, const RayCaster& caster, std::span<const int> goal_patches,
                           std::span<const ReceiverPoint> goal_points, std::span<const LightSource> sources,
                           const SampleOperatorOptions& options, const ProgressCallback& progress) {
  const auto start = std::chrono::steady_clock::now();
  require_valid_materials(scene);
  for (int p : goal_patches)
    if (p < 0 || p >= static_cast<int>(scene.patches.size()))
      throw std::invalid_argument("compute_goal_rows: patch " + std::to_string(p) + " is not in the scene");
  const SourceTable table = make_source_table(scene, sources);
  GoalRows goals;
  goals.patches.assign(goal_patches.begin(), goal_patches.end());
  goals.sources.assign(sources.begin(), sources.end());
  const bool any_reflecting = !reflecting_patches(scene).empty();
  const Eigen::Index G = static_cast<Eigen::Index>(goal_patches.size());
  RowSums sums{Eigen::VectorXd::Zero(G), Eigen::MatrixXd::Zero(G, static_cast<Eigen::Index>(table.gathered.size())),
               Eigen::VectorXd::Zero(G), Eigen::VectorXd::Zero(G)};
  if (options.indirect == IndirectMethod::exact_second_bounce && any_reflecting) {
    goals.rows = compute_form_factor_rows(scene, caster, goal_patches, options.form_factors, progress);
    sums = row_sums_from_rows(scene, goals.rows->F, table);
    goals.rays_cast = goals.rows->rays_cast;
  } else if (any_reflecting || !table.gathered.empty()) {
    sums = row_sums_by_counting(scene, caster, goal_patches, table, options.form_factors, progress);
    goals.rays_cast = static_cast<std::uint64_t>(goal_patches.size()) * options.form_factors.rays_per_patch;
  }
  DirectLightOptions goal_light = options.direct_light;
  goal_light.progress = progress;
  goal_light.progress_label = "direct light (goals)";
  DirectRows direct = direct_light_in_blocks(scene, caster, goal_patches, sources.size(), table, sums.gathered, goal_light,
                                             options);
  goals.direct_lux_per_lm = std::move(direct.D);
  goals.luminaire_form_factor = std::move(direct.absorbed);
  goals.kept_scale = apply_closed_form_loss(sums, goals.direct_lux_per_lm, goals.luminaire_form_factor, table);
  goals.reflecting_fraction = sums.reflecting;
  require_finite(goals.direct_lux_per_lm, "direct light", scene, goal_patches, sources);

  // Goal points: their own full rows, then exact direct light at the point.
  goals.points.assign(goal_points.begin(), goal_points.end());
  const Eigen::Index Q = static_cast<Eigen::Index>(goal_points.size());
  RowSums point_sums{Eigen::VectorXd::Zero(Q), Eigen::MatrixXd::Zero(Q, static_cast<Eigen::Index>(table.gathered.size())),
                     Eigen::VectorXd::Zero(Q), Eigen::VectorXd::Zero(Q)};
  if (Q > 0 && (any_reflecting || !table.gathered.empty())) {
    // Points are few (a grid has hundreds, a mesh tens of thousands of patches) and each
    // stands alone (no area to average over): their rows get kPointRayFactor x the rays.
    FormFactorOptions point_options = options.form_factors;
    point_options.rays_per_patch = options.form_factors.rays_per_patch * kPointRayFactor;
    goals.point_rows = compute_point_rows(scene, caster, goal_points, point_options, progress);
    point_sums = row_sums_from_rows(scene, goals.point_rows->F, table);
    goals.rays_cast += goals.point_rows->rays_cast;
  }
  DirectRows point_direct = point_direct_light(scene, caster, goal_points, sources.size(), table, point_sums.gathered,
                                               options.direct_light);
  goals.point_direct_lux_per_lm = std::move(point_direct.D);
  goals.point_kept_scale = apply_closed_form_loss(point_sums, goals.point_direct_lux_per_lm, point_direct.absorbed, table);
  goals.point_reflecting_fraction = point_sums.reflecting;
  if (Q > 0) {
    const std::vector<int> labels = goal_row_labels({}, goal_points.size());
    require_finite(goals.point_direct_lux_per_lm, "direct light", scene, labels, sources);
  }
  goals.seconds = seconds_since(start);
  return goals;
}

}  // namespace ilp
