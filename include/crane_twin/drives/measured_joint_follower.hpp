// The twin follows a real crane's joints (docs/twin.md "Following the crane"): measured slew
// angle [rad], trolley radius [m] and the rope the hoist drum has paid out [m] (the hoist
// drive's length), positions and optionally velocities, at 10-100 Hz with jitter and gaps,
// turned into rate commands for the model's drives, which ramp them at their acceleration
// limits (so the model's motion never has a step in acceleration beyond the drives' limits).
//
// Per axis, with the newest sample at t_k and the time t:
//   target x* = x_k + v_k min(t - t_k, max_extrapolation),      (bridges gaps and latency)
//   rate     = v_k + gain (x* - x_model),  limited to the drive's max speed.
// With measured velocities, x_k and v_k are the sample's. Without, they are the position and
// rate of a JointTrackingFilter of bandwidth tracking_bandwidth (a Kalman filter of a motion at
// constant rate): raw positions and slopes would pass the encoders' noise to the command, and
// the drive ramps every sample's new rate at its acceleration limit, so 5 mm of noise at 30 Hz
// shook the model's trolley at +-0.5 m/s^2 (and its rope with it) while the real one stood.
// At a new sample, x* and the rate move from what the command followed to the new x_k, v_k
// linearly over the sample interval (at most stale_after): the commanded rate has no steps.
// Beyond stale_after without a sample the input is flagged stale (for diagnostics) and still
// extrapolated; beyond max_extrapolation v_k = 0: the axis holds the last measured position (a
// sensor that died while the crane stopped must not drive it on); the filter predicts across
// the gap and takes the next sample with the uncertainty the gap left.
#pragma once

#include <Eigen/Dense>
#include <array>
#include <deque>
#include <optional>
#include <string>

#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/drives/joint_tracking_filter.hpp"
#include "crane_twin/io/crane_description.hpp"
#include "crane_twin/io/scene.hpp"

namespace crane_twin {

struct JointSample {
  double t = 0.0;                                      ///< [s] of the twin's simulated time
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< slew [rad], trolley [m], hoist [m]
  std::optional<Eigen::Vector3d> velocity;             ///< [rad/s, m/s, m/s]
};

struct JointFollowerSettings {
  double gain = 2.0;               ///< position loop gain [1/s]
  double max_extrapolation = 1.0;  ///< [s]
  double stale_after = 0.5;        ///< [s]
  /// JointTrackingFilter's bandwidth [rad/s]: behind an acceleration a the filter lags
  /// a / omega^2 and the position loop a further sqrt(2) a / (omega gain) (3 + 9 cm at the
  /// T8036's 0.5 m/s^2 with 4 rad/s); the noise passed into the rates grows as omega^1.5.
  double tracking_bandwidth = 4.0;
  /// The longer window of the held rates a forecast assumes [s] (holdRates): the slope's noise
  /// falls as window^-1.5, and a forecast wants the rate, not the last half second's wobble.
  double hold_window = 2.0;
  /// Throws std::invalid_argument naming the field.
  void check() const;
};

class MeasuredJointFollower {
 public:
  /// How far beyond a radius or rope-length limit a measurement is still taken [m].
  static constexpr double kLimitMargin = 0.5;
  explicit MeasuredJointFollower(const JointFollowerSettings& settings = {});
  /// A new measurement. "" when taken, else why it was refused (non-finite values, a time
  /// before the newest sample's, a radius or rope length more than kLimitMargin outside the
  /// crane's limits).
  std::string add(const JointSample& sample, const CraneDescription& crane);
  /// Rate command for the drives at time t (zero rates before the first sample).
  CommandEntry command(double t, const CraneDrives& drives, const CraneDescription& crane) const;
  /// The joint rates the command extrapolates with: measured, else filtered (zero without a
  /// sample, or beyond max_extrapolation).
  Eigen::Vector3d rates(double t) const;
  /// The rates a forecast holds: measured velocities, else the least-squares slope over
  /// hold_window (zero without samples or beyond max_extrapolation).
  Eigen::Vector3d holdRates(double t) const;
  bool hasSample() const { return last_.has_value(); }
  /// No sample within stale_after of t (or none at all).
  bool stale(double t) const;
  /// Time since the newest sample [s] (infinite without one).
  double age(double t) const;
  long refused() const { return refused_; }
  void clear();

 private:
  JointFollowerSettings settings_;
  struct Estimate {
    Eigen::Vector3d position = Eigen::Vector3d::Zero(), rate = Eigen::Vector3d::Zero();
  };
  /// The target x* and rate the command follows at t (the header's, blended).
  Estimate estimate(double t) const;
  std::optional<JointSample> last_;
  std::array<JointTrackingFilter, 3> filters_;  ///< slew, trolley, hoist
  /// At the newest sample: position and rate (measured or filtered), and the blend from what
  /// the command followed before it: offsets and their duration [s].
  Eigen::Vector3d position_ = Eigen::Vector3d::Zero(), rate_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d blend_offset_ = Eigen::Vector3d::Zero(), blend_rate_ = Eigen::Vector3d::Zero();
  double blend_time_ = 0.0;
  std::deque<JointSample> window_;  ///< samples within hold_window of the newest
  Eigen::Vector3d slope(double window) const;
  long refused_ = 0;
};

}  // namespace crane_twin
