#include "crane_sim_node.hpp"

#include <diagnostic_msgs/DiagnosticArray.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/simulation/crane_warnings.hpp"
#include "node_status.hpp"
#include "ros_messages.hpp"

namespace crane_twin {

CraneSimNode::CraneSimNode(ros::NodeHandle nh, ros::NodeHandle pnh, NodeSettings settings)
    : nh_(nh),
      pnh_(pnh),
      settings_(std::move(settings)),
      model_(buildCraneModel(loadScene(settings_.scene, settings_.overrides))) {
  if (settings_.duration < 0.0) settings_.duration = model_.scene.duration;
  paused_ = settings_.start_paused;
  frames_.prefix = settings_.frame_prefix;
  const BasePose site = basePoseOf(settings_, model_.scene);  // world -> <prefix>base, latched
  if (settings_.twin.measured_input && !settings_.command_bag.empty()) {
    throw InputError("parameters '~input' 'measured' and '~command_bag' exclude each other");
  }
  twin_ = std::make_unique<TwinAdapter>(nh_, settings_.twin, frames_, site.position, site.yaw);
  inputs_ = std::make_unique<CommandInputs>(nh_, settings_, model_, site.yaw, failure_);
  usage_ = std::make_unique<UsageLink>(nh_, settings_.usage, model_);
  resetSimulation();
  recorder_ =
      std::make_unique<RecorderLink>(nh_, settings_.wait_for_recorder, settings_.recorded_topics);
  out_ = std::make_unique<StatePublisher>(nh_, settings_, frames_, site.position, site.yaw);
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 5);
  follower_t_.assign(settings_.clock_followers.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < settings_.clock_followers.size(); ++i) {
    follower_subs_.push_back(nh_.subscribe<CraneState>(
        settings_.clock_followers[i], 10,
        [this, i](const CraneState::ConstPtr& m) { follower_t_[i] = m->t; }));
  }
  reset_srv_ = pnh_.advertiseService("reset", &CraneSimNode::onReset, this);
  pause_srv_ = pnh_.advertiseService("pause", &CraneSimNode::onPause, this);
  payload_srv_ = pnh_.advertiseService("set_payload", &CraneSimNode::onSetPayload, this);
  const bool ancf = model_.scene.rope.model != RopeModel::pendulum;
  ROS_INFO(
      "crane_sim_node: scene %s, rope model %s%s%s, time step %g s, "
      "real_time_factor %g%s%s",
      settings_.scene.c_str(), name(model_.scene.rope.model), ancf ? ", rope elements " : "",
      ancf ? std::to_string(model_.scene.rope.elements).c_str() : "", model_.scene.time_step,
      settings_.real_time_factor, settings_.publish_clock ? ", publishing /clock" : "",
      settings_.command_bag.empty() ? "" : ", replaying commands from a bag");
}

void CraneSimNode::resetSimulation() {
  t_offset_ = 0.0;
  usage_->restart(model_);
  restartSimulation(CommandInputs::Start::kFromStart);
  stamp_origin_ =
      settings_.publish_clock || settings_.follow_clock ? ros::Time(0) : ros::Time::now();
}

void CraneSimNode::restartSimulation(CommandInputs::Start start) {
  sim_ = makeSimulation(model_);
  sim_->initialize();
  group_poses_ = std::make_unique<StructureGroupPoses>(sim_->support());
  lift_off_ = LiftOffMonitor();
  tension_peak_ = StepTensionPeak();
  inputs_->attach(*sim_, model_, t_offset_, start);
  twin_->restart(model_, *sim_);
  finished_ = failed_ = false;
  failure_.clear();
  next_publish_ = sim_->time();
  last_publish_sim_ = sim_->time();
  last_publish_wall_ = ros::WallTime::now();
  step_seconds_ = 0.0;
  steps_since_publish_ = 0;
}

ros::Time CraneSimNode::stamp(double t) const {
  return stamp_origin_ + ros::Duration(t_offset_ + t);
}

bool CraneSimNode::onReset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  // ~overrides and ~real_time_factor are read again (docs/ros.md); if they are bad the running
  // simulation goes on and the reply says why.
  NodeSettings fresh;
  try {
    fresh = readNodeSettings(pnh_);
    model_ = buildCraneModel(loadScene(fresh.scene, fresh.overrides));
  } catch (const std::exception& e) {
    res.success = false;
    res.message = std::string("reset refused, the run goes on: ") + e.what();
    return true;
  }
  settings_.overrides = fresh.overrides;
  settings_.real_time_factor = fresh.real_time_factor;
  if (fresh.duration < 0.0) settings_.duration = model_.scene.duration;
  try {
    resetSimulation();
    res.success = true;
    res.message = "simulation reset to t = 0";
  } catch (const std::exception& e) {
    failed_ = true;
    failure_ = e.what();
    res.success = false;
    res.message = std::string("reset failed: ") + e.what();
  }
  publishNow();
  return true;
}

