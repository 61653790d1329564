#include "crane_twin/anchored_rope_solver.hpp"

#include <Eigen/UmfPackSupport>

#include <algorithm>
#include <cmath>
#include <string>

namespace crane_twin {

GeneralizedAlpha GeneralizedAlpha::fromRhoInf(double rho) {
  if (!(rho >= 0.0 && rho <= 1.0)) throw std::invalid_argument("rho_inf must be in [0, 1]");
  GeneralizedAlpha g;
  g.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
  g.alpha_f = rho / (rho + 1.0);
  g.gamma = 0.5 + g.alpha_f - g.alpha_m;
  g.beta = 0.25 * (g.gamma + 0.5) * (g.gamma + 0.5);
  return g;
}

GeneralizedAlpha GeneralizedAlpha::newmark() { return GeneralizedAlpha{}; }

AnchoredRopeSolver::AnchoredRopeSolver(const AncfRope& rope, const Eigen::Vector3d& anchor,
                                       const GeneralizedAlpha& scheme, double time_step,
                                       NewtonSettings newton)
    : rope_(rope), anchor_(anchor), ga_(scheme), h_(time_step), newton_(newton) {
  // Pattern: every element block, the mass matrix, and the constraint rows/columns.
  const int n = rope_.dofs();
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < rope_.elements(); ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) t.emplace_back(6 * k + i, 6 * k + j, 0.0);
  for (int d = 0; d < 3; ++d) {
    t.emplace_back(n + d, d, 1.0);
    t.emplace_back(d, n + d, 1.0);
  }
  A_.resize(n + 3, n + 3);
  A_.setFromTriplets(t.begin(), t.end());
  A_.makeCompressed();
  const SparseMatrix& M = rope_.massMatrix();
  for (int c = 0; c < M.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(M, c); it; ++it) {
      mass_index_.push_back(static_cast<int>(&A_.coeffRef(it.row(), it.col()) - A_.valuePtr()));
      mass_value_.push_back(it.value());
    }
  element_index_.reserve(144 * rope_.elements());
  for (int k = 0; k < rope_.elements(); ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i)
        element_index_.push_back(
            static_cast<int>(&A_.coeffRef(6 * k + i, 6 * k + j) - A_.valuePtr()));
  ldlt_.analyzePattern(A_);
}

// A = [ massWeight M + stiffWeight K(q)   C_q^T ; C_q  0 ],  C_q = [I3 0 ...].
void AnchoredRopeSolver::assemble(const Eigen::VectorXd& q, double massWeight,
                                  double stiffWeight, Eigen::VectorXd& Q) {
  double* val = A_.valuePtr();
  const int n = rope_.dofs();
  std::fill(val, val + A_.nonZeros(), 0.0);
  for (std::size_t i = 0; i < mass_index_.size(); ++i) val[mass_index_[i]] += massWeight * mass_value_[i];
  Q.setZero(n);
  Vector12 Qe;
  Matrix12 Ke;
  const int* idx = element_index_.data();
  for (int k = 0; k < rope_.elements(); ++k, idx += 144) {
    ancfElasticForce(rope_.element(), q.segment<12>(6 * k), Qe, stiffWeight != 0.0 ? &Ke : nullptr);
    Q.segment<12>(6 * k) += Qe;
    if (stiffWeight == 0.0) continue;
    const double* ke = Ke.data();
    for (int e = 0; e < 144; ++e) val[idx[e]] += stiffWeight * ke[e];
  }
  for (int d = 0; d < 3; ++d) {
    A_.coeffRef(n + d, d) = 1.0;
    A_.coeffRef(d, n + d) = 1.0;
  }
}

void AnchoredRopeSolver::factorize(const std::string& what) {
  ldlt_.factorize(A_);
  if (ldlt_.info() != Eigen::Success) throw NumericalFailure(what + ": singular iteration matrix");
}

