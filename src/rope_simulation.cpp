#include "crane_twin/rope_simulation.hpp"

#include <cmath>
#include <iomanip>

#include "crane_twin/config_reader.hpp"

namespace crane_twin {

const char* const kSeriesHeader =
    "t,payload_x,payload_y,payload_z,payload_vx,payload_vy,payload_vz,cab_dx,cab_dy,cab_dz,"
    "jib_tip_dx,jib_tip_dy,jib_tip_dz,trolley_x,trolley_y,trolley_z,rope_top_tension,"
    "rope_length,slew_angle,trolley_radius,energy,constraint_error,subdomains";

RopeSimulation::RopeSimulation(const CraneModel& model) : model_(model) {
  const Scene& sc = model.scene;
  if (sc.crane) {
    throw InputError(sc.file + ": key 'crane': the full-order crane coupling is not built yet; "
                     "only crane: none scenes run in this version");
  }
  if (sc.rope.model != "full") {
    throw InputError(sc.file + ": key 'rope.model': only 'full' runs in this version, got '" +
                     sc.rope.model + "'");
  }
  if (sc.rope.damping != 0.0) {
    throw InputError(sc.file + ": key 'rope.damping': rope material damping is not built yet");
  }
  for (const auto& c : sc.commands) {
    if (c.slew_rate != 0.0 || c.trolley_speed != 0.0 || c.hoist_speed != 0.0) {
      throw InputError(sc.file + ": key 'commands': drives are not built yet");
    }
  }
  rope_ = std::make_unique<AncfRope>(sc.rope.elements, sc.rope.length,
                                     model.rope.mass_per_length, model.rope.axial_stiffness,
                                     model.rope.bending_stiffness, model.end_mass,
                                     Eigen::Vector3d(0.0, 0.0, -sc.gravity));
  const GeneralizedAlpha ga = sc.integrator == "newmark"
                                  ? GeneralizedAlpha::newmark()
                                  : GeneralizedAlpha::fromRhoInf(sc.rho_inf);
  solver_ = std::make_unique<AnchoredRopeSolver>(*rope_, sc.anchor, ga, sc.time_step);
}

RopeState RopeSimulation::staticState(Eigen::Vector3d* holding_force) {
  const Scene& sc = model_.scene;
  return solver_->solveSwingEquilibrium(sc.swing_deg * M_PI / 180.0,
                                        sc.swing_azimuth_deg * M_PI / 180.0, holding_force);
}

void RopeSimulation::initialize() {
  const Scene& sc = model_.scene;
  const double th = sc.swing_deg * M_PI / 180.0, az = sc.swing_azimuth_deg * M_PI / 180.0;
  if (sc.initial_mode == "stress_free") {
    const Eigen::Vector3d d(std::sin(th) * std::cos(az), std::sin(th) * std::sin(az),
                            -std::cos(th));
    state_ = RopeState{};
    state_.q = rope_->straight(sc.anchor, d);
    state_.v = Eigen::VectorXd::Zero(rope_->dofs());
  } else {
    state_ = staticState();
  }
  state_.v.segment<3>(rope_->dofs() - 6) += sc.payload_velocity;
  state_.t = 0.0;
  solver_->initializeAccelerations(state_);
}

void RopeSimulation::step() { solver_->step(state_); }

void RopeSimulation::writeSeriesRow(std::ostream& out) const {
  const Scene& sc = model_.scene;
  const int e = rope_->dofs() - 6;
  const Eigen::Vector3d p = state_.q.segment<3>(e), v = state_.v.segment<3>(e);
  out << std::setprecision(10) << state_.t << ',' << p.x() << ',' << p.y() << ',' << p.z() << ','
      << v.x() << ',' << v.y() << ',' << v.z() << ",0,0,0,0,0,0," << sc.anchor.x() << ','
      << sc.anchor.y() << ',' << sc.anchor.z() << ',' << AnchoredRopeSolver::topTension(state_)
      << ',' << sc.rope.length << ",0,0," << solver_->energy(state_) << ','
      << (state_.q.head<3>() - sc.anchor).norm() << ",0\n";
}

void RopeSimulation::writeNodeRows(std::ostream& out) const {
  for (int j = 0; j < rope_->nodes(); ++j) {
    const Eigen::Vector3d r = AncfRope::nodePosition(state_.q, j);
    out << std::setprecision(10) << state_.t << ',' << j << ',' << r.x() << ',' << r.y() << ','
        << r.z() << '\n';
  }
}

ModalBasis RopeSimulation::ropeModes(int count) {
  const RopeState eq = solver_->solveSwingEquilibrium(0.0, 0.0);
  const int n = rope_->dofs();
  Eigen::VectorXd Q;
  std::vector<Eigen::Triplet<double>> t;
  rope_->elasticForce(eq.q, Q, &t);
  // Remove the top node's three position DOFs (held by the constraint).
  std::vector<Eigen::Triplet<double>> tk;
  for (const auto& x : t)
    if (x.row() >= 3 && x.col() >= 3) tk.emplace_back(x.row() - 3, x.col() - 3, x.value());
  SparseMatrix K(n - 3, n - 3);
  K.setFromTriplets(tk.begin(), tk.end());
  const SparseMatrix M = rope_->massMatrix().bottomRightCorner(n - 3, n - 3);
  ModalOptions opt;
  opt.count = count;
  opt.shift = -1e-3;
  return lowestModes(K, M, opt);
}

}  // namespace crane_twin