bool CraneSimNode::onSetPayload(SetPayload::Request& req, SetPayload::Response& res) {
  res.success = false;
  if (!std::isfinite(req.mass) || req.mass < 0.0) {
    res.message = "mass must be a finite number of kg >= 0, got " + std::to_string(req.mass);
    return true;
  }
  if (!settings_.command_bag.empty()) {
    res.message = "refused while replaying a bag (the recorded run's load is part of it)";
    return true;
  }
  const CraneDrives& d = sim_->drives();
  if (d.slewRate() != 0.0 || d.trolleySpeed() != 0.0 || d.hoistSpeed() != 0.0) {
    res.message = "stop the drives first: a load is picked up at rest";
    return true;
  }
  // The new load hangs in static equilibrium where the crane stands (docs/ros.md): the same
  // model with another load, pose and initial state, its structure not rebuilt.
  try {
    CraneModel m = withPayloadPickedUp(model_, d, req.mass);
    const double t = t_offset_ + sim_->time();
    model_ = std::move(m);
    t_offset_ = t;
    restartSimulation(CommandInputs::Start::kRestarted);
  } catch (const std::exception& e) {
    res.message = std::string("refused: ") + e.what();
    return true;
  }
  usage_->setPayloadMass(req.mass);
  ROS_INFO("crane_sim_node: payload set to %g kg at t = %g s", req.mass, t_offset_);
  res.success = true;
  res.message = "payload " + std::to_string(req.mass) +
                " kg, in equilibrium at t = " + std::to_string(t_offset_) + " s";
  publishNow();
  return true;
}

void CraneSimNode::takeMeasuredPayload(double mass) {
  try {
    CraneModel m = withPayloadMass(model_, mass);
    std::unique_ptr<Simulation> next = continueWithModel(m, *sim_);
    const double from = model_.scene.payload_mass;
    model_ = std::move(m);
    sim_ = std::move(next);
    group_poses_ = std::make_unique<StructureGroupPoses>(sim_->support());
    inputs_->attach(*sim_, model_, t_offset_, CommandInputs::Start::kContinued);
    twin_->loadChanged(model_);
    usage_->setPayloadMass(mass);
    ROS_INFO("crane_sim_node (twin): the load cell finds %.0f kg lifted (was %.0f kg) at t = %g s",
             mass, from, t_offset_ + sim_->time());
  } catch (const std::exception& e) {  // a model that cannot continue with another load
    inputs_->warnThrottled(std::string("the load cell's payload mass not taken: ") + e.what());
  }
}

bool CraneSimNode::onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  paused_ = req.data;
  last_publish_wall_ = ros::WallTime::now();
  res.success = true;
  res.message = paused_ ? "paused" : "running";
  return true;
}

bool CraneSimNode::stepOnce() {
  if (settings_.twin.measured_input) {
    sim_->setCommand(twin_->followCommand(*sim_));
  } else {
    inputs_->beforeStep();
  }
  const auto t0 = std::chrono::steady_clock::now();
  try {
    sim_->step();
    tension_peak_.addStep(sim_->topTension());
    usage_->observeStep(sim_->hotSpotStresses());  // the stresses' crests between publications
    twin_->afterStep(*sim_, model_.scene.time_step, [this](const ros::Time& s) {
      return (s - stamp_origin_).toSec() - t_offset_;
    });
    if (const std::optional<double> m = twin_->takePayloadMass()) takeMeasuredPayload(*m);
  } catch (const std::exception& e) {  // NumericalFailure, or anything the model refuses
    failed_ = true;
    std::ostringstream s;
    s << "t = " << sim_->time() << " s: " << e.what();
    failure_ = s.str();
    ROS_ERROR("crane_sim_node: simulation stopped at %s; call ~reset to start again",
              failure_.c_str());
    return false;
  }
  step_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++steps_since_publish_;
  ++steps_;
  return true;
}

