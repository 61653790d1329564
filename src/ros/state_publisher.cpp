#include "state_publisher.hpp"

#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>

#include <optional>

#include "crane_twin/analysis/load_shapes.hpp"

namespace crane_twin {

StatePublisher::StatePublisher(ros::NodeHandle nh, const NodeSettings& settings,
                               const CraneFrames& frames, const Eigen::Vector3d& base_position,
                               double base_yaw)
    : frames_(frames),
      owns_clock_(settings.publish_clock),
      structure_marker_rate_(settings.structure_marker_rate),
      options_(settings.snapshot) {
  // Queues for bursts: as fast as possible a recorder takes every publication.
  joint_pub_ = nh.advertise<sensor_msgs::JointState>("joint_states", 1000);
  state_pub_ = nh.advertise<CraneState>("crane/state", 1000);
  marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("crane/rope", 200);
  if (owns_clock_) clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  static_tf_.sendTransform(toBaseTransform(frames_, base_position, base_yaw, ros::Time::now()));
}

SnapshotOptions StatePublisher::optionsNow(ros::WallTime now) {
  // The structure's segments at most structure_marker_rate times per wall second (rviz keeps
  // the last marker of an id); the first publication always carries them.
  SnapshotOptions o = options_;
  o.structure_segments = last_structure_wall_.isZero() ||
                         (now - last_structure_wall_).toSec() >= 1.0 / structure_marker_rate_;
  if (o.structure_segments) last_structure_wall_ = now;
  return o;
}

CraneState StatePublisher::stateMessage(const CraneSnapshot& s, const ros::Time& stamp,
                                        double step_cost, double real_time_factor,
                                        const CraneModel& model, double t_offset,
                                        const LiftOffMonitor& lift_off) const {
  CraneState m =
      toStateMessage(s, stamp, step_cost, real_time_factor, name(model.scene.rope.model), frames_);
  m.t += t_offset;
  m.payload_mass_estimate = model.scene.payload_mass;
  if (model.hot_spots) {
    for (const HotSpotRow& r : model.hot_spots->rows) m.stress_names.push_back(r.name);
  }
  m.lift_offs = lift_off.liftOffs();
  m.lift_off_factor = lift_off.factor();
  return m;
}

void StatePublisher::publish(const CraneSnapshot& s, const CraneState& state,
                             const CraneModel& model, const ros::Time& stamp,
                             const ros::Duration& tf_offset, RecorderLink& recorder) {
  if (owns_clock_) publishClock(stamp);
  joint_pub_.publish(toJointState(s, stamp));
  recorder.published(joint_pub_);
  tf_.sendTransform(toTransforms(s, stamp + tf_offset, frames_));
  const double payload_mass = model.scene.payload_mass;
  const std::optional<double> ground =
      model.scene.ground ? std::optional<double>(model.scene.ground->height) : std::nullopt;
  marker_pub_.publish(toMarkers(s, stamp, loadShapes(s, model.scene.hookBlockMass(), payload_mass),
                                payload_mass, frames_, ground));
  recorder.published(marker_pub_);
  republish(state, recorder);
}

void StatePublisher::republish(const CraneState& state, RecorderLink& recorder) {
  state_pub_.publish(state);
  recorder.published(state_pub_);
}

void StatePublisher::publishClock(const ros::Time& stamp) {
  rosgraph_msgs::Clock c;
  c.clock = stamp;
  clock_pub_.publish(c);
}

std::vector<const ros::Publisher*> StatePublisher::publishers() const {
  return {&state_pub_, &joint_pub_, &marker_pub_, &clock_pub_};
}

}  // namespace crane_twin
