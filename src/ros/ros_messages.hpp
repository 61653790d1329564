// CraneSnapshot -> ROS messages (docs/ros.md). Pure conversions: no publishing, no state.
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/JointState.h>
#include <visualization_msgs/MarkerArray.h>

#include <string>
#include <vector>

#include "crane_twin/CraneState.h"
#include "crane_twin/analysis/crane_snapshot.hpp"

namespace crane_twin {

/// Joint names the node publishes and the URDF declares.
extern const char* const kJointNames[3];  // slew, trolley, hoist

/// slew (rad, rad/s), trolley (m, m/s), hoist (rope length m, m/s, effort = top tension N).
sensor_msgs::JointState toJointState(const CraneSnapshot& s, const ros::Time& stamp);
/// world -> slewing -> {jib_tip, cab, trolley}; world -> {hook, payload}.
std::vector<geometry_msgs::TransformStamped> toTransforms(const CraneSnapshot& s,
                                                          const ros::Time& stamp);
/// Rope LINE_STRIP, payload SPHERE, deformed structure LINE_LIST (frame world).
visualization_msgs::MarkerArray toMarkers(const CraneSnapshot& s, const ros::Time& stamp,
                                          double payload_diameter);
/// The docs/cli.md row with the step cost [s] and real-time factor.
CraneState toStateMessage(const CraneSnapshot& s, const ros::Time& stamp, double step_cost,
                          double real_time_factor, const std::string& model);

}  // namespace crane_twin
