// TwinRuntime: the twin's orchestration between two steps (docs/twin.md), ROS-free. Measured
// joint samples go to the follower; payload positions, each at the twin time it was measured,
// go through the sway estimator (the twin's payload taken back to that time,
// p(t - age) = p - v age, age at most 1 s) and, where the innovation gate accepts them, into the
// simulation as a correction of its sway; the measured rope tension's ratio to the twin's is
// filtered exponentially over about 10 measurements (r <- r + 0.1 (r_measured - r)), and goes
// with the twin's state to the load cell monitor, which sees lift-offs and set-downs and
// estimates the lifted load's mass (LoadCellMonitor; the caller changes the twin's load with
// takePayloadMass, withPayloadMass and continueWithModel). The ROS node converts messages into
// these calls (src/ros/twin_adapter.cpp).
#pragma once

#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "crane_twin/drives/measured_joint_follower.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/twin/load_cell_monitor.hpp"
#include "crane_twin/twin/sway_estimator.hpp"

namespace crane_twin {

class TwinRuntime {
 public:
  /// Throws std::invalid_argument for estimator settings that SwayEstimatorSettings::check
  /// refuses.
  TwinRuntime(const SwayEstimatorSettings& estimator, const JointFollowerSettings& follower,
              const LoadCellSettings& load_cell = LoadCellSettings());

  /// A new simulation `sim` of `model` started (reset, new load): the follower cleared, the
  /// estimator back to its prior with the structure modes that couple to the sway at the start,
  /// queues and filters emptied.
  void restart(const CraneModel& model, const Simulation& sim);
  /// The twin's load changed in a running simulation (withPayloadMass): the masses the tension
  /// is read against follow; the estimator, the follower and the load cell's state stay.
  void loadChanged(const CraneModel& model);

  /// A measured joint sample (twin time, slew / trolley / hoist); "" or why it was refused.
  std::string addJoints(const JointSample& sample);
  /// A measured payload position [m, the crane's base frame] taken at twin time t; applied
  /// after the next step.
  void addPayload(double t, const Eigen::Vector3d& position);
  /// A measured top tension [N] (finite, >= 0; the caller checks); applied after the next step.
  void addTension(double tension);
  /// A payload measurement refused before it reached the runtime (a bad frame or value).
  void countRefusedPayload() { ++payload_refused_; }

  /// After a step of h seconds: the estimator's covariance propagated, the queued payload
  /// positions applied in order, the queued tensions filtered. `warn` receives what a user
  /// should hear (refused measurements, a failed correction).
  void afterStep(Simulation& sim, double h, const std::function<void(const std::string&)>& warn);

  const MeasuredJointFollower& follower() const { return follower_; }
  const SwayEstimator& estimator() const { return *estimator_; }
  /// The payload's horizontal covariance H P H^T now (the filter's, propagated) [m^2].
  Eigen::Matrix2d payloadCovariance(const Simulation& sim, const SeriesValues& row);
  const std::vector<int>& modes() const { return modes_; }
  double gravity() const { return gravity_; }
  /// Twin time of the last payload measurement applied (-1e300: none yet) [s].
  double lastPayloadTime() const { return last_payload_t_; }
  const SwayUpdate& lastUpdate() const { return last_update_; }
  long payloadUpdates() const { return payload_updates_; }
  long payloadRefused() const { return payload_refused_; }
  /// Payload measurements taken while the twin's load rested on its ground (not applied: a
  /// landed load does not sway).
  long payloadOnGround() const { return payload_on_ground_; }
  long correctionFailures() const { return correction_failures_; }
  /// The filtered measured / twin top tension (1 until a tension arrives).
  double tensionRatio() const { return tension_ratio_; }
  bool tensionSeen() const { return tension_seen_; }
  /// The payload mass the load cell found in its last window after a lift-off, or the twin's
  /// own until one [kg].
  double payloadMassEstimate() const;
  /// A payload mass [kg] the twin should take (the load cell found the lifted load's more than
  /// 1 % off the twin's), once; empty otherwise.
  std::optional<double> takePayloadMass();
  const LoadCellMonitor& loadCell() const { return load_cell_; }

 private:
  SwayEstimatorSettings estimator_settings_;
  MeasuredJointFollower follower_;
  const CraneDescription* crane_ = nullptr;  ///< of the current model (none: crane: none)
  LoadCellSettings load_cell_settings_;
  LoadCellMonitor load_cell_;
  /// The model's end mass, hook block (kg: part of the end mass without a rigging), rope mass
  /// per metre and whether a rigging hangs under the hook.
  double end_mass_ = 0.0, hook_mass_ = 0.0, rope_mass_per_length_ = 0.0, gravity_ = 9.81;
  bool rigging_ = false;
  std::vector<int> modes_;
  std::unique_ptr<SwayEstimator> estimator_;
  std::deque<std::pair<double, Eigen::Vector3d>> payload_in_;  ///< twin time, base frame
  std::deque<double> tension_in_;
  double last_payload_t_ = -1e300;
  SwayUpdate last_update_;
  long payload_updates_ = 0, payload_refused_ = 0, correction_failures_ = 0, payload_on_ground_ = 0;
  double tension_ratio_ = 1.0;
  bool tension_seen_ = false;
};

}  // namespace crane_twin
