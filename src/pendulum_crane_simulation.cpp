#include "crane_twin/pendulum_crane_simulation.hpp"

#include <cmath>

#include "crane_twin/config_reader.hpp"
#include "crane_twin/crane_simulation.hpp"

namespace crane_twin {

PendulumCraneSimulation::PendulumCraneSimulation(const CraneModel& m)
    : model_(m), drives_(model_.scene) {
  const Scene& sc = model_.scene;
  const double trolleyMass = sc.crane ? sc.crane->trolley_mass : 0.0;
  rope_ = std::make_unique<PendulumRope>(sc.rope.length, model_.rope.mass_per_length,
                                         model_.rope.axial_stiffness, model_.end_mass,
                                         Eigen::Vector3d(0.0, 0.0, -sc.gravity), trolleyMass);
  support_ = makeRopeSupport(model_);
  solver_ = std::make_unique<PendulumSolver>(*rope_, *support_, GeneralizedAlpha::forScene(sc),
                                             sc.time_step);
  solver_->setRopeDamping(sc.rope.damping);
}

CoupledState PendulumCraneSimulation::staticState(Eigen::Vector3d* holding_force) {
  const Scene& sc = model_.scene;
  return solver_->solveSwingEquilibrium(sc.swing_deg * M_PI / 180.0,
                                        sc.swing_azimuth_deg * M_PI / 180.0, holding_force);
}

void PendulumCraneSimulation::initialize() {
  const Scene& sc = model_.scene;
  drives_.reset();
  rope_->setLength(sc.rope.length);
  support_->setPose(sc.slew_angle, sc.trolley_radius);
  support_->setSlewMotion(0.0, 0.0);
  const double th = sc.swing_deg * M_PI / 180.0, az = sc.swing_azimuth_deg * M_PI / 180.0;
  if (sc.initial_mode == "stress_free") {
    const int m = support_->size();
    state_ = CoupledState{};
    state_.z = state_.zd = Eigen::VectorXd::Zero(m);
    state_.q = PendulumRope::straight(support_->point(state_.z), swingDirection(th, az),
                                       rope_->length());
    state_.v = Eigen::VectorXd::Zero(PendulumRope::kDofs);
  } else {
    state_ = staticState();
  }
  state_.v.tail<3>() += sc.payload_velocity;
  state_.t = 0.0;
  solver_->initializeAccelerations(state_);
}

void PendulumCraneSimulation::step() {
  if (drives_.advance(state_.t, solver_->timeStep())) {
    support_->setPose(drives_.slewAngle(), drives_.trolleyRadius());
    support_->setSlewMotion(drives_.slewRate(), drives_.slewAcceleration());
    if (drives_.hoistLength() != rope_->length()) rope_->setLength(drives_.hoistLength());
  }
  solver_->step(state_);
}

SeriesValues PendulumCraneSimulation::series() const {
  SeriesValues v;
  v.t = state_.t;
  v.payload = state_.q.tail<3>();
  v.payload_velocity = state_.v.tail<3>();
  v.cab = support_->cabDisplacement(state_.z);
  v.jib_tip = support_->jibTipDisplacement(state_.z);
  v.trolley = support_->point(state_.z);
  v.rope_top_tension = solver_->topTension(state_);
  v.rope_length = rope_->length();
  v.slew_angle = drives_.slewAngle();
  v.trolley_radius = drives_.trolleyRadius();
  v.energy = solver_->energy(state_);
  v.constraint_error = solver_->constraintError(state_);
  setCraneWarnings(model_, drives_, v);
  return v;
}

void PendulumCraneSimulation::sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab,
                                     Eigen::Vector3d& jib_tip) const {
  payload = state_.q.tail<3>();
  cab = support_->cabDisplacement(state_.z);
  jib_tip = support_->jibTipDisplacement(state_.z);
}

std::vector<Eigen::Vector3d> PendulumCraneSimulation::ropeCurve(int per_element) const {
  if (per_element < 1) throw std::invalid_argument("rope samples per element must be >= 1");
  std::vector<Eigen::Vector3d> points;
  const Eigen::Vector3d top = state_.q.head<3>(), end = state_.q.tail<3>();
  for (int i = 0; i < per_element; ++i) points.push_back(top + (end - top) * i / per_element);
  points.push_back(end);
  return points;
}

}  // namespace crane_twin
