#include "twin_adapter.hpp"

#include <geometry_msgs/PoseWithCovarianceStamped.h>
#include <nav_msgs/Path.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "crane_twin/io/input_error.hpp"
#include "node_params.hpp"

namespace crane_twin {

TwinSettings readTwinSettings(const ros::NodeHandle& pnh) {
  TwinSettings s;
  std::string input = "commands";
  optionalParam(pnh, "input", input, "'commands' or 'measured'");
  if (input != "commands" && input != "measured") {
    throw InputError("parameter '~input' '" + input + "' must be 'commands' or 'measured'");
  }
  s.measured_input = input == "measured";
  optionalParam(pnh, "follow_gain", s.follower.gain, "a number");
  optionalParam(pnh, "joint_extrapolation", s.follower.max_extrapolation, "a number");
  optionalParam(pnh, "joint_stale_after", s.follower.stale_after, "a number");
  optionalParam(pnh, "joint_tracking_bandwidth", s.follower.tracking_bandwidth, "a number");
  optionalParam(pnh, "payload_noise", s.estimator.measurement_noise, "a number");
  optionalParam(pnh, "sway_process_noise", s.estimator.process_noise, "a number");
  optionalParam(pnh, "initial_sway_sigma", s.estimator.initial_position_sigma, "a number");
  optionalParam(pnh, "initial_sway_rate_sigma", s.estimator.initial_velocity_sigma, "a number");
  optionalParam(pnh, "innovation_gate", s.estimator.gate, "a number");
  optionalParam(pnh, "payload_timeout", s.payload_timeout, "a number");
  optionalParam(pnh, "twin_catch_up", s.catch_up, "a number");
  optionalParam(pnh, "forecast_horizon", s.forecast_horizon, "a number");
  optionalParam(pnh, "forecast_rate", s.forecast_rate, "a number");
  optionalParam(pnh, "forecast_time_step", s.forecast_time_step, "a number");
  optionalParam(pnh, "forecast_sample_period", s.forecast_sample_period, "a number");
  requireFinite("follow_gain", s.follower.gain, 0.0, true);
  requireFinite("joint_extrapolation", s.follower.max_extrapolation, 0.0, true);
  requireFinite("joint_stale_after", s.follower.stale_after, 0.0, true);
  requireFinite("joint_tracking_bandwidth", s.follower.tracking_bandwidth, 0.0, true);
  requireFinite("payload_noise", s.estimator.measurement_noise, 0.0, true);
  requireFinite("sway_process_noise", s.estimator.process_noise, 0.0, true);
  requireFinite("initial_sway_sigma", s.estimator.initial_position_sigma, 0.0, true);
  requireFinite("initial_sway_rate_sigma", s.estimator.initial_velocity_sigma, 0.0, true);
  requireFinite("innovation_gate", s.estimator.gate, 0.0, true);
  requireFinite("payload_timeout", s.payload_timeout, 0.0, true);
  requireFinite("twin_catch_up", s.catch_up, 0.0, false);
  requireFinite("forecast_horizon", s.forecast_horizon, 0.0, true);
  requireFinite("forecast_rate", s.forecast_rate, 0.0, false);
  requireFinite("forecast_time_step", s.forecast_time_step, 0.0, false);
  requireFinite("forecast_sample_period", s.forecast_sample_period, 0.0, true);
  return s;
}

TwinAdapter::TwinAdapter(ros::NodeHandle nh, const TwinSettings& settings,
                         const CraneFrames& frames, const Eigen::Vector3d& base_position,
                         double base_yaw)
    : nh_(nh),
      settings_(settings),
      frames_(frames),
      base_position_(base_position),
      base_yaw_(base_yaw),
      runtime_(settings.estimator, settings.follower) {
  joint_sub_ = nh_.subscribe("crane/measured_joint_states", 200, &TwinAdapter::onJoints, this);
  payload_sub_ = nh_.subscribe("crane/measured_payload", 50, &TwinAdapter::onPayload, this);
  tension_sub_ = nh_.subscribe("crane/measured_tension", 50, &TwinAdapter::onTension, this);
  estimate_pub_ =
      nh_.advertise<geometry_msgs::PoseWithCovarianceStamped>("crane/payload_estimate", 50);
  forecast_pub_ = nh_.advertise<nav_msgs::Path>("crane/forecast", 5, true);
}

void TwinAdapter::restart(const CraneModel& model, const Simulation& sim) {
  crane_ = model.scene.crane ? &*model.scene.crane : nullptr;
  runtime_.restart(model, sim);
  joints_in_.clear();
  payload_in_.clear();
  tension_in_.clear();
  rebuildForecaster(model);
  if (settings_.measured_input && !crane_) {
    throw InputError("parameter '~input' 'measured' needs a scene with a crane");
  }
}

void TwinAdapter::loadChanged(const CraneModel& model) {
  crane_ = model.scene.crane ? &*model.scene.crane : nullptr;
  runtime_.loadChanged(model);
  rebuildForecaster(model);
}

TwinAdapter::~TwinAdapter() {
  if (forecaster_) forecaster_->cancel();
}

void TwinAdapter::rebuildForecaster(const CraneModel& model) {
  // A running forecast keeps the old forecaster (its job holds it), cancelled: its forecast is
  // for the old load and dropped.
  dropFinishedRetiredJobs();
  if (forecast_job_.valid()) {
    if (forecaster_) forecaster_->cancel();
    retired_jobs_.push_back(std::move(forecast_job_));
  }
  forecast_job_ = {};
  last_forecast_ = PayloadForecast{};
  forecaster_.reset();
  forecast_error_.clear();
  if (settings_.forecast_rate > 0.0) {
    try {
      forecaster_ = std::make_shared<PayloadForecaster>(model, settings_.forecast_time_step);
    } catch (const InputError& e) {  // a rope model that cannot continue another run's state
      forecast_error_ = std::string("no forecast: ") + e.what();
      ROS_WARN("crane_sim_node (twin): %s", forecast_error_.c_str());
    }
  }
}

void TwinAdapter::warn(const std::string& what) {
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_warn_wall_).toSec() < 2.0) return;
  last_warn_wall_ = now;
  ROS_WARN("crane_sim_node (twin): %s", what.c_str());
}

