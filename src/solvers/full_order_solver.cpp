#include "crane_twin/solvers/full_order_solver.hpp"

#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "crane_twin/integrators/numerical_failure.hpp"
#include "crane_twin/integrators/step_halving.hpp"
#include "crane_twin/rope/swing_direction.hpp"

namespace crane_twin {

FullOrderSolver::FullOrderSolver(const AncfRope& rope, RopeSupport& support,
                                 const GeneralizedAlpha& scheme, double time_step,
                                 NewtonSettings newton)
    : rope_(rope), support_(support), ga_(scheme), h_(time_step), newton_(newton) {
  if (!(time_step > 0.0)) throw std::invalid_argument("time step must be positive");
  // Pattern: every element block, the mass matrix, the constraint rows/columns and the
  // 3 x 3 multiplier block (-G; lower triangle suffices for LDL^T but LU reads it all).
  const int n = rope_.dofs();
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < rope_.elements(); ++k)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) t.emplace_back(6 * k + i, 6 * k + j, 0.0);
  if (rope_.hasRigging()) {
    const std::array<int, 6> r = rope_.riggingDofs();
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i) t.emplace_back(r[i], r[j], 0.0);
  }
  for (int d = 0; d < 3; ++d) {
    t.emplace_back(n + d, d, 1.0);
    t.emplace_back(d, n + d, 1.0);
    for (int e = 0; e < 3; ++e) t.emplace_back(n + d, n + e, 0.0);
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
  if (rope_.hasRigging()) {
    const std::array<int, 6> r = rope_.riggingDofs();
    for (int j = 0; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        rigging_index_.push_back(static_cast<int>(&A_.coeffRef(r[i], r[j]) - A_.valuePtr()));
  }
  ldlt_.analyzePattern(A_);
  band_.emplace(A_);
}

void FullOrderSolver::continueSteppingOf(const FullOrderSolver& o) {
  switching_.switching = o.switching_.switching;
  switching_.energy_created = o.switching_.energy_created;
  last_step_length_ = o.last_step_length_;
}

void FullOrderSolver::refreshMass() {
  const SparseMatrix& M = rope_.massMatrix();
  std::size_t i = 0;
  for (int c = 0; c < M.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(M, c); it; ++it) mass_value_.at(i++) = it.value();
  if (i != mass_value_.size()) throw std::logic_error("rope mass pattern changed");
}

// A = [ massWeight M + stiffWeight K(q)   C_q^T ; C_q  -G ],  C_q = [I3 0 ...].
void FullOrderSolver::setRopeDamping(double c) {
  if (!std::isfinite(c) || c < 0.0) throw std::invalid_argument("rope damping must be >= 0");
  rope_damping_ = c;
}

void FullOrderSolver::assemble(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                               double massWeight, double stiffWeight, double dampWeight,
                               const Eigen::Matrix3d& G, Eigen::VectorXd& Q,
                               const CoupledState* from, bool matrix) {
  // An energy-consistent step: the damper acts at the step's midpoint q_m and its own mean
  // velocity v_m = (q - q0) / h, where its work v_m . Q_d h = h int c EA eps'^2 dx >= 0 is a
  // dissipation; d/dq of that force is C_d(q_m) / h.
  Eigen::VectorXd qm, vm;
  if (from) {
    qm = 0.5 * (from->q + q);
    vm = (q - from->q) / ec_step_;
  }
  const Eigen::VectorXd& qd = from ? qm : q;
  const Eigen::VectorXd& vd = from ? vm : v;
  if (from && step_start_.size() !=
                  static_cast<std::size_t>(rope_.elements() * rope_.element().gauss_points)) {
    throw std::logic_error("energy-consistent assembly without the step's start");
  }
  if (!matrix) stiffWeight = dampWeight = 0.0;  // Q alone
  double* val = A_.valuePtr();
  const int n = rope_.dofs();
  if (matrix) {
    std::fill(val, val + A_.nonZeros(), 0.0);
    for (std::size_t i = 0; i < mass_index_.size(); ++i)
      val[mass_index_[i]] += massWeight * mass_value_[i];
  }
  Q.setZero(n);
  Vector12 Qe;
  Matrix12 Ke;
  const int* idx = element_index_.data();
  for (int k = 0; k < rope_.elements(); ++k, idx += 144) {
    if (from) {
      // The step's start at the element's Gauss points (energyConsistentStep fills them).
      ancfElasticForceDiscreteGradient(
          rope_.element(), &step_start_[k * rope_.element().gauss_points], q.segment<12>(6 * k), Qe,
          stiffWeight != 0.0 ? &Ke : nullptr);
    } else {
      ancfElasticForce(rope_.element(), q.segment<12>(6 * k), Qe,
                       stiffWeight != 0.0 ? &Ke : nullptr);
    }
    Q.segment<12>(6 * k) += Qe;
    if (stiffWeight != 0.0) {
      const double* ke = Ke.data();
      for (int e = 0; e < 144; ++e) val[idx[e]] += stiffWeight * ke[e];
    }
    if (rope_damping_ == 0.0) continue;
    ancfAxialDampingForce(rope_.element(), rope_damping_, qd.segment<12>(6 * k),
                          vd.segment<12>(6 * k), Qe, dampWeight != 0.0 ? &Ke : nullptr);
    Q.segment<12>(6 * k) += Qe;
    if (dampWeight == 0.0) continue;
    const double* ce = Ke.data();
    for (int e = 0; e < 144; ++e) val[idx[e]] += dampWeight * ce[e];
  }
  if (rope_.hasRigging()) {
    // The rigging bar on [r_n; r_p] (AncfRope::setRigging), its axial damping as the rope's.
    const std::array<int, 6> r = rope_.riggingDofs();
    Vector6 qb, vb, Qb;
    Matrix6 Kb, Cb;
    // Its tangents only where the matrix is assembled.
    Matrix6* const kb = matrix ? &Kb : nullptr;
    for (int i = 0; i < 6; ++i) qb(i) = q(r[i]);
    if (from) {
      Vector6 qb0;
      for (int i = 0; i < 6; ++i) qb0(i) = from->q(r[i]);
      rope_.rigging().discreteGradientForce(qb0, qb, Qb, kb);
    } else {
      rope_.rigging().elasticForce(qb, Qb, kb);
    }
    for (int i = 0; i < 6; ++i) Q(r[i]) += Qb(i);
    for (int i = 0; i < 6; ++i) qb(i) = qd(r[i]), vb(i) = vd(r[i]);
    rope_.rigging().dampingForce(rope_damping_, qb, vb, Qb, matrix ? &Cb : nullptr);
    for (int i = 0; i < 6; ++i) Q(r[i]) += Qb(i);
    if (matrix) {
      const Matrix6 Ab = stiffWeight * Kb + dampWeight * Cb;
      for (int e = 0; e < 36; ++e) val[rigging_index_[e]] += Ab.data()[e];
    }
  }
  if (ground_) {
    // The ground on the payload point: Q -= f, and -df/dq, -df/dv in the iteration matrix (for
    // an energy-consistent step the step's mean force, whose derivatives are those of twice it).
    const int e = rope_.positionIndex(rope_.nodes() - 1);
    const GroundContactForce c =
        from ? ground_->stepMeanForce(from->q.segment<3>(e), q.segment<3>(e), from->v.segment<3>(e),
                                      v.segment<3>(e))
             : ground_->force(q.segment<3>(e), v.segment<3>(e));
    Q.segment<3>(e) -= c.f;
    if (matrix && (c.df_dr.any() || c.df_dv.any())) {
      const Eigen::Matrix3d Ac = contactMatrixPart(c, stiffWeight, dampWeight);
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) A_.coeffRef(e + i, e + j) += Ac(i, j);
    }
  }
  if (!matrix) return;
  for (int d = 0; d < 3; ++d) {
    A_.coeffRef(n + d, d) = 1.0;
    A_.coeffRef(d, n + d) = 1.0;
    for (int e = 0; e < 3; ++e) A_.coeffRef(n + d, n + e) = -G(d, e);
  }
}

