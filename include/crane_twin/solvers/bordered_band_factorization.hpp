// The full-order rope's Newton matrix solved as what it is: a banded rope block bordered by the
// three rows of the top constraint (FullOrderSolver, docs/model.md "Full-order solution"),
//   [ A   C^T ] [x1]   [b1]     A (n x n) symmetric positive definite with half-bandwidth kd
//   [ C   -G  ] [x2] = [b2],    (a M + gamma h C_t + beta h^2 K_t of the ANCF chain), C = [C_t 0]
//                               (3 x n) the constraint's Jacobian on the top node's position (the
//                               first three unknowns), G (3 x 3) the support's Schur complement.
// A is factorised in reversed order, P A P^T = L L^T (LAPACK dpbtrf in band storage,
// O(n kd^2); P reverses the unknowns, so the top node comes last). Then L^-1 P C^T is nonzero in
// its last three rows only, Z = L_tt^-1 C_t^T (L_tt the trailing 3 x 3 block of L), and
//   S = C A^-1 C^T + G = Z^T Z + G,
//   u = L^-1 P b1 (forward),  x2 = S^-1 (Z^T u_t - b2),  P x1 = L^-T (u - [0; Z x2]) (backward):
// two band triangular solves per right-hand side (O(n kd)). The same solution as an LDL^T of the
// whole matrix (whose last three pivots are -S), without a general sparse factorisation's
// symbolic overhead. Only the lower triangle of the matrix is read, as a symmetric LDL^T reads it.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <vector>

namespace crane_twin {

class BorderedBandFactorization {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  /// The pattern of the (n + 3) x (n + 3) matrix, compressed, column-major (its values are read
  /// by factorize): its last three rows and columns are the border, whose entries left of the
  /// diagonal block lie in the first three columns. Throws std::invalid_argument otherwise, or
  /// for a matrix smaller than 6 x 6.
  explicit BorderedBandFactorization(const SparseMatrix& pattern);

  /// Factorise the current values of `matrix` (the pattern given at construction). false where
  /// A is not positive definite (LAPACK's leading minor test) or S is singular: the caller then
  /// needs a factorisation that takes an indefinite A.
  bool factorize(const SparseMatrix& matrix);
  /// x of the bordered system for rhs (size n + 3), after a successful factorize.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

  int bandwidth() const { return kd_; }

 private:
  int n_ = 0;                       ///< rope block size
  int kd_ = 0;                      ///< half-bandwidth of the rope block's lower triangle
  std::vector<double> band_;        ///< (kd + 1) x n, LAPACK's lower band storage, then L
  std::vector<int> band_slot_;      ///< value index of each lower rope-block entry
  std::vector<int> band_position_;  ///< ... and its place in band_ (reversed order)
  std::vector<int> border_slot_;    ///< value index of each entry of the border rows
  std::vector<int> border_row_, border_col_;
  Eigen::Matrix3d Z_ = Eigen::Matrix3d::Zero();  ///< L_tt^-1 C_t^T
  Eigen::PartialPivLU<Eigen::Matrix3d> S_;       ///< S = Z^T Z + G
};

}  // namespace crane_twin
