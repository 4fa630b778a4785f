// The interreflection system of the sample-based operator, (I - K) X = B, solved by
// iteration rather than by a dense k x k LU. K = diag(rho) (W + f ambient^T): W is a
// sparse k x k gather matrix (each sample row's rays that land on sample patches, a
// handful per row), plus a rank-one "ambient" term for the rows that saw no sample
// patch (f their row scale, 0 elsewhere). Every row sum of K is below 1 (energy: no
// patch reflects more than it receives), so K is a contraction in the infinity norm
// and the Neumann iteration X <- B + K X converges; its cost grows as k x (nonzeros
// per row) x columns per sweep instead of the LU's k^3.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <optional>

namespace ilp {

struct ContractionSystem {
  Eigen::SparseMatrix<double, Eigen::RowMajor> W;  // k x k, non-negative
  Eigen::VectorXd rho;                             // k reflectances, in [0, 1)
  Eigen::VectorXd fallback_scale;                  // k: f, the ambient row's scale (0: a row of W)
  Eigen::VectorXd ambient;                         // k, sums to 1 (unused where f = 0)
};

// Largest row sum of K (its infinity norm, as every entry is >= 0).
double contraction_factor(const ContractionSystem& system);

// Sweeps the iteration needs at contraction factor q for a relative error bound of
// `tolerance`: the least m with q^m / (1 - q) <= tolerance (B's own size as the unit).
// Infinite for q >= 1.
double sweeps_needed(double q, double tolerance);

struct ContractionSolution {
  Eigen::MatrixXd X;    // k x columns
  int sweeps = 0;
  double error_bound = 0.0;  // a-posteriori: max |X - X*| <= this x max |X|
};

// X = (I - K)^-1 B by X_0 = B, X_m+1 = B + K X_m, stopped when the a-posteriori bound
// q / (1 - q) max|X_m+1 - X_m| (q = contraction_factor) is at most tolerance x max|X|.
// std::nullopt when q >= 1 or max_sweeps pass first. Deterministic: the same sums in
// the same order whatever the thread count.
//
// `largest`, when set (then ambient_product is used), maps this caller's {max|X_m+1 - X_m|, max|X_m+1|} (0 for no
// columns) to the largest over every caller solving some of the columns of one B (a
// split operator build: core/operator/work_share.h); then every caller stops after the
// same sweep and each column has the bits the whole B gives it. A caller with no column
// still takes part in every sweep.
// ambient^T X with each column's value what a product over several columns gives it
// (Eigen sums one column as a dot product, in another order: a lone column is padded
// with a zero column of the same storage order), so that a split build's share of one
// column gets the bits of the whole.
template <class Matrix>
Eigen::RowVectorXd ambient_product(const Eigen::VectorXd& ambient, const Matrix& X) {
  if (X.cols() != 1) return ambient.transpose() * X;
  Matrix padded = Matrix::Zero(X.rows(), 2);
  padded.col(0) = X.col(0);
  const Eigen::RowVectorXd both = ambient.transpose() * padded;
  return both.leftCols(1);
}

std::optional<ContractionSolution> solve_contraction(
    const ContractionSystem& system, const Eigen::MatrixXd& B, double tolerance, int max_sweeps,
    const std::function<std::array<double, 2>(std::array<double, 2>)>& largest = {});

}  // namespace ilp
