#include "crane_twin/structure/modal_analysis.hpp"

#include <Eigen/CholmodSupport>
#include <algorithm>
#include <arpack/arpack.hpp>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace crane_twin {

double ModalBasis::frequencyHz(int i) const {
  return std::sqrt(std::max(0.0, omega2(i))) / (2.0 * M_PI);
}

ModalBasis lowestModes(const SparseMatrix& K, const SparseMatrix& M, const ModalOptions& opt) {
  const int n = static_cast<int>(K.rows());
  if (K.cols() != n || M.rows() != n || M.cols() != n) {
    throw std::invalid_argument("lowestModes: K and M must be square and of equal size");
  }
  const int nev = opt.count;
  if (nev < 1 || nev >= n) {
    throw std::invalid_argument("lowestModes: mode count must be in 1.." + std::to_string(n - 1) +
                                ", got " + std::to_string(nev));
  }
  SparseMatrix A = K - opt.shift * M;
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> solver;
  solver.compute(A);
  if (solver.info() != Eigen::Success) {
    throw std::runtime_error(
        "lowestModes: CHOLMOD factorisation of K - sigma M failed "
        "(K not positive semi-definite or shift too large)");
  }

  const int ncv = std::min(n, std::max(2 * nev + 1, nev + 20));
  const int lworkl = ncv * (ncv + 8);
  std::vector<double> resid(n, 0.0), V(static_cast<std::size_t>(n) * ncv), workd(3 * n),
      workl(lworkl);
  a_int iparam[11] = {0}, ipntr[14] = {0};
  iparam[0] = 1;  // exact shifts
  iparam[2] = opt.max_iterations;
  iparam[6] = 3;  // shift-invert, generalised
  a_int ido = 0, info = 0;
  // A fixed start vector keeps runs reproducible (info = 1 means "use resid").
  for (int i = 0; i < n; ++i) resid[i] = 1.0 + 0.1 * std::sin(0.7 * i);
  info = 1;
  Eigen::VectorXd x(n), y(n);
  while (true) {
    arpack::saupd(ido, arpack::bmat::generalized, n, arpack::which::largest_magnitude, nev,
                  opt.tolerance, resid.data(), ncv, V.data(), n, iparam, ipntr, workd.data(),
                  workl.data(), lworkl, info);
    if (ido == -1 || ido == 1) {
      double* out = &workd[ipntr[1] - 1];
      if (ido == -1) {
        x = M * Eigen::Map<Eigen::VectorXd>(&workd[ipntr[0] - 1], n);
      } else {
        x = Eigen::Map<Eigen::VectorXd>(&workd[ipntr[2] - 1], n);
      }
      Eigen::Map<Eigen::VectorXd>(out, n) = solver.solve(x);
    } else if (ido == 2) {
      Eigen::Map<Eigen::VectorXd>(&workd[ipntr[1] - 1], n) =
          M * Eigen::Map<Eigen::VectorXd>(&workd[ipntr[0] - 1], n);
    } else {
      break;
    }
  }
  if (info < 0) throw std::runtime_error("ARPACK dsaupd failed, info = " + std::to_string(info));
  if (iparam[4] < nev) {
    throw std::runtime_error("ARPACK converged only " + std::to_string(iparam[4]) + " of " +
                             std::to_string(nev) + " modes");
  }
  std::vector<a_int> select(ncv, 1);
  std::vector<double> d(nev);
  std::vector<double> Z(static_cast<std::size_t>(n) * nev);
  arpack::seupd(1, arpack::howmny::ritz_vectors, select.data(), d.data(), Z.data(), n, opt.shift,
                arpack::bmat::generalized, n, arpack::which::largest_magnitude, nev, opt.tolerance,
                resid.data(), ncv, V.data(), n, iparam, ipntr, workd.data(), workl.data(), lworkl,
                info);
  if (info != 0) throw std::runtime_error("ARPACK dseupd failed, info = " + std::to_string(info));

  std::vector<int> order(nev);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return d[a] < d[b]; });
  ModalBasis out;
  out.omega2.resize(nev);
  out.phi.resize(n, nev);
  Eigen::Map<Eigen::MatrixXd> Zm(Z.data(), n, nev);
  for (int k = 0; k < nev; ++k) {
    out.omega2(k) = d[order[k]];
    Eigen::VectorXd v = Zm.col(order[k]);
    v /= std::sqrt(v.dot(M * v));
    // Sign convention: largest component positive, so modes are reproducible.
    Eigen::Index imax;
    v.cwiseAbs().maxCoeff(&imax);
    if (v(imax) < 0) v = -v;
    out.phi.col(k) = v;
  }
  return out;
}

double modalResidual(const SparseMatrix& K, const SparseMatrix& M, const ModalBasis& b) {
  double worst = 0.0;
  for (int k = 0; k < b.phi.cols(); ++k) {
    const Eigen::VectorXd Kp = K * b.phi.col(k);
    const Eigen::VectorXd r = Kp - b.omega2(k) * (M * b.phi.col(k));
    worst = std::max(worst, r.norm() / std::max(Kp.norm(), 1e-300));
  }
  return worst;
}

double massOrthonormalityError(const SparseMatrix& M, const ModalBasis& b) {
  const Eigen::MatrixXd G = b.phi.transpose() * (M * b.phi);
  return (G - Eigen::MatrixXd::Identity(G.rows(), G.cols())).cwiseAbs().maxCoeff();
}

}  // namespace crane_twin
