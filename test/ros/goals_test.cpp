// rostest of position goals (docs/ros.md "Goals"), run by goals.test at 10x real time: a
// trajectory to a slew angle and a radius is reached within tolerance, within the drives'
// limits and without overshoot, and crane/goal_reached says so; bad trajectories are refused
// and counted; a rate command cancels a goal.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Bool.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "crane_twin/CraneCommand.h"
#include "crane_twin/CraneState.h"
#include "crane_twin/SetPayload.h"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "subscribe.hpp"

namespace {
std::mutex mtx;
std::vector<crane_twin::CraneState> states;
int goal_true = 0, goal_false = 0;
int rejected = -1;
double hoist_effort = 0.0;
std::string scene_file;
ros::Publisher *trajectory_pub = nullptr, *command_pub = nullptr;
using crane_twin_test::waitFor;

trajectory_msgs::JointTrajectory goal(std::vector<std::string> joints,
                                      std::vector<std::vector<double>> points,
                                      std::vector<double> times) {
  trajectory_msgs::JointTrajectory t;
  t.joint_names = joints;
  for (std::size_t k = 0; k < points.size(); ++k) {
    trajectory_msgs::JointTrajectoryPoint p;
    p.positions = points[k];
    p.time_from_start = ros::Duration(times[k]);
    t.points.push_back(p);
  }
  return t;
}
crane_twin::CraneState latest() {
  std::lock_guard<std::mutex> l(mtx);
  return states.empty() ? crane_twin::CraneState() : states.back();
}
}  // namespace

TEST(Goals, SlewAndRadiusAreReachedWithinLimitsAndTolerance) {
  ASSERT_TRUE(waitFor([] { return latest().t > 0.5; }, 60.0));
  ASSERT_TRUE(waitFor([] { return trajectory_pub->getNumSubscribers() > 0; }, 10.0));
  std::size_t first;
  {
    std::lock_guard<std::mutex> l(mtx);
    first = states.size();
  }
  trajectory_pub->publish(goal({"slew", "trolley"}, {{0.3, 70.0}}, {0.0}));
  ASSERT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(mtx);
        return goal_true > 0;
      },
      60.0))
      << "goal not reached; at slew " << latest().slew_angle << " rad, radius "
      << latest().trolley_radius << " m";
  const crane_twin::CraneState s = latest();
  EXPECT_NEAR(s.slew_angle, 0.3, 1e-3);
  EXPECT_NEAR(s.trolley_radius, 70.0, 5e-3);
  std::lock_guard<std::mutex> l(mtx);
  double max_slew = 0, min_radius = 1e9, max_rate = 0, max_speed = 0;
  for (std::size_t k = first; k < states.size(); ++k) {
    max_slew = std::max(max_slew, states[k].slew_angle);
    min_radius = std::min(min_radius, states[k].trolley_radius);
    max_rate = std::max(max_rate, std::abs(states[k].slew_rate));
    max_speed = std::max(max_speed, std::abs(states[k].trolley_speed));
  }
  EXPECT_LE(max_slew, 0.3 + 1e-3);  // no overshoot beyond the tolerance
  EXPECT_GE(min_radius, 70.0 - 5e-3);
  EXPECT_LE(max_rate, 0.084 + 1e-9);  // the crane file's limits
  EXPECT_LE(max_speed, 1.0 + 1e-9);
  EXPECT_GT(max_speed, 0.9);  // and it used them
}

TEST(Goals, BadTrajectoriesAreRefusedAndARateCommandCancelsAGoal) {
  const int before = goal_false;
  auto rejectedNow = [] {
    std::lock_guard<std::mutex> l(mtx);
    return rejected;
  };
  ASSERT_TRUE(waitFor([&] { return rejectedNow() >= 0; }, 10.0));
  const int r0 = rejectedNow();
  trajectory_pub->publish(goal({"boom"}, {{1.0}}, {0.0}));              // unknown joint
  trajectory_pub->publish(goal({"trolley"}, {{200.0}}, {0.0}));         // beyond the radius
  trajectory_pub->publish(goal({"slew"}, {{0.1}, {0.2}}, {5.0, 1.0}));  // time goes back
  trajectory_pub->publish(goal({"slew"}, {{std::nan("")}}, {0.0}));     // not finite
  EXPECT_TRUE(waitFor([&] { return rejectedNow() >= r0 + 4; }, 5.0)) << rejectedNow() - r0;
  EXPECT_EQ(goal_false, before);  // none of them started
  // A goal far away, then a rate command: the trolley stops short of it.
  trajectory_pub->publish(goal({"trolley"}, {{40.0}}, {0.0}));
  ASSERT_TRUE(waitFor(
      [&] {
        std::lock_guard<std::mutex> l(mtx);
        return goal_false > before;
      },
      5.0));
  ros::WallDuration(0.5).sleep();
  crane_twin::CraneCommand stop;
  command_pub->publish(stop);
  ros::WallDuration(3.0).sleep();
  const crane_twin::CraneState s = latest();
  EXPECT_GT(s.trolley_radius, 45.0);
  EXPECT_NEAR(s.trolley_speed, 0.0, 1e-9);
  std::lock_guard<std::mutex> l(mtx);
  EXPECT_EQ(goal_true, 1);  // only the first goal was reached
}

