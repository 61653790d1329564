// The three crane drives of a scene (docs/model.md): slewing angle theta [rad], trolley radius s
// [m] and hanging rope length L [m], each a DriveAxis following the active rate command: the
// scene's `commands:` schedule, or an operator command set at run time (the node-facing API), which
// overrides the schedule from then on. Whichever rope model a run integrates (pendulum, full,
// reduced), it moves its support with these drives, so every model of a scene drives the same way.
#pragma once

#include <optional>

#include "crane_twin/drives/drive_axis.hpp"
#include "crane_twin/drives/slew_torque_drive.hpp"
#include "crane_twin/io/scene.hpp"

namespace crane_twin {

class CraneDrives {
 public:
  /// The scene is referenced (it must outlive the drives). Throws InputError when the schedule
  /// commands motion without a crane (crane: none), naming the key. slew_inertia [kg m^2] is the
  /// rotating part's inertia about the slewing axis (slewingInertia), needed by
  /// `slewing.drive: {model: torque}` (InputError without it).
  explicit CraneDrives(const Scene& scene, double slew_inertia = 0.0);

  /// Back to the scene's initial pose, at rest, the manual command cleared.
  void reset();
  /// Take over the drives' state (positions, speeds, flags, command) of another CraneDrives of
  /// the same scene (a forecast copy).
  void assignStateFrom(const CraneDrives& other);
  /// Operator command from now on, overriding the schedule (t is ignored). Throws
  /// std::invalid_argument for a non-finite rate and InputError for drives without a crane;
  /// nothing changes then.
  void setCommand(const CommandEntry& command);
  /// The command in force at time t: the manual one if set, else the schedule's last entry at
  /// or before t (zero before the first).
  CommandEntry activeCommand(double t) const;
  /// Advance every drive by dt under the command active at t. False (nothing moved) when the
  /// scene commands no motion.
  bool advance(double t, double dt);

  /// The scene commands motion, or a command was set.
  bool active() const { return active_; }
  /// The schedule or the manual command asks for hoisting.
  bool hoists() const;
  /// The rotating part's slewing angle: the kinematic profile, or the torque drive's state.
  double slewAngle() const {
    return slew_torque_ ? slew_torque_->angle() : slew_ ? slew_->position() : scene_.slew_angle;
  }
  double trolleyRadius() const { return trolley_ ? trolley_->position() : scene_.trolley_radius; }
  double slewRate() const {
    return slew_torque_ ? slew_torque_->rate() : slew_ ? slew_->speed() : 0.0;
  }
  /// The slewing acceleration over the last step [rad/s^2].
  double slewAcceleration() const {
    return slew_torque_ ? slew_torque_->acceleration() : slew_ ? slew_->acceleration() : 0.0;
  }
  /// The torque drive (empty with the kinematic drive).
  const std::optional<SlewTorqueDrive>& slewTorqueDrive() const { return slew_torque_; }
  double trolleySpeed() const { return trolley_ ? trolley_->speed() : 0.0; }
  double hoistSpeed() const { return hoist_ ? hoist_->speed() : 0.0; }
  /// The hoist drive's hanging length (the scene's length without a crane) [m].
  double hoistLength() const { return hoist_ ? hoist_->position() : scene_.rope.length; }
  /// What limited each drive in the last step (speed or position limits).
  const DriveFlags& slewFlags() const { return slew_flags_; }
  const DriveFlags& trolleyFlags() const { return trolley_flags_; }
  const DriveFlags& hoistFlags() const { return hoist_flags_; }

 private:
  const Scene& scene_;
  std::optional<DriveAxis> slew_, trolley_, hoist_;
  double slew_inertia_ = 0.0;
  std::optional<SlewTorqueDrive> slew_torque_;  ///< slewing.drive.model torque
  DriveFlags slew_flags_, trolley_flags_, hoist_flags_;
  bool active_ = false;
  std::optional<CommandEntry> manual_;
};

}  // namespace crane_twin
