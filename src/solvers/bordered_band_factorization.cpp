#include "crane_twin/solvers/bordered_band_factorization.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

extern "C" {
// LAPACK / BLAS: Cholesky factorisation of a symmetric positive definite band matrix, and a
// triangular band solve.
void dpbtrf_(const char* uplo, const int* n, const int* kd, double* ab, const int* ldab, int* info);
void dtbsv_(const char* uplo, const char* trans, const char* diag, const int* n, const int* k,
            const double* a, const int* lda, double* x, const int* incx);
}

namespace crane_twin {

BorderedBandFactorization::BorderedBandFactorization(const SparseMatrix& pattern) {
  if (pattern.rows() != pattern.cols() || pattern.rows() < 6) {
    throw std::invalid_argument("bordered band factorisation: a square matrix of 6 x 6 or more");
  }
  n_ = static_cast<int>(pattern.rows()) - 3;
  for (int c = 0; c < n_; ++c)
    for (SparseMatrix::InnerIterator it(pattern, c); it; ++it)
      if (it.row() >= c && it.row() < n_) kd_ = std::max(kd_, static_cast<int>(it.row()) - c);
  const int ld = kd_ + 1;
  const double* base = pattern.valuePtr();
  for (int c = 0; c < pattern.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(pattern, c); it; ++it) {
      const int r = static_cast<int>(it.row());
      const int slot = static_cast<int>(&it.value() - base);
      if (r < n_ && c < n_) {
        if (r >= c) {  // A(r, c) = A_rev(n-1-c, n-1-r), lower in the reversed order
          const int i = n_ - 1 - c, j = n_ - 1 - r;
          band_slot_.push_back(slot);
          band_position_.push_back(i - j + j * ld);
        }
      } else if (r >= n_ && (c < n_ || r >= c)) {  // C, and -G's lower triangle
        if (c >= 3 && c < n_) {
          throw std::invalid_argument(
              "bordered band factorisation: the border reaches beyond the first three columns");
        }
        border_slot_.push_back(slot);
        border_row_.push_back(r - n_);
        border_col_.push_back(c);
      }
    }
  band_.assign(static_cast<std::size_t>(ld) * n_, 0.0);
}

bool BorderedBandFactorization::factorize(const SparseMatrix& matrix) {
  const double* v = matrix.valuePtr();
  std::fill(band_.begin(), band_.end(), 0.0);
  for (std::size_t i = 0; i < band_slot_.size(); ++i) band_[band_position_[i]] = v[band_slot_[i]];
  Eigen::Matrix3d Ct = Eigen::Matrix3d::Zero(), minusG = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < border_slot_.size(); ++i) {
    const int r = border_row_[i], c = border_col_[i];
    if (c < n_) {
      Ct(r, c) = v[border_slot_[i]];
    } else {
      minusG(r, c - n_) = minusG(c - n_, r) = v[border_slot_[i]];
    }
  }
  const char lower = 'L';
  const int ld = kd_ + 1;
  int info = 0;
  dpbtrf_(&lower, &n_, &kd_, band_.data(), &ld, &info);
  if (info != 0) return false;
  // L_tt: rows and columns n-3 .. n-1 of L in the reversed order, i.e. original columns 2, 1, 0.
  Eigen::Matrix3d Ltt = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b <= a; ++b) {
      const int i = n_ - 3 + a, j = n_ - 3 + b;
      if (i - j <= kd_) Ltt(a, b) = band_[i - j + j * ld];
    }
  // C P^T: original column c sits at reversed n-1-c, i.e. row 2-c of the trailing block.
  Eigen::Matrix3d CtP;
  for (int c = 0; c < 3; ++c) CtP.col(2 - c) = Ct.col(c);
  Z_ = Ltt.triangularView<Eigen::Lower>().solve(CtP.transpose());
  const Eigen::Matrix3d S = Z_.transpose() * Z_ - minusG;
  S_.compute(S);
  return std::isfinite(S_.rcond()) && S_.rcond() > 1e-14;
}

Eigen::VectorXd BorderedBandFactorization::solve(const Eigen::VectorXd& rhs) const {
  const char lower = 'L', notrans = 'N', trans = 'T', nonunit = 'N';
  const int ld = kd_ + 1, one = 1;
  Eigen::VectorXd u = rhs.head(n_).reverse();
  dtbsv_(&lower, &notrans, &nonunit, &n_, &kd_, band_.data(), &ld, u.data(), &one);  // L u = P b1
  const Eigen::Vector3d x2 = S_.solve(Z_.transpose() * u.tail<3>() - rhs.tail<3>());
  u.tail<3>() -= Z_ * x2;
  dtbsv_(&lower, &trans, &nonunit, &n_, &kd_, band_.data(), &ld, u.data(), &one);  // L^T P x1
  Eigen::VectorXd x(n_ + 3);
  x.head(n_) = u.reverse();
  x.tail<3>() = x2;
  return x;
}

}  // namespace crane_twin
