#include "crane_twin/simulation/pendulum_crane_simulation.hpp"

#include <cmath>
#include <stdexcept>

#include "crane_twin/integrators/numerical_failure.hpp"
#include "crane_twin/io/input_error.hpp"

namespace crane_twin {

PendulumCraneSimulation::PendulumCraneSimulation(const CraneModel& m) : SupportedRopeSimulation(m) {
  const Scene& sc = model_.scene;
  // With a rigging the rope's end carries the hook block and the payload hangs on a bar of one
  // fall's wire (docs/model.md "Hook block"), tension-only.
  rope_ = std::make_unique<PendulumRope>(sc.rope.length, model_.rope.mass_per_length,
                                         model_.rope.axial_stiffness,
                                         sc.hasRigging() ? model_.hook_mass : model_.end_mass,
                                         model_.gravityVector(), model_.trolleyMass());
  rope_->setTensionOnly(sc.rope.tension_only);
  rope_->setReevingLength(model_.rope.reeving_equivalent_length);
  solver_ = std::make_unique<PendulumSolver>(*rope_, *support_, integratorFor(sc), sc.time_step);
  solver_->setRopeDamping(sc.rope.damping);
  solver_->setGround(groundContactOf(model_));
  if (sc.hasRigging()) {
    rigging_ = std::make_unique<PendulumRope>(sc.hook_rigging_length, sc.rope.mass_per_length,
                                              sc.rope.axial_stiffness, model_.end_mass,
                                              model_.gravityVector(), 0.0);
    solver_->setRigging(rigging_.get());
  }
}

CoupledState PendulumCraneSimulation::swingEquilibrium(double swing_rad, double az_rad,
                                                       Eigen::Vector3d* holding_force) {
  return solver_->solveSwingEquilibrium(swing_rad, az_rad, holding_force);
}

Eigen::VectorXd PendulumCraneSimulation::straightRope(const Eigen::Vector3d& top,
                                                      const Eigen::Vector3d& dir) const {
  if (!rigging_) return PendulumRope::straight(top, dir, rope_->length());
  Eigen::VectorXd q(9);
  q << top, top + rope_->length() * dir, top + (rope_->length() + rigging_->length()) * dir;
  return q;
}

// What the bar's end carries with the payload landed [N]: the bar's own lower half (its length
// l: lumped at the end point, it hangs from the bar as the rope's lower half hangs from the rope
// above it, so the top carries the whole rope's weight as an unloaded rope's top does), and on a
// rigging the hook block and half the rigging.
double PendulumCraneSimulation::unloadedEndLoad(double l) const {
  const double bar = 0.5 * rope_->massPerLength() * l;
  if (!rigging_) return bar * model_.scene.gravity;
  return (rope_->endMass() + 0.5 * rigging_->massPerLength() * rigging_->length() + bar) *
         model_.scene.gravity;
}

// The bar's tension is uniform: with its end unloaded it is stretched by the end's load over
// EA / L (its lower half's weight, and the hook block on a rigging).
double PendulumCraneSimulation::unloadedHangingLength(double span) {
  const double L = span / (1.0 + unloadedEndLoad(span) / rope_->axialStiffness());
  rope_->setLength(L);
  return L;
}

Eigen::VectorXd PendulumCraneSimulation::unloadedHangingRope(const Eigen::Vector3d& top,
                                                             const Eigen::Vector3d& dir) const {
  const double l =
      rope_->length() * (1.0 + unloadedEndLoad(rope_->length()) / rope_->axialStiffness());
  if (!rigging_) return PendulumRope::straight(top, dir, l);
  Eigen::VectorXd q(9);
  q << top, top + l * dir, top + (l + rigging_->length()) * dir;
  // Off-centre, the hook block on the straight inclined line is not at rest (it swung towards
  // plumb, 6 mm within 0.2 s 2 m out): it settles where the bars and its weight balance,
  // Newton on the hook's position with a backtracking line search on the potential energy
  // (settleBetweenHeldEnds at full order), the top and the payload held.
  if (dir.x() != 0.0 || dir.y() != 0.0) settleHook(q);
  return q;
}

void PendulumCraneSimulation::settleHook(Eigen::VectorXd& q) const {
  const Eigen::Vector3d F = rope_->gravityForce().tail<3>() + rigging_->gravityForce().head<3>();
  const auto bars = [&](const Eigen::VectorXd& x, Eigen::Vector3d* r, Eigen::Matrix3d* K) {
    Vector6 Q1, Q2;
    Matrix6 K1, K2;
    rope_->elasticForce(x.head<6>(), Q1, K ? &K1 : nullptr);
    rigging_->elasticForce(x.tail<6>(), Q2, K ? &K2 : nullptr);
    if (r) *r = F - Q1.tail<3>() - Q2.head<3>();
    if (K) *K = K1.bottomRightCorner<3, 3>() + K2.topLeftCorner<3, 3>();
    return rope_->elasticEnergy(x.head<6>()) + rigging_->elasticEnergy(x.tail<6>()) -
           F.dot(x.segment<3>(3));
  };
  for (int it = 0; it < kHookSettleIterations; ++it) {
    Eigen::Vector3d r;
    Eigen::Matrix3d K;
    const double pi0 = bars(q, &r, &K);
    const Eigen::LLT<Eigen::Matrix3d> llt(K);
    if (llt.info() != Eigen::Success) break;
    const Eigen::Vector3d d = llt.solve(r);
    if (d.norm() < kHookSettleTolerance) return;
    Eigen::VectorXd trial = q;
    double step = 1.0;
    for (int k = 0; k < 40; ++k, step *= 0.5) {
      trial.segment<3>(3) = q.segment<3>(3) + step * d;
      if (d.norm() < kHookLineSearchBelow ||
          bars(trial, nullptr, nullptr) <= pi0 - 1e-4 * step * d.dot(r))
        break;
    }
    q = trial;
  }
  throw NumericalFailure(
      "the hook block between the rope and the rigging (initial.mode: landed) did not settle "
      "into its static equilibrium");
}

void PendulumCraneSimulation::initialize() {
  resetDrivesAndPose();
  rope_->setLength(model_.scene.rope.length);
  state_ = sceneInitialState();
}

void PendulumCraneSimulation::step() {
  if (advanceDrives(state_.t, solver_->timeStep(), state_.z) &&
      hangingLength() != rope_->length()) {
    rope_->setLength(hangingLength());
  }
  solver_->step(state_);
  if (ground_) {
    const int e = endPointIndex();
    setHookResting(state_.q.segment<3>(e), state_.v.segment<3>(e), solver_->topTension(state_));
  }
}

void PendulumCraneSimulation::continueFrom(const Simulation& other) {
  const auto* o = dynamic_cast<const PendulumCraneSimulation*>(&other);
  if (!o) throw InputError("continueFrom: the other run is not a pendulum rope run");
  if ((rigging_ == nullptr) != (o->rigging_ == nullptr)) {
    throw InputError("continueFrom: the other pendulum run has another hook rigging");
  }
  continueDrivesFrom(*o);
  rope_->setLength(o->rope_->length());
  state_ = o->state_;
  // The generalized-alpha variables belong to a time step and a load: with another, restart.
  if (o->solver_->timeStep() != solver_->timeStep() || !carriesTheLoadOf(*o)) {
    solver_->initializeAccelerations(state_);
  }
}

std::vector<Eigen::Vector3d> PendulumCraneSimulation::ropeCurve(int per_element) const {
  if (per_element < 1) throw std::invalid_argument("rope samples per element must be >= 1");
  std::vector<Eigen::Vector3d> points;
  for (int b = 0; b + 1 < ropeNodes(); ++b) {  // each bar straight
    const Eigen::Vector3d a = ropeNode(b), e = ropeNode(b + 1);
    for (int i = 0; i < per_element; ++i) points.push_back(a + (e - a) * i / per_element);
  }
  points.push_back(state_.q.tail<3>());
  return points;
}

}  // namespace crane_twin
