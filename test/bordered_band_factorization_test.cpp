// The bordered band factorisation (solvers/bordered_band_factorization.hpp) against a dense LU
// of the same saddle-point matrix, with and without the support's block G, with a banded block
// of the ANCF chain's shape and with a wider one; an indefinite rope block is reported, not
// solved.
#include "crane_twin/solvers/bordered_band_factorization.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

using namespace crane_twin;

namespace {
using SparseMatrix = Eigen::SparseMatrix<double>;

// (n + 3) x (n + 3): A symmetric with half-bandwidth kd (diagonal shifted by `shift` above the
// absolute row sums: positive definite for shift > 0), C = [Ct 0], -G with G symmetric.
SparseMatrix borderedMatrix(int n, int kd, double shift, const Eigen::Matrix3d& Ct,
                            const Eigen::Matrix3d& G, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = j + 1; i <= std::min(n - 1, j + kd); ++i) A(i, j) = A(j, i) = u(rng);
  for (int i = 0; i < n; ++i) A(i, i) = A.row(i).cwiseAbs().sum() + shift;
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j)
    for (int i = std::max(0, j - kd); i <= std::min(n - 1, j + kd); ++i)
      t.emplace_back(i, j, A(i, j));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      t.emplace_back(n + r, c, Ct(r, c));
      t.emplace_back(c, n + r, Ct(r, c));
      t.emplace_back(n + r, n + c, -G(r, c));
    }
  }
  SparseMatrix m(n + 3, n + 3);
  m.setFromTriplets(t.begin(), t.end());
  m.makeCompressed();
  return m;
}

void expectSolvesLikeDenseLu(const SparseMatrix& m, int kd, unsigned seed) {
  BorderedBandFactorization f(m);
  EXPECT_EQ(f.bandwidth(), kd);
  ASSERT_TRUE(f.factorize(m));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd b(m.rows());
  for (int i = 0; i < b.size(); ++i) b(i) = u(rng);
  const Eigen::MatrixXd dense(m);
  const Eigen::VectorXd expected = dense.fullPivLu().solve(b);
  const Eigen::VectorXd x = f.solve(b);
  EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-10 * expected.cwiseAbs().maxCoeff());
  EXPECT_LT((dense * x - b).cwiseAbs().maxCoeff(), 1e-10 * b.cwiseAbs().maxCoeff());
}
}  // namespace

TEST(BorderedBandFactorization, SolvesAnAnchoredRopesSystemAsADenseLu) {
  // The full-order rope's case with an anchor: C = I on the top position, G = 0.
  expectSolvesLikeDenseLu(
      borderedMatrix(6 * 41, 11, 1.0, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero(), 1), 11,
      2);
}

TEST(BorderedBandFactorization, SolvesASupportedRopesSystemAsADenseLu) {
  // A compliant support: G symmetric positive definite, a general C_t.
  Eigen::Matrix3d G;
  G << 2.0, 0.3, -0.1, 0.3, 1.5, 0.2, -0.1, 0.2, 1.2;
  Eigen::Matrix3d Ct;
  Ct << 1.0, 0.2, 0.0, -0.3, 0.9, 0.1, 0.0, 0.4, 1.1;
  expectSolvesLikeDenseLu(borderedMatrix(6 * 61, 11, 0.5, Ct, 1e-3 * G, 3), 11, 4);
  // A wider band (a rigging's bar reaches further down the chain).
  expectSolvesLikeDenseLu(borderedMatrix(120, 17, 0.5, Ct, G, 5), 17, 6);
}

TEST(BorderedBandFactorization, RefusesAnIndefiniteRopeBlock) {
  SparseMatrix m =
      borderedMatrix(60, 5, 1.0, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero(), 7);
  m.coeffRef(30, 30) = -50.0;  // a negative pivot in the rope block
  BorderedBandFactorization f(m);
  EXPECT_FALSE(f.factorize(m));
}

TEST(BorderedBandFactorization, RefusesABorderBeyondTheTopNode) {
  SparseMatrix m =
      borderedMatrix(60, 5, 1.0, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero(), 8);
  m.coeffRef(60, 10) = 1.0;  // a constraint row reaching past the first three unknowns
  m.makeCompressed();
  EXPECT_THROW(BorderedBandFactorization{m}, std::invalid_argument);
}
