// Operator commands from outside (the ROS node's crane/command topic, docs/ros.md) checked before
// they reach the drives, and the command timeout. ROS-free, so both are unit-tested here.
#pragma once

#include <string>

#include "crane_twin/io/scene.hpp"

namespace crane_twin {

/// A rate more than this many times a drive's speed limit is taken as garbage, not a command.
constexpr double kAbsurdCommandFactor = 10.0;

struct CommandVerdict {
  bool accepted = false;
  bool over_limit = false;  ///< accepted, but a rate above a speed limit: the drive limits it
  std::string reason;       ///< why it was rejected, or which rate is over its limit
};

/// Rejects a command with a non-finite rate, any motion without a crane, or a rate above
/// kAbsurdCommandFactor x the drive's speed limit (docs/model.md); flags one above the limit.
/// The reason names the field, its value and the limit.
CommandVerdict checkCommand(const Scene& scene, const CommandEntry& command);

/// The command timeout of docs/ros.md, in simulated seconds: a manual command older than
/// `timeout` ramps the drives to rest (the caller then sets a zero command).
class CommandWatchdog {
 public:
  /// timeout >= 0 [s]; 0 disables the timeout. Throws std::invalid_argument otherwise.
  explicit CommandWatchdog(double timeout);
  /// A command was applied at simulated time t.
  void received(double t);
  /// True exactly once when the last command has grown older than the timeout at time t.
  bool expired(double t);
  double timeout() const { return timeout_; }

 private:
  double timeout_;
  double last_ = 0.0;
  bool armed_ = false;
};

}  // namespace crane_twin
