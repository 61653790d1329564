// rostest of position goals (docs/ros.md "Goals"), run by goals.test at 10x real time: a
// trajectory to a slew angle and a radius is reached within tolerance, within the drives'
// limits and without overshoot, and crane/goal_reached says so; bad trajectories are refused
// and counted; a rate command cancels a goal.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_msgs/Bool.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <cmath>
#include <mutex>
#include <string>
#include <vector>

#include "crane_twin/CraneCommand.h"
#include "crane_twin/CraneState.h"
#include "subscribe.hpp"

namespace {
std::mutex mtx;
std::vector<crane_twin::CraneState> states;
int goal_true = 0, goal_false = 0;
int rejected = -1;
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
  ASSERT_TRUE(waitFor([] { std::lock_guard<std::mutex> l(mtx); return goal_true > 0; }, 60.0))
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
  EXPECT_LE(max_slew, 0.3 + 1e-3);       // no overshoot beyond the tolerance
  EXPECT_GE(min_radius, 70.0 - 5e-3);
  EXPECT_LE(max_rate, 0.084 + 1e-9);     // the crane file's limits
  EXPECT_LE(max_speed, 1.0 + 1e-9);
  EXPECT_GT(max_speed, 0.9);             // and it used them
}

TEST(Goals, BadTrajectoriesAreRefusedAndARateCommandCancelsAGoal) {
  const int before = goal_false;
  auto rejectedNow = [] {
    std::lock_guard<std::mutex> l(mtx);
    return rejected;
  };
  ASSERT_TRUE(waitFor([&] { return rejectedNow() >= 0; }, 10.0));
  const int r0 = rejectedNow();
  trajectory_pub->publish(goal({"boom"}, {{1.0}}, {0.0}));                   // unknown joint
  trajectory_pub->publish(goal({"trolley"}, {{200.0}}, {0.0}));              // beyond the radius
  trajectory_pub->publish(goal({"slew"}, {{0.1}, {0.2}}, {5.0, 1.0}));       // time goes back
  trajectory_pub->publish(goal({"slew"}, {{std::nan("")}}, {0.0}));          // not finite
  EXPECT_TRUE(waitFor([&] { return rejectedNow() >= r0 + 4; }, 5.0)) << rejectedNow() - r0;
  EXPECT_EQ(goal_false, before);  // none of them started
  // A goal far away, then a rate command: the trolley stops short of it.
  trajectory_pub->publish(goal({"trolley"}, {{40.0}}, {0.0}));
  ASSERT_TRUE(waitFor([&] { std::lock_guard<std::mutex> l(mtx); return goal_false > before; }, 5.0));
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