// Block elimination of the support (see the header): the reduced right-hand side is
// [r_q; r_c + D A_z^-1 r_z]; afterwards dz = A_z^-1 (r_z + D^T dy).
Eigen::VectorXd FullOrderSolver::condensedRhs(const Eigen::VectorXd& rq, const Eigen::VectorXd& rz,
                                              const Eigen::Vector3d& rc,
                                              Eigen::VectorXd& Azinv_rz) const {
  const int n = rope_.dofs();
  Eigen::VectorXd rhs(n + 3);
  rhs.head(n) = rq;
  rhs.tail<3>() = condenseSupport(support_, rc, rz, Azinv_rz);
  return rhs;
}

void FullOrderSolver::factorize(const std::string& what) {
  if (!factorizeIterationMatrix()) throw NumericalFailure(what + ": singular iteration matrix");
}

bool FullOrderSolver::factorizeIterationMatrix() {
  ++factorizations_;
  band_factorized_ = band_->factorize(A_);
  if (band_factorized_) return true;
  ldlt_.factorize(A_);
  return ldlt_.info() == Eigen::Success;
}

Eigen::VectorXd FullOrderSolver::solveFactorized(const Eigen::VectorXd& rhs) const {
  return band_factorized_ ? band_->solve(rhs) : Eigen::VectorXd(ldlt_.solve(rhs));
}

