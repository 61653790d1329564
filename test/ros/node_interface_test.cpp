// rostest of crane_sim_node's ROS interface (docs/ros.md), run by node_interface.test
// against the live T8036 scene at real time: joint names and the rope tension they carry, the
// TF tree, the markers, bad messages (the node lives on, the state stays finite), a trolley
// command followed as the drive's limits say, the command timeout, pause and reset.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <geometry_msgs/Vector3Stamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "crane_twin/CraneCommand.h"
#include "crane_twin/CraneState.h"
#include "crane_twin/CraneUsage.h"
#include "subscribe.hpp"

namespace {

struct Recorder {
  std::mutex m;
  std::vector<crane_twin::CraneState> states;
  sensor_msgs::JointState joints;
  visualization_msgs::MarkerArray markers;
  std::vector<crane_twin::CraneCommand> applied;
  diagnostic_msgs::DiagnosticStatus diag;
  int joint_count = 0, marker_count = 0, diag_count = 0;
};

Recorder* rec = nullptr;
ros::Publisher* command_pub = nullptr;

crane_twin::CraneState latest() {
  std::lock_guard<std::mutex> l(rec->m);
  return rec->states.empty() ? crane_twin::CraneState() : rec->states.back();
}

size_t stateCount() {
  std::lock_guard<std::mutex> l(rec->m);
  return rec->states.size();
}

using crane_twin_test::waitFor;

bool finiteState(const crane_twin::CraneState& s) {
  const double v[] = {s.t,
                      s.payload.x,
                      s.payload.y,
                      s.payload.z,
                      s.payload_velocity.x,
                      s.payload_velocity.y,
                      s.payload_velocity.z,
                      s.cab_displacement.x,
                      s.jib_tip_displacement.z,
                      s.trolley.x,
                      s.rope_top_tension,
                      s.rope_length,
                      s.slew_angle,
                      s.trolley_radius,
                      s.slew_rate,
                      s.trolley_speed,
                      s.hoist_speed,
                      s.energy,
                      s.constraint_error,
                      s.tension_ratio};
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

std::string diagValue(const diagnostic_msgs::DiagnosticStatus& d, const std::string& key) {
  for (const auto& kv : d.values)
    if (kv.key == key) return kv.value;
  return "";
}

void send(double slew, double trolley, double hoist) {
  crane_twin::CraneCommand c;
  c.header.stamp = ros::Time::now();
  c.slew_rate = slew;
  c.trolley_speed = trolley;
  c.hoist_speed = hoist;
  command_pub->publish(c);
}

}  // namespace

TEST(CraneSimNode, PublishesJointsWithTheRopeTension) {
  ASSERT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(rec->m);
        return rec->joint_count > 0;
      },
      60.0));
  std::lock_guard<std::mutex> l(rec->m);
  const sensor_msgs::JointState& j = rec->joints;
  ASSERT_EQ(j.name, (std::vector<std::string>{"slew", "trolley", "hoist"}));
  ASSERT_EQ(j.position.size(), 3u);
  ASSERT_EQ(j.velocity.size(), 3u);
  ASSERT_EQ(j.effort.size(), 3u);
  EXPECT_NEAR(j.position[1], 80.0, 1e-9);  // t8036_live: trolley at 80 m, 60 m of rope
  EXPECT_NEAR(j.position[2], 60.0, 1e-9);
  // Hoist effort = rope top tension: the hanging weight (payload 3600 kg, hook block 2044 kg,
  // 2 falls x 1.9 kg/m x 60 m) g, give or take the 2.3 deg swing's dynamic part.
  const double weight = (3600.0 + 2044.0 + 2 * 1.9 * 60.0) * 9.81;
  EXPECT_NEAR(j.effort[2], weight, 0.05 * weight);
}

