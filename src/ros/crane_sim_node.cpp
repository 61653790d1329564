#include "crane_sim_node.hpp"

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/master.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>
#include <std_msgs/Bool.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "crane_twin/integrators/numerical_failure.hpp"
#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/io/site_description.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "node_params.hpp"
#include "ros_messages.hpp"

namespace crane_twin {

namespace {

CommandEntry entryOf(const CraneCommand& m) {
  CommandEntry c;
  c.slew_rate = m.slew_rate;
  c.trolley_speed = m.trolley_speed;
  c.hoist_speed = m.hoist_speed;
  return c;
}

}  // namespace

CraneSimNode::CraneSimNode(ros::NodeHandle nh, ros::NodeHandle pnh, NodeSettings settings)
    : nh_(nh),
      pnh_(pnh),
      settings_(std::move(settings)),
      model_(buildCraneModel(loadScene(settings_.scene, settings_.overrides))),
      watchdog_(settings_.command_timeout) {
  if (settings_.duration < 0.0) settings_.duration = model_.scene.duration;
  paused_ = settings_.start_paused;
  // The crane on the site: world -> <prefix>base, latched (docs/site.md).
  frames_.prefix = settings_.frame_prefix;
  Eigen::Vector3d base = model_.scene.site_position;
  double yaw = model_.scene.site_yaw_deg * M_PI / 180.0;
  if (!settings_.base_pose.empty()) {
    base = Eigen::Vector3d(settings_.base_pose[0], settings_.base_pose[1], settings_.base_pose[2]);
    yaw = settings_.base_pose[3];
  }
  if (settings_.twin.measured_input && !settings_.command_bag.empty()) {
    throw InputError("parameters '~input' 'measured' and '~command_bag' exclude each other");
  }
  base_yaw_ = yaw;
  twin_ = std::make_unique<TwinAdapter>(nh_, settings_.twin, frames_, base, yaw);
  loadReplay();
  usage_ = std::make_unique<UsageLink>(nh_, settings_.usage, model_);
  resetSimulation();
  recorder_ =
      std::make_unique<RecorderLink>(nh_, settings_.wait_for_recorder, settings_.recorded_topics);
  // Queues for bursts: as fast as possible a recorder takes every publication.
  joint_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 1000);
  state_pub_ = nh_.advertise<CraneState>("crane/state", 1000);  // rtf 0: bursts
  marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("crane/rope", 200);
  applied_pub_ = nh_.advertise<CraneCommand>("crane/command_applied", 50, true);
  diag_pub_ = nh_.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 5);
  if (settings_.publish_clock) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  static_tf_.sendTransform(toBaseTransform(frames_, base, yaw, ros::Time::now()));
  command_sub_ = nh_.subscribe("crane/command", 20, &CraneSimNode::onCommand, this);
  trajectory_sub_ = nh_.subscribe("crane/joint_trajectory", 5, &CraneSimNode::onTrajectory, this);
  wind_sub_ = nh_.subscribe("crane/wind", 10, &CraneSimNode::onWind, this);
  goal_pub_ = nh_.advertise<std_msgs::Bool>("crane/goal_reached", 1, true);
  follower_t_.assign(settings_.clock_followers.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < settings_.clock_followers.size(); ++i) {
    follower_subs_.push_back(nh_.subscribe<CraneState>(
        settings_.clock_followers[i], 10,
        [this, i](const CraneState::ConstPtr& m) { follower_t_[i] = m->t; }));
  }
  reset_srv_ = pnh_.advertiseService("reset", &CraneSimNode::onReset, this);
  pause_srv_ = pnh_.advertiseService("pause", &CraneSimNode::onPause, this);
  payload_srv_ = pnh_.advertiseService("set_payload", &CraneSimNode::onSetPayload, this);
  const bool ancf = model_.scene.rope.model != "pendulum";
  ROS_INFO(
      "crane_sim_node: scene %s, rope model %s%s%s, time step %g s, "
      "real_time_factor %g%s%s",
      settings_.scene.c_str(), model_.scene.rope.model.c_str(), ancf ? ", rope elements " : "",
      ancf ? std::to_string(model_.scene.rope.elements).c_str() : "", model_.scene.time_step,
      settings_.real_time_factor, settings_.publish_clock ? ", publishing /clock" : "",
      settings_.command_bag.empty() ? "" : ", replaying commands from a bag");
}