namespace {
// The ground set aside for a scope and put back when it ends, also by an exception.
class GroundSetAside {
 public:
  explicit GroundSetAside(std::optional<GroundContact>& ground)
      : ground_(ground), kept_(std::move(ground)) {
    ground_.reset();
  }
  ~GroundSetAside() { ground_ = std::move(kept_); }
  GroundSetAside(const GroundSetAside&) = delete;
  GroundSetAside& operator=(const GroundSetAside&) = delete;

 private:
  std::optional<GroundContact>& ground_;
  std::optional<GroundContact> kept_;
};
}  // namespace

CoupledState FullOrderSolver::solveStatic(const Eigen::VectorXd& q_guess,
                                          const Eigen::VectorXd& z_guess,
                                          const Eigen::Vector3d& end_force) {
  // The hanging rope's statics, as the pendulum's: without the ground (a start whose load it
  // would reach is refused, SupportedRopeSimulation::checkRestsClearOfGround).
  const GroundSetAside aside(ground_);
  const int n = rope_.dofs(), m = support_.size();
  CoupledState s;
  s.q = q_guess;
  s.v = Eigen::VectorXd::Zero(n);
  s.qdd = Eigen::VectorXd::Zero(n);
  s.a = Eigen::VectorXd::Zero(n);
  s.z = z_guess.size() == m ? z_guess : Eigen::VectorXd::Zero(m);
  s.zd = s.zdd = s.za = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd Q, F = rope_.gravityForce(), Azr;
  F.segment<3>(rope_.positionIndex(rope_.nodes() - 1)) += end_force;  // on the payload
  const Eigen::Matrix3d G = support_.setIterationWeights(0.0, 0.0, 1.0);
  // Statics use a pivoting LU: without the mass term the rope block can be semi-definite
  // (bending-only lateral stiffness at low tension), where LDL^T without pivoting stops.
  Eigen::UmfPackLU<SparseMatrix> lu;
  for (int it = 0; it < 50; ++it) {
    assemble(s.q, s.v, 0.0, 1.0, 0.0, G, Q);
    Eigen::VectorXd rq = -(Q - F);
    rq.head<3>() -= s.lambda;
    Eigen::VectorXd rz;
    if (m > 0)
      rz = -(support_.internalForce(s.z, s.zd, s.zdd) - support_.pointForceToCoordinates(s.lambda));
    const Eigen::Vector3d rc = -(s.q.head<3>() - support_.point(s.z));
    const Eigen::VectorXd rhs = condensedRhs(rq, rz, rc, Azr);
    lu.compute(A_);
    if (lu.info() != Eigen::Success) throw NumericalFailure("static solve: singular tangent");
    const Eigen::VectorXd dx = lu.solve(rhs);
    // Limit the step to a tenth of the rope length: a poor guess must not overshoot.
    double scale = 1.0;
    const double dmax = dx.head(n).cwiseAbs().maxCoeff();
    if (dmax > 0.1 * rope_.length()) scale = 0.1 * rope_.length() / dmax;
    s.q += scale * dx.head(n);
    s.lambda += scale * dx.tail<3>();
    if (m > 0) s.z += scale * (Azr + support_.solvePointForce(dx.tail<3>()));
    if (!s.q.allFinite() || !s.z.allFinite())
      throw NumericalFailure("static solve: non-finite state");
    if (scale == 1.0 && dmax < 1e-11 * std::max(1.0, rope_.length())) return s;
  }
  throw NumericalFailure("static solve did not converge in 50 Newton iterations");
}