void TwinAdapter::onJoints(const sensor_msgs::JointState::ConstPtr& m) {
  if (!settings_.measured_input) return;
  sensor_msgs::JointState j = *m;
  if (j.header.stamp.isZero()) j.header.stamp = ros::Time::now();  // on arrival
  joints_in_.push(std::move(j));
}

void TwinAdapter::onPayload(const geometry_msgs::PointStamped::ConstPtr& m) {
  const Eigen::Vector3d p = fromMsg(m->point);
  const std::string& f = m->header.frame_id;
  Eigen::Vector3d base;
  if (f.empty() || f == frames_.base()) {
    base = p;
  } else if (f == "world") {
    base = Eigen::AngleAxisd(-base_yaw_, Eigen::Vector3d::UnitZ()) * (p - base_position_);
  } else {
    runtime_.countRefusedPayload();
    return warn("crane/measured_payload in frame '" + f + "' refused: give 'world' or '" +
                frames_.base() + "'");
  }
  if (!base.allFinite()) {
    runtime_.countRefusedPayload();
    return warn("crane/measured_payload with a non-finite coordinate refused");
  }
  payload_in_.push({m->header.stamp.isZero() ? ros::Time::now() : m->header.stamp, base});
}

void TwinAdapter::onTension(const std_msgs::Float64::ConstPtr& m) {
  if (!std::isfinite(m->data) || m->data < 0.0) {
    return warn("crane/measured_tension must be a finite force >= 0 N, got " +
                std::to_string(m->data));
  }
  tension_in_.push({ros::Time::now(), m->data});  // no stamp of its own: on arrival
}

CommandEntry TwinAdapter::followCommand(const Simulation& sim) const {
  return runtime_.follower().command(sim.time(), sim.drives(), *crane_);
}

CommandEntry TwinAdapter::measuredRates(double t) const {
  const Eigen::Vector3d r = runtime_.follower().holdRates(t);
  CommandEntry c;
  c.slew_rate = r.x();
  c.trolley_speed = r.y();
  c.hoist_speed = r.z();
  return c;
}

void TwinAdapter::takeJoints(const sensor_msgs::JointState& m, double t) {
  if (!crane_) return;
  JointSample s;
  s.t = t;
  const char* names[3] = {"slew", "trolley", "hoist"};
  const bool velocities = m.velocity.size() == m.name.size();
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a) {
    int i = -1;
    for (std::size_t k = 0; k < m.name.size(); ++k)
      if (m.name[k] == names[a]) i = static_cast<int>(k);
    if (i < 0 || i >= static_cast<int>(m.position.size())) {
      return warn("crane/measured_joint_states needs positions of slew, trolley and hoist");
    }
    s.position[a] = m.position[i];
    if (velocities) v[a] = m.velocity[i];
  }
  if (velocities) s.velocity = v;
  const std::string why = runtime_.addJoints(s);
  if (!why.empty()) warn("crane/measured_joint_states refused: " + why);
}

