// Form-factor rows by ray casting: F(i, :) for chosen patches i, the fraction of
// the light leaving patch i diffusely that reaches each patch j directly.
// Rays leave low-discrepancy points on patch i in cosine-weighted directions, so
// F_ij ~ hits_j / rays. Invariants (tested): F_ij >= 0, row sum = 1 - escaped -
// back-hit fractions <= 1, A_i F_ij ~ A_j F_ji.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/base/progress.h"
#include "core/transport/ray_caster.h"
#include "core/scene/scene.h"

namespace ilp {

class KeyWriter;  // core/base/key_hash.h

using SparseRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

struct FormFactorOptions {
  int rays_per_patch = 256;  // per row; the noise of F_ij falls like 1/sqrt(rays)
  std::uint64_t seed = 1;    // same seed, same rows, whatever the thread count
  int threads = 0;           // 0: all cores

  bool is_valid(std::string* error) const;
};

// The operator cache's key (core/base/key_hash.h): every field but threads (the rows
// are the same for any thread count).
void hash_fields(KeyWriter& k, const FormFactorOptions& o);

struct FormFactorRows {
  std::vector<int> row_patches;        // row r of F is patch row_patches[r]
  SparseRows F;                        // #rows by #patches, columns sorted
  Eigen::VectorXd escaped_fraction;    // per row: rays that left the scene
  Eigen::VectorXd back_hit_fraction;   // per row: rays that struck a patch's back side (absorbed)
  std::uint64_t rays_cast = 0;
  double seconds = 0.0;
  // Per row and escape bin (EscapeBins): the fraction of its rays that left the scene in
  // that bin's directions; #rows by bins, empty when no bins were asked for. A row's sum
  // is at most its escaped_fraction (rays of no bin are escaped all the same).
  SparseRows escaped_by_bin = {};
};

// One row's rays, counted: (patch, hits) sorted by patch, and the rays that left the
// scene or struck a back face.
struct RayCounts {
  std::vector<std::pair<int, int>> hits;
  int escaped = 0;
  int back_hits = 0;
  std::vector<std::pair<int, int>> escaped_bins = {};  // (bin, rays) sorted by bin, when bins are asked for
};

// Where the rays that leave the scene go, for whoever gathers them (a sky patch, the
// sun's disc: daylight coefficients, issue 39): the bin of an escaping ray's direction
// (unit, scene frame, z up), in [0, count), or -1 for none. Called from the worker
// threads: `bin` must be safe to call concurrently (a pure function of the direction).
struct EscapeBins {
  int count = 0;
  std::function<int(const Eigen::Vector3d& direction)> bin;
};

// Sets out's F (rows in `counts` order, `patches` columns), escaped and back-hit
// fractions and rays_cast from each row's counts of `rays_per_row` rays.
void assemble_rows(std::span<const RayCounts> counts, std::size_t patches, int rays_per_row, FormFactorRows& out);
// The same with each row's own ray count.
void assemble_rows(std::span<const RayCounts> counts, std::size_t patches, std::span<const int> rays_per_row,
                   FormFactorRows& out);

// Rows for the given patches, in that order (scene.all_patches() for all of them).
// A ray that hits the back of a one-sided patch is absorbed: counted in
// back_hit_fraction, not in F. Throws std::invalid_argument on bad options or a
// patch index outside the scene.
FormFactorRows compute_form_factor_rows(const Scene& scene, const RayCaster& caster,
                                        std::span<const int> patches, const FormFactorOptions& options,
                                        const ProgressCallback& progress = {});
// The same with each row's own ray count, in [1, options.rays_per_patch]: the first
// rays of the row's sequence (a row of n rays is the n-ray row of the overload above).
// `escapes`: where the escaping rays go (FormFactorRows::escaped_by_bin); none: not asked.
FormFactorRows compute_form_factor_rows(const Scene& scene, const RayCaster& caster, std::span<const int> patches,
                                        std::span<const int> rays_per_row, const FormFactorOptions& options,
                                        const ProgressCallback& progress = {}, const EscapeBins* escapes = nullptr);

// The same rays as compute_form_factor_rows, counted instead of stored: for each
// row, the fraction of its rays that struck the front of a patch j in bin
// bin_of_patch[j] (in [0, bins); -1: not counted), then two more columns, the
// escaped and the back-hit fractions: #rows by bins + 2. What gives a gather's
// row sums (METHOD section 3) without keeping n rows in memory.
Eigen::MatrixXd compute_row_bin_fractions(const Scene& scene, const RayCaster& caster, std::span<const int> patches,
                                          std::span<const int> bin_of_patch, int bins,
                                          const FormFactorOptions& options, const ProgressCallback& progress = {});

// Area-weighted form factor from surface `from` to surface `to`, given rows for
// every patch of the scene.
double surface_form_factor(const Scene& scene, const FormFactorRows& rows, const std::string& from,
                           const std::string& to);

}  // namespace ilp
