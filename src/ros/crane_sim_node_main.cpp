// crane_sim_node: the ROS 1 entry point (docs/ros.md). Bad parameters or scene: a message naming
// what is wrong and exit status 2, like crane_sim.
#include <ros/master.h>
#include <ros/ros.h>
#include <signal.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <string>

#include "crane_sim_node.hpp"
#include "crane_twin/io/config_reader.hpp"

namespace {

// True when the parent process is a roslaunch that runs the launch file itself (not a remote
// machine's `roslaunch --child` server, not rostest).
bool startedByRoslaunch() {
  std::ifstream in("/proc/" + std::to_string(getppid()) + "/cmdline", std::ios::binary);
  const std::string cmd((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::string> args;
  size_t start = 0;
  for (size_t i = 0; i <= cmd.size(); ++i)
    if (i == cmd.size() || cmd[i] == '\0') {
      if (i > start) args.push_back(cmd.substr(start, i - start));
      start = i + 1;
    }
  bool roslaunch = false;
  for (size_t i = 0; i < args.size() && i < 2; ++i) {
    const std::string& a = args[i];
    roslaunch |=
        a == "roslaunch" || (a.size() > 10 && a.compare(a.size() - 10, 10, "/roslaunch") == 0);
  }
  for (const std::string& a : args) roslaunch &= a != "--child";
  return roslaunch;
}

// The scene ended and the launch should end with it: ask roslaunch to shut down as Ctrl-C
// would (SIGINT), then wait for it to stop this node. Exiting first would make roslaunch report
// "REQUIRED process has died" for a normal end.
void endTheLaunch() {
  if (!startedByRoslaunch()) return;
  ROS_INFO("crane_sim_node: the scene ended (shutdown_at_end): stopping the launch");
  if (kill(getppid(), SIGINT) != 0) return;
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && ros::WallTime::now() < until) ros::WallDuration(0.05).sleep();
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "crane_sim_node");
  ros::NodeHandle nh, pnh("~");
  try {
    const crane_twin::NodeSettings settings = crane_twin::readNodeSettings(pnh);
    crane_twin::CraneSimNode node(nh, pnh, settings);
    node.run();
    // The clock this node owned stops with it: later nodes on this master must not wait for it.
    if (settings.publish_clock && ros::master::check()) ros::param::set("/use_sim_time", false);
    if (settings.shutdown_at_end && node.finishedNormally()) endTheLaunch();
  } catch (const crane_twin::InputError& e) {
    ROS_FATAL("crane_sim_node: %s", e.what());
    return 2;
  } catch (const std::exception& e) {
    ROS_FATAL("crane_sim_node: %s", e.what());
    return 1;
  }
  return 0;
}
