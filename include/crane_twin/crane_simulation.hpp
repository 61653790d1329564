// A scene run at full order (SPEC 1.5): the ANCF rope, what holds it (a fixed anchor for
// crane: none, the T8036 structure rigid, modal or in full coordinates), the drives (SPEC 1.4:
// slewing, trolley, hoisting), the initial state of SPEC 2 (equilibrium with a holding force,
// or stress-free), time stepping, and the SPEC 3.1 output rows. The ROS-free unit the CLI's
// `run`, `static` and `modes --part rope` use; the reduced model builds on it.
#pragma once

#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "crane_twin/crane_model.hpp"
#include "crane_twin/crane_drives.hpp"
#include "crane_twin/full_order_solver.hpp"
#include "crane_twin/modal_analysis.hpp"
#include "crane_twin/rope_support.hpp"
#include "crane_twin/simulation.hpp"

namespace crane_twin {

class CraneSimulation final : public Simulation {
 public:
  /// Builds the rope and its support. Integrates at full order whatever rope.model says (the
  /// reduced model starts from this model's equilibrium and linearises it). Throws InputError
  /// for what it cannot run (a pendulum scene, drives without a crane, slewing
  /// loads without a flexible structure), naming the key.
  explicit CraneSimulation(const CraneModel& model);

  void initialize() override;
  void step() override;
  double time() const override { return state_.t; }
  SeriesValues series() const override;
  void sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab, Eigen::Vector3d& jib_tip) const override {
    payload = AncfRope::nodePosition(state_.q, rope_->nodes() - 1);
    cab = support_->cabDisplacement(state_.z);
    jib_tip = support_->jibTipDisplacement(state_.z);
  }
  int ropeNodes() const override { return rope_->nodes(); }
  Eigen::Vector3d ropeNode(int j) const override { return AncfRope::nodePosition(state_.q, j); }
  CoupledState fullState() const override { return state_; }
  std::vector<Eigen::Vector3d> ropeCurve(int per_element) const override;
  long halvedSteps() const override { return solver_->halvedSteps(); }
  const CraneModel& model() const { return model_; }
  const CoupledState& state() const { return state_; }
  RopeSupport& support() { return *support_; }
  const RopeSupport& support() const override { return *support_; }
  const AncfRope& rope() const { return *rope_; }
  const FullOrderSolver& solver() const { return *solver_; }

  // ---- Drives (SPEC 1.4), the API the ROS node uses ----
  /// Operator command from now on, overriding the scene's schedule (CraneDrives::setCommand).
  void setCommand(const CommandEntry& command) override { drives_.setCommand(command); }
  const CraneDrives& drives() const override { return drives_; }
  double ropeLength() const { return rope_->length(); }
  /// Advance the drives by dt under the active command and move the support (called before a
  /// step by either model).
  void advanceDrives(double t, double dt);
  /// The step once the drives have advanced: the rope to the hoist length, one solver step.
  void stepAfterDrives();
  /// Bring the rope to the hoist drive's length, rescaling a full-coordinate state with it.
  void applyRopeLength(CoupledState& s);

  /// Continue from a full-coordinate state (the reduced model hands a slack rope over here).
  void setState(const CoupledState& s) { state_ = s; }
  /// Output quantities of a full-coordinate state (also used by the reduced model).
  SeriesValues seriesOf(const CoupledState& s) const;

  /// The initial full-order state of SPEC 2 (what initialize() starts from).
  CoupledState initialState();
  /// Static equilibrium of the scene (SPEC 2 `equilibrium` start, holding force included).
  CoupledState staticState(Eigen::Vector3d* holding_force = nullptr);
  /// Rope modes (with the end mass) linearised at the static equilibrium without holding force:
  /// top node's position fixed, slope free.
  ModalBasis ropeModes(int count);

 private:
  const CraneModel model_;  ///< own copy: callers may pass a temporary
  std::unique_ptr<AncfRope> rope_;
  std::unique_ptr<RopeSupport> support_;
  std::unique_ptr<FullOrderSolver> solver_;
  CoupledState state_;
  CraneDrives drives_;
  void resetDrives();
};

/// The rope's support for a scene: FixedAnchor (crane: none: the anchor; structure: rigid: the
/// undeformed trolley point), ModalStructureSupport or FullStructureSupport.
std::unique_ptr<RopeSupport> makeRopeSupport(const CraneModel& model);

}  // namespace crane_twin
