#include "core/exact/radiosity.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/base/error.h"

namespace ilp {
namespace {

// Residual norms are measured every this many sweeps: a residual costs as much as a sweep.
constexpr int kResidualEvery = 4;

// ||E - (B - R F B)|| for one channel.
double residual_norm(const Scene& scene, const SparseRows& F, const Eigen::VectorXd& E, const Eigen::VectorXd& B,
                     int channel) {
  const Eigen::VectorXd gathered = F * B;
  double sum = 0.0;
  for (Eigen::Index i = 0; i < B.size(); ++i) {
    const double r = E[i] - (B[i] - scene.reflectance(static_cast<int>(i), channel) * gathered[i]);
    sum += r * r;
  }
  return std::sqrt(sum);
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
  const auto start = std::chrono::steady_clock::now();
  RadiositySolution out;
  out.radiosity_lm_per_m2.resize(n, scene.channels);
  out.illuminance_lux.resize(n, scene.channels);

  Eigen::VectorXd E(n);
  for (Eigen::Index i = 0; i < n; ++i) E[i] = scene.patches[i].exitance_lm_per_m2;
  check_finite(E, "exitance", 0);
  const double e_norm = E.norm();

  for (int c = 0; c < scene.channels; ++c) {
    const bool warm = initial && initial->rows() == n && initial->cols() == scene.channels && initial->allFinite();
    Eigen::VectorXd B = warm ? Eigen::VectorXd(initial->col(c)) : E;
    double relative = 0.0;
    int sweeps = 0;
    if (e_norm > 0.0) {
      relative = residual_norm(scene, F, E, B, c) / e_norm;
      while (relative > options.relative_residual) {
        if (sweeps >= options.max_iterations)
          throw NumericalError("radiosity did not converge: relative residual " + std::to_string(relative) +
                               " after " + std::to_string(sweeps) + " Gauss-Seidel sweeps (channel " +
                               std::to_string(c) + ")");
        for (int k = 0; k < kResidualEvery; ++k, ++sweeps) {
          // Gauss-Seidel: B_i = E_i + rho_i sum_j F_ij B_j, using the newest B_j.
          for (Eigen::Index i = 0; i < n; ++i) {
            double gathered = 0.0;
            for (SparseRows::InnerIterator it(F, i); it; ++it) gathered += it.value() * B[it.col()];
            B[i] = E[i] + scene.reflectance(static_cast<int>(i), c) * gathered;
          }
        }
        relative = residual_norm(scene, F, E, B, c) / e_norm;
        if (!std::isfinite(relative)) check_finite(B, "radiosity", c);
      }
    }
    check_finite(B, "radiosity", c);
    out.radiosity_lm_per_m2.col(c) = B;
    out.illuminance_lux.col(c) = F * B;
    out.iterations = std::max(out.iterations, sweeps);
    out.relative_residual = std::max(out.relative_residual, relative);
  }
  out.direct_lux = F * E;
  out.total_lux.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) out.total_lux[i] = photometric(out.illuminance_lux.row(i));
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace ilp
