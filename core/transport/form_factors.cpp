#include "core/transport/form_factors.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>

#include "core/transport/sampling.h"
#include "core/base/key_hash.h"

namespace ilp {
namespace {

using RowResult = RayCounts;

// Per-thread scratch: a hit counter per patch (all zero between rows) and the
// patches a row touched. Counting beats sorting the hits of every row.
struct RowScratch {
  std::vector<int> count;
  std::vector<int> touched;
};

// Casts the rays of patch `patch`'s row and calls on_hit(RayHit) for each: the
// same rays, in the same order, for full rows and for bin counts.
// `rays` of them (at most halton.size()): the first ones of the row's sequence.
template <class OnHit>
void cast_row(const Scene& scene, const RayCaster& caster, int patch, const std::vector<std::array<double, 4>>& halton,
              const FormFactorOptions& options, int rays, OnHit&& on_hit) {
  const Patch& p = scene.patches[patch];
  Eigen::Vector3d t, s;
  orthonormal_basis(p.normal, t, s);
  const RotatedHalton4 sequence(options.seed, static_cast<std::uint64_t>(patch));
  const Eigen::Vector3d offset = p.normal * caster.ray_offset_m();
  for (int r = 0; r < rays; ++r) {
    const auto u = sequence.rotate(halton[static_cast<std::size_t>(r)]);
    const Eigen::Vector3d origin = sample_triangle(p.vertices_m[0], p.vertices_m[1], p.vertices_m[2], u[0], u[1]);
    const Eigen::Vector3d direction = sample_cosine_hemisphere(p.normal, t, s, u[2], u[3]);
    on_hit(caster.first_hit(origin + offset, direction), direction);
  }
}

RowResult trace_row(const Scene& scene, const RayCaster& caster, int patch,
                    const std::vector<std::array<double, 4>>& halton, const FormFactorOptions& options, int rays,
                    RowScratch& scratch, const EscapeBins* escapes) {
  RowResult row;
  cast_row(scene, caster, patch, halton, options, rays, [&](const RayHit& hit, const Eigen::Vector3d& direction) {
    if (hit.patch < 0) {
      ++row.escaped;
      if (escapes)
        if (const int b = escapes->bin(direction); b >= 0 && b < escapes->count) row.escaped_bins.emplace_back(b, 1);
    } else if (!hit.front) {
      ++row.back_hits;
    } else if (scratch.count[hit.patch]++ == 0) {
      scratch.touched.push_back(hit.patch);
    }
  });
  std::sort(scratch.touched.begin(), scratch.touched.end());
  row.hits.reserve(scratch.touched.size());
  for (int j : scratch.touched) {
    row.hits.emplace_back(j, scratch.count[j]);
    scratch.count[j] = 0;
  }
  scratch.touched.clear();
  // One (bin, rays) per bin, ascending.
  std::sort(row.escaped_bins.begin(), row.escaped_bins.end());
  std::size_t kept = 0;
  for (std::size_t k = 0; k < row.escaped_bins.size(); ++k)
    if (kept > 0 && row.escaped_bins[kept - 1].first == row.escaped_bins[k].first) ++row.escaped_bins[kept - 1].second;
    else row.escaped_bins[kept++] = row.escaped_bins[k];
  row.escaped_bins.resize(kept);
  return row;
}

void check_request(const Scene& scene, std::span<const int> patches, const FormFactorOptions& options,
                   const char* function) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("FormFactorOptions::" + error);
  for (int patch : patches)
    if (patch < 0 || patch >= static_cast<int>(scene.patches.size()))
      throw std::invalid_argument(std::string(function) + ": patch " + std::to_string(patch) +
                                  " is not in the scene (" + std::to_string(scene.patches.size()) + " patches)");
}

}  // namespace

bool FormFactorOptions::is_valid(std::string* error) const {
  if (rays_per_patch < 1) {
    if (error) *error = "rays_per_patch = " + std::to_string(rays_per_patch) + ": must be >= 1";
    return false;
  }
  if (threads < 0) {
    if (error) *error = "threads = " + std::to_string(threads) + ": must be >= 0 (0 = all cores)";
    return false;
  }
  return true;
}

