// The torque-limited slewing drive of `slewing.drive: {model: torque}` (docs/model.md
// "Slewing drive"). The drive's speed reference w_ref(t) is the kinematic DriveAxis profile (the
// operator's rate command ramped at the crane's slewing acceleration limit); a massless motor
// tracks it through a torsional gear of stiffness k [N m/rad] and damping c [N m s/rad] into the
// rotating part of inertia J [kg m^2] about the slewing axis:
//   J theta'' = T_g,   T_g = k (phi - theta) + c (phi' - theta'),   phi' = w_ref,
// phi the motor angle (reduced to the slewing ring). The gear torque is limited, |T_g| <= T_max:
// at the limit the motor slips (phi is reset so that T_g = +-T_max), so no wind-up remains when
// the load catches up. Without a gear stiffness (k = 0: rigid gear) theta follows w_ref wherever
// J |theta''| <= T_max and accelerates at +-T_max / J otherwise.
// Integrated with the trapezoidal rule (Newmark beta = 1/4, gamma = 1/2: unconditionally stable,
// second order; exact for a constant acceleration). The elastic structure feels the resulting
// theta'' and theta'^2 as inertial loads (slewing.inertial_loads); its deformation does not act
// back on the drive (one-way coupling, docs/model.md).
#pragma once

#include <limits>

namespace crane_twin {

class SlewTorqueDrive {
 public:
  /// inertia J > 0 [kg m^2], max_torque T_max > 0 [N m] (infinity: unlimited), stiffness k >= 0
  /// [N m/rad] (0: rigid gear), damping c >= 0 [N m s/rad]; at rest at `angle` [rad]. Throws
  /// std::invalid_argument otherwise.
  SlewTorqueDrive(double inertia, double max_torque, double stiffness, double damping,
                  double angle);

  /// Advance by dt > 0 with the speed reference w_ref at the step's end [rad/s] (the reference
  /// is taken linear over the step).
  void advance(double w_ref, double dt);

  double angle() const { return theta_; }
  double rate() const { return rate_; }
  double acceleration() const { return acc_; }
  /// Gear torque T_g = J theta'' [N m] and whether it was at its limit in the last step.
  double torque() const { return inertia_ * acc_; }
  bool torqueLimited() const { return limited_; }
  double inertia() const { return inertia_; }

 private:
  double inertia_, max_torque_, k_, c_;
  double theta_, rate_ = 0.0, acc_ = 0.0;
  double phi_, w_ref_ = 0.0;  ///< motor angle and its speed at the last step's end
  bool limited_ = false;
};

}  // namespace crane_twin
