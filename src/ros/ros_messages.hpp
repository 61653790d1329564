// CraneSnapshot -> ROS messages (docs/ros.md). Pure conversions: no publishing, no state.
#pragma once

#include <diagnostic_msgs/DiagnosticStatus.h>
#include <geometry_msgs/TransformStamped.h>
#include <sensor_msgs/JointState.h>
#include <visualization_msgs/MarkerArray.h>

#include <optional>
#include <string>
#include <vector>

#include "crane_twin/CraneState.h"
#include "crane_twin/CraneUsage.h"
#include "crane_twin/analysis/crane_snapshot.hpp"
#include "crane_twin/analysis/load_shapes.hpp"
#include "crane_twin/analysis/usage_counter.hpp"

namespace crane_twin {

/// Eigen <-> geometry_msgs.
geometry_msgs::Point point(const Eigen::Vector3d& p);
Eigen::Vector3d fromMsg(const geometry_msgs::Point& p);
Eigen::Vector3d fromMsg(const geometry_msgs::Vector3& v);

/// A key-value pair of a diagnostic status; numbers as std::ostream writes them.
void addKeyValue(diagnostic_msgs::DiagnosticStatus& d, const std::string& key,
                 const std::string& value);
void addNumber(diagnostic_msgs::DiagnosticStatus& d, const std::string& key, double value);

/// Joint names the node publishes and the URDF declares.
extern const char* const kJointNames[3];  // slew, trolley, hoist

/// slew (rad, rad/s), trolley (m, m/s), hoist (rope length m, m/s, effort = top tension N).
sensor_msgs::JointState toJointState(const CraneSnapshot& s, const ros::Time& stamp);
/// The frames of one crane (docs/site.md): `prefix` (e.g. "crane_a/", "" for a lone crane)
/// before every name; `base` is the crane's own frame (the snapshot's world: mast foot, z up).
struct CraneFrames {
  std::string prefix;
  std::string operator()(const std::string& name) const { return prefix + name; }
  std::string base() const { return prefix + "base"; }
};

/// The static site transform world -> <prefix>base: the mast foot at `position`, turned by
/// `yaw` [rad] about z.
geometry_msgs::TransformStamped toBaseTransform(const CraneFrames& f,
                                                const Eigen::Vector3d& position, double yaw,
                                                const ros::Time& stamp);
/// base -> {slewing, mast, hook, payload}; slewing -> {slewing_unit, jib, counter_jib,
/// jib_tip, cab, trolley} (prefixed). mast, slewing_unit, jib, counter_jib and trolley carry the
/// URDF's rigid parts (their floating joints).
std::vector<geometry_msgs::TransformStamped> toTransforms(const CraneSnapshot& s,
                                                          const ros::Time& stamp,
                                                          const CraneFrames& f = {});
/// Rope LINE_STRIP, hook block and payload CUBEs (`loads`), the payload's mass as text,
/// deformed structure LINE_LIST (frame <prefix>base, namespaces <prefix>rope, ...); with a
/// ground height [m], a 20 m square slab of ground under the payload (namespace ground).
visualization_msgs::MarkerArray toMarkers(const CraneSnapshot& s, const ros::Time& stamp,
                                          const LoadShapes& loads, double payload_mass,
                                          const CraneFrames& f = {},
                                          std::optional<double> ground_height = std::nullopt);
/// The docs/cli.md row with the step cost [s] and real-time factor (frame <prefix>base).
/// crane/usage (docs/ros.md, docs/fatigue.md "Usage").
CraneUsage toUsageMessage(const UsageReport& u, const ros::Time& stamp);

CraneState toStateMessage(const CraneSnapshot& s, const ros::Time& stamp, double step_cost,
                          double real_time_factor, const std::string& model,
                          const CraneFrames& f = {});

}  // namespace crane_twin