CoupledState FullOrderSolver::solveSwingEquilibrium(double swing_rad, double az_rad,
                                                    Eigen::Vector3d* holding_force) {
  const Eigen::Vector3d horiz(std::cos(az_rad), std::sin(az_rad), 0.0);
  const double g = rope_.gravity().norm();
  const double endW = rope_.endMass() * g;
  const double W = endW + rope_.element().mass_per_length * rope_.length() * g;
  const Eigen::Vector3d top = support_.point(Eigen::VectorXd::Zero(support_.size()));
  auto chordAngle = [&](const CoupledState& s) {
    const Eigen::Vector3d c =
        rope_.position(s.q, rope_.nodes() - 1) - s.q.head<3>();  // the payload
    return std::atan2(c.dot(horiz), -c.z());
  };
  // Start from the straight rope stretched by the static tension profile
  // T(s) = (W_end + mu g (L - s)) / cos(theta): the tension's geometric stiffness makes the
  // tangent definite (an unstressed straight rope can rotate about the anchor at no cost).
  const Eigen::Vector3d d = swingDirection(swing_rad, az_rad);
  const double perLength = (W - endW) / rope_.length();
  const Eigen::VectorXd guess =
      rope_.stretchedStraight(top, d, endW / std::cos(swing_rad), perLength / std::cos(swing_rad));
  // Closed-form start: a massless rope's chord angle obeys tan(theta) = H / W_end; the rope's
  // own weight adds half its weight.
  double H0 = std::tan(swing_rad) * (endW + 0.5 * (W - endW));
  CoupledState s0 = solveStatic(guess, Eigen::VectorXd(), H0 * horiz);
  if (swing_rad == 0.0) {
    if (holding_force) holding_force->setZero();
    return s0;
  }
  double H1 = H0 * 1.02;
  CoupledState s1 = solveStatic(s0.q, s0.z, H1 * horiz);
  double e0 = chordAngle(s0) - swing_rad, e1 = chordAngle(s1) - swing_rad;
  for (int it = 0; it < 30 && std::abs(e1) > 1e-12; ++it) {
    const double H2 = H1 - e1 * (H1 - H0) / (e1 - e0);
    H0 = H1;
    e0 = e1;
    H1 = H2;
    s1 = solveStatic(s1.q, s1.z, H1 * horiz);
    e1 = chordAngle(s1) - swing_rad;
  }
  if (std::abs(e1) > 1e-9) throw NumericalFailure("swing equilibrium: chord angle not reached");
  if (holding_force) *holding_force = H1 * horiz;
  return s1;
}

void FullOrderSolver::initializeAccelerations(CoupledState& s) {
  const int n = rope_.dofs(), m = support_.size();
  prepareSupportState(support_, s);
  Eigen::VectorXd Q, Azr, rz;
  const Eigen::Matrix3d G = support_.setIterationWeights(1.0, 0.0, 0.0);
  assemble(s.q, s.v, 1.0, 0.0, 0.0, G, Q);
  if (m > 0) rz = -support_.internalForce(s.z, s.zd, s.zdd);
  const Eigen::VectorXd rhs =
      condensedRhs(rope_.gravityForce() - Q, rz, Eigen::Vector3d::Zero(), Azr);
  factorize("initial accelerations");
  const Eigen::VectorXd x = solveFactorized(rhs);
  storeConsistentAccelerations(support_, x.head(n), x.tail<3>(), Azr, s);
  last_step_length_ = rope_.length();  // a start, not a hoist
  switching_.switching = false;        // consistent accelerations: generalized-alpha's start
}

// One step of size h_, halved where Newton fails (stepWithHalving).
void FullOrderSolver::step(CoupledState& s) {
  hoisting_ = rope_.length() != last_step_length_;
  last_step_length_ = rope_.length();
  stepWithHalving(
      s, h_, kMaxHalvings, support_,
      [this](CoupledState& x, double h, std::string& why) { return tryStep(x, h, why); },
      halved_steps_);
}

double FullOrderSolver::ropeEnergyCreated(const CoupledState& start, const CoupledState& s) const {
  // The rope's own energy E_r = 1/2 v^T M v + U(q) - F^T q changes by the work of the top force,
  // -lambda . dr_0 (trapezoid in time), less the damper's dissipation (at the midpoint).
  const int e = rope_.positionIndex(rope_.nodes() - 1);
  const auto ropeEnergy = [&](const CoupledState& x) {
    const double ground = ground_ ? ground_->energy(x.q.segment<3>(e)) : 0.0;
    return ropeOwnEnergy(x) + ground;
  };
  const Eigen::VectorXd dq = s.q - start.q;
  const double before = ropeEnergy(start);  // first: the start is the remembered state
  double created = ropeEnergy(s) - before + 0.5 * (start.lambda + s.lambda).dot(dq.head<3>());
  if (ground_) {
    // Less the work of the ground's damper and friction (at the midpoint, <= 0).
    const Eigen::Vector3d rm = 0.5 * (start.q.segment<3>(e) + s.q.segment<3>(e));
    const Eigen::Vector3d vm = 0.5 * (start.v.segment<3>(e) + s.v.segment<3>(e));
    created -= ground_->dissipativeForce(rm, vm).dot(dq.segment<3>(e));
  }
  if (rope_damping_ > 0.0) {
    // Less the dampers' work (the rope's and the rigging bar's, at the midpoint, <= 0).
    created += rope_.axialDampingForce(rope_damping_, 0.5 * (start.q + s.q), 0.5 * (start.v + s.v))
                   .dot(dq);
  }
  return created;
}

