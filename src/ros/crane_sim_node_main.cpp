// crane_sim_node: the ROS 1 entry point (docs/ros.md). Bad parameters or scene: a message naming
// what is wrong and exit status 2, like crane_sim.
#include <ros/master.h>
#include <ros/ros.h>

#include "crane_sim_node.hpp"
#include "crane_twin/io/config_reader.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "crane_sim_node");
  ros::NodeHandle nh, pnh("~");
  try {
    const crane_twin::NodeSettings settings = crane_twin::readNodeSettings(pnh);
    crane_twin::CraneSimNode node(nh, pnh, settings);
    node.run();
    // The clock this node owned stops with it: later nodes on this master must not wait for it.
    if (settings.publish_clock && ros::master::check()) ros::param::set("/use_sim_time", false);
  } catch (const crane_twin::InputError& e) {
    ROS_FATAL("crane_sim_node: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("crane_sim_node: %s", e.what());
    return 1;
  }
  return 0;
}
