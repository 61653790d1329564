// A scene run with the pendulum rope (rope.model: pendulum, docs/scenes.md): the cheapest rung
// of the fidelity ladder. The same support, drives, initial state and output rows as the ANCF
// models (SupportedRopeSimulation), with the rope one straight elastic bar (PendulumRope)
// integrated by PendulumSolver. No ANCF rope is built. Hoisting sets the bar's unstretched
// length and mass to the hoist drive's length each step.
#pragma once

#include <memory>

#include "crane_twin/simulation/supported_rope_simulation.hpp"
#include "crane_twin/solvers/pendulum_solver.hpp"

namespace crane_twin {

class PendulumCraneSimulation final : public SupportedRopeSimulation, public ContinuableRun {
 public:
  /// Throws InputError for an inconsistent scene (makeRopeSupport), naming the key.
  explicit PendulumCraneSimulation(const CraneModel& model);

  void initialize() override;
  void step() override;
  /// Top and end point, or top, hook block and payload with a rigging.
  int ropeNodes() const override { return rigging_ ? 3 : 2; }
  int hookNode() const override { return 1; }
  std::vector<bool> fullStatePositionBlocks() const override {
    return std::vector<bool>(ropeNodes(), true);
  }
  Eigen::Vector3d ropeNode(int j) const override { return state_.q.segment<3>(3 * j); }
  /// The straight chord, per_element points and the end point.
  std::vector<Eigen::Vector3d> ropeCurve(int per_element) const override;
  RunStatistics statistics() const override {
    RunStatistics r;
    r.halved_steps = solver_->halvedSteps();
    return r;
  }
  /// Continue another pendulum run of the same scene (a forecast from the twin's state): its
  /// drives, rope length and state; with another time step the accelerations and the
  /// generalized-alpha variables restart from its positions and velocities. Throws InputError
  /// for another rope model.
  void continueFrom(const Simulation& other) override;

  double topTension(const CoupledState& s) const { return solver_->topTension(s); }
  const PendulumRope& rope() const { return *rope_; }

 protected:
  CoupledState swingEquilibrium(double swing_rad, double az_rad,
                                Eigen::Vector3d* holding_force) override;
  Eigen::VectorXd straightRope(const Eigen::Vector3d& top,
                               const Eigen::Vector3d& dir) const override;
  double unloadedHangingLength(double span) override;
  Eigen::VectorXd unloadedHangingRope(const Eigen::Vector3d& top,
                                      const Eigen::Vector3d& dir) const override;
  void initializeAccelerations(CoupledState& s) override { solver_->initializeAccelerations(s); }
  int endPointIndex() const override { return rigging_ ? 6 : 3; }
  double topTensionOf(const CoupledState& s) const override { return solver_->topTension(s); }
  double energyOf(const CoupledState& s) const override { return solver_->energy(s); }
  double ropeLength() const override { return rope_->length(); }
  void setRopeWind(const Eigen::Vector3d& per_length, const Eigen::Vector3d& end_force) override {
    if (!rigging_) {
      rope_->setExternalLoad(per_length, end_force);
      return;
    }
    rope_->setExternalLoad(per_length, Eigen::Vector3d::Zero());  // the rigging takes no wind
    rigging_->setExternalLoad(Eigen::Vector3d::Zero(), end_force);
  }

 private:
  // The load on the bar's end with the payload landed [N] (the bar of length l).
  double unloadedEndLoad(double l) const;
  /// A landed start's hook block on a rigging off-centre: its position q[3..5] where the hoist
  /// bar's and the rigging's forces balance its weight, the top and the payload held (throws
  /// NumericalFailure where it does not settle).
  void settleHook(Eigen::VectorXd& q) const;
  static constexpr int kHookSettleIterations = 100;
  static constexpr double kHookSettleTolerance = 1e-10;  ///< [m] on the Newton correction
  /// Below this correction [m] the full Newton step, without a line search (the energy's change
  /// drowns in its round-off there).
  static constexpr double kHookLineSearchBelow = 1e-6;
  std::unique_ptr<PendulumRope> rope_;
  std::unique_ptr<PendulumRope> rigging_;  ///< hook block to payload (hook.rigging_length > 0)
  std::unique_ptr<PendulumSolver> solver_;
};

}  // namespace crane_twin
