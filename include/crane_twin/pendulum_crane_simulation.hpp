// A scene run with the pendulum rope (rope.model: pendulum, SPEC 2): the cheapest rung of the
// fidelity ladder. The same support (anchor, rigid trolley point, modal or full structure),
// drives, initial state of SPEC 2 and output rows as the ANCF models, with the rope one
// straight elastic bar (PendulumRope) integrated by PendulumSolver. No ANCF rope is built.
// Hoisting sets the bar's unstretched length and mass to the hoist drive's length each step.
#pragma once

#include <memory>

#include "crane_twin/crane_drives.hpp"
#include "crane_twin/crane_model.hpp"
#include "crane_twin/pendulum_solver.hpp"
#include "crane_twin/simulation.hpp"

namespace crane_twin {

class PendulumCraneSimulation final : public Simulation {
 public:
  /// Throws InputError for an inconsistent scene (makeRopeSupport), naming the key.
  explicit PendulumCraneSimulation(const CraneModel& model);

  void initialize() override;
  void step() override;
  double time() const override { return state_.t; }
  SeriesValues series() const override;
  void sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab, Eigen::Vector3d& jib_tip) const override;
  int ropeNodes() const override { return 2; }
  Eigen::Vector3d ropeNode(int j) const override { return state_.q.segment<3>(3 * j); }
  void setCommand(const CommandEntry& command) override { drives_.setCommand(command); }
  CoupledState fullState() const override { return state_; }
  const CraneDrives& drives() const override { return drives_; }
  const RopeSupport& support() const override { return *support_; }
  /// The straight chord, per_element points and the end point.
  std::vector<Eigen::Vector3d> ropeCurve(int per_element) const override;
  long halvedSteps() const override { return solver_->halvedSteps(); }

  /// Static equilibrium of the scene (SPEC 2 `equilibrium` start; the holding force into *H).
  CoupledState staticState(Eigen::Vector3d* holding_force = nullptr);
  double topTension(const CoupledState& s) const { return solver_->topTension(s); }
  const PendulumRope& rope() const { return *rope_; }
  const CoupledState& state() const { return state_; }

 private:
  const CraneModel model_;
  CraneDrives drives_;
  std::unique_ptr<PendulumRope> rope_;
  std::unique_ptr<RopeSupport> support_;
  std::unique_ptr<PendulumSolver> solver_;
  CoupledState state_;
};

}  // namespace crane_twin
