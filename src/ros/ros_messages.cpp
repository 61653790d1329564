#include "ros_messages.hpp"

#include <cstdio>
#include <sstream>

namespace crane_twin {

const char* const kJointNames[3] = {"slew", "trolley", "hoist"};

geometry_msgs::Point point(const Eigen::Vector3d& p) {
  geometry_msgs::Point m;
  m.x = p.x();
  m.y = p.y();
  m.z = p.z();
  return m;
}

Eigen::Vector3d fromMsg(const geometry_msgs::Point& p) { return {p.x, p.y, p.z}; }
Eigen::Vector3d fromMsg(const geometry_msgs::Vector3& v) { return {v.x, v.y, v.z}; }

namespace {

geometry_msgs::Vector3 vector(const Eigen::Vector3d& p) {
  geometry_msgs::Vector3 m;
  m.x = p.x();
  m.y = p.y();
  m.z = p.z();
  return m;
}

geometry_msgs::TransformStamped transform(const std::string& parent, const std::string& child,
                                          const FramePose& pose, const ros::Time& stamp) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation = vector(pose.position);
  const Eigen::Quaterniond q = pose.orientation.normalized();
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  return t;
}

visualization_msgs::Marker marker(const CraneFrames& f, const std::string& ns, int type,
                                  const ros::Time& stamp) {
  visualization_msgs::Marker m;
  m.header.frame_id = f.base();
  m.header.stamp = stamp;
  m.ns = f(ns);
  m.id = 0;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.color.a = 1.0;
  return m;
}

geometry_msgs::Pose pose(const FramePose& p) {
  geometry_msgs::Pose m;
  m.position = point(p.position);
  const Eigen::Quaterniond q = p.orientation.normalized();
  m.orientation.x = q.x();
  m.orientation.y = q.y();
  m.orientation.z = q.z();
  m.orientation.w = q.w();
  return m;
}

}  // namespace

void addKeyValue(diagnostic_msgs::DiagnosticStatus& d, const std::string& key,
                 const std::string& value) {
  diagnostic_msgs::KeyValue x;
  x.key = key;
  x.value = value;
  d.values.push_back(x);
}

void addNumber(diagnostic_msgs::DiagnosticStatus& d, const std::string& key, double value) {
  std::ostringstream s;
  s << value;
  addKeyValue(d, key, s.str());
}

sensor_msgs::JointState toJointState(const CraneSnapshot& s, const ros::Time& stamp) {
  sensor_msgs::JointState j;
  j.header.stamp = stamp;
  j.name.assign(kJointNames, kJointNames + 3);
  j.position = {s.slew_angle, s.trolley_radius, s.hoist_length};
  j.velocity = {s.slew_rate, s.trolley_speed, s.hoist_speed};
  j.effort = {0.0, 0.0, s.series.rope_top_tension};
  return j;
}

geometry_msgs::TransformStamped toBaseTransform(const CraneFrames& f,
                                                const Eigen::Vector3d& position, double yaw,
                                                const ros::Time& stamp) {
  FramePose p;
  p.position = position;
  p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  return transform("world", f.base(), p, stamp);
}

std::vector<geometry_msgs::TransformStamped> toTransforms(const CraneSnapshot& s,
                                                          const ros::Time& stamp,
                                                          const CraneFrames& f) {
  return {transform(f.base(), f("slewing"), s.slewing, stamp),
          transform(f.base(), f("mast"), s.mast, stamp),
          transform(f("slewing"), f("slewing_unit"), s.slewing_unit, stamp),
          transform(f("slewing"), f("jib"), s.jib, stamp),
          transform(f("slewing"), f("counter_jib"), s.counter_jib, stamp),
          transform(f("slewing"), f("jib_tip"), s.jib_tip, stamp),
          transform(f("slewing"), f("cab"), s.cab, stamp),
          transform(f("slewing"), f("trolley"), s.trolley, stamp),
          transform(f.base(), f("hook"), s.hook, stamp),
          transform(f.base(), f("payload"), s.payload, stamp)};
}