// E_r = 1/2 v^T M v + U(q) - F^T q; the last state's value is kept, since a step's start is
// the end of the step before, whose check computed it (the rope's revision keys it).
double FullOrderSolver::ropeOwnEnergy(const CoupledState& x) const {
  RopeEnergyMemo& m = rope_energy_memo_;
  if (m.revision == rope_.revision() && m.q.size() == x.q.size() && m.q == x.q && m.v == x.v)
    return m.value;
  m.value = 0.5 * x.v.dot(rope_.massMatrix() * x.v) + rope_.elasticEnergy(x.q) -
            rope_.gravityForce().dot(x.q);
  m.revision = rope_.revision();
  m.q = x.q;
  m.v = x.v;
  return m.value;
}

const Eigen::VectorXd& FullOrderSolver::axialStrainsAt(const Eigen::VectorXd& q) const {
  for (int i : {strain_memo_last_, 1 - strain_memo_last_}) {
    const StrainMemo& m = strain_memo_[i];
    if (m.revision == rope_.revision() && m.q.size() == q.size() && m.q == q) {
      strain_memo_last_ = i;
      return m.eps;
    }
  }
  // Replace the entry not asked last, so that two calls in a row never evict each other.
  strain_memo_last_ = 1 - strain_memo_last_;
  StrainMemo& m = strain_memo_[strain_memo_last_];
  rope_.axialStrains(q, m.eps);
  m.q = q;
  m.revision = rope_.revision();
  return m.eps;
}

// A tension-only rope (see the header): the rule of integrators/tension_only_step.hpp.
bool FullOrderSolver::tryStep(CoupledState& s, double h, std::string& why) {
  if (!rope_.tensionOnly() && !ground_) return generalizedAlphaStep(s, h, why);
  TensionOnlyRope rope;
  rope.generalized_alpha_step = [this](CoupledState& x, double dt, std::string& w) {
    return generalizedAlphaStep(x, dt, w);
  };
  rope.energy_consistent_step = [this](CoupledState& x, double dt, std::string& w) {
    return energyConsistentStep(x, dt, w);
  };
  rope.switch_work_error = [this](const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
    const int e = rope_.positionIndex(rope_.nodes() - 1);
    const double ground =
        ground_ ? ground_->switchWorkError(q0.segment<3>(e), q1.segment<3>(e)) : 0.0;
    if (!rope_.tensionOnly()) return ground;
    // (the start's strains are the step before's end's: axialStrainsAt keeps both)
    const Eigen::VectorXd& eps0 = axialStrainsAt(q0);
    const Eigen::VectorXd& eps1 = axialStrainsAt(q1);
    return rope_.slackSwitchWorkError(q0, q1, eps0, eps1) + ground;
  };
  rope.energy_created = [this](const CoupledState& a, const CoupledState& b) {
    return ropeEnergyCreated(a, b);
  };
  rope.restart_accelerations = [this](CoupledState& x) { initializeAccelerations(x); };
  const double tolerance = tensionOnlySwitchTolerance(
      rope_.endMass() + rope_.element().mass_per_length * rope_.length(), rope_.length());
  return tensionOnlyStep(rope, tolerance, hoisting_, switching_, s, h, why);
}

