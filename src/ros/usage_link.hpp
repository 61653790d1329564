// UsageLink: crane_sim_node's usage count (docs/fatigue.md "Usage", docs/ros.md "Usage"). It
// counts the published states (UsageCounter), publishes crane/usage (latched) with the node's
// diagnostics, adds a diagnostic status that WARNs when a hot spot's damage rate projects less
// life than the crane file's design_hours, and, with ~usage_file, keeps the count in that file
// (read at start, written every ~usage_save_period s of wall time, at ~reset and at shutdown),
// so that it outlives the node.
#pragma once

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>

#include <memory>
#include <string>

#include "crane_twin/analysis/usage_counter.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/lift_off_monitor.hpp"
#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

struct UsageSettings {
  std::string file;           ///< ~usage_file: "" counts since the start or ~reset
  double save_period = 10.0;  ///< ~usage_save_period [s of wall time] (> 0)
};

class UsageLink {
 public:
  /// Reads `settings.file` when it exists. Throws InputError naming the file when it cannot be
  /// read or counted other hot spots than `model`'s crane file names.
  UsageLink(ros::NodeHandle nh, UsageSettings settings, const CraneModel& model);
  /// Writes the file (a failure is logged, not thrown).
  ~UsageLink();
  /// A new simulation from t = 0 (~reset): without a file the count starts again, with one it
  /// goes on (the crane's life does not restart with its twin).
  void restart(const CraneModel& model);
  /// One published state (row) after `lift_off` saw it; `time_offset` as UsageCounter's.
  void observe(const SeriesValues& row, const LiftOffMonitor& lift_off, double time_offset);
  /// One time step's hot-spot stresses (UsageCounter::observeStep).
  void observeStep(const Eigen::VectorXd& stresses) { counter_->observeStep(stresses); }
  void setPayloadMass(double mass) { counter_->setPayloadMass(mass); }
  /// Publish crane/usage stamped `stamp`, append the usage status (named after `node_name`) to
  /// `diagnostics`, and write the file when its period is up.
  void publish(const ros::Time& stamp, const std::string& node_name,
               diagnostic_msgs::DiagnosticArray& diagnostics);

 private:
  void save();
  UsageSettings settings_;
  std::unique_ptr<UsageCounter> counter_;
  ros::Publisher pub_;
  ros::WallTime last_save_;
};

}  // namespace crane_twin
