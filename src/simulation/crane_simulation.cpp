#include "crane_twin/simulation/crane_simulation.hpp"

#include <cmath>
#include <iomanip>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/rope/held_rope_equilibrium.hpp"
#include "crane_twin/rope/rope_modes.hpp"

namespace crane_twin {

namespace {
// The model, refused before the support (and its structural modes) is built where it asks for
// a rope this simulation cannot carry.
const CraneModel& ancfRopeModel(const CraneModel& m) {
  if (m.scene.rope.model == RopeModel::pendulum) {
    throw InputError(m.scene.file +
                     ": key 'rope.model': the ANCF rope cannot run a pendulum "
                     "scene (makeSimulation builds PendulumCraneSimulation for it)");
  }
  return m;
}
}  // namespace

AncfRope sceneRope(const CraneModel& m) {
  AncfRope rope(m.scene.rope.elements, m.scene.rope.length, m.rope.mass_per_length,
                m.rope.axial_stiffness, m.rope.bending_stiffness, m.end_mass, m.gravityVector(),
                m.trolleyMass());
  rope.setTensionOnly(m.scene.rope.tension_only);
  rope.setReevingLength(m.rope.reeving_equivalent_length);
  // The rigging: one sling leg of the hoist rope's wire (one fall's data, docs/model.md "Hook
  // block").
  if (m.scene.hasRigging()) {
    const RopeSettings& r = m.scene.rope;
    rope.setRigging(m.scene.hook_rigging_length, m.hook_mass, r.mass_per_length, r.axial_stiffness);
  }
  return rope;
}

CraneSimulation::CraneSimulation(const CraneModel& m) : SupportedRopeSimulation(ancfRopeModel(m)) {
  // Everything below refers to the own copy model_ (the support keeps references into it).
  const CraneModel& model = model_;
  const Scene& sc = model.scene;
  rope_ = std::make_unique<AncfRope>(sceneRope(model));
  solver_ = std::make_unique<FullOrderSolver>(*rope_, *support_, integratorFor(sc), sc.time_step);
  solver_->setRopeDamping(sc.rope.damping);
  solver_->setGround(groundContactOf(model));
}

CoupledState CraneSimulation::swingEquilibrium(double swing_rad, double az_rad,
                                               Eigen::Vector3d* holding_force) {
  return solver_->solveSwingEquilibrium(swing_rad, az_rad, holding_force);
}

void CraneSimulation::resetDrives() {
  const Scene& sc = model_.scene;
  resetDrivesAndPose();
  if (sc.crane && rope_->length() != sc.rope.length) {
    rope_->setLength(sc.rope.length);
    solver_->refreshMass();
  }
}

// Hoisting by uniform rescaling (docs/model.md): the new reference length is spread over all
// elements, the geometry and nodal velocities are kept (slope coordinates rescaled), M and F_g
// rebuilt so the rope's mass is mu L exactly.
void CraneSimulation::applyRopeLength(CoupledState& s) {
  const double from = rope_->length();
  if (!followHoistLength()) return;
  const double to = rope_->length();
  for (Eigen::VectorXd* x : {&s.q, &s.v, &s.qdd, &s.a}) rope_->rescaleHoistSlopes(*x, from, to);
}

bool CraneSimulation::followHoistLength() {
  const double to = hoistTargetLength();
  if (to == rope_->length()) return false;
  rope_->setLength(to);
  solver_->refreshMass();
  return true;
}

void CraneSimulation::continueFrom(const Simulation& other) {
  const auto* o = dynamic_cast<const CraneSimulation*>(&other);
  if (!o) throw InputError("continueFrom: the other run is not a full-order rope run");
  continueDrivesFrom(*o);
  if (o->rope_->length() != rope_->length()) {
    rope_->setLength(o->rope_->length());
    solver_->refreshMass();
  }
  // The generalized-alpha variables belong to a time step and a load: with another, restart.
  if (o->solver_->timeStep() == solver_->timeStep() && carriesTheLoadOf(*o)) {
    state_ = o->state_;
    solver_->continueSteppingOf(*o->solver_);
  } else {
    restartFrom(o->state_);
  }
}

void CraneSimulation::setMotion(const CoupledState& m) {
  checkMotionSizes(m, state_);
  CoupledState s = state_;
  s.q = m.q;
  s.v = m.v;
  s.z = m.z;
  s.zd = m.zd;
  restartFrom(s);
}

CoupledState CraneSimulation::initialState() {
  resetDrives();
  return sceneInitialState();
}

void CraneSimulation::initialize() { state_ = initialState(); }

void CraneSimulation::step() {
  advanceDrives(state_.t, solver_->timeStep(), state_.z);
  stepAfterDrives();
}

void CraneSimulation::stepAfterDrives() {
  applyRopeLength(state_);
  solver_->step(state_);
  if (ground_) {
    const int e = endPointIndex();
    setHookResting(state_.q.segment<3>(e), state_.v.segment<3>(e), solver_->topTension(state_));
  }
}

Eigen::VectorXd CraneSimulation::straightRope(const Eigen::Vector3d& top,
                                              const Eigen::Vector3d& dir) const {
  return rope_->straight(top, dir);
}

// The straight rope's stretched length from its tension profile T(x) = T_hook + w (L - x):
// S(L) = L + (T_hook L + w L^2 / 2) / EA = span, solved for L (EA follows L through the
// reeving: three fixed-point passes, each exact for the EA it takes).
double CraneSimulation::unloadedHangingLength(double span) {
  const double g = model_.scene.gravity;
  const double w = rope_->element().mass_per_length * g;
  const double hook = rope_->hasRigging()
                          ? (rope_->hookMass() +
                             0.5 * rope_->rigging().massPerLength() * rope_->rigging().length()) *
                                g
                          : 0.0;
  double L = span;
  for (int pass = 0; pass < 3; ++pass) {
    const double EA = rope_->element().axial_stiffness;
    const double a = 0.5 * w / EA, b = 1.0 + hook / EA;
    L = a > 0.0 ? (-b + std::sqrt(b * b + 4.0 * a * span)) / (2.0 * a) : span / b;
    rope_->setLength(L);
  }
  solver_->refreshMass();
  return L;
}

Eigen::VectorXd CraneSimulation::unloadedHangingRope(const Eigen::Vector3d& top,
                                                     const Eigen::Vector3d& dir) const {
  const double g = model_.scene.gravity, w = rope_->element().mass_per_length * g;
  // A rigging's lower half rests on the landed load (unloadedHangingLength): its bar
  // unstretched, the hoist rope carrying the hook block and the upper half.
  const double end_force =
      rope_->hasRigging() ? -0.5 * g * rope_->rigging().massPerLength() * rope_->rigging().length()
                          : 0.0;
  Eigen::VectorXd q = rope_->stretchedStraight(top, dir, end_force, w);
  // Hanging plumb without wind, that is its rest state. Inclined (a load landed off-centre),
  // the straight rope is not: its weight across it would sag it by decimetres in the first
  // seconds (2 m out under 64 m on the T8036: 0.48 m). Nor in a wind, which blows a rope
  // carrying only its own weight sideways (15 m/s across 66 m of the T8036's falls: 0.54 m at
  // its middle). So the rope settles between its held ends under its weight and the wind.
  const bool windswept = rope_->externalPerLength().head<2>().norm() > 0.0;
  if (dir.x() != 0.0 || dir.y() != 0.0 || windswept) settleBetweenHeldEnds(*rope_, q);
  return q;
}

void CraneSimulation::initializeAccelerations(CoupledState& s) {
  solver_->initializeAccelerations(s);
}

int CraneSimulation::endPointIndex() const { return rope_->positionIndex(rope_->nodes() - 1); }

double CraneSimulation::topTensionOf(const CoupledState& s) const {
  return ropeTopTension(*rope_, s);
}

double CraneSimulation::energyOf(const CoupledState& s) const { return solver_->energy(s); }

std::vector<bool> CraneSimulation::fullStatePositionBlocks() const {
  std::vector<bool> b(rope_->dofs() / 3, false);
  for (int j = 0; j < rope_->nodes(); ++j) b[rope_->positionIndex(j) / 3] = true;
  return b;
}

std::vector<Eigen::Vector3d> CraneSimulation::ropeCurve(int per_element) const {
  return rope_->sampleCurve(state_.q, per_element);
}

ModalBasis CraneSimulation::ropeModes(int count) {
  const CoupledState eq = solver_->solveSwingEquilibrium(0.0, 0.0);
  // The top node's three position DOFs are held by the constraint.
  const SparseMatrix K = withoutTopPosition(rope_->tangentStiffness(eq.q));
  const SparseMatrix M = withoutTopPosition(rope_->massMatrix());
  ModalOptions opt;
  opt.count = count;
  opt.shift = -1e-3;
  return lowestModes(K, M, opt);
}

}  // namespace crane_twin
