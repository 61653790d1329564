// crane_sim_node's private parameters (docs/ros.md, "Interface"): what they are and how they are
// read and checked at start-up (a bad one stops the node with a message naming it).
#pragma once

#include <ros/ros.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "crane_twin/analysis/crane_snapshot.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/pacer.hpp"
#include "twin_adapter.hpp"
#include "usage_link.hpp"

namespace crane_twin {

/// Parameters of the node (private namespace), validated at start-up.
struct NodeSettings {
  std::string scene;
  std::vector<std::string> overrides;  ///< ~overrides: "key=value" like crane_sim's --set
  double real_time_factor = 1.0;       ///< 0: as fast as possible (drives /clock)
  double publish_rate = 30.0;          ///< Hz of simulated time
  /// Hz of wall time for the deformed structure's marker (thousands of points): when running
  /// faster than real time it would otherwise dominate the publishing (docs/ros.md).
  double structure_marker_rate = 10.0;
  double command_timeout = 0.5;  ///< s of simulated time, 0: never
  bool publish_clock = false;    ///< forced on when real_time_factor is 0
  /// Step to keep up with /clock (another node owns it, docs/site.md) instead of the wall
  /// clock; needs use_sim_time, excludes publish_clock, ignores real_time_factor.
  bool follow_clock = false;
  /// The owner of /clock does not run ahead of these followers (their crane/state topics) by
  /// more than 2.5 publication periods, so a site at real_time_factor 0 stays in lockstep.
  std::vector<std::string> clock_followers;
  double duration = -1.0;  ///< s; < 0: the scene's; 0: run until shut down
  bool shutdown_at_end = false;
  bool start_paused = false;  ///< wait for ~pause false before the first step
  std::string command_bag;    ///< replay crane/command_applied from this bag
  /// Hold the first step until this node (a recorder, resolved in the node's namespace)
  /// subscribes to every topic of recorded_topics, so a recording starts at t = 0; pace the run
  /// to it when it reports its progress (crane_recorder, RecorderLink).
  std::string wait_for_recorder;
  /// Before every frame the node publishes (docs/site.md), e.g. "crane_a/".
  std::string frame_prefix;
  /// ~base_pose [x, y, z, yaw] (m, rad): the mast foot on the site; empty: the scene's `site`.
  std::vector<double> base_pose;
  std::vector<std::string> recorded_topics;  ///< default: crane/state
  SnapshotOptions snapshot;
  TwinSettings twin;    ///< measured input, sway estimator, forecast (docs/twin.md)
  UsageSettings usage;  ///< ~usage_file, ~usage_save_period (docs/ros.md "Usage")
};

/// Read and check the private parameters. Throws InputError naming the parameter.
NodeSettings readNodeSettings(const ros::NodeHandle& pnh);

/// The mast foot on the site (world -> <prefix>base): ~base_pose if given, else the scene's
/// `site` (docs/site.md). position [m], yaw [rad] about world z.
struct BasePose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double yaw = 0.0;
};
BasePose basePoseOf(const NodeSettings& settings, const Scene& scene);

/// The node's pacing (Pacer): real_time_factor, a publication every 1 / publish_rate s, steps of
/// `time_step`, /clock followed or not; a twin races back from a lag within its catch-up
/// (docs/twin.md: its measurements are held until it gets there, TwinAdapter).
PacerSettings pacerSettingsOf(const NodeSettings& settings, double time_step);

}  // namespace crane_twin
