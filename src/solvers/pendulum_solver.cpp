#include "crane_twin/solvers/pendulum_solver.hpp"

#include <cmath>

#include "crane_twin/integrators/step_halving.hpp"
#include "crane_twin/rope/swing_direction.hpp"

namespace crane_twin {

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

PendulumSolver::MatrixN PendulumSolver::massMatrix() const {
  MatrixN M = MatrixN::Zero(dofs(), dofs());
  M.topLeftCorner<6, 6>() = rope_.massMatrix();
  if (rigging_) M.bottomRightCorner<6, 6>() += rigging_->massMatrix();
  return M;
}

PendulumSolver::VectorN PendulumSolver::appliedForce() const {
  VectorN F = VectorN::Zero(dofs());
  F.head<6>() = rope_.gravityForce();
  if (rigging_) F.tail<6>() += rigging_->gravityForce();
  return F;
}

void PendulumSolver::forces(const VectorN& q, const VectorN& v, VectorN& Q, VectorN& Qd, MatrixN* K,
                            MatrixN* C) const {
  Vector6 Qb, Qdb;
  Matrix6 Kb, Cb;
  Q = Qd = VectorN::Zero(dofs());
  if (K) *K = MatrixN::Zero(dofs(), dofs());
  if (C) *C = MatrixN::Zero(dofs(), dofs());
  rope_.elasticForce(q.head<6>(), Qb, K ? &Kb : nullptr);
  rope_.dampingForce(damping_, q.head<6>(), v.head<6>(), Qdb, C ? &Cb : nullptr);
  Q.head<6>() = Qb;
  Qd.head<6>() = Qdb;
  if (K) K->topLeftCorner<6, 6>() = Kb;
  if (C) C->topLeftCorner<6, 6>() = Cb;
  if (ground_) {
    // The ground on the end point (the payload): with the damping forces, -df/dq and -df/dv
    // in K and C.
    const GroundContactForce g = ground_->force(q.tail<3>(), v.tail<3>());
    Qd.tail<3>() -= g.f;
    if (K) K->bottomRightCorner<3, 3>() -= g.df_dr;
    if (C) C->bottomRightCorner<3, 3>() -= g.df_dv;
  }
  if (!rigging_) return;
  rigging_->elasticForce(q.tail<6>(), Qb, K ? &Kb : nullptr);
  rigging_->dampingForce(damping_, q.tail<6>(), v.tail<6>(), Qdb, C ? &Cb : nullptr);
  Q.tail<6>() += Qb;
  Qd.tail<6>() += Qdb;
  if (K) K->bottomRightCorner<6, 6>() += Kb;
  if (C) C->bottomRightCorner<6, 6>() += Cb;
}

CoupledState PendulumSolver::solveSwingEquilibrium(double swing_rad, double az_rad,
                                                   Eigen::Vector3d* holding_force) {
  const int m = support_.size();
  // Each point carries its share of the applied load (PendulumRope::gravityForce): P_2 on the
  // payload, P_1 on the hook block (without a rigging, only the end point's P_1). A horizontal
  // holding force H on the end point turns the chain; each bar lies along the load below it:
  // u_2 ~ P_2 + H, u_1 ~ P_1 + P_2 + H, T = |load below|. H is found so that the chord from
  // the top to the end point makes swing_rad with the vertical (closed form without a rigging).
  const VectorN F = appliedForce();
  const Eigen::Vector3d top0 = support_.point(Eigen::VectorXd::Zero(m));
  const Eigen::Vector3d horiz(std::cos(az_rad), std::sin(az_rad), 0.0);
  struct Chain {
    Eigen::Vector3d u1, u2, r1, r2;
    double T1 = 0.0, T2 = 0.0;
  };
  const Eigen::Vector3d P2 = rigging_ ? Eigen::Vector3d(F.tail<3>()) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d P = F.segment<3>(3) + P2;  // all the load below the top
  auto chain = [&](const Eigen::Vector3d& H) {
    Chain c;
    const Eigen::Vector3d P1 = P + H;
    c.T1 = P1.norm();
    c.u1 = c.T1 > 0.0 ? Eigen::Vector3d(P1 / c.T1) : Eigen::Vector3d(0.0, 0.0, -1.0);
    c.r1 = top0 + rope_.length() * (1.0 + c.T1 / rope_.axialStiffness()) * c.u1;
    c.r2 = c.r1;
    if (rigging_) {
      const Eigen::Vector3d B = P2 + H;
      c.T2 = B.norm();
      c.u2 = c.T2 > 0.0 ? Eigen::Vector3d(B / c.T2) : Eigen::Vector3d(0.0, 0.0, -1.0);
      c.r2 = c.r1 + rigging_->length() * (1.0 + c.T2 / rigging_->axialStiffness()) * c.u2;
    }
    return c;
  };
  auto angle = [&](const Chain& c) {
    const Eigen::Vector3d d = c.r2 - top0;
    return std::atan2(d.dot(horiz), -d.z());
  };
  Eigen::Vector3d H = Eigen::Vector3d::Zero();
  if (swing_rad != 0.0) {
    // Without a rigging, exactly: the bar along u, T = P_z / u_z, H = T u - P. With one, H
    // cancels the loads' horizontal part (wind) and pushes along the azimuth by h, h by secant
    // iterations on the chord's angle from there.
    const Eigen::Vector3d u = swingDirection(swing_rad, az_rad);
    H = P.z() / u.z() * u - P;
    if (rigging_) {
      const Eigen::Vector3d Ph(P.x(), P.y(), 0.0);
      auto error = [&](double h) { return angle(chain(h * horiz - Ph)) - swing_rad; };
      double h0 = H.dot(horiz) + Ph.dot(horiz), h1 = 1.01 * h0 + 1e-9;
      double e0 = error(h0), e1 = error(h1);
      for (int it = 0; it < 50 && std::abs(e1) > 1e-14; ++it) {
        const double h2 = h1 - e1 * (h1 - h0) / (e1 - e0);
        h0 = h1;
        e0 = e1;
        h1 = h2;
        e1 = error(h1);
      }
      if (!(std::abs(e1) < 1e-10))
        throw NumericalFailure("swing equilibrium: chord angle not reached");
      H = h1 * horiz - Ph;
    }
  }
  const Chain c = chain(H);
  CoupledState s;
  s.lambda = F.head<3>() + c.T1 * c.u1;
  s.z = Eigen::VectorXd::Zero(m);
  if (m > 0) {
    // K z = D^T lambda + f_z: the rope's pull and the loads on the structure itself (wind).
    support_.setIterationWeights(0.0, 0.0, 1.0);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(m);
    s.z = support_.solvePointForce(s.lambda) +
          support_.solve(-support_.internalForce(zero, zero, zero));
  }
  // The support's deflection moves the whole chain with the top point.
  const Eigen::Vector3d shift = support_.point(s.z) - top0;
  s.q.resize(dofs());
  s.q.head<3>() = top0 + shift;
  s.q.segment<3>(3) = c.r1 + shift;
  if (rigging_) s.q.tail<3>() = c.r2 + shift;
  s.v = s.qdd = s.a = Eigen::VectorXd::Zero(dofs());
  s.zd = s.zdd = s.za = Eigen::VectorXd::Zero(m);
  if (holding_force) *holding_force = swing_rad == 0.0 ? Eigen::Vector3d::Zero() : H;
  return s;
}

void PendulumSolver::initializeAccelerations(CoupledState& s) {
  const int m = support_.size(), n = dofs();
  prepareSupportState(support_, s);
  const Eigen::Matrix3d G = support_.setIterationWeights(1.0, 0.0, 0.0);
  VectorN Q, Qd;
  forces(s.q, s.v, Q, Qd, nullptr, nullptr);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 3, n + 3);
  A.topLeftCorner(n, n) = massMatrix();
  A.block<3, 3>(0, n) = A.block<3, 3>(n, 0) = Eigen::Matrix3d::Identity();
  A.bottomRightCorner<3, 3>() = -G;
  Eigen::VectorXd rhs(n + 3);
  rhs.head(n) = appliedForce() - Q - Qd;
  Eigen::VectorXd Azr, rz;
  if (m > 0) rz = -support_.internalForce(s.z, s.zd, s.zdd);
  rhs.tail<3>() = condenseSupport(support_, Eigen::Vector3d::Zero(), rz, Azr);
  const Eigen::VectorXd x = A.partialPivLu().solve(rhs);
  storeConsistentAccelerations(support_, x.head(n), x.tail<3>(), Azr, s);
}

