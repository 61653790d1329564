// Lowest modes of K phi = w^2 M phi (docs/model.md) by ARPACK's symmetric Lanczos (dsaupd/dseupd)
// in shift-invert mode 3: OP = (K - sigma M)^-1 M, B = M, with (K - sigma M) factorised once by
// CHOLMOD (supernodal LL^T through Eigen's CholmodSupport). K symmetric positive semi-definite,
// M symmetric positive definite. Modes are returned mass-normalised (phi^T M phi = I), sorted by
// frequency.
#pragma once

#include <Eigen/Dense>

#include "crane_twin/elements/sparse_assembly.hpp"

namespace crane_twin {

struct ModalBasis {
  Eigen::VectorXd omega2;  ///< eigenvalues w^2 [rad^2/s^2], ascending
  Eigen::MatrixXd phi;     ///< mass-normalised mode shapes, one per column

  /// Natural frequency of mode i [Hz].
  double frequencyHz(int i) const;
};

struct ModalOptions {
  int count = 10;       ///< number of modes
  double shift = -1.0;  ///< sigma [rad^2/s^2]; negative keeps K - sigma M positive definite
  double tolerance = 1e-12;
  int max_iterations = 1000;
};

/// Throws std::runtime_error when the factorisation or ARPACK fails, std::invalid_argument on
/// bad sizes (count must be in 1 .. n-1).
ModalBasis lowestModes(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& opt);

/// Max over modes of |K phi - w^2 M phi| / |K phi| (relative residual), and
/// max |phi^T M phi - I|: the two checks every mode set must pass.
double modalResidual(const SparseMatrix& K, const SparseMatrix& M, const ModalBasis& b);
double massOrthonormalityError(const SparseMatrix& M, const ModalBasis& b);

}  // namespace crane_twin
