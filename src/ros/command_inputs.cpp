#include "command_inputs.hpp"

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <std_msgs/Bool.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"
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

CommandInputs::CommandInputs(ros::NodeHandle nh, const NodeSettings& settings,
                             const CraneModel& model, double base_yaw, const std::string& failure)
    : measured_input_(settings.twin.measured_input),
      command_bag_(settings.command_bag),
      command_timeout_(settings.command_timeout),
      base_yaw_(base_yaw),
      failure_(failure),
      watchdog_(settings.command_timeout) {
  loadReplay(model);
  applied_pub_ = nh.advertise<CraneCommand>("crane/command_applied", 50, true);
  goal_pub_ = nh.advertise<std_msgs::Bool>("crane/goal_reached", 1, true);
  command_sub_ = nh.subscribe("crane/command", 20, &CommandInputs::onCommand, this);
  trajectory_sub_ = nh.subscribe("crane/joint_trajectory", 5, &CommandInputs::onTrajectory, this);
  wind_sub_ = nh.subscribe("crane/wind", 10, &CommandInputs::onWind, this);
}

// Commands the recorded run applied, by simulated time (crane/command_applied stamps).
void CommandInputs::loadReplay(const CraneModel& model) {
  if (command_bag_.empty()) return;
  try {
    rosbag::Bag bag(command_bag_, rosbag::bagmode::Read);
    rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{"crane/command_applied",
                                                                       "/crane/command_applied"}));
    for (const rosbag::MessageInstance& m : view) {
      const CraneCommand::ConstPtr c = m.instantiate<CraneCommand>();
      if (c) replay_all_.push_back({c->header.stamp.toSec(), entryOf(*c)});
    }
  } catch (const rosbag::BagException& e) {
    throw InputError("parameter '~command_bag' '" + command_bag_ + "': " + e.what());
  }
  if (replay_all_.empty()) {
    throw InputError("parameter '~command_bag' '" + command_bag_ +
                     "': no crane_twin/CraneCommand on /crane/command_applied");
  }
  std::stable_sort(replay_all_.begin(), replay_all_.end(),
                   [](const Replayed& a, const Replayed& b) { return a.t < b.t; });
  for (const auto& r : replay_all_) {
    const CommandVerdict v = checkCommand(model.scene, r.command);
    if (!v.accepted) {
      throw InputError("parameter '~command_bag' '" + command_bag_ +
                       "': recorded command at t = " + std::to_string(r.t) + " s: " + v.reason);
    }
  }
}

void CommandInputs::attach(Simulation& sim, const CraneModel& model, double t_offset, Start start) {
  sim_ = &sim;
  model_ = &model;
  t_offset_ = t_offset;
  if (start == Start::kContinued) return;
  if (measured_wind_) {
    // The anemometer's last wind carries over into a rebuilt run that takes wind.
    if (MeasuredWindInput* input = capabilityOf<MeasuredWindInput>(sim)) {
      input->setMeasuredWind(*measured_wind_);
    } else {
      warnThrottled(std::string("crane/wind dropped: ") + MeasuredWindInput::kWhat);
      measured_wind_.reset();
    }
  }
  if (start == Start::kFromStart) replay_.assign(replay_all_.begin(), replay_all_.end());
  follower_.cancel();
  watchdog_ = CommandWatchdog(command_timeout_);
}

void CommandInputs::warnThrottled(const std::string& what) {
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_warn_wall_).toSec() < 2.0) return;
  last_warn_wall_ = now;
  ROS_WARN("crane_sim_node: %s (%ld commands rejected so far)", what.c_str(), rejected_);
}

// Commands act from the next step on; each applied command is republished with its simulated
// time on crane/command_applied, which is what replay feeds back.
void CommandInputs::apply(const CommandEntry& c, const char* source) {
  sim_->setCommand(c);
  CraneCommand m;
  m.header.stamp = ros::Time(t_offset_ + sim_->time());
  m.header.frame_id = source;
  m.slew_rate = c.slew_rate;
  m.trolley_speed = c.trolley_speed;
  m.hoist_speed = c.hoist_speed;
  applied_pub_.publish(m);
}

