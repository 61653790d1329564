#include "usage_link.hpp"

#include <sys/stat.h>

#include <sstream>
#include <stdexcept>

#include "crane_twin/CraneUsage.h"
#include "crane_twin/analysis/usage_store.hpp"
#include "crane_twin/io/input_error.hpp"
#include "ros_messages.hpp"

namespace crane_twin {
namespace {

bool fileExists(const std::string& path) {
  struct stat st;
  return stat(path.c_str(), &st) == 0;
}

}  // namespace

UsageLink::UsageLink(ros::NodeHandle nh, UsageSettings settings, const CraneModel& model)
    : settings_(std::move(settings)), last_save_(ros::WallTime::now()) {
  if (!settings_.file.empty() && fileExists(settings_.file)) {
    try {
      counter_ = std::make_unique<UsageCounter>(model, loadUsageState(settings_.file));
    } catch (const std::invalid_argument& e) {
      throw InputError("parameter '~usage_file' '" + settings_.file + "': " + e.what());
    }
    const UsageReport r = counter_->report();
    ROS_INFO("crane_sim_node: usage count from %s: %.4g h, %ld lifts", settings_.file.c_str(),
             r.hours, r.lift_count);
  } else {
    counter_ = std::make_unique<UsageCounter>(model);
    if (!settings_.file.empty()) save();  // the file is writable, or the start fails here
  }
  pub_ = nh.advertise<CraneUsage>("crane/usage", 5, true);
}

UsageLink::~UsageLink() {
  try {
    if (!settings_.file.empty()) save();
  } catch (const std::exception& e) {
    ROS_ERROR("crane_sim_node: usage count not kept: %s", e.what());
  }
}

void UsageLink::restart(const CraneModel& model) {
  if (settings_.file.empty()) {
    counter_ = std::make_unique<UsageCounter>(model);
  } else {
    counter_ = std::make_unique<UsageCounter>(model, counter_->state());
    save();
  }
}

void UsageLink::observe(const SeriesValues& row, const LiftOffMonitor& lift_off,
                        double time_offset) {
  counter_->observe(row, lift_off, time_offset);
}

void UsageLink::save() {
  saveUsageState(counter_->state(), settings_.file);
  last_save_ = ros::WallTime::now();
}

void UsageLink::publish(const ros::Time& stamp, const std::string& node_name,
                        diagnostic_msgs::DiagnosticArray& diagnostics) {
  const UsageReport r = counter_->report();
  CraneUsage m = toUsageMessage(r, stamp);
  m.usage_file = settings_.file;
  pub_.publish(m);

  diagnostic_msgs::DiagnosticStatus d;
  d.name = node_name + ": usage";
  d.hardware_id = settings_.file;
  std::ostringstream msg;
  for (const HotSpotUsage& h : r.hot_spots) {
    if (!h.short_of_design_life) continue;
    msg << (msg.tellp() > 0 ? "; " : "") << h.name << " reaches D = 1 after " << h.hours_to_failure
        << " h";
  }
  if (msg.tellp() > 0) {
    d.level = diagnostic_msgs::DiagnosticStatus::WARN;
    d.message = msg.str() + " at this rate, short of the design's " +
                std::to_string(static_cast<long>(r.design_hours)) + " h";
  } else {
    d.level = diagnostic_msgs::DiagnosticStatus::OK;
    d.message = r.design_hours > 0.0 ? "every hot spot's projected life exceeds the design hours"
                                     : "no design_hours in the crane file";
  }
  addNumber(d, "hours", r.hours);
  addNumber(d, "lifts", static_cast<double>(r.lift_count));
  addNumber(d, "k_q", r.k_q);
  addKeyValue(d, "u_class", r.u_class);
  addKeyValue(d, "q_class", r.q_class);
  addNumber(d, "design_hours", r.design_hours);
  addKeyValue(d, "u_class_in_design_life",
              r.u_class_in_design_life.empty() ? "none" : r.u_class_in_design_life);
  for (const HotSpotUsage& h : r.hot_spots) {
    addNumber(d, "damage_" + h.name, h.damage);
    addNumber(d, "hours_to_d1_" + h.name, h.hours_to_failure);
  }
  diagnostics.status.push_back(d);

  if (!settings_.file.empty() &&
      (ros::WallTime::now() - last_save_).toSec() >= settings_.save_period) {
    try {
      save();
    } catch (const std::exception& e) {
      ROS_ERROR_THROTTLE(60.0, "crane_sim_node: usage count not kept: %s", e.what());
    }
  }
}

}  // namespace crane_twin
