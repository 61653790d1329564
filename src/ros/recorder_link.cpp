#include "recorder_link.hpp"

#include <ros/master.h>

#include <set>

namespace crane_twin {

RecorderLink::RecorderLink(ros::NodeHandle nh, const std::string& recorder,
                           const std::vector<std::string>& topics)
    : nh_(nh) {
  if (recorder.empty()) return;
  recorder_ = nh_.resolveName(recorder);
  for (const std::string& t : topics) topics_.push_back(nh_.resolveName(t));
  progress_sub_ = nh_.subscribe(recorder_ + "/progress", 10, &RecorderLink::onProgress, this);
}

void RecorderLink::onProgress(const RecorderProgress::ConstPtr& p) {
  reports_progress_ = true;
  bool moved = false;
  for (std::size_t i = 0; i < p->topics.size() && i < p->messages.size(); ++i) {
    uint64_t& w = written_[p->topics[i]];
    moved |= p->messages[i] > w;
    w = p->messages[i];
  }
  if (moved || last_progress_.isZero()) last_progress_ = ros::WallTime::now();
}

bool RecorderLink::ready(const std::vector<const ros::Publisher*>& own) {
  if (!enabled() || ready_) return true;
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_check_).toSec() < 0.1) return false;
  last_check_ = now;
  // getSystemState: [publishers, subscribers, services], each [[name, [node, ...]], ...].
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  std::string missing;
  if (!ros::master::execute("getSystemState", request, response, payload, false)) {
    missing = " (the master did not answer)";
  } else {
    std::set<std::string> subscribed;
    std::map<std::string, int> registered;  // subscribers per topic on the master
    XmlRpc::XmlRpcValue& subscribers = payload[1];
    for (int i = 0; i < subscribers.size(); ++i) {
      XmlRpc::XmlRpcValue& nodes = subscribers[i][1];
      const std::string topic = subscribers[i][0];
      registered[topic] = nodes.size();
      for (int j = 0; j < nodes.size(); ++j)
        if (static_cast<std::string>(nodes[j]) == recorder_) subscribed.insert(topic);
    }
    // A registration precedes the connection: our own publishers must also have connected
    // every registered subscriber, or the first messages would go nowhere.
    for (const std::string& name : topics_) {
      bool connected = subscribed.count(name) > 0;
      for (const ros::Publisher* p : own)
        if (*p && p->getTopic() == name &&
            static_cast<int>(p->getNumSubscribers()) < registered[name])
          connected = false;
      if (!connected) missing += " " + name;
    }
  }
  if (!missing.empty()) {
    seen_ = ros::WallTime();
    if ((now - last_warn_).toSec() >= 5.0) {
      last_warn_ = now;
      ROS_WARN("crane_sim_node: waiting for %s to subscribe to%s", recorder_.c_str(),
               missing.c_str());
    }
    return false;
  }
  if (seen_.isZero()) seen_ = now;  // subscribed: let its connections settle
  if ((now - seen_).toSec() < kSettleSeconds) return false;
  ready_ = true;
  ROS_INFO("crane_sim_node: %s is recording; starting", recorder_.c_str());
  return true;
}

void RecorderLink::published(const ros::Publisher& p) {
  if (enabled()) ++published_[p.getTopic()];
}

bool RecorderLink::lagging(uint64_t window) const {
  for (const auto& [topic, n] : published_) {
    const auto w = written_.find(topic);
    if (w != written_.end() && n > w->second + window) return true;
  }
  return false;
}

bool RecorderLink::behind() {
  if (!enabled() || !reports_progress_ || stalled_) return false;
  if (!lagging(kWindow)) return false;
  if ((ros::WallTime::now() - last_progress_).toSec() > kStallSeconds) {
    stalled_ = true;
    ROS_WARN("crane_sim_node: %s wrote nothing for %g s: running on without waiting for it",
             recorder_.c_str(), kStallSeconds);
    return false;
  }
  return true;
}

void RecorderLink::drain() {
  if (!enabled()) return;
  if (!reports_progress_) {
    // A recorder without progress (rosbag record): give it a second to write our last messages.
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(1.0);
    while (ros::ok() && ros::WallTime::now() < until) {
      ros::spinOnce();
      ros::WallDuration(0.02).sleep();
    }
    return;
  }
  last_progress_ = ros::WallTime::now();
  while (ros::ok() && lagging(0) &&
         (ros::WallTime::now() - last_progress_).toSec() <= kStallSeconds) {
    ros::spinOnce();
    ros::WallDuration(0.01).sleep();
  }
  std::string counts;
  uint64_t lost = 0;
  for (const auto& [topic, n] : published_) {
    const auto w = written_.find(topic);
    if (w == written_.end()) continue;  // not recorded
    counts += " " + topic + " " + std::to_string(w->second) + " of " + std::to_string(n);
    if (n > w->second) lost += n - w->second;
  }
  if (lost == 0) {
    ROS_INFO("crane_sim_node: %s holds every message we published:%s", recorder_.c_str(),
             counts.c_str());
  } else {
    ROS_WARN("crane_sim_node: %s lost %llu of our messages:%s", recorder_.c_str(),
             static_cast<unsigned long long>(lost), counts.c_str());
  }
}

}  // namespace crane_twin