void CraneSimNode::publish() {
  const double t = sim_->time();
  const ros::Time st = stamp(t);
  const ros::WallTime now = ros::WallTime::now();
  if (steps_since_publish_ > 0) {
    last_step_cost_ = step_seconds_ / static_cast<double>(steps_since_publish_);
    const double wall = (now - last_publish_wall_).toSec();
    last_rtf_ = wall > 0.0 ? (t - last_publish_sim_) / wall : 0.0;
  }
  step_seconds_ = 0.0;
  steps_since_publish_ = 0;
  last_publish_sim_ = t;
  last_publish_wall_ = now;

  SnapshotOptions options = out_->optionsNow(now);
  options.group_poses = group_poses_.get();
  CraneSnapshot s = snapshotOf(*sim_, options);
  // A twin reading a load cell: landed as the load cell sees it, for crane/state, the lift-offs
  // and the usage (its own load may bounce where the real one does not; docs/twin.md).
  if (const std::optional<bool> landed = twin_->loadCellLanded()) {
    s.series.payload_landed = *landed;
  }
  // The steps' crests since the last publication: the lift-off factor and the tension warnings.
  const double peak = tension_peak_.takeAtRow(s.series.rope_top_tension);
  lift_off_.observe(s.series, staticTopTension(model_, s.series.rope_length), peak);
  addStepPeakTensionWarnings(model_, peak, s.series);
  usage_->observe(s.series, lift_off_, t_offset_);  // at the publication rate
  s.series.warnings |= lift_off_.warningFor(model_.scene.hoist_design_phi2);
  warnings_seen_ |= s.series.warnings;
  last_wind_3s_ = s.series.wind_3s;
  last_state_ = out_->stateMessage(s, st, last_step_cost_, last_rtf_, model_, t_offset_, lift_off_);
  out_->publish(s, last_state_, model_, st, tf_stamp_offset_, *recorder_);
  last_state_wall_ = now;
  if (!failed_) twin_->publish(*sim_, st, forecastCommand(), [this](double t) { return stamp(t); });
}

PayloadForecaster::CommandSource CraneSimNode::forecastCommand() const {
  if (!settings_.twin.measured_input) return inputs_->forecastCommand();
  const CommandEntry c = twin_->measuredRates(sim_->time());
  return [c](double, const CraneDrives&) { return c; };
}

void CraneSimNode::publishNow() {
  publish();
  next_publish_ = sim_->time() + 1.0 / settings_.publish_rate;
}

void CraneSimNode::publishPaused() {
  if (settings_.publish_clock || settings_.follow_clock) {
    // Simulated time stands still (the clock we own is republished frozen): TF 1 ns further on
    // each time, at most half a step, so the next step's stamps still come after.
    const ros::Duration ns(0, 1);
    if (tf_stamp_offset_ + ns < ros::Duration(0.5 * model_.scene.time_step)) tf_stamp_offset_ += ns;
  } else {
    // Stamps are wall time: the frozen state is valid now, and the run resumes from here.
    stamp_origin_ = ros::Time::now() - ros::Duration(t_offset_ + sim_->time());
  }
  publish();
}

void CraneSimNode::publishDiagnostics() {
  NodeRunRecord r;
  r.node_name = ros::this_node::getName();
  r.scene_file = model_.scene.file;
  r.rope_model = name(model_.scene.rope.model);
  r.paused = paused_;
  r.finished = finished_;
  if (failed_) r.failure = failure_;
  r.sim_time = sim_->time();
  r.real_time_factor = last_rtf_;
  r.requested_real_time_factor = settings_.real_time_factor;
  r.step_cost = last_step_cost_;
  r.steps = steps_;
  r.rejected_commands = inputs_->rejected();
  r.pacing_overruns = pacer_ ? pacer_->overruns() : 0;
  r.warnings_seen = warnings_seen_;
  r.wind_3s = last_wind_3s_;
  r.statistics = sim_->statistics();
  diagnostic_msgs::DiagnosticArray a;
  a.header.stamp = stamp(sim_->time());
  a.status.push_back(simulationStatus(r));
  twin_->diagnose(*sim_, a.status.back());
  usage_->publish(stamp(sim_->time()), r.node_name, a);
  diag_pub_.publish(a);
}

