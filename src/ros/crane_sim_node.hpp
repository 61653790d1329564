// crane_sim_node (docs/ros.md): a thin ROS 1 adapter over the ROS-free simulation. It owns one
// Simulation, paces it (Pacer: real_time_factor, lockstep, another node's /clock), lets
// CommandInputs drive it (commands, trajectories, wind, a replayed bag) or the twin follow the
// measured crane (TwinAdapter), and publishes what snapshotOf() computes, with the usage count
// (UsageLink). Nothing here is physics.
#pragma once

#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "command_inputs.hpp"
#include "crane_twin/SetPayload.h"
#include "crane_twin/analysis/crane_snapshot.hpp"
#include "crane_twin/analysis/structure_group_poses.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/lift_off_monitor.hpp"
#include "crane_twin/simulation/pacer.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/step_tension_peak.hpp"
#include "node_settings.hpp"
#include "recorder_link.hpp"
#include "ros_messages.hpp"
#include "state_publisher.hpp"
#include "twin_adapter.hpp"
#include "usage_link.hpp"

namespace crane_twin {

class CraneSimNode {
 public:
  /// Builds the model and the simulation. Throws InputError (bad scene or parameter).
  CraneSimNode(ros::NodeHandle nh, ros::NodeHandle pnh, NodeSettings settings);
  /// Spin, step and publish until ROS shuts down (or the end with shutdown_at_end).
  void run();
  /// The run reached its end (not a failure, not a shutdown from outside).
  bool finishedNormally() const { return finished_ && !failed_; }

 private:
  ros::NodeHandle nh_, pnh_;
  NodeSettings settings_;
  CraneModel model_;
  std::unique_ptr<Simulation> sim_;
  /// The structure groups' poses for sim_'s support (set up with each new simulation).
  std::unique_ptr<StructureGroupPoses> group_poses_;
  std::unique_ptr<CommandInputs> inputs_;  ///< commands, trajectories, wind, replay
  std::vector<ros::Subscriber> follower_subs_;
  std::vector<double> follower_t_;  ///< latest simulated time of each clock follower [s]
  CraneState last_state_;           ///< the last crane/state published
  LiftOffMonitor lift_off_;         ///< lift-offs and their dynamic factor (crane/state)
  StepTensionPeak tension_peak_;    ///< the steps' top tension peak between publications
  /// What the run has cost the crane (crane/usage and its diagnostic status, 1 Hz).
  std::unique_ptr<UsageLink> usage_;
  /// While paused under simulated time: TF stamps step by 1 ns a publication past the frozen
  /// clock (tf2 drops a transform whose stamp repeats).
  ros::Duration tf_stamp_offset_;
  ros::WallTime last_paused_publish_;
  void publishPaused();
  /// Publish at once and start the next publication period (after ~reset, ~set_payload).
  void publishNow();
  ros::WallTime last_state_wall_;        ///< when it was last (re)published
  ros::WallTime last_clock_wall_;        ///< when /clock was last repeated while waiting (lockstep)
  std::unique_ptr<StatePublisher> out_;  ///< joints, TF, markers, crane/state, /clock
  ros::Publisher diag_pub_;
  ros::ServiceServer reset_srv_, pause_srv_, payload_srv_;
  /// Simulated time before the current simulation started [s] (a load change runs time on).
  double t_offset_ = 0.0;
  bool onSetPayload(SetPayload::Request& req, SetPayload::Response& res);
  /// A new simulation of model_ from t_offset_ on, keeping the stamps' origin.
  void restartSimulation(CommandInputs::Start start);
  /// The twin takes the payload mass its load cell found: the running simulation continues
  /// with it (withPayloadMass, continueWithModel; docs/twin.md "Picks and set-downs").
  void takeMeasuredPayload(double mass);
  std::unique_ptr<TwinAdapter> twin_;
  /// What the forecast assumes the drives are asked: the measured rates, the trajectory being
  /// followed, or the operator's command held.
  PayloadForecaster::CommandSource forecastCommand() const;
  CraneFrames frames_;

  bool paused_ = false, finished_ = false, failed_ = false;
  std::unique_ptr<RecorderLink> recorder_;  ///< the recording's start, pace and end
  std::string failure_;
  ros::Time stamp_origin_;
  double next_publish_ = 0.0;
  // Cost accounting since the last published state.
  double step_seconds_ = 0.0;
  long steps_since_publish_ = 0;
  double last_publish_sim_ = 0.0;
  ros::WallTime last_publish_wall_;
  double last_step_cost_ = 0.0, last_rtf_ = 0.0;
  long steps_ = 0;
  std::unique_ptr<Pacer> pacer_;  ///< when the loop may step (run())
  int warnings_seen_ = 0;
  double last_wind_3s_ = 0.0;  ///< 3 s mean wind at the jib in the last publication [m/s]
  ros::WallTime last_warn_wall_, last_diag_wall_;

  void resetSimulation();
  bool stepOnce();
  void publish();
  void publishDiagnostics();
  ros::Time stamp(double t) const;
  bool onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res);
  bool onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
};

}  // namespace crane_twin
