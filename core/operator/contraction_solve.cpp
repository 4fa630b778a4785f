#include "core/operator/contraction_solve.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ilp {

double contraction_factor(const ContractionSystem& s) {
  const double ambient_sum = s.ambient.sum();
  double q = 0.0;
  for (Eigen::Index a = 0; a < s.W.rows(); ++a)
    q = std::max(q, s.rho[a] * (s.W.row(a).sum() + s.fallback_scale[a] * ambient_sum));
  return q;
}

double sweeps_needed(double q, double tolerance) {
  if (!(q < 1.0)) return std::numeric_limits<double>::infinity();
  if (q <= 0.0) return 1.0;
  return std::max(1.0, std::ceil(std::log(tolerance * (1.0 - q)) / std::log(q)));
}

namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// next = B + diag(rho) (W X + f (ambient^T X)), row by row (rows in parallel: each
// row's sum is its own, so the result does not depend on the split). Row-major, as
// each gather adds a whole row.
void sweep(const ContractionSystem& s, const RowMajorMatrix& B, const RowMajorMatrix& X, RowMajorMatrix& next,
           bool as_many_columns) {
  const Eigen::RowVectorXd ambient_x = as_many_columns ? ambient_product(s.ambient, X) : Eigen::RowVectorXd(s.ambient.transpose() * X);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, X.rows(), 256), [&](const tbb::blocked_range<Eigen::Index>& r) {
    Eigen::RowVectorXd row(X.cols());
    for (Eigen::Index a = r.begin(); a < r.end(); ++a) {
      row.setZero();
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(s.W, a); it; ++it)
        row += it.value() * X.row(it.col());
      if (s.fallback_scale[a] > 0.0) row += s.fallback_scale[a] * ambient_x;
      next.row(a) = B.row(a) + s.rho[a] * row;
    }
  });
}

}  // namespace

std::optional<ContractionSolution> solve_contraction(
    const ContractionSystem& s, const Eigen::MatrixXd& B, double tolerance, int max_sweeps,
    const std::function<std::array<double, 2>(std::array<double, 2>)>& largest) {
  const double q = contraction_factor(s);
  if (!(q < 1.0)) return std::nullopt;
  ContractionSolution out;
  if (B.size() == 0 && !largest) {  // no source (or no sample): nothing to solve, and no max of nothing
    out.X = B;
    return out;
  }
  const RowMajorMatrix b = B;
  RowMajorMatrix x = b, next(B.rows(), B.cols());
  const double factor = q / (1.0 - q);
  for (int m = 1; m <= max_sweeps; ++m) {
    sweep(s, b, x, next, static_cast<bool>(largest));
    double change = x.size() > 0 ? (next - x).cwiseAbs().maxCoeff() : 0.0;
    x.swap(next);
    out.sweeps = m;
    double size = x.size() > 0 ? x.cwiseAbs().maxCoeff() : 0.0;
    if (largest) {
      const std::array<double, 2> most = largest({change, size});
      change = most[0];
      size = most[1];
    }
    out.error_bound = size > 0.0 ? factor * change / size : 0.0;
    if (out.error_bound <= tolerance || change == 0.0) {
      out.X = x;
      return out;
    }
  }
  return std::nullopt;
}

}  // namespace ilp
