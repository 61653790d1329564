// crane_recorder: a bag recorder that loses nothing and says how far it got (docs/ros.md
// "Recording"). Like `rosbag record` it subscribes to the named topics whatever their type
// (topic_tools::ShapeShifter) and writes each message with its connection header, so rosbag
// play, rosbag info and the Python rosbag API read the bag as usual. Unlike it, the incoming
// queues are unbounded (rosbag record's hold 100 messages: a burst from a node running as fast as
// possible overflowed them) and it publishes ~progress (crane_twin/RecorderProgress), the
// messages written per topic, to which crane_sim_node paces itself. The bag is written as
// <bag>.active and renamed to <bag> when the node shuts down.
//
//   rosrun crane_twin crane_recorder _bag:=run.bag _topics:="/crane/state /tf" [_compression:=lz4]
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <topic_tools/shape_shifter.h>

#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "crane_twin/RecorderProgress.h"

namespace {

class CraneRecorder {
 public:
  CraneRecorder(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh) {
    if (!pnh.getParam("bag", bag_path_) || bag_path_.empty())
      throw std::invalid_argument("parameter '" + pnh.resolveName("bag") +
                                  "' (the bag's path) is required and must be a string");
    std::string topics;
    if (!pnh.getParam("topics", topics))
      throw std::invalid_argument("parameter '" + pnh.resolveName("topics") +
                                  "' (topic names separated by blanks) is required");
    std::istringstream in(topics);
    for (std::string name; in >> name;) topics_.push_back(nh_.resolveName(name));
    if (topics_.empty())
      throw std::invalid_argument("parameter '" + pnh.resolveName("topics") + "' names no topic");
    std::string compression = "lz4";
    pnh.getParam("compression", compression);
    rosbag::CompressionType type;
    if (compression == "lz4")
      type = rosbag::compression::LZ4;
    else if (compression == "bz2")
      type = rosbag::compression::BZ2;
    else if (compression == "none")
      type = rosbag::compression::Uncompressed;
    else
      throw std::invalid_argument("parameter '" + pnh.resolveName("compression") + "' '" +
                                  compression + "': lz4, bz2 or none");
    bag_.open(bag_path_ + ".active", rosbag::bagmode::Write);
    bag_.setCompression(type);
    progress_pub_ = pnh.advertise<crane_twin::RecorderProgress>("progress", 10, true);
    for (const std::string& topic : topics_) {
      written_[topic] = 0;
      // Queue size 0: unbounded; nothing is dropped however far the writing falls behind.
      boost::function<void(const ros::MessageEvent<topic_tools::ShapeShifter const>&)> cb =
          [this, topic](const ros::MessageEvent<topic_tools::ShapeShifter const>& e) {
            write(topic, e);
          };
      subs_.push_back(
          nh_.subscribe<topic_tools::ShapeShifter,
                        const ros::MessageEvent<topic_tools::ShapeShifter const>&>(topic, 0, cb));
    }
    timer_ = nh_.createWallTimer(ros::WallDuration(0.01), [this](const ros::WallTimerEvent&) {
      if (changed_) publishProgress();
    });
    publishProgress();
    ROS_INFO("crane_recorder: recording %zu topics to %s", topics_.size(), bag_path_.c_str());
  }

  /// Close the bag under its final name and say what it holds.
  void close() {
    subs_.clear();
    bag_.close();
    if (std::rename((bag_path_ + ".active").c_str(), bag_path_.c_str()) != 0)
      ROS_ERROR("crane_recorder: could not rename %s.active to %s", bag_path_.c_str(),
                bag_path_.c_str());
    std::string counts;
    for (const auto& [topic, n] : written_) counts += " " + topic + " " + std::to_string(n);
    ROS_INFO("crane_recorder: wrote %s:%s", bag_path_.c_str(), counts.c_str());
  }

 private:
  void write(const std::string& topic,
             const ros::MessageEvent<topic_tools::ShapeShifter const>& e) {
    // The bag's index time is the receipt time (simulated time under /use_sim_time); before the
    // first /clock that is zero, which a bag cannot hold: such messages are filed at its
    // earliest time, ros::TIME_MIN (1 ns).
    ros::Time t = e.getReceiptTime();
    if (t < ros::TIME_MIN) t = ros::TIME_MIN;
    bag_.write(topic, t, e.getMessage(), e.getConnectionHeaderPtr());
    ++written_[topic];
    changed_ = true;
  }

  void publishProgress() {
    crane_twin::RecorderProgress p;
    p.header.stamp = ros::Time::now();
    p.bag = bag_path_;
    for (const auto& [topic, n] : written_) {
      p.topics.push_back(topic);
      p.messages.push_back(n);
    }
    progress_pub_.publish(p);
    changed_ = false;
  }

  ros::NodeHandle nh_;
  std::string bag_path_;
  std::vector<std::string> topics_;
  rosbag::Bag bag_;
  std::map<std::string, uint64_t> written_;
  bool changed_ = false;
  std::vector<ros::Subscriber> subs_;
  ros::Publisher progress_pub_;
  ros::WallTimer timer_;
};

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "crane_recorder");
  ros::NodeHandle nh, pnh("~");
  try {
    CraneRecorder recorder(nh, pnh);
    ros::spin();  // one thread: callbacks write in the order they arrive
    recorder.close();
  } catch (const std::exception& e) {
    ROS_FATAL("crane_recorder: %s", e.what());
    return 2;
  }
  return 0;
}
