// Position goals for the crane's rate drives (docs/ros.md "Goals"): a joint trajectory of slew
// angle [rad], trolley radius [m] and hoisted rope length [m] followed point by point by a
// position controller on top of the rate drives.
//
// Each axis with a position in the active point is driven at
//   v = sign(e) min(v_max, sqrt(2 a_b |e|)),  e = target - position,  a_b = 0.8 a_max,
// the speed from which the drive can still stop at the target with 80 % of its deceleration
// (the drive ramps the commanded rate at a_max, so it follows this braking curve without
// overshoot beyond a few steps' a_max dt^2). Within the tolerance the axis is commanded to rest.
// A point is done when every axis it names is within tolerance, at rest, and its
// time_from_start has passed; then the next point is active. Points are reached in order as
// fast as the limits allow, never before their time.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/io/crane_description.hpp"

namespace crane_twin {

struct TrajectoryPoint {
  double time_from_start = 0.0;                 ///< [s]
  std::array<std::optional<double>, 3> target;  ///< slew [rad], trolley [m], hoist [m]; empty: hold
};

class TrajectoryFollower {
 public:
  /// Tolerances: slew [rad], trolley [m], hoist [m]; speed under which an axis counts at rest.
  static constexpr std::array<double, 3> kTolerance = {1e-3, 5e-3, 5e-3};
  static constexpr std::array<double, 3> kRestSpeed = {2e-3, 1e-2, 1e-2};
  static constexpr double kBrakingFraction = 0.8;

  /// "" if the points are acceptable for this crane, else what is wrong: no points, a
  /// non-finite value, times not increasing (or negative), a radius or rope length outside the
  /// crane's limits.
  static std::string validate(const std::vector<TrajectoryPoint>& points,
                              const CraneDescription& crane);

  /// Start following (replaces any active trajectory); t: current simulated time [s].
  void start(std::vector<TrajectoryPoint> points, double t);
  void cancel() { points_.clear(); }
  bool active() const { return !points_.empty(); }
  /// The rate command for the drives at time t; marks the trajectory done when the last point
  /// is reached (active() then turns false and reached() true until the next start).
  CommandEntry command(double t, const CraneDrives& drives, const CraneDescription& crane);
  bool reached() const { return reached_; }
  std::size_t activePoint() const { return next_; }

 private:
  std::vector<TrajectoryPoint> points_;
  std::size_t next_ = 0;
  double start_ = 0.0;
  bool reached_ = false;
};

}  // namespace crane_twin
