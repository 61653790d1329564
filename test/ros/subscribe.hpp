// Shared by the rostest nodes: nh.subscribe with a lambda (roscpp needs the callback's type
// spelled out).
#pragma once

#include <ros/ros.h>

#include <string>

namespace crane_twin_test {

template <typename M, typename F>
ros::Subscriber subscribe(ros::NodeHandle& nh, const std::string& topic, int queue, F f) {
  return nh.subscribe<M>(topic, queue, boost::function<void(const typename M::ConstPtr&)>(f));
}

}  // namespace crane_twin_test