bool FullOrderSolver::generalizedAlphaStep(CoupledState& s, double h, std::string& why) {
  const int n = rope_.dofs();
  const SparseMatrix& M = rope_.massMatrix();
  Eigen::VectorXd Q;
  const RopeIncrement increment = [&](const CoupledState& x, const NewtonWeights& w,
                                      const Eigen::Vector3d& rc, Eigen::VectorXd& dq,
                                      Eigen::Vector3d& dmu, std::string& reason) {
    // d/dq of the damping force through v' = gamma / (beta h) dq, times beta h^2.
    bool keep = w.keep_matrix && (!w.keep_foreseen_from_last_step || lawBranchesAsAtMatrix(x.q));
    rank_one_terms_.clear();
    // The tangent changes of the few points that switched since the matrix's iterate, as
    // rank-one terms (rankOneTermsApply): where the last step's matrix was offered and a point
    // switched; where a kept matrix follows a correction that needed them; and within the step
    // where this step's matrix would otherwise be assembled afresh.
    const bool offered_across_switch = w.keep_matrix && w.keep_foreseen_from_last_step && !keep;
    const bool offered_after_terms = w.keep_matrix && !w.keep_foreseen_from_last_step &&
                                     column_factorization_ == matrix_factorization_ &&
                                     !column_point_.empty();
    const bool this_steps_matrix =
        !w.keep_matrix && matrix_ga_step_ == ga_steps_ && step_looks_for_switches_;
    bool strains_at_iterate = false;  // iterate_eps_ holds x.q's strains
    if ((offered_across_switch || offered_after_terms || this_steps_matrix) &&
        rankOneTermsApply(x.q, h)) {
      const bool few = axialTangentChanges(x.q, w.stiffness, rank_one_terms_, rank_one_points_) &&
                       contactTangentChanges(x.q, x.v, w, rank_one_terms_, rank_one_points_);
      strains_at_iterate = true;
      keep = few && (offered_after_terms || !rank_one_terms_.empty());
      if (!keep) rank_one_terms_.clear();
    }
    assemble(x.q, x.v, w.mass, w.stiffness, w.damping, w.G, Q, nullptr, !keep);
    if (!keep) assembledMatrixAt(x, w, h, strains_at_iterate);
    Eigen::VectorXd rhs(n + 3);
    rhs.head(n) = -w.stiffness * (M * x.qdd + Q - rope_.gravityForce());
    rhs.head<3>() -= w.stiffness * x.lambda;
    rhs.tail<3>() = rc;
    if (!rank_one_terms_.empty()) {
      Eigen::VectorXd dx;
      const auto solve = [this](const Eigen::VectorXd& b) { return solveFactorized(b); };
      std::vector<const Eigen::VectorXd*> columns;
      contact_columns_.clear();
      for (std::size_t j = 0; j < rank_one_terms_.size(); ++j)
        columns.push_back(&rankOneColumn(rank_one_terms_[j], rank_one_points_[j]));
      if (solveWithRankOneTerms(solve, rank_one_terms_, columns, rhs, dx)) {
        ++matrix_reusing_corrections_;
        ++rank_one_corrections_;
        if (std::count(rank_one_points_.begin(), rank_one_points_.end(), kContactPoint) > 0)
          ++contact_rank_one_corrections_;
        dq = dx.head(n);
        dmu = dx.tail<3>();
        return true;
      }
      // The terms' system singular: this iterate's own matrix.
      assemble(x.q, x.v, w.mass, w.stiffness, w.damping, w.G, Q, nullptr, true);
      assembledMatrixAt(x, w, h, strains_at_iterate);
      keep = false;
    }
    const bool ok = solveIncrement(rhs, dq, dmu, reason, !keep);
    if (!keep) matrix_factorization_ = factorizations_;
    return ok;
  };
  ++ga_steps_;
  // Within a step, only a rope slack somewhere at its start, or a payload on the ground, looks
  // for switched points (a taut rope's corrections that miss quadratic contraction do so for
  // its geometry, not its law).
  step_looks_for_switches_ = rankOneTermsPossible() &&
                             (payloadTouchesAt(s.q) || axialStrainsAt(s.q).minCoeff() < kSlackBand);
  return newtonStep(ga_, support_, newton_, h, increment, s, why, newton_workspace_, nullptr,
                    &newton_memory_);
}

void FullOrderSolver::assembledMatrixAt(const CoupledState& x, const NewtonWeights& w, double h,
                                        bool strains_at_iterate) {
  matrix_q_ = x.q;
  matrix_contact_ = contactMatrixPartAt(x.q, x.v, w);
  if (strains_at_iterate)
    std::swap(matrix_eps_, iterate_eps_);
  else
    matrix_eps_.resize(0);
  matrix_h_ = h;
  matrix_revision_ = rope_.revision();
  matrix_ga_step_ = ga_steps_;
}

bool FullOrderSolver::rankOneTermsPossible() const {
  return newton_.rank_one_switch_updates && rope_.tensionOnly() && !rope_.hasRigging() &&
         rope_damping_ == 0.0;
}

bool FullOrderSolver::rankOneTermsApply(const Eigen::VectorXd& q, double h) const {
  return rankOneTermsPossible() && matrix_q_.size() == q.size() && matrix_h_ == h &&
         matrix_revision_ == rope_.revision() && band_factorized_ &&
         matrix_factorization_ == factorizations_;
}

double FullOrderSolver::payloadPenetrationAt(const Eigen::VectorXd& q) const {
  return ground_->penetration(q.segment<3>(rope_.positionIndex(rope_.nodes() - 1)));
}

bool FullOrderSolver::payloadTouchesAt(const Eigen::VectorXd& q) const {
  return ground_ && payloadPenetrationAt(q) > 0.0;
}

Eigen::Matrix3d FullOrderSolver::contactMatrixPart(const GroundContactForce& c, double stiffWeight,
                                                   double dampWeight) {
  return -stiffWeight * c.df_dr - dampWeight * c.df_dv;
}

