#include "crane_twin/crane_simulation.hpp"

#include <cmath>
#include <iomanip>

#include "crane_twin/config_reader.hpp"
#include "crane_twin/rope_modes.hpp"
#include "crane_twin/structure_support.hpp"

namespace crane_twin {

std::unique_ptr<RopeSupport> makeRopeSupport(const CraneModel& model) {
  const Scene& sc = model.scene;
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
    return std::make_unique<ModalStructureSupport>(st, b, sc.structure_damping_ratio,
                                                   sc.trolley_radius, theta);
  }
  // full: Rayleigh damping matched at the first and the structure.modes-th frequency (a single
  // mode gives no second frequency: match at 10 w1 then).
  const double w1 = std::sqrt(b.omega2(0));
  const double wk = b.omega2.size() > 1 ? std::sqrt(b.omega2(b.omega2.size() - 1)) : 10.0 * w1;
  return std::make_unique<FullStructureSupport>(st, sc.structure_damping_ratio, w1,
                                                wk > w1 ? wk : 10.0 * w1, sc.trolley_radius,
                                                theta);
}

CraneSimulation::CraneSimulation(const CraneModel& m) : model_(m) {
  // Everything below refers to the own copy model_ (the support keeps references into it).
  const CraneModel& model = model_;
  const Scene& sc = model.scene;
  if (sc.rope.model == "pendulum") {
    throw InputError(sc.file + ": key 'rope.model': the pendulum rope is not built yet");
  }
  if (sc.slew_inertial_loads) {
    throw InputError(sc.file + ": key 'slewing.inertial_loads': the inertial loads of slewing on the structure are not built yet");
  }
  for (const auto& c : sc.commands) {
    if (c.slew_rate != 0.0 || c.trolley_speed != 0.0 || c.hoist_speed != 0.0) {
      if (!sc.crane) {
        throw InputError(sc.file + ": key 'commands': drives need a crane (crane: none has none)");
      }
      drives_ = true;
    }
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
  if (!sc.crane) return;
  const CraneDescription& c = *sc.crane;
  slew_.emplace(c.slewing, sc.slew_angle);
  trolley_.emplace(c.trolley, sc.trolley_radius, c.min_radius, c.max_radius);
  hoist_.emplace(c.hoist, sc.rope.length, c.min_rope_length, c.max_rope_length);
  if (rope_->length() != sc.rope.length) {
    rope_->setLength(sc.rope.length);
    solver_->refreshMass();
  }
  slew_flags_ = trolley_flags_ = hoist_flags_ = DriveFlags{};
  manual_.reset();
  support_->setPose(sc.slew_angle, sc.trolley_radius);
}

void CraneSimulation::setCommand(const CommandEntry& c) {
  if (!std::isfinite(c.slew_rate) || !std::isfinite(c.trolley_speed) ||
      !std::isfinite(c.hoist_speed)) {
    throw std::invalid_argument("command with a non-finite rate");
  }
  if (!model_.scene.crane && (c.slew_rate != 0.0 || c.trolley_speed != 0.0 || c.hoist_speed != 0.0)) {
    throw InputError("drives need a crane (crane: none has none)");
  }
  manual_ = c;
  drives_ = true;
}

bool CraneSimulation::hoists() const {
  if (manual_ && manual_->hoist_speed != 0.0) return true;
  for (const auto& c : model_.scene.commands)
    if (c.hoist_speed != 0.0) return true;
  return false;
}

CommandEntry CraneSimulation::activeCommand(double t) const {
  if (manual_) return *manual_;
  CommandEntry active;
  for (const auto& c : model_.scene.commands) {
    if (c.t <= t + 1e-9) active = c;
  }
  return active;
}

void CraneSimulation::advanceDrives(double t, double dt) {
  if (!drives_ || !slew_) return;
  const CommandEntry c = activeCommand(t);
  slew_flags_ = slew_->advance(c.slew_rate, dt);
  trolley_flags_ = trolley_->advance(c.trolley_speed, dt);
  hoist_flags_ = hoist_->advance(c.hoist_speed, dt);
  support_->setPose(slew_->position(), trolley_->position());
}

// Hoisting by uniform rescaling (docs/model.md): the new reference length is spread over all
// elements, the geometry and nodal velocities are kept (slope coordinates rescaled), M and F_g
// rebuilt so the rope's mass is mu L exactly.
void CraneSimulation::applyRopeLength(CoupledState& s) {
  if (!hoist_) return;
  const double from = rope_->length(), to = hoist_->position();
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
    const Eigen::Vector3d d(std::sin(th) * std::cos(az), std::sin(th) * std::sin(az),
                            -std::cos(th));
    s.q = rope_->straight(support_->point(Eigen::VectorXd::Zero(support_->size())), d);
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
  applyRopeLength(state_);
  solver_->step(state_);
}

SeriesValues CraneSimulation::seriesOf(const CoupledState& s) const {
  const Scene& sc = model_.scene;
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
  v.slew_angle = slewAngle();
  v.trolley_radius = trolleyRadius();
  v.energy = mechanicalEnergy(*rope_, *support_, s);
  v.constraint_error = (s.q.head<3>() - support_->point(s.z)).norm();
  v.tension_ratio = v.rope_top_tension / model_.rope.breaking_force;
  if (v.tension_ratio > 1.0) v.warnings |= kTensionOverBreakingForce;
  if (sc.crane) {
    v.load_chart_ratio = sc.payload_mass / allowedLoad(*sc.crane, trolleyRadius());
    if (v.load_chart_ratio > 1.0 + 1e-12) v.warnings |= kOutsideLoadChart;
  }
  if (hoist_flags_.at_position_limit) v.warnings |= kRopeLengthAtLimit;
  if (trolley_flags_.at_position_limit) v.warnings |= kTrolleyAtLimit;
  if (slew_flags_.speed_limited || trolley_flags_.speed_limited || hoist_flags_.speed_limited) {
    v.warnings |= kCommandLimited;
  }
  return v;
}

SeriesValues CraneSimulation::series() const { return seriesOf(state_); }

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
