#include "crane_twin/drives/slew_torque_drive.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace crane_twin {

SlewTorqueDrive::SlewTorqueDrive(double inertia, double max_torque, double stiffness,
                                 double damping, double angle)
    : inertia_(inertia),
      max_torque_(max_torque),
      k_(stiffness),
      c_(damping),
      theta_(angle),
      phi_(angle) {
  if (!(std::isfinite(inertia) && inertia > 0.0)) {
    throw std::invalid_argument("slewing drive: inertia must be finite and > 0");
  }
  if (!(max_torque > 0.0)) throw std::invalid_argument("slewing drive: max_torque must be > 0");
  if (!(std::isfinite(stiffness) && stiffness >= 0.0) ||
      !(std::isfinite(damping) && damping >= 0.0)) {
    throw std::invalid_argument("slewing drive: stiffness and damping must be finite and >= 0");
  }
  if (!std::isfinite(angle)) throw std::invalid_argument("slewing drive: angle must be finite");
}

void SlewTorqueDrive::advance(double w_ref, double dt) {
  if (!(dt > 0.0) || !std::isfinite(w_ref)) {
    throw std::invalid_argument("slewing drive: dt must be > 0 and the reference finite");
  }
  const double a_max = max_torque_ / inertia_;
  if (k_ == 0.0) {
    // Rigid gear: the constant acceleration over the step that meets w_ref at its end, limited
    // to T_max / J (positions exact for a constant acceleration).
    double a1 = (w_ref - rate_) / dt;
    limited_ = std::abs(a1) > a_max;
    if (limited_) a1 = std::copysign(a_max, a1);
    const double v1 = rate_ + dt * a1;
    theta_ += 0.5 * dt * (rate_ + v1);
    rate_ = v1;
    acc_ = a1;
    phi_ = theta_;
    w_ref_ = w_ref;
    return;
  }
  // Newmark (1/4, 1/2): J a1 + c v1 + k th1 = k phi1 + c w_ref with
  // th1 = th + dt v + dt^2/4 (a + a1), v1 = v + dt/2 (a + a1).
  const double phi1 = phi_ + 0.5 * dt * (w_ref_ + w_ref);
  const double thp = theta_ + dt * rate_ + 0.25 * dt * dt * acc_;
  const double vp = rate_ + 0.5 * dt * acc_;
  double a1 =
      (k_ * (phi1 - thp) + c_ * (w_ref - vp)) / (inertia_ + 0.5 * dt * c_ + 0.25 * dt * dt * k_);
  limited_ = std::abs(a1) > a_max;
  if (limited_) a1 = std::copysign(a_max, a1);
  theta_ = thp + 0.25 * dt * dt * a1;
  rate_ = vp + 0.5 * dt * a1;
  acc_ = a1;
  w_ref_ = w_ref;
  // At the limit the motor slips: its angle is where the gear carries T_max.
  phi_ = limited_ ? theta_ + (inertia_ * a1 - c_ * (w_ref - rate_)) / k_ : phi1;
}

}  // namespace crane_twin