// Commands the recorded run applied, by simulated time (crane/command_applied stamps).
void CraneSimNode::loadReplay() {
  replay_all_.clear();
  if (settings_.command_bag.empty()) return;
  try {
    rosbag::Bag bag(settings_.command_bag, rosbag::bagmode::Read);
    rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{"crane/command_applied",
                                                                       "/crane/command_applied"}));
    for (const rosbag::MessageInstance& m : view) {
      const CraneCommand::ConstPtr c = m.instantiate<CraneCommand>();
      if (c) replay_all_.push_back({c->header.stamp.toSec(), entryOf(*c)});
    }
  } catch (const rosbag::BagException& e) {
    throw InputError("parameter '~command_bag' '" + settings_.command_bag + "': " + e.what());
  }
  if (replay_all_.empty()) {
    throw InputError("parameter '~command_bag' '" + settings_.command_bag +
                     "': no crane_twin/CraneCommand on /crane/command_applied");
  }
  std::stable_sort(replay_all_.begin(), replay_all_.end(),
                   [](const Replayed& a, const Replayed& b) { return a.t < b.t; });
  for (const auto& r : replay_all_) {
    const CommandVerdict v = checkCommand(model_.scene, r.command);
    if (!v.accepted) {
      throw InputError("parameter '~command_bag' '" + settings_.command_bag +
                       "': recorded command at t = " + std::to_string(r.t) + " s: " + v.reason);
    }
  }
}

void CraneSimNode::resetSimulation() {
  t_offset_ = 0.0;
  usage_->restart(model_);
  restartSimulation();
  replay_.assign(replay_all_.begin(), replay_all_.end());
  stamp_origin_ =
      settings_.publish_clock || settings_.follow_clock ? ros::Time(0) : ros::Time::now();
}

void CraneSimNode::restartSimulation() {
  sim_ = makeSimulation(model_);
  sim_->initialize();
  lift_off_ = LiftOffMonitor();
  if (measured_wind_) sim_->setMeasuredWind(*measured_wind_);
  twin_->restart(model_, *sim_);
  follower_.cancel();
  watchdog_ = CommandWatchdog(settings_.command_timeout);
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

void CraneSimNode::warnThrottled(const std::string& what) {
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_warn_wall_).toSec() < 2.0) return;
  last_warn_wall_ = now;
  ROS_WARN("crane_sim_node: %s (%ld commands rejected so far)", what.c_str(), rejected_);
}

// Commands act from the next step on; each applied command is republished with its simulated
// time on crane/command_applied, which is what replay feeds back.
void CraneSimNode::apply(const CommandEntry& c, const char* source) {
  sim_->setCommand(c);
  CraneCommand m;
  m.header.stamp = ros::Time(t_offset_ + sim_->time());
  m.header.frame_id = source;
  m.slew_rate = c.slew_rate;
  m.trolley_speed = c.trolley_speed;
  m.hoist_speed = c.hoist_speed;
  applied_pub_.publish(m);
}

void CraneSimNode::onCommand(const CraneCommand::ConstPtr& msg) {
  if (settings_.twin.measured_input) {
    ++rejected_;
    warnThrottled(
        "~input measured: the twin follows crane/measured_joint_states; crane/command ignored");
    return;
  }
  if (!settings_.command_bag.empty()) {
    ++rejected_;
    warnThrottled("replaying a bag: live command on crane/command ignored");
    return;
  }
  const CommandEntry c = entryOf(*msg);
  const CommandVerdict v = checkCommand(model_.scene, c);
  if (!v.accepted) {
    ++rejected_;
    warnThrottled("command rejected: " + v.reason);
    return;
  }
  if (failed_) {
    ++rejected_;
    warnThrottled("command ignored: the simulation stopped (" + failure_ + "); call ~reset");
    return;
  }
  try {
    apply(c, "operator");
  } catch (const std::exception& e) {  // InputError: not built for this model
    ++rejected_;
    warnThrottled(std::string("command rejected: ") + e.what());
    return;
  }
  if (v.over_limit) warnThrottled("command above a speed limit: " + v.reason);
  watchdog_.received(sim_->time());
  if (follower_.active()) {  // a rate command takes over from a goal
    follower_.cancel();
    ROS_INFO("crane_sim_node: trajectory cancelled by a rate command on crane/command");
  }
}

