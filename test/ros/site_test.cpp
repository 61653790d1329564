// rostest of a site (docs/site.md), run by site_clearance.test: two T8036 cranes from
// config/sites/two_t8036.yaml, their frames on the site under their prefixes, the clearance
// monitor's OK at the start (crane_b slewed away), and its WARN once crane_b slews its jib over
// crane_a's.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <mutex>
#include <string>

#include "crane_twin/CraneCommand.h"
#include "crane_twin/CraneState.h"
#include "crane_twin/SiteClearance.h"
#include "subscribe.hpp"

namespace {

std::mutex mtx;
crane_twin::SiteClearance last_clearance;
int clearance_count = 0;
int forecast_count = 0;
long first_forecast_warn = -1, first_warn = -1;  // message counts at the first (predicted) warning
double least_distance = 1e300;
int warn_diagnostics = 0;
crane_twin::CraneState state_b;
int state_b_count = 0;
ros::Publisher* command_b = nullptr;

using crane_twin_test::waitFor;

}  // namespace

TEST(Site, FramesOfBothCranesStandOnTheSite) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  for (const char* frame :
       {"crane_a/base", "crane_a/payload", "crane_a/jib", "crane_b/base", "crane_b/slewing",
        "crane_b/trolley", "crane_b/payload", "crane_b/counter_jib"}) {
    std::string error;
    EXPECT_TRUE(buffer.canTransform("world", frame, ros::Time(0), ros::Duration(20.0), &error))
        << frame << ": " << error;
  }
  // crane_b's mast foot at (100, 0, 10), turned 180 deg (the site file).
  const auto b = buffer.lookupTransform("world", "crane_b/base", ros::Time(0));
  EXPECT_NEAR(b.transform.translation.x, 100.0, 1e-9);
  EXPECT_NEAR(b.transform.translation.z, 10.0, 1e-9);
  EXPECT_NEAR(std::abs(b.transform.rotation.z), 1.0, 1e-9);
  // crane_b's own trolley point (crane/state, its base frame) carried onto the site by the base
  // pose, p_site = (100, 0, 10) + Rz(180 deg) p: where TF puts crane_b/trolley (the crane barely
  // moves: the latest state and the latest transform are within millimetres).
  ASSERT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(mtx);
        return state_b_count > 0;
      },
      20.0));
  crane_twin::CraneState sb;
  {
    std::lock_guard<std::mutex> l(mtx);
    sb = state_b;
  }
  EXPECT_EQ(sb.header.frame_id, "crane_b/base");
  const auto tr = buffer.lookupTransform("world", "crane_b/trolley", ros::Time(0));
  EXPECT_NEAR(tr.transform.translation.x, 100.0 - sb.trolley.x, 0.01);
  EXPECT_NEAR(tr.transform.translation.y, 0.0 - sb.trolley.y, 0.01);
  EXPECT_NEAR(tr.transform.translation.z, 10.0 + sb.trolley.z, 0.01);
  // Slewed 90 deg, its trolley is at the site's -y, 80 m out.
  EXPECT_NEAR(std::hypot(tr.transform.translation.x - 100.0, tr.transform.translation.y), 80.0,
              1.0);
  EXPECT_LT(tr.transform.translation.y, -79.0);
}

TEST(Site, MonitorWarnsWhenAJibSlewsOverTheOther) {
  // At the start crane_b's jib points away: clearance above the warning distance.
  ASSERT_TRUE(waitFor(
      [] {
        std::lock_guard<std::mutex> l(mtx);
        return clearance_count > 3;
      },
      30.0));
  {
    std::lock_guard<std::mutex> l(mtx);
    EXPECT_EQ(last_clearance.crane_a, "crane_a");
    EXPECT_EQ(last_clearance.crane_b, "crane_b");
    EXPECT_EQ(last_clearance.level, 0) << last_clearance.min_distance;
    EXPECT_GT(last_clearance.min_distance, 10.0);
    EXPECT_EQ(last_clearance.header.frame_id, "world");
  }
  // Slew crane_b back towards crane_a at its full rate until the monitor warns.
  const bool warned = waitFor(
      [] {
        crane_twin::CraneCommand c;
        c.header.stamp = ros::Time::now();
        c.slew_rate = -0.084;
        command_b->publish(c);
        std::lock_guard<std::mutex> l(mtx);
        return last_clearance.level >= 1 && warn_diagnostics > 0;
      },
      60.0);
  std::lock_guard<std::mutex> l(mtx);
  ASSERT_TRUE(warned) << "least clearance " << least_distance;
  EXPECT_LT(last_clearance.min_distance, 10.0);
  // The closest points are min_distance apart.
  const double dx = last_clearance.point_a.x - last_clearance.point_b.x;
  const double dy = last_clearance.point_a.y - last_clearance.point_b.y;
  const double dz = last_clearance.point_a.z - last_clearance.point_b.z;
  EXPECT_NEAR(std::sqrt(dx * dx + dy * dy + dz * dz), std::abs(last_clearance.min_distance), 1e-6);
  // The cranes' forecasts (docs/twin.md) saw it coming: a predicted warning before the warning.
  EXPECT_GT(forecast_count, 0);
  EXPECT_GE(first_forecast_warn, 0) << "no forecast predicted the approach";
  EXPECT_LT(first_forecast_warn, first_warn);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "site_test");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<crane_twin::CraneCommand>("crane_b/crane/command", 10);
  command_b = &pub;
  ros::Subscriber s = crane_twin_test::subscribe<crane_twin::SiteClearance>(
      nh, "site/clearance", 100, [](const crane_twin::SiteClearance::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        last_clearance = *m;
        if (m->forecast_valid) ++forecast_count;
        if (m->forecast_valid && m->forecast_level >= 1 && first_forecast_warn < 0)
          first_forecast_warn = clearance_count;
        if (m->level >= 1 && first_warn < 0) first_warn = clearance_count;
        ++clearance_count;
        least_distance = std::min(least_distance, m->min_distance);
      });
  ros::Subscriber sb = crane_twin_test::subscribe<crane_twin::CraneState>(
      nh, "crane_b/crane/state", 10, [](const crane_twin::CraneState::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        state_b = *m;
        ++state_b_count;
      });
  ros::Subscriber d = crane_twin_test::subscribe<diagnostic_msgs::DiagnosticArray>(
      nh, "/diagnostics", 100, [](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
        std::lock_guard<std::mutex> l(mtx);
        for (const auto& st : m->status)
          if (st.name == "/site_monitor: crane_a - crane_b" &&
              st.level == diagnostic_msgs::DiagnosticStatus::WARN)
            ++warn_diagnostics;
      });
  ros::AsyncSpinner spinner(2);
  spinner.start();
  const int r = RUN_ALL_TESTS();
  spinner.stop();
  return r;
}