TEST(CraneSimNode, PublishesItsUsage) {
  // crane/usage (docs/fatigue.md "Usage"): the T8036's four hot spots with a damage that grows
  // as the run goes on; no lift on the live scene (its load hangs from the start).
  ros::NodeHandle nh;
  const auto first =
      ros::topic::waitForMessage<crane_twin::CraneUsage>("/crane/usage", nh, ros::Duration(10.0));
  ASSERT_TRUE(first) << "no crane/usage";
  ros::WallDuration(2.5).sleep();
  const auto later =
      ros::topic::waitForMessage<crane_twin::CraneUsage>("/crane/usage", nh, ros::Duration(5.0));
  ASSERT_TRUE(later);
  ASSERT_EQ(later->hot_spots.size(), 4u);
  ASSERT_EQ(later->damage.size(), 4u);
  EXPECT_EQ(later->hot_spots[0], "mast_foot");
  EXPECT_GT(later->hours, first->hours);
  EXPECT_EQ(later->lifts, 0);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_TRUE(std::isfinite(later->damage[i]));
    EXPECT_GE(later->damage[i], 0.0);
  }
}

TEST(CraneSimNode, TfTreeIsComplete) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  // The node's frames; mast, slewing_unit, jib, counter_jib and trolley are also the URDF's
  // links (floating joints), which have no other publisher.
  for (const char* frame : {"base", "slewing", "mast", "slewing_unit", "jib", "counter_jib",
                            "jib_tip", "cab", "trolley", "hook", "payload"}) {
    std::string error;
    EXPECT_TRUE(buffer.canTransform("world", frame, ros::Time(0), ros::Duration(10.0), &error))
        << frame << ": " << error;
  }
  // The payload frame hangs about 60 m below the trolley frame.
  const auto trolley = buffer.lookupTransform("world", "trolley", ros::Time(0));
  const auto payload = buffer.lookupTransform("world", "payload", ros::Time(0));
  const double drop = trolley.transform.translation.z - payload.transform.translation.z;
  EXPECT_GT(drop, 59.0);
  EXPECT_LT(drop, 61.0);
  // The rigid jib sits on the deformed one: its undeformed tip point (81.225, 0, 68) in the jib
  // frame lands within 0.5 m of the deformed jib tip (the model's jib sags 2.3 m at the tip
  // under this load; the old fixed URDF jib was that far above it).
  const auto jib = buffer.lookupTransform("slewing", "jib", ros::Time(0));
  const auto tip = buffer.lookupTransform("slewing", "jib_tip", ros::Time(0));
  const auto& q = jib.transform.rotation;
  const Eigen::Vector3d rigid_tip =
      Eigen::Quaterniond(q.w, q.x, q.y, q.z) * Eigen::Vector3d(81.225, 0.0, 68.0) +
      Eigen::Vector3d(jib.transform.translation.x, jib.transform.translation.y,
                      jib.transform.translation.z);
  const Eigen::Vector3d deformed_tip(tip.transform.translation.x, tip.transform.translation.y,
                                     tip.transform.translation.z);
  EXPECT_LT(deformed_tip.z(), 68.0 - 1.5);
  EXPECT_LT((rigid_tip - deformed_tip).norm(), 0.5);
  // The URDF has no hook: the only hook block is the marker at the simulated rope end.
  std::string urdf;
  ASSERT_TRUE(ros::param::get("robot_description", urdf));
  EXPECT_EQ(urdf.find("<link name=\"hook"), std::string::npos);
  EXPECT_EQ(urdf.find("<joint name=\"hoist\""), std::string::npos);
  // Without a site pose the crane's base is the world's origin.
  const auto base = buffer.lookupTransform("world", "base", ros::Time(0));
  EXPECT_EQ(base.transform.translation.x, 0.0);
  EXPECT_EQ(base.transform.translation.z, 0.0);
  EXPECT_EQ(base.transform.rotation.w, 1.0);
}

