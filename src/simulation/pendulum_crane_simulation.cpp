#include "crane_twin/simulation/pendulum_crane_simulation.hpp"

#include <cmath>
#include <stdexcept>

namespace crane_twin {

PendulumCraneSimulation::PendulumCraneSimulation(const CraneModel& m)
    : SupportedRopeSimulation(m) {
  const Scene& sc = model_.scene;
  rope_ = std::make_unique<PendulumRope>(sc.rope.length, model_.rope.mass_per_length,
                                         model_.rope.axial_stiffness, model_.end_mass,
                                         model_.gravityVector(), model_.trolleyMass());
  rope_->setTensionOnly(sc.rope.tension_only);
  rope_->setReevingLength(model_.rope.reeving_equivalent_length);
  solver_ = std::make_unique<PendulumSolver>(*rope_, *support_, GeneralizedAlpha::forScene(sc),
                                             sc.time_step);
  solver_->setRopeDamping(sc.rope.damping);
}

CoupledState PendulumCraneSimulation::swingEquilibrium(double swing_rad, double az_rad,
                                                       Eigen::Vector3d* holding_force) {
  return solver_->solveSwingEquilibrium(swing_rad, az_rad, holding_force);
}

Eigen::VectorXd PendulumCraneSimulation::straightRope(const Eigen::Vector3d& top,
                                                      const Eigen::Vector3d& dir) const {
  return PendulumRope::straight(top, dir, rope_->length());
}

void PendulumCraneSimulation::initialize() {
  resetDrivesAndPose();
  rope_->setLength(model_.scene.rope.length);
  state_ = sceneInitialState();
}

void PendulumCraneSimulation::step() {
  if (advanceDrives(state_.t, solver_->timeStep(), state_.z) && drives_.hoistLength() != rope_->length()) {
    rope_->setLength(drives_.hoistLength());
  }
  solver_->step(state_);
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
