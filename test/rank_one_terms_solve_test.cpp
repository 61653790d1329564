// The solve with rank-one terms (solvers/rank_one_terms_solve.hpp) against a dense LU of the
// matrix with the terms added, for terms that stiffen and soften, overlapping and apart; and the
// axial law's rank-one share of an element tangent (ancfAxialTangentShape) against the tangent
// of an unstretched element, where the law's other share vanishes; and a symmetric 3 x 3 block
// (the ground contact's) as such terms.
#include "crane_twin/solvers/rank_one_terms_solve.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

using namespace crane_twin;

TEST(RankOneTermsSolve, SolvesTheMatrixWithItsTermsAsADenseLu) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int n = 40;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) A(i, j) = u(rng);
  A = A * A.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  const Eigen::LLT<Eigen::MatrixXd> llt(A);
  std::vector<RankOneTerm> terms(3);
  const int offsets[3] = {0, 6, 24};  // the first two overlap, as neighbouring elements do
  const double c[3] = {5.0, -2.0, 30.0};
  Eigen::MatrixXd B = A;
  for (int j = 0; j < 3; ++j) {
    terms[j].offset = offsets[j];
    for (int i = 0; i < 12; ++i) terms[j].u(i) = u(rng);
    terms[j].c = c[j];
    Eigen::VectorXd full = Eigen::VectorXd::Zero(n);
    full.segment<12>(offsets[j]) = terms[j].u;
    B += c[j] * full * full.transpose();
  }
  std::vector<Eigen::VectorXd> Y;
  for (const RankOneTerm& t : terms) {
    Eigen::VectorXd full = Eigen::VectorXd::Zero(n);
    full.segment<12>(t.offset) = t.u;
    Y.push_back(llt.solve(full));
  }
  const std::vector<const Eigen::VectorXd*> columns{&Y[0], &Y[1], &Y[2]};
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b(i) = u(rng);
  Eigen::VectorXd x;
  const auto solve = [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(llt.solve(r)); };
  ASSERT_TRUE(solveWithRankOneTerms(solve, terms, columns, b, x));
  const Eigen::VectorXd expected = B.fullPivLu().solve(b);
  EXPECT_LT((x - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  // Without terms: A's own solution.
  ASSERT_TRUE(solveWithRankOneTerms(solve, {}, {}, b, x));
  EXPECT_LT((x - llt.solve(b)).cwiseAbs().maxCoeff(), 1e-14 * x.cwiseAbs().maxCoeff());
}

TEST(RankOneTermsSolve, RefusesATermThatMakesTheMatrixSingular) {
  // A = I, one term -u u^T / |u|^2: A + c u u^T has the null vector u.
  const int n = 12;
  RankOneTerm t;
  t.u.setLinSpaced(1.0, 2.0);
  t.c = -1.0 / t.u.squaredNorm();
  const Eigen::VectorXd y = t.u;
  const std::vector<const Eigen::VectorXd*> columns{&y};
  Eigen::VectorXd x;
  const auto solve = [](const Eigen::VectorXd& r) { return r; };
  EXPECT_FALSE(solveWithRankOneTerms(solve, {t}, columns, Eigen::VectorXd::Ones(n), x));
  EXPECT_THROW(solveWithRankOneTerms(solve, {t, t}, columns, Eigen::VectorXd::Ones(n), x),
               std::invalid_argument);
}

TEST(SymmetricBlockTerms, AddUpToTheBlockAndSolveAsItsDenseMatrix) {
  // A symmetric indefinite 3 x 3 block (the ground contact's change at the payload point: a
  // touchdown's -k on z, the friction's slope on x and y) as rank-one terms: their sum is the
  // block at its rows, and the solve with them is the dense solve of A plus the block.
  Eigen::Matrix3d D;
  D << 4.0e3, -1.5e3, 0.0,  //
      -1.5e3, 2.0e3, 0.0,   //
      0.0, 0.0, -25.0;
  const int n = 20, offset = 5, at = 3;
  std::vector<RankOneTerm> terms;
  ASSERT_EQ(symmetricBlockTerms(D, offset, at, 1e-12 * 4.0e3, terms), 3);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(n, n);
  for (const RankOneTerm& t : terms) {
    Eigen::VectorXd full = Eigen::VectorXd::Zero(n);
    full.segment<12>(t.offset) = t.u;
    sum += t.c * full * full.transpose();
    EXPECT_EQ(t.u.head(at).norm() + t.u.tail(12 - at - 3).norm(), 0.0) << "outside the block";
  }
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(n, n);
  expected.block<3, 3>(offset + at, offset + at) = D;
  EXPECT_LT((sum - expected).cwiseAbs().maxCoeff(), 1e-12 * 4.0e3);
  // The solve with the terms, against a dense LU of A + D at the block.
  const Eigen::MatrixXd A =
      1.0e4 * Eigen::MatrixXd::Identity(n, n) + Eigen::MatrixXd::Constant(n, n, 10.0);  // SPD
  const Eigen::LLT<Eigen::MatrixXd> llt(A);
  std::vector<Eigen::VectorXd> Y;
  std::vector<const Eigen::VectorXd*> columns;
  for (const RankOneTerm& t : terms) {
    Eigen::VectorXd full = Eigen::VectorXd::Zero(n);
    full.segment<12>(t.offset) = t.u;
    Y.push_back(llt.solve(full));
  }
  for (const Eigen::VectorXd& y : Y) columns.push_back(&y);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  Eigen::VectorXd x;
  const auto solve = [&](const Eigen::VectorXd& r) { return Eigen::VectorXd(llt.solve(r)); };
  ASSERT_TRUE(solveWithRankOneTerms(solve, terms, columns, b, x));
  const Eigen::VectorXd dense = (A + expected).fullPivLu().solve(b);
  EXPECT_LT((x - dense).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff());
}

TEST(SymmetricBlockTerms, SkipRoundOffAndRefuseANonFiniteBlock) {
  std::vector<RankOneTerm> terms;
  EXPECT_EQ(symmetricBlockTerms(Eigen::Matrix3d::Zero(), 0, 0, 0.0, terms), 0);
  // A rank-one block: its two zero eigenvalues are round-off.
  const Eigen::Vector3d u(1.0, 2.0, -2.0);
  EXPECT_EQ(symmetricBlockTerms(u * u.transpose(), 0, 0, 1e-12 * 9.0, terms), 1);
  ASSERT_EQ(terms.size(), 1u);
  EXPECT_NEAR(terms[0].c, 9.0, 1e-12);
  Eigen::Matrix3d bad = Eigen::Matrix3d::Identity();
  bad(1, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(symmetricBlockTerms(bad, 0, 0, 0.0, terms), -1);
  EXPECT_THROW(symmetricBlockTerms(Eigen::Matrix3d::Identity(), 0, 10, 0.0, terms),
               std::invalid_argument);
}

TEST(AncfAxialTangentShape, IsTheWholeTangentOfAnUnstretchedStringElement) {
  // An element without bending stiffness, straight along a tilted direction d with its slopes
  // d: |r_x| = 1 at every point, so the symmetric law's N = 0 and its tangent is
  // sum_g w_g l EA v_g v_g^T. The weights sum to the element's length.
  AncfCableProperties p;
  p.length = 0.8;
  p.axial_stiffness = 3.0e7;
  p.bending_stiffness = 0.0;
  p.gauss_points = 5;
  const Eigen::Vector3d d = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const Eigen::Vector3d r0(1.0, 2.0, 3.0);
  Vector12 e;
  e << r0, d, r0 + p.length * d, d;
  Vector12 Q;
  Matrix12 K;
  ancfElasticForce(p, e, Q, &K);
  Matrix12 expected = Matrix12::Zero();
  Vector12 v;
  double weights = 0.0;
  for (int g = 0; g < p.gauss_points; ++g) {
    const double w = ancfAxialTangentShape(p, e, g, v);
    weights += w;
    expected += w * p.axial_stiffness * v * v.transpose();
  }
  EXPECT_NEAR(weights, p.length, 1e-14);
  EXPECT_LT((K - expected).cwiseAbs().maxCoeff(), 1e-9 * K.cwiseAbs().maxCoeff());
  EXPECT_LT(Q.cwiseAbs().maxCoeff(), 1e-6) << "an unstretched element carries no force";
  // Shortened by a tenth and tension-only: every point slack, no tangent at all.
  p.tension_only = true;
  e << r0, 0.9 * d, r0 + 0.9 * p.length * d, 0.9 * d;
  ancfElasticForce(p, e, Q, &K);
  EXPECT_EQ(K.cwiseAbs().maxCoeff(), 0.0);
}