// The loop: spin, then step up to what the Pacer allows (real_time_factor, lockstep with the
// clock's followers, another node's /clock), publish at each publication time.
void CraneSimNode::run() {
  const double dt = model_.scene.time_step, period = 1.0 / settings_.publish_rate;
  pacer_ = std::make_unique<Pacer>(pacerSettingsOf(settings_, dt));
  std::vector<const ros::Publisher*> own = out_->publishers();
  own.push_back(&inputs_->appliedPublisher());
  own.push_back(&diag_pub_);
  bool awaiting_recorder = recorder_->enabled();
  if (!awaiting_recorder) publish();  // else once the recorder listens: the bag starts at t = 0
  next_publish_ = sim_->time() + period;
  bool was_running = false;
  while (ros::ok()) {
    ros::spinOnce();
    const ros::WallTime now = ros::WallTime::now();
    if ((now - last_diag_wall_).toSec() >= 1.0) {
      last_diag_wall_ = now;
      publishDiagnostics();
    }
    if (awaiting_recorder && recorder_->ready(own)) {
      awaiting_recorder = false;
      publish();  // the bag starts at t = 0
    }
    const bool running = !paused_ && !finished_ && !failed_ && !awaiting_recorder;
    if (running && recorder_->behind()) {  // a recorder falling behind holds the run
      ros::WallDuration(0.001).sleep();
      continue;
    }
    if (!running) {
      was_running = false;
      // Paused as in gazebo_ros: the frozen state keeps coming at ~publish_rate of wall time.
      if (paused_ && !finished_ && !failed_ && (now - last_paused_publish_).toSec() >= period) {
        last_paused_publish_ = now;
        publishPaused();
      }
      if (finished_ && settings_.shutdown_at_end) {
        recorder_->drain();  // the recorder writes our last messages
        break;
      }
      ros::WallDuration(std::min(period, 0.05)).sleep();
      continue;
    }
    if (!was_running) {  // (re)start pacing after a pause or reset
      tf_stamp_offset_ = ros::Duration(0.0);
      pacer_->restart(now.toSec(), sim_->time());
      was_running = true;
    }
    // Followers report total simulated time; ours runs from t_offset_ (a load change).
    const double slowest =
        follower_t_.empty() ? std::numeric_limits<double>::infinity()
                            : *std::min_element(follower_t_.begin(), follower_t_.end()) - t_offset_;
    const double clock = settings_.follow_clock ? ros::Time::now().toSec() - t_offset_ : 0.0;
    const long overruns = pacer_->overruns();
    const Pacer::Decision pace =
        pacer_->decide(now.toSec(), sim_->time(), next_publish_, slowest, clock);
    if (pacer_->overruns() > overruns && settings_.twin.measured_input &&
        !settings_.publish_clock && !settings_.follow_clock) {
      // A twin that fell further behind than its catch-up starts again from the present: its
      // time maps to the wall's again, so the crane's next measurements are due at once and
      // its states are stamped when they are valid.
      stamp_origin_ = ros::Time::now() - ros::Duration(t_offset_ + sim_->time());
    }
    if (pace.wait == Pacer::Wait::followers) {
      if ((now - last_warn_wall_).toSec() >= 5.0 && !std::isfinite(slowest)) {
        last_warn_wall_ = now;
        ROS_WARN("crane_sim_node: waiting for the clock's followers to publish their state");
      }
      // A follower waits for the clock while we wait for it: a clock message sent before its
      // subscription connected is lost, so repeat the clock now and then.
      if ((now - last_clock_wall_).toSec() >= 0.2) {
        out_->publishClock(stamp(sim_->time()));
        last_clock_wall_ = now;
      }
    } else if (pace.wait == Pacer::Wait::clock) {
      // Waiting for the clock: its owner may be waiting for our state (lockstep), and a
      // message sent before its subscription connected is lost, so repeat it now and then.
      if ((now - last_state_wall_).toSec() >= 0.2) {
        out_->republish(last_state_, *recorder_);
        last_state_wall_ = now;
      }
    }
    if (pace.wait != Pacer::Wait::none) {
      ros::WallDuration(pace.sleep).sleep();
      continue;
    }
    const double target = pace.target;
    while (sim_->time() + 0.5 * dt <= target) {
      if (!stepOnce()) break;
      if (settings_.duration > 0.0 && t_offset_ + sim_->time() >= settings_.duration - 0.5 * dt) {
        finished_ = true;
        ROS_INFO("crane_sim_node: end of scene at t = %g s", sim_->time());
        break;
      }
    }
    if (sim_->time() + 0.5 * dt > next_publish_ || finished_ || failed_) {
      publish();
      while (next_publish_ <= sim_->time() + 0.5 * dt) next_publish_ += period;
    }
  }
  publishDiagnostics();
}

}  // namespace crane_twin
