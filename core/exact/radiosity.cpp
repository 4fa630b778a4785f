#include "core/exact/radiosity.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "core/base/error.h"

namespace ilp {
namespace {

// Residual norms are measured every this many sweeps: a residual costs as much as a sweep.
constexpr int kResidualEvery = 4;

// The colour channels a scene has at most (core/scene/scene.h: 1 or 3).
constexpr int kMaxChannels = 3;
// Patches x channels, a patch's channels side by side (one pass over F reads them all).
using ChannelMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// One Gauss-Seidel sweep, B_i = E_i + rho_i sum_j F_ij B_j with the newest B_j, of
// each channel `active` marks (the others keep their values); kChannels: the scene's,
// or kMaxChannels for any (the unused lanes are never written).
template <int kChannels>
void gauss_seidel_sweep(const SparseRows& F, const Eigen::VectorXd& E, const ChannelMatrix& rho, ChannelMatrix& B,
                        const std::array<bool, kMaxChannels>& active) {
  const int C = static_cast<int>(B.cols());
  for (Eigen::Index i = 0; i < F.rows(); ++i) {
    std::array<double, kChannels> gathered{};
    for (SparseRows::InnerIterator it(F, i); it; ++it) {
      const double* b = &B(it.col(), 0);
      for (int c = 0; c < kChannels && c < C; ++c) gathered[static_cast<std::size_t>(c)] += it.value() * b[c];
    }
    for (int c = 0; c < kChannels && c < C; ++c)
      if (active[static_cast<std::size_t>(c)]) B(i, c) = E[i] + rho(i, c) * gathered[static_cast<std::size_t>(c)];
  }
}

// F X, rows in blocks over the arena's threads (each row summed in its own order, as
// one thread sums it: the same bits for any thread count).
template <class Matrix>
Matrix gather_rows(const SparseRows& F, const Matrix& X, tbb::task_arena& arena) {
  Matrix out = Matrix::Zero(F.rows(), X.cols());
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, F.rows(), 4096), [&](const auto& range) {
      for (Eigen::Index i = range.begin(); i != range.end(); ++i)
        for (SparseRows::InnerIterator it(F, i); it; ++it)
          for (Eigen::Index c = 0; c < X.cols(); ++c) out(i, c) += it.value() * X(it.col(), c);
    });
  });
  return out;
}

void check_finite(const Eigen::VectorXd& v, const char* what, int channel) {
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw NumericalError(std::string(what) + " of patch " + std::to_string(i) + " (channel " +
                           std::to_string(channel) + ") is not finite");
}

}  // namespace

bool RadiosityOptions::is_valid(std::string* error) const {
  if (!(relative_residual > 0.0 && relative_residual < 1.0)) {
    if (error) *error = "relative_residual = " + std::to_string(relative_residual) + ": must be in (0, 1)";
    return false;
  }
  if (max_iterations < 1) {
    if (error) *error = "max_iterations = " + std::to_string(max_iterations) + ": must be >= 1";
    return false;
  }
  return true;
}

double photometric(const Eigen::Ref<const Eigen::RowVectorXd>& channels) {
  if (channels.size() == 1) return channels[0];
  return channels.dot(kLuminanceWeights.transpose());
}

RadiositySolution solve_radiosity(const Scene& scene, const SparseRows& F, const RadiosityOptions& options,
                                  const Eigen::MatrixXd* initial) {
  std::string error;
  if (!options.is_valid(&error)) throw std::invalid_argument("RadiosityOptions::" + error);
  const Eigen::Index n = static_cast<Eigen::Index>(scene.patches.size());
  if (F.rows() != n || F.cols() != n)
    throw std::invalid_argument("solve_radiosity: F is " + std::to_string(F.rows()) + " x " +
                                std::to_string(F.cols()) + ", expected " + std::to_string(n) + " x " +
                                std::to_string(n));
  if (scene.channels < 1 || scene.channels > kMaxChannels)
    throw std::invalid_argument("solve_radiosity: " + std::to_string(scene.channels) + " colour channels");
  const auto start = std::chrono::steady_clock::now();
  RadiositySolution out;
  Eigen::VectorXd E(n);
  for (Eigen::Index i = 0; i < n; ++i) E[i] = scene.patches[i].exitance_lm_per_m2;
  check_finite(E, "exitance", 0);
  const double e_norm = E.norm();
  const int C = scene.channels;
  ChannelMatrix rho(n, C);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < C; ++c) rho(i, c) = scene.reflectance(static_cast<int>(i), c);
  const bool warm = initial && initial->rows() == n && initial->cols() == C && initial->allFinite();
  ChannelMatrix B(n, C);
  for (int c = 0; c < C; ++c) B.col(c) = warm ? Eigen::VectorXd(initial->col(c)) : E;
  // Every channel is its own system; one pass over F sweeps all that are not yet
  // converged, each exactly as a sweep of it alone would (its own newest values, in row
  // order), and each stops at its own residual, as if solved alone.
  std::array<bool, kMaxChannels> active{};
  std::array<double, kMaxChannels> relative{};
  std::array<int, kMaxChannels> sweeps{};
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  auto measure = [&] {
    const ChannelMatrix gathered = gather_rows(F, B, arena);
    for (int c = 0; c < C; ++c) {
      if (!active[static_cast<std::size_t>(c)]) continue;
      const double r = (E - (B.col(c) - rho.col(c).cwiseProduct(gathered.col(c)))).norm() / e_norm;
      relative[static_cast<std::size_t>(c)] = r;
      if (!std::isfinite(r)) check_finite(B.col(c), "radiosity", c);
      active[static_cast<std::size_t>(c)] = r > options.relative_residual;
    }
  };
  if (e_norm > 0.0) {
    active.fill(true);
    measure();
  }
  while (std::any_of(active.begin(), active.begin() + C, [](bool a) { return a; })) {
    for (int c = 0; c < C; ++c)
      if (active[static_cast<std::size_t>(c)] && sweeps[static_cast<std::size_t>(c)] >= options.max_iterations)
        throw NumericalError("radiosity did not converge: relative residual " +
                             std::to_string(relative[static_cast<std::size_t>(c)]) + " after " +
                             std::to_string(sweeps[static_cast<std::size_t>(c)]) + " Gauss-Seidel sweeps (channel " +
                             std::to_string(c) + ")");
    for (int k = 0; k < kResidualEvery; ++k) {
      if (C == 1) {
        gauss_seidel_sweep<1>(F, E, rho, B, active);
      } else {
        gauss_seidel_sweep<kMaxChannels>(F, E, rho, B, active);
      }
    }
    for (int c = 0; c < C; ++c) sweeps[static_cast<std::size_t>(c)] += active[static_cast<std::size_t>(c)] ? kResidualEvery : 0;
    measure();
  }
  for (int c = 0; c < C; ++c) check_finite(B.col(c), "radiosity", c);
  out.radiosity_lm_per_m2 = B;
  out.illuminance_lux = gather_rows(F, B, arena);
  for (int c = 0; c < C; ++c) {
    out.iterations = std::max(out.iterations, sweeps[static_cast<std::size_t>(c)]);
    out.relative_residual = std::max(out.relative_residual, relative[static_cast<std::size_t>(c)]);
  }
  out.direct_lux = gather_rows(F, Eigen::MatrixXd(E), arena).col(0);
  out.total_lux.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) out.total_lux[i] = photometric(out.illuminance_lux.row(i));
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace ilp
