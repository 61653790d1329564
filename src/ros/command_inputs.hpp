// CommandInputs: what drives crane_sim_node's crane (docs/ros.md "Commands"): rate commands on
// crane/command (checked by command_guard, timed out by CommandWatchdog), trajectories on
// crane/joint_trajectory (TrajectoryFollower), an anemometer on crane/wind, or the commands of
// a recorded run replayed from ~command_bag. Every command applied is republished with its
// simulated time on crane/command_applied (what a replay reads back). A twin that follows
// measured joints (~input: measured) takes none of these; the node drives it.
#pragma once

#include <geometry_msgs/Vector3Stamped.h>
#include <ros/ros.h>
#include <trajectory_msgs/JointTrajectory.h>

#include <Eigen/Core>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "crane_twin/CraneCommand.h"
#include "crane_twin/drives/command_guard.hpp"
#include "crane_twin/drives/trajectory_follower.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/twin/payload_forecast.hpp"
#include "node_settings.hpp"

namespace crane_twin {

class CommandInputs {
 public:
  /// Subscribes and advertises in `nh`'s namespace; reads ~command_bag. Throws InputError for a
  /// bag without commands or with a command the scene refuses. `base_yaw` [rad]: the crane's
  /// frame turned about z on the site (the wind comes in the world's frame). `failure`: the
  /// node's reason the simulation stopped ("" while it runs), read as commands come (it must
  /// outlive this object): while it is set commands and trajectories are refused.
  CommandInputs(ros::NodeHandle nh, const NodeSettings& settings, const CraneModel& model,
                double base_yaw, const std::string& failure);
  enum class Start {
    kContinued,  ///< the same run continued by another simulation (the twin's new load)
    kRestarted,  ///< a new simulation where the crane stands (~set_payload): any trajectory
                 ///< cancelled, the watchdog anew, the measured wind re-applied
    kFromStart,  ///< back to t = 0 (~reset): as kRestarted, and the replay starts again
  };
  /// The simulation the inputs drive from now on, its model, and the simulated time before it
  /// started [s].
  void attach(Simulation& sim, const CraneModel& model, double t_offset, Start start);
  /// Before each step: the replayed commands now due, the trajectory's rates, a timeout's stop.
  void beforeStep();
  /// What a forecast assumes the drives are asked from now on (the trajectory being followed,
  /// else the command held).
  PayloadForecaster::CommandSource forecastCommand() const;
  /// Commands, trajectories and wind messages refused so far.
  long rejected() const { return rejected_; }
  /// The publisher of crane/command_applied (a recorder waits for its connection).
  const ros::Publisher& appliedPublisher() const { return applied_pub_; }
  /// A WARN at most every 2 s, with the count of refusals.
  void warnThrottled(const std::string& what);

 private:
  struct Replayed {
    double t;
    CommandEntry command;
  };
  void loadReplay(const CraneModel& model);
  void apply(const CommandEntry& c, const char* source);
  void onCommand(const CraneCommand::ConstPtr& msg);
  void onWind(const geometry_msgs::Vector3Stamped::ConstPtr& msg);
  void onTrajectory(const trajectory_msgs::JointTrajectory::ConstPtr& msg);
  void publishGoalReached(bool reached);

  const bool measured_input_;
  const std::string command_bag_;
  const double command_timeout_, base_yaw_;
  Simulation* sim_ = nullptr;
  const CraneModel* model_ = nullptr;
  double t_offset_ = 0.0;
  const std::string& failure_;  ///< the node's: non-empty while the simulation is stopped
  CommandWatchdog watchdog_;
  TrajectoryFollower follower_;
  std::deque<Replayed> replay_;  ///< commands still to apply, by simulated time
  std::vector<Replayed> replay_all_;
  std::optional<Eigen::Vector3d> measured_wind_;  ///< crane frame, re-applied after a restart
  long rejected_ = 0;
  ros::WallTime last_warn_wall_;
  ros::Subscriber command_sub_, trajectory_sub_, wind_sub_;
  ros::Publisher applied_pub_, goal_pub_;
};

}  // namespace crane_twin