TEST(CraneSimNode, MarkersShowRopePayloadAndStructure) {
  // The structure's marker comes with a publication at most ~structure_marker_rate times per
  // wall second (docs/ros.md): wait for one that carries it.
  ASSERT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(rec->m);
        for (const auto& m : rec->markers.markers)
          if (m.ns == "structure") return true;
        return false;
      },
      10.0));
  std::lock_guard<std::mutex> l(rec->m);
  bool rope = false, payload = false, hook_block = false, structure = false;
  geometry_msgs::Point hook_centre, payload_centre;
  for (const auto& m : rec->markers.markers) {
    EXPECT_EQ(m.header.frame_id, "base");  // the crane's own frame (no prefix, at the origin)
    if (m.ns == "rope") {
      rope = true;
      EXPECT_EQ(m.type, visualization_msgs::Marker::LINE_STRIP);
      EXPECT_EQ(m.points.size(), 40u * 4u + 1u);  // 40 elements (test override), 4 samples each
    } else if (m.ns == "payload") {
      payload = true;
      EXPECT_EQ(m.type, visualization_msgs::Marker::CUBE);
      // A cube of the payload's volume at 1000 kg/m^3: 3.6 m^3 (docs/ros.md "Frames").
      EXPECT_NEAR(m.scale.x * m.scale.y * m.scale.z, 3.6, 1e-9);
      payload_centre = m.pose.position;
    } else if (m.ns == "hook_block") {
      hook_block = true;
      EXPECT_EQ(m.type, visualization_msgs::Marker::CUBE);
      EXPECT_NEAR(m.scale.x * m.scale.y * m.scale.z, 2044.0 / (0.5 * 7850.0), 1e-9);
      hook_centre = m.pose.position;
    } else if (m.ns == "structure") {
      structure = true;
      EXPECT_EQ(m.type, visualization_msgs::Marker::LINE_LIST);
      EXPECT_GT(m.points.size(), 100u);
      EXPECT_EQ(m.points.size() % 2, 0u);
    }
  }
  EXPECT_TRUE(rope && payload && hook_block && structure);
  // One hook: the hook block hangs just below the rope's end, the payload just below it.
  const auto end = rec->markers.markers.front().points.back();  // the rope's last point
  EXPECT_LT(std::hypot(hook_centre.x - end.x, hook_centre.y - end.y, hook_centre.z - end.z), 1.0);
  EXPECT_LT(payload_centre.z, hook_centre.z);
  EXPECT_LT(std::hypot(payload_centre.x - hook_centre.x, payload_centre.y - hook_centre.y,
                       payload_centre.z - hook_centre.z),
            2.0);
}

TEST(CraneSimNode, BadCommandsAreRejectedAndTheNodeLivesOn) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const double bad[][3] = {{nan, 0, 0},    {0, inf, 0},  {0, 0, -inf},   {1e9, 0, 0},
                           {0, -1e300, 0}, {0, 0, 50.0}, {nan, nan, nan}};
  for (const auto& b : bad) send(b[0], b[1], b[2]);
  ros::WallDuration(2.0).sleep();
  const size_t before = stateCount();
  ros::WallDuration(1.0).sleep();
  EXPECT_GT(stateCount(), before + 10) << "the node stopped publishing";
  const crane_twin::CraneState s = latest();
  EXPECT_TRUE(finiteState(s));
  EXPECT_EQ(s.trolley_speed, 0.0);
  EXPECT_EQ(s.slew_rate, 0.0);
  EXPECT_NEAR(s.trolley_radius, 80.0, 1e-12);
  // The T8036's hot spots (docs/fatigue.md): named, finite, the mast foot's chord pushed.
  ASSERT_EQ(s.stress_names.size(), 4u);
  ASSERT_EQ(s.stresses.size(), 4u);
  EXPECT_EQ(s.stress_names[0], "mast_foot");
  for (double sigma : s.stresses) EXPECT_TRUE(std::isfinite(sigma));
  EXPECT_LT(s.stresses[0], 0.0);
  ASSERT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(rec->m);
        return rec->diag_count > 0 && diagValue(rec->diag, "rejected_commands") != "" &&
               std::stoi(diagValue(rec->diag, "rejected_commands")) >= 7;
      },
      5.0))
      << "diagnostics do not count the 7 rejected commands";
}