Eigen::Matrix3d FullOrderSolver::contactMatrixPartAt(const Eigen::VectorXd& q,
                                                     const Eigen::VectorXd& v,
                                                     const NewtonWeights& w) const {
  if (!ground_) return Eigen::Matrix3d::Zero();
  const int e = rope_.positionIndex(rope_.nodes() - 1);
  return contactMatrixPart(ground_->force(q.segment<3>(e), v.segment<3>(e)), w.stiffness,
                           w.damping);
}

// The contact's share of A_ at (q, v) less its share at the matrix's iterate, as rank-one
// terms at the payload point (symmetricBlockTerms).
bool FullOrderSolver::contactTangentChanges(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                            const NewtonWeights& w, std::vector<RankOneTerm>& terms,
                                            std::vector<int>& points) const {
  if (!ground_) return true;
  const Eigen::Matrix3d at = contactMatrixPartAt(q, v, w);
  const double size = std::max(at.cwiseAbs().maxCoeff(), matrix_contact_.cwiseAbs().maxCoeff());
  const int e = rope_.positionIndex(rope_.nodes() - 1);
  // (twelve entries from the offset within A_: the end node's positions at 3)
  const int added =
      symmetricBlockTerms(at - matrix_contact_, e - 3, 3, kContactRoundOff * size, terms);
  if (added < 0) return false;
  points.insert(points.end(), added, kContactPoint);
  return true;
}

bool FullOrderSolver::payloadClearAtMatrixAnd(const Eigen::VectorXd& q) const {
  return !ground_ || (payloadPenetrationAt(matrix_q_) <= 0.0 && payloadPenetrationAt(q) <= 0.0);
}

// A_ at q differs from A_ at matrix_q_ by stiffWeight times the change of the element tangents;
// at a Gauss point whose law changed its slope N' that change is w_g l (N'_1 - N'_0) v v^T
// (ancfAxialTangentShape) plus what q's change turns in the other terms (the small change a
// kept matrix ignores anyway).
bool FullOrderSolver::axialTangentChanges(const Eigen::VectorXd& q, double stiffWeight,
                                          std::vector<RankOneTerm>& terms,
                                          std::vector<int>& points) const {
  terms.clear();
  points.clear();
  if (matrix_eps_.size() == 0) rope_.axialStrains(matrix_q_, matrix_eps_);
  rope_.axialStrains(q, iterate_eps_);
  const AncfCableProperties& p = rope_.element();
  const int g = p.gauss_points;
  const double EA = p.axial_stiffness;
  for (int i = 0; i < iterate_eps_.size(); ++i) {
    double N0, dN0, N1, dN1;
    ancfAxialLaw(EA, matrix_eps_(i), true, N0, dN0);
    ancfAxialLaw(EA, iterate_eps_(i), true, N1, dN1);
    if (dN1 == dN0) continue;
    if (static_cast<int>(terms.size()) == kMaxRankOneTerms) return false;
    RankOneTerm t;
    const int k = i / g;
    t.offset = 6 * k;
    t.c = stiffWeight * ancfAxialTangentShape(p, matrix_q_.segment<12>(6 * k), i % g, t.u) *
          (dN1 - dN0);
    terms.push_back(t);
    points.push_back(i);
  }
  return true;
}

const Eigen::VectorXd& FullOrderSolver::rankOneColumn(const RankOneTerm& term, int point) {
  if (column_factorization_ != matrix_factorization_) {
    column_factorization_ = matrix_factorization_;
    column_point_.clear();
    column_.clear();
  }
  if (point == kContactPoint) {
    // A^-1 u = sum_i u_i A^-1 e_i over the end node's three positions (their columns kept under
    // the ids -1 - i).
    Eigen::VectorXd y = Eigen::VectorXd::Zero(A_.rows());
    for (int i = 0; i < 3; ++i) {
      RankOneTerm unit;
      unit.offset = term.offset;
      unit.u(3 + i) = 1.0;
      y += term.u(3 + i) * rankOneColumn(unit, -1 - i);
    }
    contact_columns_.push_back(std::move(y));
    return contact_columns_.back();
  }
  for (std::size_t j = 0; j < column_point_.size(); ++j)
    if (column_point_[j] == point) return column_[j];
  Eigen::VectorXd u = Eigen::VectorXd::Zero(A_.rows());
  u.segment<12>(term.offset) = term.u;
  column_point_.push_back(point);
  column_.push_back(solveFactorized(u));
  return column_.back();
}

