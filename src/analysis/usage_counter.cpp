#include "crane_twin/analysis/usage_counter.hpp"

#include <cmath>

namespace crane_twin {

UsageCounter::UsageCounter(const CraneModel& model)
    : payload_mass_(model.scene.payload_mass),
      max_load_(model.scene.crane ? model.scene.crane->max_load : 0.0) {
  if (model.hot_spots) {
    for (const HotSpotRow& r : model.hot_spots->rows) {
      names_.push_back(r.name);
      curves_.push_back(SnCurve{r.detail_category, 1.0});
    }
  }
  counters_.resize(names_.size());
  closed_damage_.assign(names_.size(), 0.0);
}

void UsageCounter::observe(const SeriesValues& row, const LiftOffMonitor& lift_off,
                           double time_offset) {
  const double t = row.t + time_offset;
  if (std::isnan(t0_)) t0_ = t;
  t_ = t;
  // A new lift when the monitor confirms one; its factor grows over the monitor's window.
  if (lift_off.liftOffs() < seen_lift_offs_) seen_lift_offs_ = 0;  // a new monitor
  if (lift_off.liftOffs() > seen_lift_offs_) {
    LiftRecord l;
    l.lift_off = lift_off.lastLiftOffTime() + time_offset;
    l.mass = payload_mass_;
    lifts_.push_back(l);
  }
  seen_lift_offs_ = lift_off.liftOffs();
  if (!lifts_.empty()) {
    LiftRecord& l = lifts_.back();
    if (std::isnan(l.set_down)) {
      l.dynamic_factor = lift_off.lastFactor();
      if (row.payload_landed && t > l.lift_off) l.set_down = t;
    }
  }
  // Each hot spot's cycles as they close (the history itself is not kept).
  std::vector<RainflowCycle> closed;
  for (std::size_t i = 0; i < counters_.size() && i < row.stresses.size(); ++i) {
    closed.clear();
    counters_[i].add(row.stresses[i], closed);
    closed_damage_[i] += minerDamage(closed, curves_[i]);
  }
}

void UsageCounter::setPayloadMass(double mass) {
  payload_mass_ = mass;
  if (!lifts_.empty() && std::isnan(lifts_.back().set_down)) lifts_.back().mass = mass;
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
    u.damage = closed_damage_[i] + minerDamage(counters_[i].finish(), curves_[i]);
    if (r.hours > 0.0) {
      u.damage_per_hour = u.damage / r.hours;
      if (u.damage_per_hour > 0.0) u.hours_to_failure = 1.0 / u.damage_per_hour;
    }
    r.hot_spots.push_back(u);
  }
  return r;
}

}  // namespace crane_twin
