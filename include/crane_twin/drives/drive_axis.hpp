// One crane drive (slewing angle, trolley radius or hanging rope length) following an operator's
// rate command within its speed and acceleration limits (docs/model.md): the speed moves toward the
// command at the acceleration limit (a trapezoidal profile for a step command); a command
// beyond the speed limit is limited to it and flagged; near a position limit the drive brakes
// at the acceleration limit so that it stops at the limit, and a command pushing past the limit
// is flagged. Positions integrate the piecewise-linear speed exactly.
#pragma once

#include <limits>

#include "crane_twin/io/crane_description.hpp"

namespace crane_twin {

struct DriveFlags {
  bool speed_limited = false;      ///< |command| exceeded the speed limit
  bool at_position_limit = false;  ///< braking for, or holding at, a position limit
  bool torque_limited = false;     ///< slewing torque drive at its torque limit
};

class DriveAxis {
 public:
  /// limits: max_speed > 0, max_acceleration > 0; position range [lo, hi] (infinite: no limit).
  DriveAxis(const DriveLimits& limits, double position,
            double lo = -std::numeric_limits<double>::infinity(),
            double hi = std::numeric_limits<double>::infinity());

  /// Advance by dt under the rate command; returns what limited it.
  DriveFlags advance(double command, double dt);

  double position() const { return position_; }
  double speed() const { return speed_; }
  double acceleration() const { return acceleration_; }  ///< over the last step
  const DriveLimits& limits() const { return limits_; }

 private:
  DriveLimits limits_;
  double lo_, hi_;
  double position_, speed_ = 0.0, acceleration_ = 0.0;
};

}  // namespace crane_twin