// An anemometer's wind at the jib's height (docs/ros.md): m/s in the world frame, turned into
// the crane's frame; its horizontal part replaces the scene's wind from the next step on.
void CraneSimNode::onWind(const geometry_msgs::Vector3Stamped::ConstPtr& msg) {
  const Eigen::Vector3d w(msg->vector.x, msg->vector.y, msg->vector.z);
  const std::string& frame = msg->header.frame_id;
  std::string why;
  if (!w.allFinite()) why = "a non-finite component";
  if (!frame.empty() && frame != "world" && frame != "/world") {
    why = "frame '" + frame + "' (the wind is taken in 'world')";
  }
  if (!why.empty()) {
    ++rejected_;
    warnThrottled("crane/wind rejected: " + why);
    return;
  }
  const Eigen::Vector3d v = Eigen::AngleAxisd(-base_yaw_, Eigen::Vector3d::UnitZ()) * w;
  try {
    sim_->setMeasuredWind(v);
    measured_wind_ = v;
  } catch (const std::exception& e) {  // InputError: this rope model takes no wind
    ++rejected_;
    warnThrottled(std::string("crane/wind rejected: ") + e.what());
  }
}

void CraneSimNode::onTrajectory(const trajectory_msgs::JointTrajectory::ConstPtr& msg) {
  auto reject = [&](const std::string& why) {
    ++rejected_;
    ROS_WARN("crane_sim_node: trajectory rejected: %s", why.c_str());
  };
  if (!settings_.command_bag.empty()) return reject("replaying a bag");
  if (settings_.twin.measured_input) return reject("~input measured: the twin follows the crane");
  if (failed_) return reject("the simulation stopped (" + failure_ + "); call ~reset");
  if (!model_.scene.crane) return reject("the scene has no crane (crane: none)");
  int index[3] = {-1, -1, -1};
  for (std::size_t j = 0; j < msg->joint_names.size(); ++j) {
    int a = -1;
    for (int k = 0; k < 3; ++k)
      if (msg->joint_names[j] == kJointNames[k]) a = k;
    if (a < 0) return reject("unknown joint '" + msg->joint_names[j] + "' (slew, trolley, hoist)");
    if (index[a] >= 0) return reject("joint '" + msg->joint_names[j] + "' named twice");
    index[a] = static_cast<int>(j);
  }
  std::vector<TrajectoryPoint> points;
  for (std::size_t k = 0; k < msg->points.size(); ++k) {
    const auto& p = msg->points[k];
    if (p.positions.size() != msg->joint_names.size()) {
      return reject("point " + std::to_string(k) + " has " + std::to_string(p.positions.size()) +
                    " positions for " + std::to_string(msg->joint_names.size()) + " joints");
    }
    TrajectoryPoint q;
    q.time_from_start = p.time_from_start.toSec();
    for (int a = 0; a < 3; ++a)
      if (index[a] >= 0) q.target[a] = p.positions[index[a]];
    points.push_back(q);
  }
  const std::string why = TrajectoryFollower::validate(points, *model_.scene.crane);
  if (!why.empty()) return reject(why);
  follower_.start(std::move(points), sim_->time());
  publishGoalReached(false);
  ROS_INFO("crane_sim_node: following a trajectory of %zu points", msg->points.size());
}

void CraneSimNode::publishGoalReached(bool reached) {
  std_msgs::Bool b;
  b.data = reached;
  goal_pub_.publish(b);
}

void CraneSimNode::followTrajectory() {
  if (!follower_.active()) return;
  const CommandEntry c = follower_.command(sim_->time(), sim_->drives(), *model_.scene.crane);
  sim_->setCommand(c);
  watchdog_.received(sim_->time());
  if (!follower_.active() && follower_.reached()) {
    publishGoalReached(true);
    ROS_INFO("crane_sim_node: trajectory reached at t = %g s", sim_->time());
  }
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
  // model with another load, pose and initial state, its structure not rebuilt (withScene).
  try {
    Scene s = model_.scene;
    s.payload_mass = req.mass;
    if (s.crane) {
      s.slew_angle = d.slewAngle();
      s.trolley_radius = d.trolleyRadius();
      s.rope.length = d.hoistLength();
    }
    s.initial_mode = "equilibrium";
    s.swing_deg = 0.0;
    s.payload_velocity = Eigen::Vector3d::Zero();
    s.commands.clear();
    CraneModel m = withScene(model_, s);
    const double t = t_offset_ + sim_->time();
    model_ = std::move(m);
    t_offset_ = t;
    restartSimulation();
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
    twin_->loadChanged(model_);
    usage_->setPayloadMass(mass);
    ROS_INFO("crane_sim_node (twin): the load cell finds %.0f kg lifted (was %.0f kg) at t = %g s",
             mass, from, t_offset_ + sim_->time());
  } catch (const std::exception& e) {  // a model that cannot continue with another load
    warnThrottled(std::string("the load cell's payload mass not taken: ") + e.what());
  }
}

