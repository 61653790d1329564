// rostest of clock ownership on a site (docs/site.md), run by site_fast_clock.test: with
// real_time_factor 0 crane_a alone publishes /clock, faster than the wall clock but never more
// than a few publication periods ahead of crane_b, which follows it (lockstep).
#include <gtest/gtest.h>
#include <ros/master.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include <mutex>
#include <string>
#include <vector>

#include "crane_twin/CraneState.h"
#include "subscribe.hpp"

namespace {
std::mutex mtx;
double clock_s = 0.0, t_a = 0.0, t_b = 0.0, stamp_b = 0.0;
int states_b = 0;
using crane_twin_test::waitFor;

// The nodes that publish a topic (master's getSystemState).
std::vector<std::string> publishersOf(const std::string& topic) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  std::vector<std::string> out;
  if (!ros::master::execute("getSystemState", request, response, payload, false)) return out;
  XmlRpc::XmlRpcValue& publishers = payload[0];
  for (int i = 0; i < publishers.size(); ++i) {
    if (static_cast<std::string>(publishers[i][0]) != topic) continue;
    for (int j = 0; j < publishers[i][1].size(); ++j)
      out.push_back(static_cast<std::string>(publishers[i][1][j]));
  }
  return out;
}
}  // namespace

TEST(SiteClock, OneNodeOwnsTheClockAndTheOtherFollowsIt) {
  ASSERT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(mtx);
        return clock_s > 20.0;
      },
      120.0))
      << "the clock did not pass 20 s";
  EXPECT_EQ(publishersOf("/clock"), std::vector<std::string>{"/crane_a/crane_sim_node"});
  std::lock_guard<std::mutex> l(mtx);
  // Faster than the wall: 20 simulated seconds in well under the 120 s allowed.
  EXPECT_GT(t_a, 20.0);
  // crane_b follows the clock in lockstep (the owner waits for it): within 0.2 s of the clock
  // (2.5 publication periods of 1/30 s and the messages in flight), never beyond it, its states
  // stamped in simulated time.
  EXPECT_GT(states_b, 10);
  EXPECT_NEAR(t_b, clock_s, 0.2) << "clock " << clock_s << " s, crane_b at " << t_b << " s";
  EXPECT_LE(t_b, clock_s + 0.05);
  EXPECT_NEAR(stamp_b, t_b, 1e-6);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "site_clock_test");
  ros::NodeHandle nh;
  ros::Subscriber c = crane_twin_test::subscribe<rosgraph_msgs::Clock>(
      nh, "/clock", 10, [](const rosgraph_msgs::Clock::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        clock_s = m->clock.toSec();
      });
  ros::Subscriber a = crane_twin_test::subscribe<crane_twin::CraneState>(
      nh, "crane_a/crane/state", 100, [](const crane_twin::CraneState::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        t_a = m->t;
      });
  ros::Subscriber b = crane_twin_test::subscribe<crane_twin::CraneState>(
      nh, "crane_b/crane/state", 100, [](const crane_twin::CraneState::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        t_b = m->t;
        stamp_b = m->header.stamp.toSec();
        ++states_b;
      });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int r = RUN_ALL_TESTS();
  spinner.stop();
  return r;
}
