#include "crane_twin/drives/trajectory_follower.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace crane_twin {

namespace {
const char* const kAxis[3] = {"slew", "trolley", "hoist"};

std::array<double, 3> positions(const CraneDrives& d) {
  return {d.slewAngle(), d.trolleyRadius(), d.hoistLength()};
}
std::array<double, 3> speeds(const CraneDrives& d) {
  return {d.slewRate(), d.trolleySpeed(), d.hoistSpeed()};
}
std::array<const DriveLimits*, 3> limits(const CraneDescription& c) {
  return {&c.slewing, &c.trolley, &c.hoist};
}
}  // namespace

std::string TrajectoryFollower::validate(const std::vector<TrajectoryPoint>& points,
                                         const CraneDescription& c) {
  if (points.empty()) return "a trajectory needs at least one point";
  std::ostringstream why;
  double last = -1.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const TrajectoryPoint& p = points[k];
    if (!std::isfinite(p.time_from_start) || p.time_from_start < 0.0 || p.time_from_start <= last) {
      why << "point " << k << ": time_from_start " << p.time_from_start
          << " s must be finite, >= 0 and after the previous point's";
      return why.str();
    }
    last = p.time_from_start;
    for (int a = 0; a < 3; ++a) {
      if (!p.target[a]) continue;
      const double v = *p.target[a];
      if (!std::isfinite(v)) {
        why << "point " << k << ": " << kAxis[a] << " is not a finite number";
        return why.str();
      }
      const double lo = a == 1 ? c.min_radius : c.min_rope_length;
      const double hi = a == 1 ? c.max_radius : c.max_rope_length;
      if (a > 0 && (v < lo || v > hi)) {
        why << "point " << k << ": " << kAxis[a] << " " << v << " m is outside the crane's "
            << (a == 1 ? "radius" : "rope length") << " limits [" << lo << ", " << hi << "] m";
        return why.str();
      }
    }
  }
  return "";
}

void TrajectoryFollower::start(std::vector<TrajectoryPoint> points, double t) {
  points_ = std::move(points);
  next_ = 0;
  start_ = t;
  reached_ = false;
}

CommandEntry TrajectoryFollower::command(double t, const CraneDrives& drives,
                                         const CraneDescription& crane) {
  CommandEntry cmd;
  cmd.t = t;
  if (points_.empty()) return cmd;
  const std::array<double, 3> x = positions(drives), v = speeds(drives);
  const std::array<const DriveLimits*, 3> lim = limits(crane);
  // Done points (every named axis within tolerance and at rest, time passed) make way.
  while (next_ < points_.size()) {
    const TrajectoryPoint& p = points_[next_];
    bool done = t - start_ >= p.time_from_start - 1e-12;
    for (int a = 0; a < 3 && done; ++a)
      if (p.target[a])
        done = std::abs(*p.target[a] - x[a]) <= kTolerance[a] && std::abs(v[a]) <= kRestSpeed[a];
    if (!done) break;
    ++next_;
  }
  if (next_ == points_.size()) {
    points_.clear();
    reached_ = true;
    return cmd;  // at rest
  }
  const TrajectoryPoint& p = points_[next_];
  double rate[3] = {0.0, 0.0, 0.0};
  for (int a = 0; a < 3; ++a) {
    if (!p.target[a]) continue;
    const double e = *p.target[a] - x[a];
    if (std::abs(e) <= kTolerance[a]) continue;
    const double vb = std::sqrt(2.0 * kBrakingFraction * lim[a]->max_acceleration * std::abs(e));
    rate[a] = std::copysign(std::min(lim[a]->max_speed, vb), e);
  }
  cmd.slew_rate = rate[0];
  cmd.trolley_speed = rate[1];
  cmd.hoist_speed = rate[2];
  return cmd;
}

}  // namespace crane_twin