void TwinAdapter::afterStep(Simulation& sim, double h,
                            const std::function<double(const ros::Time&)>& time_of) {
  const double now = sim.time(), horizon = settings_.catch_up;
  // Each measurement at the twin time it was taken, once the twin has reached it
  // (TimedInputQueue: a stamp further ahead than the catch-up, clocks apart, counts as now).
  joints_in_.release(
      now, horizon, [&](const sensor_msgs::JointState& m) { return time_of(m.header.stamp); },
      [&](const sensor_msgs::JointState& m, double at) { takeJoints(m, at); });
  payload_in_.release(
      now, horizon, [&](const auto& p) { return time_of(p.first); },
      [&](const auto& p, double at) { runtime_.addPayload(at, p.second); });
  tension_in_.release(
      now, horizon, [&](const auto& p) { return time_of(p.first); },
      [&](const auto& p, double) { runtime_.addTension(p.second); });
  runtime_.afterStep(sim, h, [this](const std::string& what) { warn(what); });
}

void TwinAdapter::publish(const Simulation& sim, const ros::Time& stamp,
                          const PayloadForecaster::CommandSource& forecast_command,
                          const std::function<ros::Time(double)>& stamp_of) {
  const SeriesValues row = sim.series();
  geometry_msgs::PoseWithCovarianceStamped e;
  e.header.stamp = stamp;
  e.header.frame_id = frames_.base();
  e.pose.pose.position = point(row.payload);
  e.pose.pose.orientation.w = 1.0;
  // The payload's horizontal covariance H P H^T (the filter's, propagated to now); row-major
  // 6 x 6 (x, y, z, rot x, rot y, rot z): the vertical position is not estimated (the
  // measurement noise stands in), nor the rotation.
  const Eigen::Matrix2d C = runtime_.payloadCovariance(sim, row);
  e.pose.covariance[0] = C(0, 0);
  e.pose.covariance[1] = C(0, 1);
  e.pose.covariance[6] = C(1, 0);
  e.pose.covariance[7] = C(1, 1);
  e.pose.covariance[14] = std::pow(settings_.estimator.measurement_noise, 2);
  e.pose.covariance[21] = e.pose.covariance[28] = e.pose.covariance[35] = 1e6;
  estimate_pub_.publish(e);

  dropFinishedRetiredJobs();
  if (!forecaster_) return;
  if (forecast_job_.valid()) {
    if (forecast_job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
    collectForecast(stamp_of);
  }
  const ros::WallTime now = ros::WallTime::now();
  if (!last_forecast_wall_.isZero() &&
      (now - last_forecast_wall_).toSec() < 1.0 / settings_.forecast_rate) {
    return;
  }
  last_forecast_wall_ = now;
  try {
    forecaster_->prepare(sim);  // the twin's state, copied on this thread
  } catch (const std::exception& ex) {
    forecast_error_ = ex.what();
    return warn(std::string("forecast failed: ") + ex.what());
  }
  std::shared_ptr<PayloadForecaster> f = forecaster_;
  const double horizon = settings_.forecast_horizon, period = settings_.forecast_sample_period;
  forecast_job_ = std::async(std::launch::async, [f, forecast_command, horizon, period]() {
    return f->runPrepared(forecast_command, horizon, period);
  });
}

void TwinAdapter::dropFinishedRetiredJobs() {
  retired_jobs_.erase(std::remove_if(retired_jobs_.begin(), retired_jobs_.end(),
                                     [](std::future<PayloadForecast>& j) {
                                       return j.wait_for(std::chrono::seconds(0)) ==
                                              std::future_status::ready;
                                     }),
                      retired_jobs_.end());
}

void TwinAdapter::collectForecast(const std::function<ros::Time(double)>& stamp_of) {
  try {
    last_forecast_ = forecast_job_.get();
    forecast_error_ = last_forecast_.failed ? "the forecast run failed numerically" : "";
  } catch (const std::exception& ex) {
    forecast_error_ = ex.what();
    return warn(std::string("forecast failed: ") + ex.what());
  }
  nav_msgs::Path path;
  path.header.stamp = stamp_of(last_forecast_.t0);
  path.header.frame_id = "world";
  const Eigen::AngleAxisd yaw(base_yaw_, Eigen::Vector3d::UnitZ());
  for (std::size_t i = 0; i < last_forecast_.t.size(); ++i) {
    geometry_msgs::PoseStamped ps;
    ps.header.frame_id = "world";
    ps.header.stamp = stamp_of(last_forecast_.t[i]);
    ps.pose.position = point(base_position_ + yaw * last_forecast_.payload[i]);
    ps.pose.orientation.w = 1.0;
    path.poses.push_back(ps);
  }
  forecast_pub_.publish(path);
}

void TwinAdapter::diagnose(const Simulation& sim, diagnostic_msgs::DiagnosticStatus& d) const {
  auto warn_level = [&d](const std::string& why) {
    if (d.level < diagnostic_msgs::DiagnosticStatus::WARN) {
      d.level = diagnostic_msgs::DiagnosticStatus::WARN;
      d.message = why;
    } else {
      d.message += "; " + why;
    }
  };
  const double t = sim.time();
  addKeyValue(d, "input", settings_.measured_input ? "measured" : "commands");
  if (settings_.measured_input) {
    const MeasuredJointFollower& follower = runtime_.follower();
    addNumber(d, "joint_input_age_s", follower.age(t));
    addKeyValue(d, "joint_input",
                !follower.hasSample() ? "none yet"
                : follower.stale(t)   ? "stale"
                                      : "fresh");
    addNumber(d, "joint_samples_refused", static_cast<double>(follower.refused()));
    if (follower.stale(t)) warn_level("measured joint input stale or missing");
    // Measurements that did not fit the queue while the twin caught up (TimedInputQueue).
    const long dropped = joints_in_.dropped() + payload_in_.dropped() + tension_in_.dropped();
    addNumber(d, "measurements_dropped", static_cast<double>(dropped));
    addNumber(d, "measurements_waiting",
              static_cast<double>(joints_in_.size() + payload_in_.size() + tension_in_.size()));
  }
  const bool closed = t - runtime_.lastPayloadTime() <= settings_.payload_timeout;
  addKeyValue(d, "sway_estimator",
              closed ? "closed loop (payload measurements)" : "open loop (no payload measurement)");
  addNumber(d, "sway_uncertainty_m", runtime_.estimator().positionSigma());
  addNumber(d, "structure_modes_estimated", static_cast<double>(runtime_.modes().size()));
  addNumber(d, "innovation_m", runtime_.lastUpdate().innovation.norm());
  addNumber(d, "normalized_innovation", runtime_.lastUpdate().normalized);
  addNumber(d, "payload_updates", static_cast<double>(runtime_.payloadUpdates()));
  addNumber(d, "payload_measurements_refused", static_cast<double>(runtime_.payloadRefused()));
  addNumber(d, "payload_measurements_on_ground", static_cast<double>(runtime_.payloadOnGround()));
  addNumber(d, "sway_corrections_failed", static_cast<double>(runtime_.correctionFailures()));
  if (runtime_.tensionSeen()) {
    addNumber(d, "tension_ratio_measured_to_twin", runtime_.tensionRatio());
    // The load cell's last window after a lift-off (docs/twin.md "Picks and set-downs").
    addNumber(d, "payload_mass_estimate_kg", runtime_.payloadMassEstimate());
    addKeyValue(d, "load_cell", runtime_.loadCell().landed() ? "landed" : "hanging");
    addNumber(d, "load_cell_lifts", runtime_.loadCell().lifts());
    addNumber(d, "load_cell_set_downs", runtime_.loadCell().setDowns());
    if (std::abs(runtime_.tensionRatio() - 1.0) > 0.05) {
      warn_level("measured tension differs from the twin's by more than 5 % (~set_payload?)");
    }
  }
  if (!forecast_error_.empty()) addKeyValue(d, "forecast_error", forecast_error_);
  if (forecaster_) {
    addNumber(d, "forecast_horizon_s", settings_.forecast_horizon);
    addNumber(d, "forecast_cost_s", last_forecast_.wall_seconds);
    addNumber(d, "forecast_cost_fraction",
              last_forecast_.wall_seconds / settings_.forecast_horizon);
    addNumber(d, "forecast_max_swing_m", last_forecast_.max_swing);
    addNumber(d, "forecast_max_swing_at_s", last_forecast_.max_swing_time);
  }
}

}  // namespace crane_twin