void CommandInputs::onCommand(const CraneCommand::ConstPtr& msg) {
  auto refuse = [&](const std::string& why) {
    ++rejected_;
    warnThrottled(why);
  };
  if (!sim_) return refuse("command ignored: no simulation yet");
  if (measured_input_) {
    return refuse(
        "~input measured: the twin follows crane/measured_joint_states; crane/command ignored");
  }
  if (!command_bag_.empty())
    return refuse("replaying a bag: live command on crane/command ignored");
  const CommandEntry c = entryOf(*msg);
  const CommandVerdict v = checkCommand(model_->scene, c);
  if (!v.accepted) return refuse("command rejected: " + v.reason);
  if (!failure_.empty()) {
    return refuse("command ignored: the simulation stopped (" + failure_ + "); call ~reset");
  }
  try {
    apply(c, "operator");
  } catch (const std::exception& e) {  // InputError: not built for this model
    return refuse(std::string("command rejected: ") + e.what());
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
void CommandInputs::onWind(const geometry_msgs::Vector3Stamped::ConstPtr& msg) {
  const Eigen::Vector3d w(msg->vector.x, msg->vector.y, msg->vector.z);
  const std::string& frame = msg->header.frame_id;
  std::string why;
  if (!w.allFinite()) why = "a non-finite component";
  if (!frame.empty() && frame != "world" && frame != "/world") {
    why = "frame '" + frame + "' (the wind is taken in 'world')";
  }
  if (!why.empty() || !sim_) {
    ++rejected_;
    warnThrottled("crane/wind rejected: " + (why.empty() ? "no simulation yet" : why));
    return;
  }
  const Eigen::Vector3d v = Eigen::AngleAxisd(-base_yaw_, Eigen::Vector3d::UnitZ()) * w;
  MeasuredWindInput* input = capabilityOf<MeasuredWindInput>(*sim_);
  if (!input) {
    ++rejected_;
    warnThrottled(std::string("crane/wind rejected: ") + MeasuredWindInput::kWhat);
    return;
  }
  input->setMeasuredWind(v);  // finite: checked above
  measured_wind_ = v;
}

void CommandInputs::onTrajectory(const trajectory_msgs::JointTrajectory::ConstPtr& msg) {
  auto reject = [&](const std::string& why) {
    ++rejected_;
    ROS_WARN("crane_sim_node: trajectory rejected: %s", why.c_str());
  };
  if (!sim_) return reject("no simulation yet");
  if (!command_bag_.empty()) return reject("replaying a bag");
  if (measured_input_) return reject("~input measured: the twin follows the crane");
  if (!failure_.empty()) return reject("the simulation stopped (" + failure_ + "); call ~reset");
  if (!model_->scene.crane) return reject("the scene has no crane (crane: none)");
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
  const std::string why = TrajectoryFollower::validate(points, *model_->scene.crane);
  if (!why.empty()) return reject(why);
  follower_.start(std::move(points), sim_->time());
  publishGoalReached(false);
  ROS_INFO("crane_sim_node: following a trajectory of %zu points", msg->points.size());
}

void CommandInputs::publishGoalReached(bool reached) {
  std_msgs::Bool b;
  b.data = reached;
  goal_pub_.publish(b);
}

void CommandInputs::beforeStep() {
  const double t = sim_->time(), half = 0.5 * model_->scene.time_step;
  while (!replay_.empty() && replay_.front().t <= t + half) {
    apply(replay_.front().command, "replay");
    replay_.pop_front();
  }
  if (command_bag_.empty() && watchdog_.expired(t)) {
    apply(CommandEntry{}, "timeout");
    warnThrottled("no command for " + std::to_string(command_timeout_) + " s: drives ramp to rest");
  }
  if (!follower_.active()) return;
  const CommandEntry c = follower_.command(t, sim_->drives(), *model_->scene.crane);
  sim_->setCommand(c);
  watchdog_.received(t);
  if (!follower_.active() && follower_.reached()) {
    publishGoalReached(true);
    ROS_INFO("crane_sim_node: trajectory reached at t = %g s", t);
  }
}

PayloadForecaster::CommandSource CommandInputs::forecastCommand() const {
  if (follower_.active() && model_->scene.crane) {
    const CraneDescription crane = *model_->scene.crane;
    return [f = follower_, crane](double time, const CraneDrives& d) mutable {
      return f.command(time, d, crane);
    };
  }
  const CommandEntry c = sim_->drives().activeCommand(sim_->time());
  return [c](double, const CraneDrives&) { return c; };
}

}  // namespace crane_twin
