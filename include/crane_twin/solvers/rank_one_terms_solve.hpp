// A linear solve with a factorised matrix A and a few symmetric rank-one terms added to it:
//   (A + sum_j c_j u_j u_j^T) x = b,
// by Woodbury's identity in its push-through form, which needs no inverse of the c_j:
//   x = x0 - Y y,   x0 = A^-1 b,   Y = A^-1 U,   (I + C U^T Y) y = C U^T x0,
// U = [u_1 ... u_k], C = diag(c_j): k + 1 solves with A and a k x k system. Each u_j has twelve
// nonzeros from an offset (one ANCF element's coordinates). Used where a Newton iteration's
// matrix changes by the axial tangent of a few Gauss points whose law changed branch, and by
// the ground contact's 3 x 3 block at the payload point (docs/model.md "Full-order solution").
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "crane_twin/elements/ancf_cable_element.hpp"

namespace crane_twin {

/// c u u^T with u nonzero in entries offset .. offset + 11 only.
struct RankOneTerm {
  int offset = 0;
  Vector12 u = Vector12::Zero();
  double c = 0.0;
};

/// A symmetric 3 x 3 block D at rows and columns offset + at .. offset + at + 2 (at <= 9) as
/// rank-one terms by its eigen-decomposition, D = sum_i d_i e_i e_i^T: one term (c = d_i,
/// u = e_i there) for each |d_i| above `round_off`, appended to `terms`. Returns how many, or
/// -1 where the decomposition fails (a non-finite block).
int symmetricBlockTerms(const Eigen::Matrix3d& D, int offset, int at, double round_off,
                        std::vector<RankOneTerm>& terms);

/// x of (A + sum_j c_j u_j u_j^T) x = b, given x -> A^-1 x (`solve`, for vectors of b's size)
/// and the columns Y_j = A^-1 u_j (`columns`, one per term). False where the k x k system is
/// singular to working precision (then A with the terms must be factorised itself).
bool solveWithRankOneTerms(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& solve,
                           const std::vector<RankOneTerm>& terms,
                           const std::vector<const Eigen::VectorXd*>& columns,
                           const Eigen::VectorXd& b, Eigen::VectorXd& x);

}  // namespace crane_twin
