// The iterative interreflection solve against an independent dense LU of the same
// system, its a-posteriori error bound against the true error, and its refusals.
#include "core/operator/contraction_solve.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/LU>
#include <array>
#include <barrier>
#include <optional>
#include <random>
#include <thread>
#include <vector>

namespace ilp {
namespace {

// k patches, ~6 gathers per row, two rows falling back to ambient; every row sum of K
// is rho_a x (a share below 1), the largest near `q`.
ContractionSystem random_system(int k, double q, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ContractionSystem s;
  s.rho = Eigen::VectorXd::Constant(k, q);
  for (int a = 0; a < k; a += 3) s.rho[a] = 0.2 * q;
  s.fallback_scale = Eigen::VectorXd::Zero(k);
  s.ambient = Eigen::VectorXd::NullaryExpr(k, [&] { return u(rng); });
  s.ambient /= s.ambient.sum();
  std::vector<Eigen::Triplet<double>> t;
  for (int a = 0; a < k; ++a) {
    if (a == 5 || a == k - 1) {
      s.fallback_scale[a] = 0.999;
      continue;
    }
    std::vector<double> w(6);
    double sum = 0.0;
    for (double& x : w) sum += (x = u(rng));
    for (double& x : w) t.emplace_back(a, static_cast<int>(u(rng) * k) % k, 0.999 * x / sum);
  }
  s.W.resize(k, k);
  s.W.setFromTriplets(t.begin(), t.end());
  return s;
}

Eigen::MatrixXd dense_solve(const ContractionSystem& s, const Eigen::MatrixXd& B) {
  Eigen::MatrixXd K = Eigen::MatrixXd(s.W);
  for (Eigen::Index a = 0; a < K.rows(); ++a) K.row(a) += s.fallback_scale[a] * s.ambient.transpose();
  K = s.rho.asDiagonal() * K;
  return (Eigen::MatrixXd::Identity(K.rows(), K.cols()) - K).partialPivLu().solve(B);
}

TEST(ContractionSolve, MatchesADenseLuWithinItsOwnErrorBound) {
  for (double q : {0.5, 0.9, 0.99}) {
    SCOPED_TRACE(q);
    const ContractionSystem s = random_system(400, q, 7);
    EXPECT_NEAR(contraction_factor(s), q * 0.999, 1e-9);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(400, 5, [&] { return u(rng); });
    const auto x = solve_contraction(s, B, 1e-10, 10000);
    ASSERT_TRUE(x);
    const Eigen::MatrixXd exact = dense_solve(s, B);
    const double error = (x->X - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
    EXPECT_LE(error, x->error_bound * (1.0 + 1e-6) + 1e-14) << "the bound holds";
    EXPECT_LE(x->error_bound, 1e-10);
    EXPECT_LE(x->sweeps, sweeps_needed(contraction_factor(s), 1e-10)) << "never more than the a-priori count";
  }
}

TEST(ContractionSolve, TheSameWhateverTheThreadCount) {
  const ContractionSystem s = random_system(3000, 0.9, 11);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(3000, 3);
  Eigen::MatrixXd one, many;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = solve_contraction(s, B, 1e-10, 10000)->X;
  }
  many = solve_contraction(s, B, 1e-10, 10000)->X;
  EXPECT_EQ((one - many).cwiseAbs().maxCoeff(), 0.0);
}

TEST(ContractionSolve, NoColumnsIsNoWork) {
  const ContractionSystem s = random_system(50, 0.9, 5);
  const auto x = solve_contraction(s, Eigen::MatrixXd(50, 0), 1e-10, 10);
  ASSERT_TRUE(x);
  EXPECT_EQ(x->X.cols(), 0);
  EXPECT_EQ(x->sweeps, 0);
}

TEST(ContractionSolve, RefusesWhatWouldNotConverge) {
  ContractionSystem s = random_system(50, 0.9, 5);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(50, 1);
  EXPECT_FALSE(solve_contraction(s, B, 1e-10, 3)) << "too few sweeps";
  s.rho.setConstant(1.0 / 0.999);  // rows summing to 1: no contraction
  EXPECT_FALSE(solve_contraction(s, B, 1e-10, 10000));
  EXPECT_TRUE(std::isinf(sweeps_needed(1.0, 1e-10)));
  EXPECT_EQ(sweeps_needed(0.5, 0.25), 3.0);  // 0.5^2 / 0.5 = 0.5 > 0.25, 0.5^3 / 0.5 = 0.25
}

}  // namespace
}  // namespace ilp

namespace ilp {
namespace {

// A split build solves its ranks' columns apart, each sweep's stopping test taking the
// largest change and value over every rank (`largest`): each column then has the bits the
// whole right-hand side gives it, and every part stops after the same sweep, a part with
// no column too.
TEST(ContractionSolve, ColumnsSolvedApartWithTheLargestOverAllHaveTheWholeBits) {
  const ContractionSystem s = random_system(300, 0.9, 11);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::MatrixXd B = Eigen::MatrixXd::NullaryExpr(300, 7, [&] { return u(rng); });
  B.leftCols(3) *= 1e-3;  // the first part's values are small: alone it would judge its own change
  const auto whole = solve_contraction(s, B, 1e-10, 10000);
  ASSERT_TRUE(whole);
  const std::array<std::pair<int, int>, 3> parts{{{0, 3}, {3, 7}, {7, 7}}};
  std::array<std::array<double, 2>, 3> seen{};
  std::barrier sync(3);
  std::array<std::optional<ContractionSolution>, 3> solved;
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < parts.size(); ++i)
    threads.emplace_back([&, i] {
      auto largest = [&, i](std::array<double, 2> mine) {
        seen[i] = mine;
        sync.arrive_and_wait();
        std::array<double, 2> most{0.0, 0.0};
        for (const auto& v : seen) most = {std::max(most[0], v[0]), std::max(most[1], v[1])};
        sync.arrive_and_wait();  // every part has read before the next sweep writes
        return most;
      };
      const auto [first, last] = parts[i];
      solved[i] = solve_contraction(s, B.middleCols(first, last - first), 1e-10, 10000, largest);
    });
  for (std::thread& t : threads) t.join();
  for (std::size_t i = 0; i < parts.size(); ++i) {
    ASSERT_TRUE(solved[i]) << "part " << i;
    EXPECT_EQ(solved[i]->sweeps, whole->sweeps) << "part " << i;
    const auto [first, last] = parts[i];
    const Eigen::MatrixXd expected = whole->X.middleCols(first, last - first);
    ASSERT_EQ(solved[i]->X.cols(), expected.cols());
    EXPECT_TRUE(solved[i]->X == expected) << "part " << i << ": not the whole solve's bits";
  }
}

}  // namespace
}  // namespace ilp