RopeState AnchoredRopeSolver::solveStatic(const Eigen::VectorXd& q_guess,
                                          const Eigen::Vector3d& end_force) {
  const int n = rope_.dofs();
  RopeState s;
  s.q = q_guess;
  s.v = Eigen::VectorXd::Zero(n);
  s.qdd = Eigen::VectorXd::Zero(n);
  s.a = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd Q, rhs(n + 3), F = rope_.gravityForce();
  F.segment<3>(n - 6) += end_force;
  // Statics use a pivoting LU: without the mass term the rope block can be semi-definite
  // (bending-only lateral stiffness at low tension), where LDL^T without pivoting stops.
  Eigen::UmfPackLU<SparseMatrix> lu;
  for (int it = 0; it < 50; ++it) {
    assemble(s.q, 0.0, 1.0, Q);
    rhs.head(n) = -(Q - F);
    rhs.head<3>() -= s.lambda;
    rhs.tail<3>() = -(s.q.head<3>() - anchor_);
    lu.compute(A_);
    if (lu.info() != Eigen::Success) throw NumericalFailure("static solve: singular tangent");
    const Eigen::VectorXd dx = lu.solve(rhs);
    // Limit the step to a tenth of the rope length: a poor guess must not overshoot.
    double scale = 1.0;
    const double dmax = dx.head(n).cwiseAbs().maxCoeff();
    if (dmax > 0.1 * rope_.length()) scale = 0.1 * rope_.length() / dmax;
    s.q += scale * dx.head(n);
    s.lambda += scale * dx.tail<3>();
    if (!s.q.allFinite()) throw NumericalFailure("static solve: non-finite state");
    if (scale == 1.0 && dmax < 1e-11 * std::max(1.0, rope_.length())) return s;
  }
  throw NumericalFailure("static solve did not converge in 50 Newton iterations");
}

RopeState AnchoredRopeSolver::solveSwingEquilibrium(double swing_rad, double az_rad,
                                                    Eigen::Vector3d* holding_force) {
  const Eigen::Vector3d horiz(std::cos(az_rad), std::sin(az_rad), 0.0);
  // Total weight from the gravity force (sum of z components, incl. the end mass).
  double W = 0.0;
  for (int j = 0; j < rope_.nodes(); ++j) W -= rope_.gravityForce()(6 * j + 2);
  const double endW = rope_.endMass() * W / (rope_.endMass() + rope_.element().mass_per_length * rope_.length());
  auto chordAngle = [&](const RopeState& s) {
    const Eigen::Vector3d c = s.q.segment<3>(rope_.dofs() - 6) - anchor_;
    return std::atan2(c.dot(horiz), -c.z());
  };
  // Start from the straight rope stretched by the static tension profile
  // T(s) = (W_end + mu g (L - s)) / cos(theta): the tension's geometric stiffness makes the
  // tangent definite (an unstressed straight rope can rotate about the anchor at no cost).
  const Eigen::Vector3d d(std::sin(swing_rad) * horiz.x(), std::sin(swing_rad) * horiz.y(),
                          -std::cos(swing_rad));
  Eigen::VectorXd guess(rope_.dofs());
  {
    const double l = rope_.element().length, EA = rope_.element().axial_stiffness;
    const double perLength = (W - endW) / rope_.length();
    Eigen::Vector3d r = anchor_;
    for (int j = 0; j < rope_.nodes(); ++j) {
      const double T = (endW + perLength * (rope_.length() - j * l)) / std::cos(swing_rad);
      guess.segment<3>(6 * j) = r;
      guess.segment<3>(6 * j + 3) = (1.0 + T / EA) * d;
      const double Tmid = (endW + perLength * (rope_.length() - (j + 0.5) * l)) / std::cos(swing_rad);
      r += (1.0 + Tmid / EA) * l * d;
    }
  }
  // Closed-form start: a massless rope's chord angle obeys tan(theta) = H / W_end; the rope's
  // own weight adds half its weight.
  double H0 = std::tan(swing_rad) * (endW + 0.5 * (W - endW));
  RopeState s0 = solveStatic(guess, H0 * horiz);
  if (swing_rad == 0.0) {
    if (holding_force) holding_force->setZero();
    return s0;
  }
  double H1 = H0 * 1.02;
  RopeState s1 = solveStatic(s0.q, H1 * horiz);
  double e0 = chordAngle(s0) - swing_rad, e1 = chordAngle(s1) - swing_rad;
  for (int it = 0; it < 30 && std::abs(e1) > 1e-12; ++it) {
    const double H2 = H1 - e1 * (H1 - H0) / (e1 - e0);
    H0 = H1;
    e0 = e1;
    H1 = H2;
    s1 = solveStatic(s1.q, H1 * horiz);
    e1 = chordAngle(s1) - swing_rad;
  }
  if (std::abs(e1) > 1e-9) throw NumericalFailure("swing equilibrium: chord angle not reached");
  if (holding_force) *holding_force = H1 * horiz;
  return s1;
}

