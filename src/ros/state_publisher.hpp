// StatePublisher: what crane_sim_node publishes of each state it samples (docs/ros.md
// "Interface"): joint_states, TF (world -> <prefix>base latched, the crane's frames under it),
// the crane/rope markers (with the deformed structure at most ~structure_marker_rate times a
// wall second), crane/state, and /clock when the node owns it; each publication counted for a
// recorder that paces the node (RecorderLink).
#pragma once

#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <Eigen/Core>
#include <vector>

#include "crane_twin/CraneState.h"
#include "crane_twin/analysis/crane_snapshot.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/lift_off_monitor.hpp"
#include "node_settings.hpp"
#include "recorder_link.hpp"
#include "ros_messages.hpp"

namespace crane_twin {

class StatePublisher {
 public:
  /// Advertises in `nh`'s namespace and sends world -> <prefix>base at `base_position`,
  /// `base_yaw` [m, rad].
  StatePublisher(ros::NodeHandle nh, const NodeSettings& settings, const CraneFrames& frames,
                 const Eigen::Vector3d& base_position, double base_yaw);
  /// The snapshot options for the state sampled now (the structure's segments when due).
  SnapshotOptions optionsNow(ros::WallTime now);
  /// The run's state as crane/state carries it: the snapshot stamped `stamp`, its step cost
  /// and real-time factor, the time before this simulation started `t_offset` [s] added, the
  /// model's payload mass and hot spots, the lift-offs counted.
  CraneState stateMessage(const CraneSnapshot& s, const ros::Time& stamp, double step_cost,
                          double real_time_factor, const CraneModel& model, double t_offset,
                          const LiftOffMonitor& lift_off) const;
  /// Publish it all: /clock at `stamp` (when owned), joints, TF at `stamp + tf_offset`,
  /// markers, `state`.
  void publish(const CraneSnapshot& s, const CraneState& state, const CraneModel& model,
               const ros::Time& stamp, const ros::Duration& tf_offset, RecorderLink& recorder);
  /// crane/state again (lockstep: the clock's owner may wait for it).
  void republish(const CraneState& state, RecorderLink& recorder);
  /// /clock at `stamp` (a follower waiting for it may have missed the last one).
  void publishClock(const ros::Time& stamp);
  /// The publishers a recorder must be connected to before the first step.
  std::vector<const ros::Publisher*> publishers() const;

 private:
  CraneFrames frames_;
  bool owns_clock_;
  double structure_marker_rate_;
  SnapshotOptions options_;
  ros::WallTime last_structure_wall_;
  ros::Publisher joint_pub_, state_pub_, marker_pub_, clock_pub_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
};

}  // namespace crane_twin
