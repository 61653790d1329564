#include "crane_twin/analysis/usage_counter.hpp"

#include <cmath>

#include "crane_twin/analysis/rainflow.hpp"

namespace crane_twin {

UsageCounter::UsageCounter(const CraneModel& model)
    : payload_mass_(model.scene.payload_mass),
      max_load_(model.scene.crane ? model.scene.crane->max_load : 0.0) {
  if (model.hot_spots) {
    for (const HotSpotRow& r : model.hot_spots->rows) {
      names_.push_back(r.name);
      categories_.push_back(r.detail_category);
    }
  }
  turning_.resize(names_.size());
}

void UsageCounter::observe(const SeriesValues& row, const LiftOffMonitor& lift_off) {
  if (std::isnan(t0_)) t0_ = row.t;
  t_ = row.t;
  // A new lift when the monitor confirms one; its factor grows over the monitor's window.
  if (static_cast<int>(lifts_.size()) < lift_off.liftOffs()) {
    LiftRecord l;
    l.lift_off = lift_off.lastLiftOffTime();
    l.mass = payload_mass_;
    lifts_.push_back(l);
  }
  if (!lifts_.empty()) {
    LiftRecord& l = lifts_.back();
    if (std::isnan(l.set_down)) {
      l.dynamic_factor = lift_off.lastFactor();
      if (row.payload_landed && row.t > l.lift_off) l.set_down = row.t;
    }
  }
  // Turning points as they come (the history itself is not kept).
  for (std::size_t i = 0; i < turning_.size() && i < row.stresses.size(); ++i) {
    std::vector<double>& p = turning_[i];
    const double x = row.stresses[i];
    if (!p.empty() && x == p.back()) continue;
    if (p.size() >= 2 && (p.back() - p[p.size() - 2]) * (x - p.back()) > 0.0) {
      p.back() = x;
    } else {
      p.push_back(x);
    }
  }
}

UsageReport UsageCounter::report() const {
  UsageReport r;
  r.hours = std::isnan(t0_) ? 0.0 : (t_ - t0_) / 3600.0;
  r.lifts = lifts_;
  if (!lifts_.empty() && max_load_ > 0.0) {
    double sum = 0.0;
    for (const LiftRecord& l : lifts_) sum += std::pow(l.mass / max_load_, 3);
    r.k_q = sum / static_cast<double>(lifts_.size());
  }
  for (std::size_t i = 0; i < names_.size(); ++i) {
    HotSpotUsage u;
    u.name = names_[i];
    u.damage = minerDamage(rainflowCount(turning_[i]), SnCurve{categories_[i], 1.0});
    if (r.hours > 0.0) {
      u.damage_per_hour = u.damage / r.hours;
      if (u.damage_per_hour > 0.0) u.hours_to_failure = 1.0 / u.damage_per_hour;
    }
    r.hot_spots.push_back(u);
  }
  return r;
}

}  // namespace crane_twin