TEST(CraneSimNode, TrolleyFollowsTheCommandWithinTheDriveLimits) {
  // -0.5 m/s (under the 1 m/s limit) sent at 20 Hz for 3 s: the drive reaches it after a 1 s
  // ramp at 0.5 m/s^2; the radius falls by the integral of the reported speed.
  const crane_twin::CraneState s0 = latest();
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(3.0);
  while (ros::WallTime::now() < end) {
    send(0.0, -0.5, 0.0);
    ros::WallDuration(0.05).sleep();
  }
  const crane_twin::CraneState s1 = latest();
  EXPECT_NEAR(s1.trolley_speed, -0.5, 1e-12);
  // Then silence: after the 0.5 s timeout the drive ramps to rest within 1 s.
  ros::WallDuration(2.5).sleep();
  const crane_twin::CraneState s2 = latest();
  EXPECT_EQ(s2.trolley_speed, 0.0);
  EXPECT_TRUE(finiteState(s2));
  // Radius change against the trapezoid integral of the recorded speeds.
  double integral = 0.0;
  {
    std::lock_guard<std::mutex> l(rec->m);
    for (size_t i = 1; i < rec->states.size(); ++i) {
      const auto& a = rec->states[i - 1];
      const auto& b = rec->states[i];
      if (a.t < s0.t || b.t > s2.t) continue;
      integral += 0.5 * (a.trolley_speed + b.trolley_speed) * (b.t - a.t);
    }
    bool timed_out = false;
    for (const auto& c : rec->applied) timed_out |= c.header.frame_id == "timeout";
    EXPECT_TRUE(timed_out) << "no timeout command on crane/command_applied";
  }
  const double moved = s2.trolley_radius - s0.trolley_radius;
  EXPECT_LT(moved, -1.0);  // at least 1 s at full speed plus the ramps
  EXPECT_NEAR(moved, integral, 0.02);
  // The rope's top follows the trolley point (constraint), the load swings but stays finite.
  EXPECT_LT(s2.constraint_error, 1e-6);
}

TEST(CraneSimNode, PauseHoldsAndResetRestarts) {
  ros::NodeHandle nh;
  std_srvs::SetBool pause;
  pause.request.data = true;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/pause", pause));
  EXPECT_TRUE(pause.response.success);
  ros::WallDuration(0.3).sleep();
  const double t_paused = latest().t;
  // A TF listener started during the pause still finds the payload (the frozen state keeps
  // being published, as gazebo_ros does).
  {
    tf2_ros::Buffer buffer;
    tf2_ros::TransformListener listener(buffer);
    std::string error;
    EXPECT_TRUE(buffer.canTransform("world", "payload", ros::Time(0), ros::Duration(2.0), &error))
        << error;
  }
  const size_t before = stateCount();
  ros::WallDuration(1.0).sleep();
  EXPECT_EQ(latest().t, t_paused);
  // crane/state at ~publish_rate (30 Hz) of wall time while paused.
  const size_t during = stateCount() - before;
  EXPECT_GT(during, 20u);
  EXPECT_LT(during, 45u);
  pause.request.data = false;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/pause", pause));
  ros::WallDuration(1.0).sleep();
  EXPECT_GT(latest().t, t_paused + 0.5);

  std_srvs::Trigger reset;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/reset", reset));
  EXPECT_TRUE(reset.response.success) << reset.response.message;
  ros::WallDuration(0.5).sleep();
  const crane_twin::CraneState s = latest();
  EXPECT_LT(s.t, 2.0);
  EXPECT_NEAR(s.trolley_radius, 80.0, 1e-12);
  EXPECT_TRUE(finiteState(s));
}