void PendulumSolver::step(CoupledState& s) {
  stepWithHalving(
      s, h_, kMaxHalvings, support_,
      [this](CoupledState& x, double h, std::string& why) { return tryStep(x, h, why); },
      halved_steps_);
}

bool PendulumSolver::tryStep(CoupledState& s, double h, std::string& why) {
  const int n = dofs();
  const MatrixN M = massMatrix();
  const VectorN F = appliedForce();
  using MatrixA = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 12, 12>;
  using VectorA = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 12, 1>;
  const RopeIncrement increment = [&](const CoupledState& x, const NewtonWeights& w,
                                      const Eigen::Vector3d& rc, Eigen::VectorXd& dq,
                                      Eigen::Vector3d& dmu, std::string&) {
    VectorN Q, Qd;
    MatrixN K, Cd;
    forces(x.q, x.v, Q, Qd, &K, &Cd);
    MatrixA A = MatrixA::Zero(n + 3, n + 3);
    A.topLeftCorner(n, n) = w.mass * M + w.stiffness * K + w.damping * Cd;
    A.block<3, 3>(0, n) = A.block<3, 3>(n, 0) = Eigen::Matrix3d::Identity();
    A.bottomRightCorner<3, 3>() = -w.G;
    VectorA rhs(n + 3);
    rhs.head(n) = -w.stiffness * (M * x.qdd + Q + Qd - F);
    rhs.head<3>() -= w.stiffness * x.lambda;
    rhs.tail<3>() = rc;
    const VectorA dx = Eigen::PartialPivLU<MatrixA>(A).solve(rhs);
    dq = dx.head(n);
    dmu = dx.tail<3>();
    return true;
  };
  return newtonStep(ga_, support_, newton_, h, increment, s, why, newton_workspace_);
}

double PendulumSolver::energy(const CoupledState& s) const {
  double U = rope_.elasticEnergy(s.q.head<6>());
  if (rigging_) U += rigging_->elasticEnergy(s.q.tail<6>());
  if (ground_) U += ground_->energy(s.q.tail<3>());
  return 0.5 * s.v.dot(massMatrix() * s.v) + U - appliedForce().dot(s.q) +
         support_.energy(s.z, s.zd);
}

double PendulumSolver::topTension(const CoupledState& s) const {
  return ropeTopTension(s.lambda, rope_.topMass(), s.qdd.head<3>(), rope_.gravity());
}

double PendulumSolver::constraintError(const CoupledState& s) const {
  return crane_twin::constraintError(support_, s);
}

}  // namespace crane_twin
