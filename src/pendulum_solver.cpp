#include "crane_twin/pendulum_solver.hpp"

#include <cmath>

namespace crane_twin {

namespace {
using Matrix9 = Eigen::Matrix<double, 9, 9>;
using Vector9 = Eigen::Matrix<double, 9, 1>;
}  // namespace

PendulumSolver::PendulumSolver(const PendulumRope& rope, RopeSupport& support,
                               const GeneralizedAlpha& scheme, double time_step,
                               NewtonSettings newton)
    : rope_(rope), support_(support), ga_(scheme), h_(time_step), newton_(newton) {
  if (!(time_step > 0.0)) throw std::invalid_argument("time step must be positive");
}

void PendulumSolver::setRopeDamping(double c) {
  if (!std::isfinite(c) || c < 0.0) throw std::invalid_argument("rope damping must be >= 0");
  damping_ = c;
}

CoupledState PendulumSolver::solveSwingEquilibrium(double swing_rad, double az_rad,
                                                   Eigen::Vector3d* holding_force) {
  const int m = support_.size();
  const Eigen::Vector3d g = rope_.gravity();
  const double gn = g.norm();
  const double mu_l = rope_.massPerLength() * rope_.length();
  const double endW = (rope_.endMass() + 0.5 * mu_l) * gn;  // weight the end point carries
  const Eigen::Vector3d horiz(std::cos(az_rad), std::sin(az_rad), 0.0);
  const Eigen::Vector3d u = swingDirection(swing_rad, az_rad);
  const double H = std::tan(swing_rad) * endW;
  const double T = endW / std::cos(swing_rad);
  CoupledState s;
  s.lambda = (0.5 * mu_l + rope_.topMass()) * g + T * u;
  s.z = Eigen::VectorXd::Zero(m);
  if (m > 0) {
    support_.setIterationWeights(0.0, 0.0, 1.0);
    s.z = support_.solvePointForce(s.lambda);
  }
  const double l = rope_.length() * (1.0 + T / rope_.axialStiffness());
  s.q = PendulumRope::straight(support_.point(s.z), u, l);
  s.v = s.qdd = s.a = Eigen::VectorXd::Zero(PendulumRope::kDofs);
  s.zd = s.zdd = s.za = Eigen::VectorXd::Zero(m);
  if (holding_force) *holding_force = swing_rad == 0.0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(H * horiz);
  return s;
}

void PendulumSolver::initializeAccelerations(CoupledState& s) {
  const int m = support_.size();
  if (s.z.size() != m) s.z = Eigen::VectorXd::Zero(m);
  if (s.zd.size() != m) s.zd = Eigen::VectorXd::Zero(m);
  s.zdd = Eigen::VectorXd::Zero(m);
  const Eigen::Matrix3d G = support_.setIterationWeights(1.0, 0.0, 0.0);
  Vector6 Q, Qd;
  rope_.elasticForce(s.q, Q);
  rope_.dampingForce(damping_, s.q, s.v, Qd);
  Matrix9 A = Matrix9::Zero();
  A.topLeftCorner<6, 6>() = rope_.massMatrix();
  A.block<3, 3>(0, 6) = A.block<3, 3>(6, 0) = Eigen::Matrix3d::Identity();
  A.bottomRightCorner<3, 3>() = -G;
  Vector9 rhs = Vector9::Zero();
  rhs.head<6>() = rope_.gravityForce() - Q - Qd;
  Eigen::VectorXd Azr;
  if (m > 0) {
    Azr = support_.solve(-support_.internalForce(s.z, s.zd, s.zdd));
    rhs.tail<3>() += support_.pointMotion(Azr);
  }
  const Vector9 x = A.partialPivLu().solve(rhs);
  s.qdd = x.head<6>();
  s.a = s.qdd;
  s.lambda = x.tail<3>();
  if (m > 0) s.zdd = Azr + support_.solvePointForce(s.lambda);
  s.za = s.zdd;
}

void PendulumSolver::step(CoupledState& s) {
  stepWithHalving(s, h_, FullOrderSolver::kMaxHalvings,
                  [this](CoupledState& x, double h, std::string& why) { return tryStep(x, h, why); },
                  halved_steps_);
}

bool PendulumSolver::tryStep(CoupledState& s, double h, std::string& why) {
  const int m = support_.size();
  const double bh2 = ga_.beta * h * h, a = ga_.massWeight();
  const CoupledState start = s;
  ga_.predict(h, start.qdd, start.a, s.q, s.v);
  if (m > 0) ga_.predict(h, start.zdd, start.za, s.z, s.zd);
  const Eigen::Matrix3d G = support_.setIterationWeights(a, ga_.gamma * h, bh2);
  const Matrix6& M = rope_.massMatrix();
  const std::string at = "t = " + std::to_string(s.t + h) + " s";
  Vector6 Q, Qd;
  Matrix6 K, Cd;
  Eigen::VectorXd Azr;
  for (int it = 0; it < newton_.max_iterations; ++it) {
    rope_.elasticForce(s.q, Q, &K);
    rope_.dampingForce(damping_, s.q, s.v, Qd, &Cd);
    Matrix9 A = Matrix9::Zero();
    A.topLeftCorner<6, 6>() = a * M + bh2 * K + ga_.gamma * h * Cd;
    A.block<3, 3>(0, 6) = A.block<3, 3>(6, 0) = Eigen::Matrix3d::Identity();
    A.bottomRightCorner<3, 3>() = -G;
    Vector9 rhs;
    rhs.head<6>() = -bh2 * (M * s.qdd + Q + Qd - rope_.gravityForce());
    rhs.head<3>() -= bh2 * s.lambda;
    rhs.tail<3>() = -(s.q.head<3>() - support_.point(s.z));
    if (m > 0) {
      Azr = support_.solve(-bh2 * (support_.internalForce(s.z, s.zd, s.zdd) -
                                   support_.pointForceToCoordinates(s.lambda)));
      rhs.tail<3>() += support_.pointMotion(Azr);
    }
    const Eigen::PartialPivLU<Matrix9> lu(A);
    const Vector9 dx = lu.solve(rhs);
    const Eigen::VectorXd dq = dx.head<6>();
    ga_.correct(h, dq, s.q, s.v, s.qdd);
    s.lambda += dx.tail<3>() / bh2;
    const double dmax = std::max(dq.cwiseAbs().maxCoeff(),
                                 correctSupport(ga_, support_, h, Azr, dx.tail<3>(), s));
    if (!s.q.allFinite() || !s.z.allFinite() || !s.lambda.allFinite()) {
      why = at + ": non-finite state";
      s = start;
      return false;
    }
    if (dmax < newton_.position_tolerance && constraintError(s) < newton_.constraint_tolerance) {
      completeStep(ga_, start, h, it + 1, s);
      return true;
    }
  }
  why = at + ": Newton did not converge in " + std::to_string(newton_.max_iterations) +
        " iterations";
  s = start;
  return false;
}

double PendulumSolver::energy(const CoupledState& s) const {
  const Vector6 q = s.q, v = s.v;
  return 0.5 * v.dot(rope_.massMatrix() * v) + rope_.elasticEnergy(q) -
         rope_.gravityForce().dot(q) + support_.energy(s.z, s.zd);
}

double PendulumSolver::topTension(const CoupledState& s) const {
  return (s.lambda + rope_.topMass() * (s.qdd.head<3>() - rope_.gravity())).norm();
}

double PendulumSolver::constraintError(const CoupledState& s) const {
  return (s.q.head<3>() - support_.point(s.z)).norm();
}

}  // namespace crane_twin
