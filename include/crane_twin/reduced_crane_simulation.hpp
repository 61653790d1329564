// A scene run with the reduced rope (rope.model: reduced, SPEC 1.6): the same rope, support and
// initial equilibrium as the full-order model (CraneSimulation), integrated by
// ReducedOrderSolver.
#pragma once

#include "crane_twin/crane_simulation.hpp"
#include "crane_twin/reduced_order_solver.hpp"

namespace crane_twin {

/// Rope modes kept for a scene: rope.mode_count if set, else mode_fraction of the rope DOF less
/// the three translations, at least 1 (SPEC 1.6). Throws InputError naming the key.
int keptRopeModes(const CraneModel& model);
int keptRopeModes(const Scene& scene);

class ReducedCraneSimulation final : public Simulation {
 public:
  explicit ReducedCraneSimulation(const CraneModel& model);
  void initialize() override;
  void step() override;
  void setCommand(const CommandEntry& command) override;
  double time() const override { return solver_->state().t; }
  SeriesValues series() const override;
  void sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab, Eigen::Vector3d& jib_tip) const override {
    payload = solver_->nodePosition(full_.ropeNodes() - 1);
    cab = full_.support().cabDisplacement(solver_->state().z);
    jib_tip = full_.support().jibTipDisplacement(solver_->state().z);
  }
  int ropeNodes() const override { return full_.ropeNodes(); }
  Eigen::Vector3d ropeNode(int j) const override { return solver_->nodePosition(j); }
  CoupledState fullState() const override { return solver_->fullState(); }
  const CraneSimulation& crane() const override { return full_; }
  int subdomains() const override { return solver_->statistics().subdomains; }
  double modeUpdateSeconds() const override { return solver_->statistics().mode_update_seconds; }
  const ReducedOrderSolver& solver() const { return *solver_; }

 private:
  CraneSimulation full_;  ///< model setup and initial state
  std::unique_ptr<ReducedOrderSolver> solver_;
};

}  // namespace crane_twin
