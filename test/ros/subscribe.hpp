// Shared by the rostest nodes: nh.subscribe with a lambda (roscpp needs the callback's type
// spelled out).
#pragma once

#include <ros/ros.h>

#include <functional>
#include <string>

namespace crane_twin_test {

template <typename M, typename F>
ros::Subscriber subscribe(ros::NodeHandle& nh, const std::string& topic, int queue, F f) {
  return nh.subscribe<M>(topic, queue, boost::function<void(const typename M::ConstPtr&)>(f));
}

/// Poll `done` every 20 ms of wall time for up to `seconds`; its last value.
inline bool waitFor(const std::function<bool()>& done, double seconds) {
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::WallTime::now() < end && ros::ok()) {
    if (done()) return true;
    ros::WallDuration(0.02).sleep();
  }
  return done();
}

}  // namespace crane_twin_test
