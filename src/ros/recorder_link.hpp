// RecorderLink: crane_sim_node's side of a recording (docs/ros.md "Recording"). Before the first
// step it waits until the recorder has subscribed to every recorded topic and our publishers have
// connected it (so a bag starts at t = 0); while running it holds the simulation when a recorder
// that reports its progress (crane_recorder's ~progress) is more than kWindow messages behind on a
// topic we publish (so a bag holds every message at any real_time_factor); at the end it waits
// until the recorder has written everything, and says how many messages it lost, if any.
#pragma once

#include <ros/ros.h>

#include <map>
#include <string>
#include <vector>

#include "crane_twin/RecorderProgress.h"

namespace crane_twin {

class RecorderLink {
 public:
  /// Messages a recorder may fall behind on one topic before the publisher waits for it.
  static constexpr uint64_t kWindow = 100;
  /// Wall time the connections must have stood before the first step [s]: without it a
  /// recording at real_time_factor 0 lost its first states.
  static constexpr double kSettleSeconds = 0.5;
  /// Wall time without progress after which a publisher stops waiting for its recorder [s].
  static constexpr double kStallSeconds = 10.0;

  RecorderLink() = default;
  /// recorder: a node name resolved in nh's namespace ("" = no recording); topics: the topics it
  /// records (resolved in nh's namespace).
  RecorderLink(ros::NodeHandle nh, const std::string& recorder,
               const std::vector<std::string>& topics);

  bool enabled() const { return !recorder_.empty(); }
  /// Polled before the first step: true once the recorder listens on every recorded topic and
  /// our own publishers (`own`) have connected every registered subscriber, for kSettleSeconds.
  bool ready(const std::vector<const ros::Publisher*>& own);
  /// Count one publication on `p` (a publisher of ours).
  void published(const ros::Publisher& p);
  /// True while a progress-reporting recorder is more than kWindow messages behind on a topic we
  /// publish (and has not stalled for kStallSeconds).
  bool behind();
  /// At the end: wait (at most kStallSeconds without progress) until the recorder has written
  /// what we published; log how many of our messages the bag holds.
  void drain();

 private:
  bool lagging(uint64_t window) const;
  void onProgress(const RecorderProgress::ConstPtr& p);
  ros::NodeHandle nh_;
  std::string recorder_;
  std::vector<std::string> topics_;
  ros::Subscriber progress_sub_;
  bool reports_progress_ = false;
  std::map<std::string, uint64_t> published_, written_;
  ros::WallTime seen_, last_check_, last_warn_, last_progress_;
  bool ready_ = false, stalled_ = false;
};

}  // namespace crane_twin
