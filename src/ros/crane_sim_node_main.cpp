// crane_sim_node: the ROS 1 entry point (docs/ros.md). Bad parameters or scene: a message naming
// what is wrong and exit status 2, like crane_sim.
#include <ros/ros.h>

#include "crane_sim_node.hpp"
#include "crane_twin/io/config_reader.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "crane_sim_node");
  ros::NodeHandle nh, pnh("~");
  try {
    crane_twin::CraneSimNode node(nh, pnh, crane_twin::readNodeSettings(pnh));
    node.run();
  } catch (const crane_twin::InputError& e) {
    ROS_FATAL("crane_sim_node: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("crane_sim_node: %s", e.what());
    return 1;
  }
  return 0;
}