TEST(CraneSimNode, WindFromTheTopicPushesTheLoadAndWarnsOverTheLimit) {
  // After the reset above. Bad wind messages are refused and counted; then 25 m/s along the
  // world's y at the jib (the node's crane/wind, an anemometer) for 3 s: the load drifts along
  // +y, the 3 s mean climbs over the 20 m/s in-service limit and the diagnostics say so.
  ros::NodeHandle nh;
  ros::Publisher wind = nh.advertise<geometry_msgs::Vector3Stamped>("crane/wind", 10);
  ASSERT_TRUE(waitFor([&wind] { return wind.getNumSubscribers() > 0; }, 10.0));
  auto rejected = [] {
    std::lock_guard<std::mutex> l(rec->m);
    const std::string v = diagValue(rec->diag, "rejected_commands");
    return v.empty() ? -1 : std::stoi(v);
  };
  ASSERT_TRUE(waitFor([&] { return rejected() >= 0; }, 5.0));
  const int before = rejected();
  geometry_msgs::Vector3Stamped m;
  m.header.frame_id = "world";
  m.vector.x = std::numeric_limits<double>::quiet_NaN();
  wind.publish(m);
  m.vector.x = 0.0;
  m.vector.y = 25.0;
  m.header.frame_id = "trolley";
  wind.publish(m);
  EXPECT_TRUE(waitFor([&] { return rejected() >= before + 2; }, 5.0)) << "bad winds not counted";
  const crane_twin::CraneState s0 = latest();
  m.header.frame_id = "world";
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(3.5);
  while (ros::WallTime::now() < end) {
    m.header.stamp = ros::Time::now();
    wind.publish(m);
    ros::WallDuration(0.1).sleep();
  }
  const crane_twin::CraneState s1 = latest();
  EXPECT_GT(s1.payload.y - s0.payload.y, 0.1) << "the load did not drift with the wind";
  EXPECT_TRUE(finiteState(s1));
  EXPECT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(rec->m);
        const std::string w = diagValue(rec->diag, "wind_3s");
        return !w.empty() && std::stod(w) > 20.0 &&
               diagValue(rec->diag, "warnings_seen_names").find("in-service limit") !=
                   std::string::npos;
      },
      5.0))
      << "diagnostics: wind_3s " << diagValue(rec->diag, "wind_3s") << ", warnings "
      << diagValue(rec->diag, "warnings_seen_names");
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_interface_test");
  ros::NodeHandle nh;
  Recorder r;
  rec = &r;
  ros::Subscriber a = crane_twin_test::subscribe<crane_twin::CraneState>(
      nh, "crane/state", 100, [](const crane_twin::CraneState::ConstPtr& m) {
        std::lock_guard<std::mutex> l(rec->m);
        rec->states.push_back(*m);
      });
  ros::Subscriber b = crane_twin_test::subscribe<sensor_msgs::JointState>(
      nh, "joint_states", 10, [](const sensor_msgs::JointState::ConstPtr& m) {
        std::lock_guard<std::mutex> l(rec->m);
        rec->joints = *m;
        ++rec->joint_count;
      });
  ros::Subscriber c = crane_twin_test::subscribe<visualization_msgs::MarkerArray>(
      nh, "crane/rope", 2, [](const visualization_msgs::MarkerArray::ConstPtr& m) {
        std::lock_guard<std::mutex> l(rec->m);
        rec->markers = *m;
        ++rec->marker_count;
      });
  ros::Subscriber d = crane_twin_test::subscribe<crane_twin::CraneCommand>(
      nh, "crane/command_applied", 100, [](const crane_twin::CraneCommand::ConstPtr& m) {
        std::lock_guard<std::mutex> l(rec->m);
        rec->applied.push_back(*m);
      });
  ros::Subscriber e = crane_twin_test::subscribe<diagnostic_msgs::DiagnosticArray>(
      nh, "/diagnostics", 10, [](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        std::lock_guard<std::mutex> l(rec->m);
        for (const auto& s : m->status)
          if (s.name == "/crane_sim_node: simulation") {  // named after the node
            rec->diag = s;
            ++rec->diag_count;
          }
      });
  ros::Publisher p = nh.advertise<crane_twin::CraneCommand>("crane/command", 20);
  command_pub = &p;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  // Wait until the node hears us (a command published before would be lost).
  waitFor([&p] { return p.getNumSubscribers() > 0; }, 60.0);
  return RUN_ALL_TESTS();
}
