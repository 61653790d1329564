#include "crane_twin/drives/drive_axis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace crane_twin {

DriveAxis::DriveAxis(const DriveLimits& limits, double position, double lo, double hi)
    : limits_(limits), lo_(lo), hi_(hi), position_(position) {
  if (!(limits.max_speed > 0.0) || !(limits.max_acceleration > 0.0)) {
    throw std::invalid_argument("drive limits must be positive");
  }
  if (!(lo <= position && position <= hi)) {
    throw std::invalid_argument("drive position outside its limits");
  }
}

DriveFlags DriveAxis::advance(double command, double dt) {
  DriveFlags f;
  const double vmax = limits_.max_speed, amax = limits_.max_acceleration;
  double target = command;
  if (std::abs(target) > vmax) {
    target = std::copysign(vmax, target);
    f.speed_limited = true;
  }
  // Braking distance to a limit: stop there at the acceleration limit. Plan on the distance
  // left after this step so the limit is not overrun within it.
  const double toHi = hi_ - position_, toLo = position_ - lo_;
  if (speed_ >= 0.0 && target > 0.0 && std::isfinite(hi_)) {
    const double vStop = std::sqrt(std::max(0.0, 2.0 * amax * std::max(0.0, toHi - speed_ * dt)));
    if (target > vStop) {
      target = vStop;
      f.at_position_limit = true;
    }
  }
  if (speed_ <= 0.0 && target < 0.0 && std::isfinite(lo_)) {
    const double vStop = std::sqrt(std::max(0.0, 2.0 * amax * std::max(0.0, toLo + speed_ * dt)));
    if (-target > vStop) {
      target = -vStop;
      f.at_position_limit = true;
    }
  }
  const double dv = std::clamp(target - speed_, -amax * dt, amax * dt);
  const double v0 = speed_;
  speed_ += dv;
  acceleration_ = dv / dt;
  position_ += 0.5 * (v0 + speed_) * dt;
  if (position_ > hi_ || position_ < lo_) {
    // Round-off or a step too long for the braking plan: hold at the limit.
    position_ = std::clamp(position_, lo_, hi_);
    speed_ = 0.0;
    f.at_position_limit = true;
  }
  return f;
}

}  // namespace crane_twin