visualization_msgs::MarkerArray toMarkers(const CraneSnapshot& s, const ros::Time& stamp,
                                          const LoadShapes& loads, double payload_mass,
                                          const CraneFrames& f,
                                          std::optional<double> ground_height) {
  visualization_msgs::MarkerArray a;
  if (ground_height) {
    // 20 m x 20 m, 0.2 m thick, its top at the ground height, under the payload.
    auto ground = marker(f, "ground", visualization_msgs::Marker::CUBE, stamp);
    ground.pose.position =
        point(Eigen::Vector3d(s.series.payload.x(), s.series.payload.y(), *ground_height - 0.1));
    ground.pose.orientation.w = 1.0;
    ground.scale.x = ground.scale.y = 20.0;
    ground.scale.z = 0.2;
    ground.color.r = 0.35f;
    ground.color.g = 0.3f;
    ground.color.b = 0.25f;
    a.markers.push_back(ground);
  }
  auto rope = marker(f, "rope", visualization_msgs::Marker::LINE_STRIP, stamp);
  rope.scale.x = 0.12;
  rope.color.r = rope.color.g = rope.color.b = 0.85f;
  rope.points.reserve(s.rope_curve.size());
  for (const auto& p : s.rope_curve) rope.points.push_back(point(p));
  a.markers.push_back(rope);

  auto box = [&](const std::string& ns, const LoadBox& b, float r, float g, float bl) {
    auto m = marker(f, ns, visualization_msgs::Marker::CUBE, stamp);
    m.pose = pose(b.pose);
    m.scale = vector(b.size);
    m.color.r = r;
    m.color.g = g;
    m.color.b = bl;
    return m;
  };
  a.markers.push_back(box("hook_block", loads.hook_block, 0.95f, 0.8f, 0.1f));
  a.markers.push_back(box("payload", loads.payload, 1.0f, 0.45f, 0.0f));
  // The payload's mass beside it, readable from the default view (text height 3 m).
  auto label = marker(f, "payload_label", visualization_msgs::Marker::TEXT_VIEW_FACING, stamp);
  label.pose.position = point(loads.payload.pose.position +
                              Eigen::Vector3d(0.0, 0.0, -0.5 * loads.payload.size.z() - 2.5));
  label.scale.z = 3.0;
  label.color.r = label.color.g = label.color.b = 0.95f;
  char text[64];
  std::snprintf(text, sizeof text, "payload %.1f t", payload_mass / 1000.0);
  label.text = text;
  a.markers.push_back(label);

  if (!s.structure_segments.empty()) {
    auto structure = marker(f, "structure", visualization_msgs::Marker::LINE_LIST, stamp);
    structure.scale.x = 0.08;
    structure.color.r = 0.95f;
    structure.color.g = 0.75f;
    structure.color.b = 0.05f;
    structure.points.reserve(s.structure_segments.size());
    for (const auto& p : s.structure_segments) structure.points.push_back(point(p));
    a.markers.push_back(structure);
  }
  return a;
}

CraneState toStateMessage(const CraneSnapshot& s, const ros::Time& stamp, double step_cost,
                          double real_time_factor, const std::string& model, const CraneFrames& f) {
  const SeriesValues& v = s.series;
  CraneState m;
  m.header.stamp = stamp;
  m.header.frame_id = f.base();
  m.t = v.t;
  m.payload = point(v.payload);
  m.payload_velocity = vector(v.payload_velocity);
  m.cab_displacement = vector(v.cab);
  m.jib_tip_displacement = vector(v.jib_tip);
  m.trolley = point(v.trolley);
  m.rope_top_tension = v.rope_top_tension;
  m.rope_length = v.rope_length;
  m.slew_angle = v.slew_angle;
  m.trolley_radius = v.trolley_radius;
  m.slew_rate = s.slew_rate;
  m.trolley_speed = s.trolley_speed;
  m.hoist_speed = s.hoist_speed;
  m.energy = v.energy;
  m.constraint_error = v.constraint_error;
  m.subdomains = v.subdomains;
  m.tension_ratio = v.tension_ratio;
  m.load_chart_ratio = v.load_chart_ratio;
  m.warnings = v.warnings;
  m.step_compute_time = step_cost;
  m.real_time_factor = real_time_factor;
  m.model = model;
  m.payload_landed = v.payload_landed;
  m.contact_force = v.contact_force;
  m.stresses = v.stresses;
  return m;
}

CraneUsage toUsageMessage(const UsageReport& u, const ros::Time& stamp) {
  CraneUsage m;
  m.header.stamp = stamp;
  m.hours = u.hours;
  m.lifts = static_cast<int>(u.lift_count);
  m.k_q = u.k_q;
  m.u_class = u.u_class;
  m.q_class = u.q_class;
  m.design_hours = u.design_hours;
  m.lifts_in_design_life = u.lifts_in_design_life;
  m.u_class_in_design_life = u.u_class_in_design_life;
  for (const LiftRecord& l : u.lifts) {
    m.lift_masses.push_back(l.mass);
    m.lift_factors.push_back(l.dynamic_factor);
  }
  for (const HotSpotUsage& h : u.hot_spots) {
    m.hot_spots.push_back(h.name);
    m.damage.push_back(h.damage);
    m.damage_per_hour.push_back(h.damage_per_hour);
    m.hours_to_failure.push_back(h.hours_to_failure);
    m.short_of_design_life.push_back(h.short_of_design_life);
  }
  return m;
}

}  // namespace crane_twin