// Taut at every Gauss point (and the rigging bar) at both iterates: the trapezoid work error of
// the axial law is then exactly 0 (AncfRope::slackSwitchWorkError), as for a symmetric law; and
// the payload clear of the ground at both.
bool FullOrderSolver::lawBranchesAsAtMatrix(const Eigen::VectorXd& q) const {
  if (matrix_q_.size() != q.size() || rope_.slackSwitchWorkError(matrix_q_, q) != 0.0) return false;
  return payloadClearAtMatrixAnd(q);
}

// The energy-consistent step (docs/model.md "Energy-consistent step", energyConsistentScheme):
//   M (v1 - v0) / h = F - Qbar(q0, q1) - Q_d(q_m, (q1 - q0) / h) - C_q^T lambda,
//   q1 - q0 = h ((1/2 + theta) v1 + (1/2 - theta) v0),
// Qbar the discrete gradient of the elastic energy, the damper at the midpoint and the step's own
// mean velocity, lambda the step's mean constraint force, and the support at the same means
// (newtonStep). The elastic forces' work equals U(q1) - U(q0), the damper dissipates, the
// constraint force does no work (C is linear and holds at both ends), and the kinetic energy
// changes by the work less theta dv^T M dv.
bool FullOrderSolver::energyConsistentStep(CoupledState& s, double h, std::string& why) {
  const int n = rope_.dofs();
  const SparseMatrix& M = rope_.massMatrix();
  const GeneralizedAlpha scheme = energyConsistentScheme(h);
  const CoupledState start = s;
  const int points = rope_.element().gauss_points;
  step_start_.resize(static_cast<std::size_t>(rope_.elements() * points));
  for (int k = 0; k < rope_.elements(); ++k)
    ancfElementStepStart(rope_.element(), start.q.segment<12>(6 * k), &step_start_[k * points]);
  startEnergyConsistentStep(s);
  ec_step_ = h;
  Eigen::VectorXd Q;
  const RopeIncrement increment = [&](const CoupledState& x, const NewtonWeights& w,
                                      const Eigen::Vector3d& rc, Eigen::VectorXd& dq,
                                      Eigen::Vector3d& dmu, std::string& reason) {
    // d Qbar / d q1 is half the stand-in (the tangent at q1 = q0); the damper's velocity moves
    // by dq / h.
    assemble(x.q, x.v, w.mass, 0.5 * w.stiffness, scheme.beta * h, w.G, Q, &start, !w.keep_matrix);
    Eigen::VectorXd rhs(n + 3);
    rhs.head(n) = -w.stiffness * (M * x.qdd + Q - rope_.gravityForce());
    rhs.head<3>() -= w.stiffness * x.lambda;
    rhs.tail<3>() = rc;
    return solveIncrement(rhs, dq, dmu, reason, !w.keep_matrix);
  };
  const Eigen::VectorXd& z0 = start.z;
  if (!newtonStep(scheme, support_, newton_, h, increment, s, why, newton_workspace_,
                  support_.size() > 0 ? &z0 : nullptr)) {
    s = start;
    return false;
  }
  return true;
}

bool FullOrderSolver::solveIncrement(const Eigen::VectorXd& rhs, Eigen::VectorXd& dq,
                                     Eigen::Vector3d& dmu, std::string& reason, bool refactorize) {
  if (!refactorize) ++matrix_reusing_corrections_;
  if (refactorize && !factorizeIterationMatrix()) {
    reason = "singular iteration matrix";
    return false;
  }
  const Eigen::VectorXd dx = solveFactorized(rhs);
  dq = dx.head(rope_.dofs());
  dmu = dx.tail<3>();
  return true;
}

double mechanicalEnergy(const AncfRope& rope, const RopeSupport& support, const CoupledState& s) {
  return 0.5 * s.v.dot(rope.massMatrix() * s.v) + rope.elasticEnergy(s.q) -
         rope.gravityForce().dot(s.q) + support.energy(s.z, s.zd);
}

double ropeTopTension(const AncfRope& rope, const CoupledState& s) {
  return ropeTopTension(s.lambda, rope.topMass(), s.qdd.head<3>(), rope.gravity());
}

double FullOrderSolver::energy(const CoupledState& s) const {
  const double ground =
      ground_ ? ground_->energy(s.q.segment<3>(rope_.positionIndex(rope_.nodes() - 1))) : 0.0;
  return mechanicalEnergy(rope_, support_, s) + ground;
}

double FullOrderSolver::topTension(const CoupledState& s) const { return ropeTopTension(rope_, s); }

double FullOrderSolver::constraintError(const CoupledState& s) const {
  return crane_twin::constraintError(support_, s);
}

}  // namespace crane_twin
