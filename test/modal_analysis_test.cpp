// ARPACK shift-invert modes against Eigen's dense generalised solver on a small 3D frame, and
// the residual / mass-orthonormality checks of docs/model.md.
#include "crane_twin/structure/modal_analysis.hpp"

#include <gtest/gtest.h>

#include "crane_twin/elements/timoshenko_beam_element.hpp"

using namespace crane_twin;

namespace {

// A small 3D portal frame: four columns, a roof ring and a diagonal, base clamped.
void portalFrame(SparseMatrix& K, SparseMatrix& M) {
  const BeamSection s = BeamSection::circularTube(0.2, 0.01, 2.1e11, 8.1e10, 7850);
  std::vector<Eigen::Vector3d> nodes;
  const double a = 4.0, h = 6.0;
  const int per = 6;  // elements per column
  std::vector<std::pair<int, int>> members;
  std::vector<int> top;
  for (int c = 0; c < 4; ++c) {
    const double x = (c == 1 || c == 2) ? a : 0.0, y = (c >= 2) ? a : 0.0;
    for (int k = 0; k <= per; ++k) {
      nodes.emplace_back(x, y, h * k / per);
      if (k > 0) members.emplace_back(nodes.size() - 2, nodes.size() - 1);
    }
    top.push_back(static_cast<int>(nodes.size()) - 1);
  }
  for (int c = 0; c < 4; ++c) members.emplace_back(top[c], top[(c + 1) % 4]);
  members.emplace_back(top[0], top[2]);
  std::vector<int> eqOf(6 * nodes.size(), -1);
  int n = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].z() == 0.0) continue;
    for (int d = 0; d < 6; ++d) eqOf[6 * i + d] = n++;
  }
  SparseAssembler KA(n), MA(n);
  for (auto [i, j] : members) {
    const Eigen::Vector3d ax = (nodes[j] - nodes[i]).normalized();
    const Eigen::Vector3d orient =
        std::abs(ax.z()) > 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
    const auto m = timoshenkoBeamGlobal(s, nodes[i], nodes[j], orient);
    std::vector<int> eq(12);
    for (int d = 0; d < 6; ++d) {
      eq[d] = eqOf[6 * i + d];
      eq[6 + d] = eqOf[6 * j + d];
    }
    KA.add(m.K, eq);
    MA.add(m.M, eq);
  }
  MA.addEntry(eqOf[6 * top[0]], eqOf[6 * top[0]], 500.0);  // a lumped mass breaks symmetry
  K = KA.build();
  M = MA.build();
}

}  // namespace

TEST(ModalAnalysis, MatchesDenseSolverOnSmallFrame) {
  SparseMatrix K, M;
  portalFrame(K, M);
  ModalOptions opt;
  opt.count = 12;
  const ModalBasis b = lowestModes(K, M, opt);
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense{Eigen::MatrixXd(K),
                                                                  Eigen::MatrixXd(M)};
  for (int i = 0; i < opt.count; ++i) {
    EXPECT_NEAR(b.omega2(i), dense.eigenvalues()(i), 1e-8 * dense.eigenvalues()(i)) << i;
  }
  EXPECT_LT(modalResidual(K, M, b), 1e-8);
  EXPECT_LT(massOrthonormalityError(M, b), 1e-10);
  // Mode shapes agree up to sign for well-separated eigenvalues (the first one here).
  const Eigen::VectorXd d0 = dense.eigenvectors().col(0);
  const double c = std::abs(d0.dot(M * b.phi.col(0))) / std::sqrt(d0.dot(M * d0));
  EXPECT_NEAR(c, 1.0, 1e-8);
}

TEST(ModalAnalysis, RejectsBadCounts) {
  SparseMatrix K, M;
  portalFrame(K, M);
  ModalOptions opt;
  opt.count = 0;
  EXPECT_THROW(lowestModes(K, M, opt), std::invalid_argument);
  opt.count = static_cast<int>(K.rows());
  EXPECT_THROW(lowestModes(K, M, opt), std::invalid_argument);
}

TEST(ModalAnalysis, ReportsIndefiniteShiftedMatrix) {
  SparseMatrix K, M;
  portalFrame(K, M);
  ModalOptions opt;
  opt.count = 4;
  opt.shift = 1e9;  // far above the spectrum's bottom: K - sigma M is indefinite
  EXPECT_THROW(lowestModes(K, M, opt), std::runtime_error);
}