void AnchoredRopeSolver::initializeAccelerations(RopeState& s) {
  const int n = rope_.dofs();
  Eigen::VectorXd Q, rhs(n + 3);
  assemble(s.q, 1.0, 0.0, Q);
  rhs.head(n) = rope_.gravityForce() - Q;
  rhs.tail<3>().setZero();
  factorize("initial accelerations");
  const Eigen::VectorXd x = ldlt_.solve(rhs);
  s.qdd = x.head(n);
  s.a = s.qdd;
  s.lambda = x.tail<3>();
}

void AnchoredRopeSolver::step(RopeState& s) {
  const int n = rope_.dofs();
  const double h = h_, am = ga_.alpha_m, af = ga_.alpha_f, be = ga_.beta, ga = ga_.gamma;
  const double betaP = (1.0 - am) / (h * h * be * (1.0 - af));
  const double gammaP = ga / (h * be);
  // Predictor with q''_{n+1} = q''_n.
  const Eigen::VectorXd qdd0 = s.qdd, a0 = s.a, v0 = s.v;
  Eigen::VectorXd aNew = (qdd0 - am * a0) / (1.0 - am);
  s.q += h * v0 + h * h * ((0.5 - be) * a0 + be * aNew);
  s.v = v0 + h * ((1.0 - ga) * a0 + ga * aNew);
  // s.qdd stays qdd0
  Eigen::VectorXd Q, rhs(n + 3);
  const double bh2 = be * h * h;
  const SparseMatrix& M = rope_.massMatrix();
  int it = 0;
  for (; it < newton_.max_iterations; ++it) {
    assemble(s.q, (1.0 - am) / (1.0 - af), bh2, Q);
    rhs.head(n) = -bh2 * (M * s.qdd + Q - rope_.gravityForce());
    rhs.head<3>() -= bh2 * s.lambda;
    rhs.tail<3>() = -(s.q.head<3>() - anchor_);
    factorize("t = " + std::to_string(s.t + h) + " s");
    const Eigen::VectorXd dx = ldlt_.solve(rhs);
    const Eigen::VectorXd dq = dx.head(n);
    s.q += dq;
    s.v += gammaP * dq;
    s.qdd += betaP * dq;
    s.lambda += dx.tail<3>() / bh2;
    if (!s.q.allFinite()) {
      throw NumericalFailure("t = " + std::to_string(s.t + h) + " s: non-finite state");
    }
    const double cerr = (s.q.head<3>() - anchor_).norm();
    if (dq.cwiseAbs().maxCoeff() < newton_.position_tolerance &&
        cerr < newton_.constraint_tolerance) {
      ++it;
      break;
    }
    if (it + 1 == newton_.max_iterations) {
      throw NumericalFailure("t = " + std::to_string(s.t + h) +
                             " s: Newton did not converge in " +
                             std::to_string(newton_.max_iterations) + " iterations");
    }
  }
  s.a = (af * qdd0 - am * a0 + (1.0 - af) * s.qdd) / (1.0 - am);
  s.t += h;
  s.newton_iterations = it;
}

double AnchoredRopeSolver::energy(const RopeState& s) const {
  return 0.5 * s.v.dot(rope_.massMatrix() * s.v) + rope_.elasticEnergy(s.q) -
         rope_.gravityForce().dot(s.q);
}

}  // namespace crane_twin
