// A scene run at full order (docs/model.md): the ANCF rope on its support, the drives and the
// initial state (SupportedRopeSimulation), time stepping with FullOrderSolver, hoisting by
// uniform rescaling. The ROS-free unit the CLI's `run`, `static` and `modes --part rope` use;
// the reduced model builds on it.
#pragma once

#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "crane_twin/simulation/supported_rope_simulation.hpp"
#include "crane_twin/solvers/full_order_solver.hpp"
#include "crane_twin/structure/modal_analysis.hpp"

namespace crane_twin {

/// The scene's ANCF rope at its initial length: elements, material of the equivalent rope, the
/// end mass, gravity and the trolley mass on the top node (docs/model.md).
AncfRope sceneRope(const CraneModel& model);

class CraneSimulation final : public SupportedRopeSimulation,
                              public ContinuableRun,
                              public CorrectableMotion {
 public:
  /// Builds the rope and its support. Integrates at full order whatever rope.model says (the
  /// reduced model starts from this model's equilibrium and linearises it). Throws InputError
  /// for what it cannot run (a pendulum scene, drives without a crane, slewing
  /// loads without a flexible structure), naming the key.
  explicit CraneSimulation(const CraneModel& model);

  void initialize() override;
  void step() override;
  int ropeNodes() const override { return rope_->nodes(); }
  Eigen::Vector3d ropeNode(int j) const override { return rope_->position(state_.q, j); }
  int hookNode() const override { return rope_->hookNode(); }
  std::vector<bool> fullStatePositionBlocks() const override;
  std::vector<Eigen::Vector3d> ropeCurve(int per_element) const override;
  RunStatistics statistics() const override {
    RunStatistics r;
    r.halved_steps = solver_->halvedSteps();
    r.energy_consistent_steps = solver_->energyConsistentSteps();
    return r;
  }
  const AncfRope& rope() const { return *rope_; }
  const FullOrderSolver& solver() const { return *solver_; }
  double ropeLength() const override { return rope_->length(); }
  void setRopeWind(const Eigen::Vector3d& per_length, const Eigen::Vector3d& end_force) override {
    rope_->setExternalLoad(per_length, end_force);
  }

  /// The step once the drives have advanced (advanceDrives): the rope to the hoist length, one
  /// solver step.
  void stepAfterDrives();
  /// Bring the rope to the hoist drive's length, rescaling a full-coordinate state with it.
  void applyRopeLength(CoupledState& s);
  /// The rope (and the solver's mass) to the hoist drive's length, no state touched; true where
  /// the length changed (the reduced rope keeps its own coordinates through a length change).
  bool followHoistLength();
  /// The rope length the hoist asks for [m]: its length less the rope lying on a landed load
  /// (the scene's rope when there is no crane).
  double hoistTargetLength() const {
    return model_.scene.crane ? hangingLength() : rope_->length();
  }

  /// Continue from a full-coordinate state (the reduced model hands a slack rope over here).
  void setState(const CoupledState& s) { state_ = s; }
  /// Continue from positions and velocities of a state (q, v, z, z'), with accelerations and
  /// the generalized-alpha variables recomputed consistently (Arnold & Bruls 2007).
  void restartFrom(const CoupledState& s) {
    state_ = s;
    solver_->initializeAccelerations(state_);
  }

  void continueFrom(const Simulation& other) override;
  void setMotion(const CoupledState& s) override;
  /// The initial full-order state of the scene (what initialize() starts from).
  CoupledState initialState();
  /// Rope modes (with the end mass) linearised at the static equilibrium without holding force:
  /// top node's position fixed, slope free.
  ModalBasis ropeModes(int count);

 protected:
  CoupledState swingEquilibrium(double swing_rad, double az_rad,
                                Eigen::Vector3d* holding_force) override;
  Eigen::VectorXd straightRope(const Eigen::Vector3d& top,
                               const Eigen::Vector3d& dir) const override;
  double unloadedHangingLength(double span) override;
  Eigen::VectorXd unloadedHangingRope(const Eigen::Vector3d& top,
                                      const Eigen::Vector3d& dir) const override;
  void initializeAccelerations(CoupledState& s) override;
  int endPointIndex() const override;
  double topTensionOf(const CoupledState& s) const override;
  double energyOf(const CoupledState& s) const override;

 private:
  std::unique_ptr<AncfRope> rope_;
  std::unique_ptr<FullOrderSolver> solver_;
  void resetDrives();
};

}  // namespace crane_twin