// Static top tension of the live scene with this payload: (end mass + rope mass) g, the end
// mass being payload and hook block (the model's own bookkeeping of the scene's masses).
double hangingWeight(double payload) {
  const crane_twin::CraneModel m = crane_twin::buildCraneModel(crane_twin::loadScene(
      scene_file, {"rope.elements=40", "payload.mass=" + std::to_string(payload)}));
  return (m.end_mass + m.ropeMass()) * m.scene.gravity;
}

double effort() {
  std::lock_guard<std::mutex> l(mtx);
  return hoist_effort;
}

TEST(Payload, SetPayloadAndResetChangeTheLoadWithoutARestart) {
  // Refused while a drive moves.
  crane_twin::CraneCommand move;
  move.trolley_speed = 0.5;
  command_pub->publish(move);
  ASSERT_TRUE(waitFor([] { return std::abs(latest().trolley_speed) > 0.1; }, 10.0));
  crane_twin::SetPayload sp;
  sp.request.mass = 2000.0;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/set_payload", sp));
  EXPECT_FALSE(sp.response.success);
  EXPECT_NE(sp.response.message.find("stop the drives"), std::string::npos) << sp.response.message;
  command_pub->publish(crane_twin::CraneCommand());
  ASSERT_TRUE(waitFor(
      [] {
        const auto s = latest();
        return s.trolley_speed == 0.0 && s.slew_rate == 0.0;
      },
      20.0));
  // A bad mass is refused and named.
  sp.request.mass = -3.0;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/set_payload", sp));
  EXPECT_FALSE(sp.response.success);
  EXPECT_NE(sp.response.message.find("-3"), std::string::npos) << sp.response.message;
  // 2 t: the hoist effort (top tension) becomes the new hanging weight within 1 %, simulated
  // time runs on, the crane stays where it stood.
  const crane_twin::CraneState before = latest();
  sp.request.mass = 2000.0;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/set_payload", sp));
  ASSERT_TRUE(sp.response.success) << sp.response.message;
  ros::WallDuration(0.5).sleep();
  const crane_twin::CraneState after = latest();
  EXPECT_GT(after.t, before.t);
  EXPECT_NEAR(after.trolley_radius, before.trolley_radius, 1e-6);
  EXPECT_NEAR(after.slew_angle, before.slew_angle, 1e-9);
  const double w2 = hangingWeight(2000.0);
  EXPECT_NEAR(effort(), w2, 0.01 * w2);
  // Paused after the change, the frozen state is stamped with the wall time now (stamps are
  // wall time in this scene), whatever time ran before the load change.
  std_srvs::SetBool pause;
  pause.request.data = true;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/pause", pause));
  ros::WallDuration(0.3).sleep();
  EXPECT_NEAR((latest().header.stamp - ros::Time::now()).toSec(), 0.0, 0.2);
  pause.request.data = false;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/pause", pause));
  // ~reset reads ~overrides again: 1.5 t.
  ros::param::set("/crane_sim_node/overrides",
                  std::vector<std::string>{"rope.elements=40", "payload.mass=1500"});
  std_srvs::Trigger reset;
  const double t_before_reset = latest().t;
  ASSERT_TRUE(ros::service::call("/crane_sim_node/reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  ros::WallDuration(0.5).sleep();
  const double w15 = hangingWeight(1500.0);
  EXPECT_NEAR(effort(), w15, 0.02 * w15);  // the live scene's 2.3 deg release swings
  EXPECT_LT(latest().t, t_before_reset);   // back to t = 0 (then 0.5 s at 10x)
  // A bad override: the reset is refused, naming it, and the run goes on.
  ros::param::set("/crane_sim_node/overrides", std::vector<std::string>{"payload.mas=1"});
  ASSERT_TRUE(ros::service::call("/crane_sim_node/reset", reset));
  EXPECT_FALSE(reset.response.success);
  EXPECT_NE(reset.response.message.find("payload.mas"), std::string::npos)
      << reset.response.message;
  const double t0 = latest().t;
  ros::WallDuration(0.5).sleep();
  EXPECT_GT(latest().t, t0);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "goals_test");
  ros::NodeHandle nh;
  ros::Publisher tp = nh.advertise<trajectory_msgs::JointTrajectory>("crane/joint_trajectory", 10);
  ros::Publisher cp = nh.advertise<crane_twin::CraneCommand>("crane/command", 10);
  trajectory_pub = &tp;
  command_pub = &cp;
  ros::Subscriber a = crane_twin_test::subscribe<crane_twin::CraneState>(
      nh, "crane/state", 1000, [](const crane_twin::CraneState::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        states.push_back(*m);
      });
  ros::Subscriber b = crane_twin_test::subscribe<std_msgs::Bool>(
      nh, "crane/goal_reached", 10, [](const std_msgs::Bool::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        ++(m->data ? goal_true : goal_false);
      });
  ros::NodeHandle("~").getParam("scene", scene_file);
  ros::Subscriber j = crane_twin_test::subscribe<sensor_msgs::JointState>(
      nh, "joint_states", 10, [](const sensor_msgs::JointState::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        if (m->effort.size() == 3) hoist_effort = m->effort[2];
      });
  ros::Subscriber c = crane_twin_test::subscribe<diagnostic_msgs::DiagnosticArray>(
      nh, "/diagnostics", 10, [](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        for (const auto& s : m->status)
          for (const auto& kv : s.values)
            if (s.name == "/crane_sim_node: simulation" && kv.key == "rejected_commands")
              rejected = std::stoi(kv.value);
      });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int r = RUN_ALL_TESTS();
  spinner.stop();
  return r;
}
