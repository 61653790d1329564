#include "crane_twin/solvers/pendulum_solver.hpp"

#include <cmath>

#include "crane_twin/integrators/step_halving.hpp"
#include "crane_twin/rope/swing_direction.hpp"

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
  // The end point carries P, its share of the applied load (the end mass's and half the rope's
  // weight, and the wind's, PendulumRope::gravityForce). At swing 0 the bar hangs along P;
  // otherwise a horizontal holding force H turns it to u: P + H = T u with T = P_z / u_z.
  const Vector6& F = rope_.gravityForce();
  const Eigen::Vector3d P = F.tail<3>();
  Eigen::Vector3d u = swingDirection(swing_rad, az_rad);
  if (swing_rad == 0.0 && P.norm() > 0.0) u = P.normalized();
  const double T = swing_rad == 0.0 ? P.norm() : P.z() / u.z();
  const Eigen::Vector3d H = T * u - P;
  CoupledState s;
  s.lambda = F.head<3>() + T * u;
  s.z = Eigen::VectorXd::Zero(m);
  if (m > 0) {
    // K z = D^T lambda + f_z: the rope's pull and the loads on the structure itself (wind).
    support_.setIterationWeights(0.0, 0.0, 1.0);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m);
    s.z = support_.solvePointForce(s.lambda) + support_.solve(-support_.internalForce(zero, zero, zero));
  }
  const double l = rope_.length() * (1.0 + T / rope_.axialStiffness());
  s.q = PendulumRope::straight(support_.point(s.z), u, l);
  s.v = s.qdd = s.a = Eigen::VectorXd::Zero(PendulumRope::kDofs);
  s.zd = s.zdd = s.za = Eigen::VectorXd::Zero(m);
  if (holding_force) *holding_force = swing_rad == 0.0 ? Eigen::Vector3d::Zero() : H;
  return s;
}

void PendulumSolver::initializeAccelerations(CoupledState& s) {
  const int m = support_.size();
  prepareSupportState(support_, s);
  const Eigen::Matrix3d G = support_.setIterationWeights(1.0, 0.0, 0.0);
  Vector6 Q, Qd;
  rope_.elasticForce(s.q, Q);
  rope_.dampingForce(damping_, s.q, s.v, Qd);
  Matrix9 A = Matrix9::Zero();
  A.topLeftCorner<6, 6>() = rope_.massMatrix();
  A.block<3, 3>(0, 6) = A.block<3, 3>(6, 0) = Eigen::Matrix3d::Identity();
  A.bottomRightCorner<3, 3>() = -G;
  Vector9 rhs;
  rhs.head<6>() = rope_.gravityForce() - Q - Qd;
  Eigen::VectorXd Azr, rz;
  if (m > 0) rz = -support_.internalForce(s.z, s.zd, s.zdd);
  rhs.tail<3>() = condenseSupport(support_, Eigen::Vector3d::Zero(), rz, Azr);
  const Vector9 x = A.partialPivLu().solve(rhs);
  storeConsistentAccelerations(support_, x.head<6>(), x.tail<3>(), Azr, s);
}

void PendulumSolver::step(CoupledState& s) {
  stepWithHalving(s, h_, kMaxHalvings,
                  [this](CoupledState& x, double h, std::string& why) { return tryStep(x, h, why); },
                  halved_steps_);
}

bool PendulumSolver::tryStep(CoupledState& s, double h, std::string& why) {
  const Matrix6& M = rope_.massMatrix();
  const RopeIncrement increment = [&](const CoupledState& x, const NewtonWeights& w,
                                      const Eigen::Vector3d& rc, Eigen::VectorXd& dq,
                                      Eigen::Vector3d& dmu, std::string&) {
    Vector6 Q, Qd;
    Matrix6 K, Cd;
    rope_.elasticForce(x.q, Q, &K);
    rope_.dampingForce(damping_, x.q, x.v, Qd, &Cd);
    Matrix9 A = Matrix9::Zero();
    A.topLeftCorner<6, 6>() = w.mass * M + w.stiffness * K + w.damping * Cd;
    A.block<3, 3>(0, 6) = A.block<3, 3>(6, 0) = Eigen::Matrix3d::Identity();
    A.bottomRightCorner<3, 3>() = -w.G;
    Vector9 rhs;
    rhs.head<6>() = -w.stiffness * (M * x.qdd + Q + Qd - rope_.gravityForce());
    rhs.head<3>() -= w.stiffness * x.lambda;
    rhs.tail<3>() = rc;
    const Vector9 dx = Eigen::PartialPivLU<Matrix9>(A).solve(rhs);
    dq = dx.head<6>();
    dmu = dx.tail<3>();
    return true;
  };
  return newtonStep(ga_, support_, newton_, h, increment, s, why);
}

double PendulumSolver::energy(const CoupledState& s) const {
  const Vector6 q = s.q, v = s.v;
  return 0.5 * v.dot(rope_.massMatrix() * v) + rope_.elasticEnergy(q) -
         rope_.gravityForce().dot(q) + support_.energy(s.z, s.zd);
}

double PendulumSolver::topTension(const CoupledState& s) const {
  return ropeTopTension(s.lambda, rope_.topMass(), s.qdd.head<3>(), rope_.gravity());
}

double PendulumSolver::constraintError(const CoupledState& s) const {
  return crane_twin::constraintError(support_, s);
}

}  // namespace crane_twin