void assemble_rows(std::span<const RayCounts> counts, std::size_t patches, int rays_per_row, FormFactorRows& out) {
  assemble_rows(counts, patches, std::vector<int>(counts.size(), rays_per_row), out);
}

void assemble_rows(std::span<const RayCounts> counts, std::size_t patches, std::span<const int> rays_per_row,
                   FormFactorRows& out) {
  const std::size_t rows = counts.size();
  out.rays_cast = 0;
  std::size_t nnz = 0;
  for (const RayCounts& r : counts) nnz += r.hits.size();
  out.F.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(patches));
  out.F.reserve(static_cast<Eigen::Index>(nnz));
  out.escaped_fraction.resize(static_cast<Eigen::Index>(rows));
  out.back_hit_fraction.resize(static_cast<Eigen::Index>(rows));
  for (std::size_t r = 0; r < rows; ++r) {
    const double inv_rays = 1.0 / rays_per_row[r];
    out.rays_cast += static_cast<std::uint64_t>(rays_per_row[r]);
    out.F.startVec(static_cast<Eigen::Index>(r));
    for (const auto& [patch, count] : counts[r].hits)
      out.F.insertBack(static_cast<Eigen::Index>(r), patch) = count * inv_rays;
    out.escaped_fraction[static_cast<Eigen::Index>(r)] = counts[r].escaped * inv_rays;
    out.back_hit_fraction[static_cast<Eigen::Index>(r)] = counts[r].back_hits * inv_rays;
  }
  out.F.finalize();
}

FormFactorRows compute_form_factor_rows(const Scene& scene, const RayCaster& caster,
                                        std::span<const int> patches, const FormFactorOptions& options,
                                        const ProgressCallback& progress) {
  return compute_form_factor_rows(scene, caster, patches, std::vector<int>(patches.size(), options.rays_per_patch),
                                  options, progress);
}

