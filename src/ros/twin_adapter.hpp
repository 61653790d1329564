// The twin's ROS side (docs/twin.md), owned by crane_sim_node: measured joints, payload and
// tension in; the estimate, the forecast and diagnostics out. The estimator, the joint follower
// and the forecaster are the ROS-free core's (include/crane_twin/twin, drives); this class only
// converts messages, queues them for the node's thread and calls the core between steps.
#pragma once

#include <diagnostic_msgs/DiagnosticStatus.h>
#include <geometry_msgs/PointStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Float64.h>

#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "crane_twin/drives/measured_joint_follower.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/twin/payload_forecast.hpp"
#include "crane_twin/twin/sway_estimator.hpp"
#include "crane_twin/twin/timed_input_queue.hpp"
#include "crane_twin/twin/twin_runtime.hpp"
#include "ros_messages.hpp"

namespace crane_twin {

/// Parameters (private namespace of crane_sim_node; docs/twin.md has the table).
struct TwinSettings {
  bool measured_input = false;  ///< ~input: commands | measured
  JointFollowerSettings follower;
  SwayEstimatorSettings estimator;
  double payload_timeout = 2.0;  ///< [s] without a payload measurement: open loop
  /// [s] how far behind real time the twin races to catch up, holding the crane's
  /// measurements until it reaches their times (TimedInputQueue, Pacer's catch_up)
  double catch_up = 5.0;
  double forecast_horizon = 30.0;       ///< [s]
  double forecast_rate = 1.0;           ///< [Hz of wall time], 0: no forecast
  double forecast_time_step = 0.01;     ///< [s], 0: the scene's
  double forecast_sample_period = 0.5;  ///< [s] between the path's poses
};

/// Read and check them. Throws InputError naming the parameter.
TwinSettings readTwinSettings(const ros::NodeHandle& pnh);

class TwinAdapter {
 public:
  /// `base_position`, `base_yaw`: the crane's base in the world (measurements may come in
  /// either frame). Subscribes crane/measured_joint_states, crane/measured_payload,
  /// crane/measured_tension; advertises crane/payload_estimate and crane/forecast.
  TwinAdapter(ros::NodeHandle nh, const TwinSettings& settings, const CraneFrames& frames,
              const Eigen::Vector3d& base_position, double base_yaw);
  /// Cancels a running forecast (its job then ends after its current step, not its horizon).
  ~TwinAdapter();
  TwinAdapter(const TwinAdapter&) = delete;
  TwinAdapter& operator=(const TwinAdapter&) = delete;
  /// A new simulation `sim` of `model` started (reset, new load): the estimator back to its
  /// prior with the structure modes it sees at the start, the forecaster rebuilt for the model.
  /// Throws InputError for a forecast the model cannot run.
  void restart(const CraneModel& model, const Simulation& sim);
  /// The twin's load changed in the running simulation (the load cell found the lifted mass):
  /// the runtime reads tensions against it and the forecaster is rebuilt for it.
  void loadChanged(const CraneModel& model);
  /// A payload mass [kg] the load cell found for the lifted load, once (TwinRuntime); only a
  /// twin that follows the measured joints (~input: measured) takes it.
  std::optional<double> takePayloadMass() {
    const std::optional<double> m = runtime_.takePayloadMass();
    return settings_.measured_input ? m : std::nullopt;
  }
  /// Landed as the load cell sees it (empty before a measured tension arrived).
  std::optional<bool> loadCellLanded() const {
    if (!runtime_.loadCell().started()) return std::nullopt;
    return runtime_.loadCell().landed();
  }
  bool measuredInput() const { return settings_.measured_input; }
  /// The rate command that follows the measured joints (measured input), at twin time t.
  CommandEntry followCommand(const Simulation& sim) const;
  /// After a step of h seconds: the covariance propagated, the measurements the twin's time
  /// has reached applied (joint samples to the follower, payload positions through the
  /// estimator into `sim`, tensions to the load cell). `time_of` maps a ROS time to twin time:
  /// a measurement counts at its stamp (latency compensated), a tension or a measurement
  /// without a stamp at its arrival; one the twin has not reached yet waits
  /// (TimedInputQueue).
  void afterStep(Simulation& sim, double h, const std::function<double(const ros::Time&)>& time_of);
  /// Estimate at each publication; a forecast when one is due (`forecast_command`: what the
  /// drives will be asked, a held rate or a trajectory). `stamp_of` maps twin time to stamps.
  void publish(const Simulation& sim, const ros::Time& stamp,
               const PayloadForecaster::CommandSource& forecast_command,
               const std::function<ros::Time(double)>& stamp_of);
  /// Key values and a level for the node's diagnostics.
  void diagnose(const Simulation& sim, diagnostic_msgs::DiagnosticStatus& d) const;
  /// The measured-joint follower's rates as a held command (the forecast in measured mode).
  CommandEntry measuredRates(double t) const;

 private:
  void onJoints(const sensor_msgs::JointState::ConstPtr& m);
  void onPayload(const geometry_msgs::PointStamped::ConstPtr& m);
  void onTension(const std_msgs::Float64::ConstPtr& m);
  /// A joint sample taken at twin time t to the follower (a warning for an incomplete one).
  void takeJoints(const sensor_msgs::JointState& m, double t);
  void warn(const std::string& what);

  ros::NodeHandle nh_;
  TwinSettings settings_;
  CraneFrames frames_;
  Eigen::Vector3d base_position_;
  double base_yaw_ = 0.0;
  const CraneDescription* crane_ = nullptr;  ///< of the current model (none: crane: none)
  TwinRuntime runtime_;  ///< the follower, the estimator and the filters (ROS-free)
  /// Shared with the forecast job that runs on it (a rebuilt forecaster leaves the old one to
  /// its job).
  std::shared_ptr<PayloadForecaster> forecaster_;
  std::string forecast_error_;
  /// The forecaster for `model` (none with ~forecast_rate 0, or a model that cannot forecast).
  void rebuildForecaster(const CraneModel& model);

  /// Measurements with the ROS time they were taken (stamp, else arrival) until the twin's
  /// time reaches it.
  /// Each holds 10 s at 100 Hz, twice the default catch-up at the fastest rate docs/twin.md
  /// names; beyond, the oldest is dropped (diagnostics `measurements_dropped`).
  TimedInputQueue<sensor_msgs::JointState> joints_in_{1000};
  TimedInputQueue<std::pair<ros::Time, Eigen::Vector3d>> payload_in_{1000};  ///< base frame
  TimedInputQueue<std::pair<ros::Time, double>> tension_in_{1000};           ///< [N]
  ros::Subscriber joint_sub_, payload_sub_, tension_sub_;
  ros::Publisher estimate_pub_, forecast_pub_;

  ros::WallTime last_forecast_wall_, last_warn_wall_;
  PayloadForecast last_forecast_;
  /// The forecast running on its own thread (the node's steps go on meanwhile).
  std::future<PayloadForecast> forecast_job_;
  /// Jobs of forecasters replaced while they ran (a new load): cancelled, never waited for on
  /// the twin's thread, their forecasts dropped.
  std::vector<std::future<PayloadForecast>> retired_jobs_;
  void dropFinishedRetiredJobs();
  void collectForecast(const std::function<ros::Time(double)>& stamp_of);
};

}  // namespace crane_twin
