#include "crane_twin/crane_simulation.hpp"

#include <cmath>
#include <iomanip>

#include "crane_twin/config_reader.hpp"
#include "crane_twin/crane_snapshot.hpp"
#include "crane_twin/rope_modes.hpp"
#include "crane_twin/structure_support.hpp"

namespace crane_twin {

std::unique_ptr<RopeSupport> makeRopeSupport(const CraneModel& model) {
  const Scene& sc = model.scene;
  if (sc.slew_inertial_loads && (!model.structure || sc.structure_model == "rigid")) {
    throw InputError(sc.file + ": key 'slewing.inertial_loads': the inertial loads of slewing act "
                     "on a flexible structure (structure.model: modal or full); this scene has " +
                     (model.structure ? std::string("a rigid one") : std::string("none (crane: none)")));
  }
  if (!model.structure) return std::make_unique<FixedAnchor>(sc.anchor);
  const TowerCraneStructure& st = *model.structure;
  const double theta = sc.slew_angle;
  if (sc.structure_model == "rigid") {
    return std::make_unique<RigidTrolleySupport>(st, sc.trolley_radius, theta);
  }
  if (sc.structure_modes >= st.free_dofs) {
    throw InputError(sc.file + ": key 'structure.modes': must be below the structure's " +
                     std::to_string(st.free_dofs) + " DOF, got " +
                     std::to_string(sc.structure_modes));
  }
  ModalOptions opt;
  opt.count = sc.structure_modes;
  const ModalBasis b = lowestModes(st.K, st.M, opt);
  if (sc.structure_model == "modal") {
    auto modal = std::make_unique<ModalStructureSupport>(st, b, sc.structure_damping_ratio,
                                                         sc.trolley_radius, theta);
    if (sc.slew_inertial_loads) modal->enableSlewingLoads();
    return modal;
  }
  // full: Rayleigh damping matched at the first and the structure.modes-th frequency (a single
  // mode gives no second frequency: match at 10 w1 then).
  const double w1 = std::sqrt(b.omega2(0));
  const double wk = b.omega2.size() > 1 ? std::sqrt(b.omega2(b.omega2.size() - 1)) : 10.0 * w1;
  auto full = std::make_unique<FullStructureSupport>(st, sc.structure_damping_ratio, w1,
                                                     wk > w1 ? wk : 10.0 * w1, sc.trolley_radius,
                                                     theta);
  if (sc.slew_inertial_loads) full->enableSlewingLoads();
  return full;
}

CraneSimulation::CraneSimulation(const CraneModel& m) : model_(m), drives_(model_.scene) {
  // Everything below refers to the own copy model_ (the support keeps references into it).
  const CraneModel& model = model_;
  const Scene& sc = model.scene;
  if (sc.rope.model == "pendulum") {
    throw InputError(sc.file + ": key 'rope.model': the ANCF rope cannot run a pendulum scene "
                     "(makeSimulation builds PendulumCraneSimulation for it)");
  }
  const double trolleyMass = sc.crane ? sc.crane->trolley_mass : 0.0;
  rope_ = std::make_unique<AncfRope>(sc.rope.elements, sc.rope.length,
                                     model.rope.mass_per_length, model.rope.axial_stiffness,
                                     model.rope.bending_stiffness, model.end_mass,
                                     Eigen::Vector3d(0.0, 0.0, -sc.gravity), trolleyMass);
  support_ = makeRopeSupport(model);
  solver_ = std::make_unique<FullOrderSolver>(*rope_, *support_, GeneralizedAlpha::forScene(sc),
                                              sc.time_step);
  solver_->setRopeDamping(sc.rope.damping);
}

CoupledState CraneSimulation::staticState(Eigen::Vector3d* holding_force) {
  const Scene& sc = model_.scene;
  return solver_->solveSwingEquilibrium(sc.swing_deg * M_PI / 180.0,
                                        sc.swing_azimuth_deg * M_PI / 180.0, holding_force);
}

void CraneSimulation::resetDrives() {
  const Scene& sc = model_.scene;
  drives_.reset();
  if (!sc.crane) return;
  if (rope_->length() != sc.rope.length) {
    rope_->setLength(sc.rope.length);
    solver_->refreshMass();
  }
  support_->setPose(sc.slew_angle, sc.trolley_radius);
  support_->setSlewMotion(0.0, 0.0);
}

void CraneSimulation::advanceDrives(double t, double dt) {
  if (!drives_.advance(t, dt)) return;
  support_->setPose(drives_.slewAngle(), drives_.trolleyRadius());
  support_->setSlewMotion(drives_.slewRate(), drives_.slewAcceleration());
}

// Hoisting by uniform rescaling (docs/model.md): the new reference length is spread over all
// elements, the geometry and nodal velocities are kept (slope coordinates rescaled), M and F_g
// rebuilt so the rope's mass is mu L exactly.
void CraneSimulation::applyRopeLength(CoupledState& s) {
  if (!model_.scene.crane) return;
  const double from = rope_->length(), to = drives_.hoistLength();
  if (to == from) return;
  rope_->setLength(to);
  solver_->refreshMass();
  for (Eigen::VectorXd* x : {&s.q, &s.v, &s.qdd, &s.a}) AncfRope::rescaleSlopes(*x, from, to);
}

CoupledState CraneSimulation::initialState() {
  resetDrives();
  const Scene& sc = model_.scene;
  const double th = sc.swing_deg * M_PI / 180.0, az = sc.swing_azimuth_deg * M_PI / 180.0;
  CoupledState s;
  if (sc.initial_mode == "stress_free") {
    s.q = rope_->straight(support_->point(Eigen::VectorXd::Zero(support_->size())),
                          swingDirection(th, az));
    s.v = Eigen::VectorXd::Zero(rope_->dofs());
  } else {
    s = staticState();
  }
  s.v.segment<3>(rope_->dofs() - 6) += sc.payload_velocity;
  s.t = 0.0;
  solver_->initializeAccelerations(s);
  return s;
}

void CraneSimulation::initialize() { state_ = initialState(); }

void CraneSimulation::step() {
  advanceDrives(state_.t, solver_->timeStep());
  stepAfterDrives();
}

void CraneSimulation::stepAfterDrives() {
  applyRopeLength(state_);
  solver_->step(state_);
}

SeriesValues CraneSimulation::seriesOf(const CoupledState& s) const {
  const int e = rope_->dofs() - 6;
  SeriesValues v;
  v.t = s.t;
  v.payload = s.q.segment<3>(e);
  v.payload_velocity = s.v.segment<3>(e);
  v.cab = support_->cabDisplacement(s.z);
  v.jib_tip = support_->jibTipDisplacement(s.z);
  v.trolley = support_->point(s.z);
  v.rope_top_tension = ropeTopTension(*rope_, s);
  v.rope_length = rope_->length();
  v.slew_angle = drives_.slewAngle();
  v.trolley_radius = drives_.trolleyRadius();
  v.energy = mechanicalEnergy(*rope_, *support_, s);
  v.constraint_error = (s.q.head<3>() - support_->point(s.z)).norm();
  setCraneWarnings(model_, drives_, v);
  return v;
}

SeriesValues CraneSimulation::series() const { return seriesOf(state_); }

std::vector<Eigen::Vector3d> CraneSimulation::ropeCurve(int per_element) const {
  return sampleRopeCurve(state_.q, rope_->element().length, per_element);
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