FormFactorRows compute_form_factor_rows(const Scene& scene, const RayCaster& caster, std::span<const int> patches,
                                        std::span<const int> rays_per_row, const FormFactorOptions& options,
                                        const ProgressCallback& progress, const EscapeBins* escapes) {
  check_request(scene, patches, options, "compute_form_factor_rows");
  if (rays_per_row.size() != patches.size())
    throw std::invalid_argument("compute_form_factor_rows: " + std::to_string(rays_per_row.size()) + " ray counts for " +
                                std::to_string(patches.size()) + " rows");
  for (int n : rays_per_row)
    if (n < 1 || n > options.rays_per_patch)
      throw std::invalid_argument("compute_form_factor_rows: a row's rays (" + std::to_string(n) + ") must be in [1, " +
                                  std::to_string(options.rays_per_patch) + "]");
  const auto start = std::chrono::steady_clock::now();
  FormFactorRows out;
  out.row_patches.assign(patches.begin(), patches.end());
  const std::size_t rows = out.row_patches.size();
  std::vector<RowResult> results(rows);
  const auto halton = halton4_points(static_cast<std::uint32_t>(options.rays_per_patch));
  tbb::enumerable_thread_specific<RowScratch> scratches;
  std::atomic<std::size_t> done{0};
  constexpr std::size_t kChunk = 64;

  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, kChunk), [&](const tbb::blocked_range<std::size_t>& range) {
      const auto ray_modes = RayCaster::prepare_thread();
      RowScratch& scratch = scratches.local();
      if (scratch.count.empty()) scratch.count.assign(scene.patches.size(), 0);
      for (std::size_t r = range.begin(); r != range.end(); ++r)
        results[r] = trace_row(scene, caster, out.row_patches[r], halton, options, rays_per_row[r], scratch, escapes);
      const std::size_t now = done.fetch_add(range.size()) + range.size();
      if (progress) progress("form factors", now, rows);
    });
  });

  // Assemble in row order, so the result is the same whatever ran where.
  assemble_rows(results, scene.patches.size(), rays_per_row, out);
  if (escapes) {
    out.escaped_by_bin.resize(static_cast<Eigen::Index>(rows), escapes->count);
    for (std::size_t r = 0; r < rows; ++r) {
      out.escaped_by_bin.startVec(static_cast<Eigen::Index>(r));
      for (const auto& [bin, count] : results[r].escaped_bins)
        out.escaped_by_bin.insertBack(static_cast<Eigen::Index>(r), bin) = static_cast<double>(count) / rays_per_row[r];
    }
    out.escaped_by_bin.finalize();
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

Eigen::MatrixXd compute_row_bin_fractions(const Scene& scene, const RayCaster& caster, std::span<const int> patches,
                                          std::span<const int> bin_of_patch, int bins,
                                          const FormFactorOptions& options, const ProgressCallback& progress) {
  check_request(scene, patches, options, "compute_row_bin_fractions");
  if (bin_of_patch.size() != scene.patches.size() || bins < 0)
    throw std::invalid_argument("compute_row_bin_fractions: need one bin per patch (" +
                                std::to_string(scene.patches.size()) + "), got " + std::to_string(bin_of_patch.size()));
  for (int b : bin_of_patch)
    if (b < -1 || b >= bins) throw std::invalid_argument("compute_row_bin_fractions: bin " + std::to_string(b) + " out of range");
  const std::size_t rows = patches.size();
  Eigen::MatrixXd fractions = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows), bins + 2);
  const auto halton = halton4_points(static_cast<std::uint32_t>(options.rays_per_patch));
  const double inv_rays = 1.0 / options.rays_per_patch;
  std::atomic<std::size_t> done{0};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 64), [&](const tbb::blocked_range<std::size_t>& range) {
      const auto ray_modes = RayCaster::prepare_thread();
      std::vector<int> count(static_cast<std::size_t>(bins) + 2);
      for (std::size_t r = range.begin(); r != range.end(); ++r) {
        std::fill(count.begin(), count.end(), 0);
        cast_row(scene, caster, patches[r], halton, options, options.rays_per_patch, [&](const RayHit& hit, const Eigen::Vector3d&) {
          if (hit.patch < 0) ++count[static_cast<std::size_t>(bins)];
          else if (!hit.front) ++count[static_cast<std::size_t>(bins) + 1];
          else if (const int b = bin_of_patch[static_cast<std::size_t>(hit.patch)]; b >= 0) ++count[static_cast<std::size_t>(b)];
        });
        for (int b = 0; b < bins + 2; ++b)
          fractions(static_cast<Eigen::Index>(r), b) = count[static_cast<std::size_t>(b)] * inv_rays;
      }
      const std::size_t now = done.fetch_add(range.size()) + range.size();
      if (progress) progress("row sums", now, rows);
    });
  });
  return fractions;
}

static_assert(field_count<FormFactorOptions>() == 3, "FormFactorOptions changed: hash the new field here (or say why not)");
void hash_fields(KeyWriter& k, const FormFactorOptions& o) {
  k.field("rays_per_patch", o.rays_per_patch).field("seed", o.seed);
  // Not threads: the same rows for any thread count.
}

double surface_form_factor(const Scene& scene, const FormFactorRows& rows, const std::string& from,
                           const std::string& to) {
  const int s_to = scene.find_surface(to);
  double weighted = 0.0, area = 0.0;
  for (std::size_t r = 0; r < rows.row_patches.size(); ++r) {
    const Patch& p = scene.patches[rows.row_patches[r]];
    if (scene.surfaces[p.surface].name != from) continue;
    double f = 0.0;
    for (SparseRows::InnerIterator it(rows.F, static_cast<Eigen::Index>(r)); it; ++it)
      if (scene.patches[it.col()].surface == s_to) f += it.value();
    weighted += p.area_m2 * f;
    area += p.area_m2;
  }
  return weighted / area;
}

}  // namespace ilp
