#include "crane_twin/rope/rope_modes.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <stdexcept>
#include <string>

#include "crane_twin/structure/modal_analysis.hpp"

namespace crane_twin {

SparseMatrix withoutTopPosition(const SparseMatrix& A) {
  const int n = static_cast<int>(A.rows());
  return A.bottomRightCorner(n - 3, n - 3);
}

namespace {

int blockSize(int n3, const RopeModeSettings& s) {
  const int guard = s.guard > 0 ? s.guard : std::max(4, s.kept / 4);
  return std::min(n3, s.kept + guard);
}

// Embed interior vectors (n - 3 rows) into full rope coordinates with zero top position.
Eigen::MatrixXd embed(const Eigen::MatrixXd& X) {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(X.rows() + 3, X.cols());
  P.bottomRows(X.rows()) = X;
  return P;
}

// Rayleigh-Ritz on the block X (interior rows): modes of (X^T K X, X^T M X), mass-normalised.
RopeModes rayleighRitz(const SparseMatrix& Ki, const SparseMatrix& Mi, const Eigen::MatrixXd& X,
                       int kept) {
  const Eigen::MatrixXd KX = Ki * X, MX = Mi * X;
  Eigen::MatrixXd Kh = X.transpose() * KX, Mh = X.transpose() * MX;
  Kh = 0.5 * (Kh + Kh.transpose()).eval();
  Mh = 0.5 * (Mh + Mh.transpose()).eval();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kh, Mh);
  if (es.info() != Eigen::Success) throw std::runtime_error("rope modes: Rayleigh-Ritz failed");
  RopeModes m;
  m.omega2 = es.eigenvalues();  // ascending, eigenvectors M-normalised by Eigen
  m.phi = embed(X * es.eigenvectors());
  m.kept = kept;
  return m;
}

}  // namespace

RopeModes coldRopeModes(const SparseMatrix& K, const SparseMatrix& M, const RopeModeSettings& s) {
  const SparseMatrix Ki = withoutTopPosition(K), Mi = withoutTopPosition(M);
  const int n3 = static_cast<int>(Ki.rows());
  if (s.kept < 1 || s.kept > n3) {
    throw std::invalid_argument("rope modes: kept count must be in 1.." + std::to_string(n3) +
                                ", got " + std::to_string(s.kept));
  }
  const int q = blockSize(n3, s);
  // ARPACK for a small part of the spectrum (its Krylov space is about twice the count);
  // the dense solver when the block is a large part of it or ARPACK cannot run.
  if (q < n3 / 4) {
    try {
      ModalOptions opt;
      opt.count = q;
      opt.shift = s.shift;
      const ModalBasis b = lowestModes(Ki, Mi, opt);
      return RopeModes{b.omega2, embed(b.phi), s.kept};
    } catch (const std::runtime_error&) {
      // K_ii - sigma M_ii not positive definite (compressed rope): dense solver below.
    }
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es{Eigen::MatrixXd(Ki),
                                                               Eigen::MatrixXd(Mi)};
  if (es.info() != Eigen::Success) throw std::runtime_error("rope modes: dense eigensolver failed");
  return RopeModes{es.eigenvalues().head(q), embed(es.eigenvectors().leftCols(q)), s.kept};
}

RopeModes warmRopeModes(const SparseMatrix& K, const SparseMatrix& M, const RopeModes& previous,
                        const RopeModeSettings& s) {
  const SparseMatrix Ki = withoutTopPosition(K), Mi = withoutTopPosition(M);
  const int n3 = static_cast<int>(Ki.rows());
  if (previous.phi.rows() != n3 + 3) throw std::invalid_argument("rope modes: size changed");
  // The rope's matrices are banded in their natural node order: no fill-reducing ordering.
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt(Ki -
                                                                                      s.shift * Mi);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("rope modes: singular K - sigma M");
  // Inverse iteration sweeps on the block, one Rayleigh-Ritz step at the end (the block's
  // columns separate by the factors 1/(w_i^2 - sigma) per sweep; two sweeps keep them
  // independent).
  Eigen::MatrixXd X = previous.phi.bottomRows(n3);
  for (int k = 0; k < std::max(1, s.sweeps); ++k) X = ldlt.solve(Mi * X);
  return rayleighRitz(Ki, Mi, X, s.kept);
}

double ropeModeResidual(const SparseMatrix& K, const SparseMatrix& M, const RopeModes& m,
                        double shift) {
  double r = 0.0;
  for (int i = 0; i < m.kept; ++i) {
    const Eigen::VectorXd Kp = K * m.phi.col(i), Mp = M * m.phi.col(i);
    // Top position rows carry the constraint reaction: excluded.
    const Eigen::VectorXd res = (Kp - m.omega2(i) * Mp).tail(K.rows() - 3);
    r = std::max(r, res.norm() / (Kp - shift * Mp).tail(K.rows() - 3).norm());
  }
  return r;
}

double ropeModeOrthonormalityError(const SparseMatrix& M, const RopeModes& m) {
  const Eigen::MatrixXd P = m.phi.leftCols(m.kept);
  return (P.transpose() * (M * P) - Eigen::MatrixXd::Identity(m.kept, m.kept))
      .cwiseAbs()
      .maxCoeff();
}

}  // namespace crane_twin
