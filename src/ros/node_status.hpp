// crane_sim_node's diagnostic status "<node>: simulation" (docs/ros.md, /diagnostics): how the
// run goes (ERROR after a numerical failure, WARN behind the requested real-time factor) and
// what it has counted, from a plain record the node fills once a second.
#pragma once

#include <diagnostic_msgs/DiagnosticStatus.h>

#include <string>

#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

struct NodeRunRecord {
  std::string node_name, scene_file, rope_model;
  bool paused = false, finished = false;
  std::string failure;  ///< non-empty: the simulation stopped, why
  double sim_time = 0.0, real_time_factor = 0.0, requested_real_time_factor = 0.0;
  double step_cost = 0.0;  ///< [s] of wall time per step, over the last publication period
  long steps = 0, rejected_commands = 0, pacing_overruns = 0;
  int warnings_seen = 0;  ///< OR of the warning bits published
  double wind_3s = 0.0;   ///< [m/s]
  RunStatistics statistics;
};

/// The status of `r`: WARN when the run is not paused or finished and runs below 0.9 times a
/// requested real-time factor > 0.
diagnostic_msgs::DiagnosticStatus simulationStatus(const NodeRunRecord& r);

}  // namespace crane_twin
