#include "crane_twin/simulation/lift_off_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "crane_twin/simulation/crane_model.hpp"

namespace crane_twin {

double staticTopTension(const CraneModel& m, double rope_length) {
  return (m.hangingPointMass() + m.rope.mass_per_length * rope_length) * m.scene.gravity;
}

LiftOffMonitor::LiftOffMonitor(double window) : window_(window) {
  if (!(std::isfinite(window) && window > kConfirmation))
    throw std::invalid_argument("lift-off window must be finite and longer than the confirmation");
}

void LiftOffMonitor::observe(const SeriesValues& row, double static_tension, double peak_tension) {
  if (row.payload_landed) {
    if (!was_landed_) {
      landing_time_ = row.t;
      // A lifted load's landing: the hoist must reel in anew from the longest rope it lies on
      // from here (not read while the lift goes on). After a bounce (a lift not confirmed)
      // the load lies as it lay before.
      if (lifted_) landed_length_ = row.rope_length;
    }
    was_landed_ = true;
    measuring_ = false;  // landed again: the window ends (and a bounce is forgotten)
    landed_length_ = std::max(landed_length_, row.rope_length);
    // Set down once it has lain kConfirmation; a touch until then.
    if (lifted_ && row.t >= landing_time_ + kConfirmation - 1e-9) {
      lifted_ = false;
      ++set_downs_;
    }
    return;
  }
  if (was_landed_) {
    was_landed_ = false;
    if (lifted_) return;  // a touch: the lift goes on (its window ended at the touch)
    measuring_ = true;
    confirmed_ = false;
    candidate_time_ = row.t;
    candidate_factor_ = 0.0;
  }
  if (!measuring_) return;
  if (row.t > candidate_time_ + window_) {
    measuring_ = false;
    return;
  }
  if (static_tension > 0.0)
    candidate_factor_ = std::max(candidate_factor_, peak_tension / static_tension);
  if (!confirmed_ && row.t >= candidate_time_ + kConfirmation &&
      landed_length_ - row.rope_length >= kReelIn) {
    confirmed_ = true;  // off the ground long enough: a lift, not a bounce
    lifted_ = true;
    ++lift_offs_;
    last_time_ = candidate_time_;
  }
  if (confirmed_) {
    last_factor_ = candidate_factor_;
    factor_ = std::max(factor_, last_factor_);
  }
}

}  // namespace crane_twin
