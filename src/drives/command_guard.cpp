#include "crane_twin/drives/command_guard.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace crane_twin {

namespace {

struct Field {
  const char* name;
  double value;
  double limit;  ///< speed limit, 0 without a crane
  const char* unit;
};

}  // namespace

CommandVerdict checkCommand(const Scene& scene, const CommandEntry& c) {
  const CraneDescription* crane = scene.crane ? &*scene.crane : nullptr;
  const Field fields[] = {
      {"slew_rate", c.slew_rate, crane ? crane->slewing.max_speed : 0.0, "rad/s"},
      {"trolley_speed", c.trolley_speed, crane ? crane->trolley.max_speed : 0.0, "m/s"},
      {"hoist_speed", c.hoist_speed, crane ? crane->hoist.max_speed : 0.0, "m/s"},
  };
  CommandVerdict v;
  std::ostringstream over;
  for (const Field& f : fields) {
    std::ostringstream why;
    if (!std::isfinite(f.value)) {
      why << f.name << " is " << f.value << " (not a finite number)";
    } else if (!crane && f.value != 0.0) {
      why << f.name << " = " << f.value << " " << f.unit << " but the scene has no crane to drive";
    } else if (crane && std::abs(f.value) > kAbsurdCommandFactor * f.limit) {
      why << f.name << " = " << f.value << " " << f.unit << " is beyond " << kAbsurdCommandFactor
          << " x the speed limit " << f.limit << " " << f.unit;
    } else {
      if (crane && std::abs(f.value) > f.limit) {
        v.over_limit = true;
        over << (over.tellp() > 0 ? "; " : "") << f.name << " = " << f.value << " " << f.unit
             << " limited to " << f.limit;
      }
      continue;
    }
    v.accepted = false;
    v.over_limit = false;
    v.reason = why.str();
    return v;
  }
  v.accepted = true;
  v.reason = over.str();
  return v;
}

CommandWatchdog::CommandWatchdog(double timeout) : timeout_(timeout) {
  if (!std::isfinite(timeout) || timeout < 0.0) {
    throw std::invalid_argument("command timeout must be a finite number >= 0 (0 disables it)");
  }
}

void CommandWatchdog::received(double t) {
  last_ = t;
  armed_ = timeout_ > 0.0;
}

bool CommandWatchdog::expired(double t) {
  if (!armed_ || t - last_ <= timeout_) return false;
  armed_ = false;
  return true;
}

}  // namespace crane_twin
