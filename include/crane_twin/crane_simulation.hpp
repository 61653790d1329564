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
#include "crane_twin/drive_axis.hpp"
#include "crane_twin/full_order_solver.hpp"
#include "crane_twin/modal_analysis.hpp"
#include "crane_twin/rope_support.hpp"
#include "crane_twin/simulation.hpp"

namespace crane_twin {

class CraneSimulation final : public Simulation {
 public:
  /// Builds the rope and its support. Integrates at full order whatever rope.model says (the
  /// reduced model starts from this model's equilibrium and linearises it). Throws InputError
  /// for what this version cannot run (pendulum rope, rope damping, slewing inertial loads,
  /// drives without a crane), naming the key.
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
  const CraneSimulation& crane() const override { return *this; }
  long halvedSteps() const override { return solver_->halvedSteps(); }
  const CraneModel& model() const { return model_; }
  const CoupledState& state() const { return state_; }
  RopeSupport& support() { return *support_; }
  const RopeSupport& support() const { return *support_; }
  const AncfRope& rope() const { return *rope_; }
  const FullOrderSolver& solver() const { return *solver_; }

  // ---- Drives (SPEC 1.4), the API the ROS node uses ----
  /// Operator command from now on, overriding the scene's schedule (t is ignored). Throws
  /// std::invalid_argument for a non-finite value and InputError for drives without a crane;
  /// the state is unchanged then.
  void setCommand(const CommandEntry& command) override;
  /// The command in force at time t: the manual one if set, else the schedule's last entry at
  /// or before t (zero before the first).
  CommandEntry activeCommand(double t) const;
  double slewAngle() const { return slew_ ? slew_->position() : 0.0; }
  double trolleyRadius() const { return trolley_ ? trolley_->position() : 0.0; }
  double slewRate() const { return slew_ ? slew_->speed() : 0.0; }
  double trolleySpeed() const { return trolley_ ? trolley_->speed() : 0.0; }
  double ropeLength() const { return rope_->length(); }
  double hoistSpeed() const { return hoist_ ? hoist_->speed() : 0.0; }
  /// The hoist drive's length; the rope's own (ropeLength) catches up in applyRopeLength.
  double hoistLength() const { return hoist_ ? hoist_->position() : rope_->length(); }
  const DriveFlags& hoistFlags() const { return hoist_flags_; }
  /// What limited the drives in the last step (speed or position limits).
  const DriveFlags& slewFlags() const { return slew_flags_; }
  const DriveFlags& trolleyFlags() const { return trolley_flags_; }
  /// Advance the drives by dt under the active command and move the support (called before a
  /// step by either model).
  void advanceDrives(double t, double dt);
  bool hasDrives() const { return drives_; }
  /// Bring the rope to the hoist drive's length, rescaling a full-coordinate state with it.
  void applyRopeLength(CoupledState& s);
  /// True when the schedule or the manual command asks for hoisting.
  bool hoists() const;

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
  std::optional<DriveAxis> slew_, trolley_, hoist_;
  DriveFlags slew_flags_, trolley_flags_, hoist_flags_;
  bool drives_ = false;  ///< the scene commands motion (or a command was set)
  std::optional<CommandEntry> manual_;
  void resetDrives();
};

/// The rope's support for a scene: FixedAnchor (crane: none: the anchor; structure: rigid: the
/// undeformed trolley point), ModalStructureSupport or FullStructureSupport.
std::unique_ptr<RopeSupport> makeRopeSupport(const CraneModel& model);

}  // namespace crane_twin