bool CraneSimNode::onPause(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  paused_ = req.data;
  last_publish_wall_ = ros::WallTime::now();
  res.success = true;
  res.message = paused_ ? "paused" : "running";
  return true;
}

void CraneSimNode::applyDueCommands() {
  const double t = sim_->time(), half = 0.5 * model_.scene.time_step;
  while (!replay_.empty() && replay_.front().t <= t + half) {
    apply(replay_.front().command, "replay");
    replay_.pop_front();
  }
  if (settings_.twin.measured_input) {
    sim_->setCommand(twin_->followCommand(*sim_));
    return;
  }
  if (settings_.command_bag.empty() && watchdog_.expired(t)) {
    apply(CommandEntry{}, "timeout");
    warnThrottled("no command for " + std::to_string(settings_.command_timeout) +
                  " s: drives ramp to rest");
  }
}

bool CraneSimNode::stepOnce() {
  applyDueCommands();
  followTrajectory();
  const auto t0 = std::chrono::steady_clock::now();
  try {
    sim_->step();
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

  // The structure's segments at most structure_marker_rate times per wall second (rviz keeps
  // the last marker of an id); the first publication always carries them.
  SnapshotOptions options = settings_.snapshot;
  options.structure_segments =
      last_structure_wall_.isZero() ||
      (now - last_structure_wall_).toSec() >= 1.0 / settings_.structure_marker_rate;
  if (options.structure_segments) last_structure_wall_ = now;
  CraneSnapshot s = snapshotOf(*sim_, options);
  // A twin reading a load cell: landed as the load cell sees it, for crane/state, the lift-offs
  // and the usage (its own load may bounce where the real one does not; docs/twin.md).
  if (const std::optional<bool> landed = twin_->loadCellLanded()) {
    s.series.payload_landed = *landed;
  }
  lift_off_.observe(s.series, staticTopTension(model_, s.series.rope_length));
  usage_->observe(s.series, lift_off_, t_offset_);  // at the publication rate
  s.series.warnings |= lift_off_.warningFor(model_.scene.hoist_design_phi2);
  warnings_seen_ |= s.series.warnings;
  last_wind_3s_ = s.series.wind_3s;
  if (settings_.publish_clock) {
    rosgraph_msgs::Clock c;
    c.clock = st;
    clock_pub_.publish(c);
  }
  joint_pub_.publish(toJointState(s, st));
  recorder_->published(joint_pub_);
  tf_.sendTransform(toTransforms(s, st + tf_stamp_offset_, frames_));
  const double payload_mass = model_.scene.payload_mass;
  const std::optional<double> ground =
      model_.scene.ground ? std::optional<double>(model_.scene.ground->height) : std::nullopt;
  marker_pub_.publish(toMarkers(s, st, loadShapes(s, model_.scene.hookBlockMass(), payload_mass),
                                payload_mass, frames_, ground));
  recorder_->published(marker_pub_);
  last_state_ = toStateMessage(s, st, last_step_cost_, last_rtf_, model_.scene.rope.model, frames_);
  last_state_.t += t_offset_;
  last_state_.payload_mass_estimate = model_.scene.payload_mass;
  last_state_.stress_names.clear();
  if (model_.hot_spots) {
    for (const HotSpotRow& r : model_.hot_spots->rows) last_state_.stress_names.push_back(r.name);
  }
  last_state_.lift_offs = lift_off_.liftOffs();
  last_state_.lift_off_factor = lift_off_.factor();
  state_pub_.publish(last_state_);
  recorder_->published(state_pub_);
  last_state_wall_ = now;
  if (!failed_) twin_->publish(*sim_, st, forecastCommand(), [this](double t) { return stamp(t); });
}

PayloadForecaster::CommandSource CraneSimNode::forecastCommand() const {
  const double t = sim_->time();
  if (settings_.twin.measured_input) {
    const CommandEntry c = twin_->measuredRates(t);
    return [c](double, const CraneDrives&) { return c; };
  }
  if (follower_.active() && model_.scene.crane) {
    const CraneDescription crane = *model_.scene.crane;
    return [f = follower_, crane](double time, const CraneDrives& d) mutable {
      return f.command(time, d, crane);
    };
  }
  const CommandEntry c = sim_->drives().activeCommand(t);
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
  diagnostic_msgs::DiagnosticArray a;
  a.header.stamp = stamp(sim_->time());
  diagnostic_msgs::DiagnosticStatus d;
  d.name = ros::this_node::getName() + ": simulation";  // one per crane on a site
  d.hardware_id = model_.scene.file;
  const bool slow = settings_.real_time_factor > 0.0 && !paused_ && !finished_ &&
                    last_rtf_ < 0.9 * settings_.real_time_factor;
  if (failed_) {
    d.level = diagnostic_msgs::DiagnosticStatus::ERROR;
    d.message = "stopped: " + failure_;
  } else if (slow) {
    d.level = diagnostic_msgs::DiagnosticStatus::WARN;
    d.message = "behind the requested real-time factor";
  } else {
    d.level = diagnostic_msgs::DiagnosticStatus::OK;
    d.message = paused_ ? "paused" : finished_ ? "end of scene reached" : "running";
  }
  addNumber(d, "sim_time_s", sim_->time());
  addNumber(d, "real_time_factor", last_rtf_);
  addNumber(d, "requested_real_time_factor", settings_.real_time_factor);
  addNumber(d, "step_cost_s", last_step_cost_);
  addNumber(d, "steps", static_cast<double>(steps_));
  const RunStatistics stats = sim_->statistics();
  addNumber(d, "subdomains", stats.subdomains);
  addNumber(d, "hand_overs", static_cast<double>(stats.hand_overs));
  addNumber(d, "full_order_steps", static_cast<double>(stats.full_order_steps));
  addNumber(d, "mode_updates_s", stats.mode_update_seconds);
  addNumber(d, "rejected_commands", static_cast<double>(rejected_));
  addNumber(d, "pacing_overruns", pacer_ ? static_cast<double>(pacer_->overruns()) : 0.0);
  addNumber(d, "warnings_seen", warnings_seen_);
  {
    std::string names;
    for (int bit = 1; bit <= kLastWarning; bit <<= 1)
      if (warnings_seen_ & bit)
        names += (names.empty() ? "" : "; ") + std::string(warningName(bit));
    addKeyValue(d, "warnings_seen_names", names.empty() ? "none" : names);
  }
  addNumber(d, "wind_3s", last_wind_3s_);
  addKeyValue(d, "rope_model", model_.scene.rope.model);
  twin_->diagnose(*sim_, d);
  a.status.push_back(d);
  usage_->publish(stamp(sim_->time()), ros::this_node::getName(), a);
  diag_pub_.publish(a);
}

// The loop: spin, then step up to what the Pacer allows (real_time_factor, lockstep with the
// clock's followers, another node's /clock), publish at each publication time.
void CraneSimNode::run() {
  const double dt = model_.scene.time_step, period = 1.0 / settings_.publish_rate;
  PacerSettings pacing;
  pacing.real_time_factor = settings_.real_time_factor;
  pacing.publish_period = period;
  pacing.time_step = dt;
  pacing.follow_clock = settings_.follow_clock;
  pacer_ = std::make_unique<Pacer>(pacing);
  const std::vector<const ros::Publisher*> own = {&state_pub_,   &joint_pub_, &marker_pub_,
                                                  &applied_pub_, &diag_pub_,  &clock_pub_};
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
    const Pacer::Decision pace =
        pacer_->decide(now.toSec(), sim_->time(), next_publish_, slowest, clock);
    if (pace.wait == Pacer::Wait::followers) {
      if ((now - last_warn_wall_).toSec() >= 5.0 && !std::isfinite(slowest)) {
        last_warn_wall_ = now;
        ROS_WARN("crane_sim_node: waiting for the clock's followers to publish their state");
      }
      // A follower waits for the clock while we wait for it: a clock message sent before its
      // subscription connected is lost, so repeat the clock now and then.
      if ((now - last_clock_wall_).toSec() >= 0.2) {
        rosgraph_msgs::Clock c;
        c.clock = stamp(sim_->time());
        clock_pub_.publish(c);
        last_clock_wall_ = now;
      }
    } else if (pace.wait == Pacer::Wait::clock) {
      // Waiting for the clock: its owner may be waiting for our state (lockstep), and a
      // message sent before its subscription connected is lost, so repeat it now and then.
      if ((now - last_state_wall_).toSec() >= 0.2) {
        state_pub_.publish(last_state_);
        recorder_->published(state_pub_);
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
