#include "crane_twin/solvers/rank_one_terms_solve.hpp"

#include <cmath>
#include <stdexcept>

namespace crane_twin {

int symmetricBlockTerms(const Eigen::Matrix3d& D, int offset, int at, double round_off,
                        std::vector<RankOneTerm>& terms) {
  if (at < 0 || at > 9) throw std::invalid_argument("rank-one terms: a 3 x 3 block at 0 .. 9");
  if (!D.allFinite()) return -1;
  if (D.isZero(0.0)) return 0;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(D);
  if (eig.info() != Eigen::Success) return -1;
  int added = 0;
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(eig.eigenvalues()(i)) > round_off)) continue;
    RankOneTerm t;
    t.offset = offset;
    t.u.segment<3>(at) = eig.eigenvectors().col(i);
    t.c = eig.eigenvalues()(i);
    terms.push_back(t);
    ++added;
  }
  return added;
}

bool solveWithRankOneTerms(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& solve,
                           const std::vector<RankOneTerm>& terms,
                           const std::vector<const Eigen::VectorXd*>& columns,
                           const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const int k = static_cast<int>(terms.size());
  if (static_cast<int>(columns.size()) != k)
    throw std::invalid_argument("rank-one terms: one column A^-1 u per term");
  x = solve(b);
  if (k == 0) return true;
  const auto dot = [](const RankOneTerm& t, const Eigen::VectorXd& y) {
    return t.u.dot(y.segment<12>(t.offset));
  };
  // S = I + C U^T Y, rhs = C U^T x0.
  Eigen::MatrixXd S = Eigen::MatrixXd::Identity(k, k);
  Eigen::VectorXd rhs(k);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) S(i, j) += terms[i].c * dot(terms[i], *columns[j]);
    rhs(i) = terms[i].c * dot(terms[i], x);
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(S);
  if (!(std::abs(lu.determinant()) > 1e-12)) return false;
  const Eigen::VectorXd y = lu.solve(rhs);
  for (int j = 0; j < k; ++j) x -= y(j) * *columns[j];
  return x.allFinite();
}

}  // namespace crane_twin
