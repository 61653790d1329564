#include "crane_twin/analysis/usage_counter.hpp"

#include <cmath>
#include <stdexcept>

#include "crane_twin/analysis/crane_classification.hpp"

namespace crane_twin {
namespace {

bool finiteNonNegative(double x) { return std::isfinite(x) && x >= 0.0; }

}  // namespace

UsageCounter::UsageCounter(const CraneModel& model)
    : payload_mass_(model.scene.payload_mass),
      max_load_(model.scene.crane ? model.scene.crane->max_load : 0.0),
      design_hours_(model.scene.crane ? model.scene.crane->design_hours : 0.0) {
  if (model.hot_spots) {
    for (const HotSpotRow& r : model.hot_spots->rows) {
      names_.push_back(r.name);
      curves_.push_back(SnCurve{r.detail_category, 1.0});
    }
  }
  counters_.resize(names_.size());
  closed_damage_.assign(names_.size(), 0.0);
}

UsageCounter::UsageCounter(const CraneModel& model, const UsageState& before)
    : UsageCounter(model) {
  const auto fail = [](const std::string& what) {
    throw std::invalid_argument("usage counts: " + what);
  };
  if (!finiteNonNegative(before.hours)) fail("hours must be >= 0");
  if (before.lift_count < 0) fail("the number of lifts must be >= 0");
  if (!finiteNonNegative(before.max_load) || !finiteNonNegative(before.mass_ratio_cubed_sum)) {
    fail("max_load and the sum of (m / m_max)^3 must be >= 0");
  }
  if (before.hot_spots.size() != names_.size()) {
    std::string mine, theirs;
    for (const std::string& n : names_) mine += (mine.empty() ? "" : ", ") + n;
    for (const auto& h : before.hot_spots) theirs += (theirs.empty() ? "" : ", ") + h.name;
    fail("counted " + std::to_string(before.hot_spots.size()) + " hot spots (" +
         (theirs.empty() ? "none" : theirs) + "), the crane file has " +
         std::to_string(names_.size()) + " (" + (mine.empty() ? "none" : mine) + ")");
  }
  for (std::size_t i = 0; i < names_.size(); ++i) {
    const UsageState::HotSpot& h = before.hot_spots[i];
    if (h.name != names_[i]) {
      fail("hot spot " + std::to_string(i + 1) + " was '" + h.name + "', the crane file's is '" +
           names_[i] + "'");
    }
    if (h.detail_category != curves_[i].detail_category) {
      fail("hot spot '" + h.name + "' was counted on detail category " +
           std::to_string(h.detail_category) + " MPa, the crane file's is " +
           std::to_string(curves_[i].detail_category));
    }
    if (!finiteNonNegative(h.closed_damage)) {
      fail("hot spot '" + h.name + "': the closed cycles' damage must be >= 0");
    }
    counters_[i] = RainflowCounter(h.counter);
    closed_damage_[i] = h.closed_damage;
  }
  hours_before_ = before.hours;
  lift_count_ = before.lift_count;
  earlier_cubed_sum_ = before.mass_ratio_cubed_sum;
  if (before.lift_count > 0 && max_load_ != before.max_load) {
    if (!(before.max_load > 0.0) || !(max_load_ > 0.0)) {
      fail("the lifts were counted with max_load " + std::to_string(before.max_load) +
           " kg, the crane file has " + std::to_string(max_load_));
    }
    earlier_cubed_sum_ *= std::pow(before.max_load / max_load_, 3);  // m_max changed
  }
  for (const LiftRecord& l : before.recent_lifts) {
    if (!finiteNonNegative(l.mass) || !std::isfinite(l.lift_off)) fail("a lift's figures");
    remember(l);
  }
}

void UsageCounter::remember(const LiftRecord& l) {
  lifts_.push_back(l);
  if (lifts_.size() > kRecentLifts) lifts_.pop_front();
}

double UsageCounter::massRatioCubed(double mass) const {
  return max_load_ > 0.0 ? std::pow(mass / max_load_, 3) : 0.0;
}

double UsageCounter::massRatioCubedSum() const {
  return earlier_cubed_sum_ + (last_from_this_count_ ? massRatioCubed(lifts_.back().mass) : 0.0);
}

void UsageCounter::observe(const SeriesValues& row, const LiftOffMonitor& lift_off,
                           double time_offset) {
  const double t = row.t + time_offset;
  if (std::isnan(t0_)) t0_ = t;
  t_ = t;
  // A new lift when the monitor confirms one; its factor grows over the monitor's window.
  if (lift_off.liftOffs() < seen_lift_offs_) seen_lift_offs_ = 0;  // a new monitor
  if (lift_off.liftOffs() > seen_lift_offs_) {
    earlier_cubed_sum_ = massRatioCubedSum();  // the last lift's mass is final now
    LiftRecord l;
    l.lift_off = lift_off.lastLiftOffTime() + time_offset;
    l.mass = payload_mass_;
    remember(l);
    ++lift_count_;
    last_from_this_count_ = true;
  }
  seen_lift_offs_ = lift_off.liftOffs();
  if (last_from_this_count_) {
    LiftRecord& l = lifts_.back();
    if (std::isnan(l.set_down)) {
      l.dynamic_factor = lift_off.lastFactor();
      // Set down where the monitor confirms it (a touch during the lift is none), dated at the
      // landing; a monitor started after the lift-off (a restored count) knows no lift: the
      // first landed row then.
      if (row.payload_landed && !lift_off.liftInProgress() && t > l.lift_off) {
        l.set_down = std::max(lift_off.landingTime() + time_offset, l.lift_off);
      }
    }
  }
  countStresses(row.stresses.data(), row.stresses.size());
}

void UsageCounter::observeStep(const Eigen::VectorXd& stresses) {
  countStresses(stresses.data(), static_cast<std::size_t>(stresses.size()));
}

void UsageCounter::countStresses(const double* stresses, std::size_t count) {
  // Each hot spot's cycles as they close (the history itself is not kept).
  std::vector<RainflowCycle> closed;
  for (std::size_t i = 0; i < counters_.size() && i < count; ++i) {
    closed.clear();
    counters_[i].add(stresses[i], closed);
    closed_damage_[i] += minerDamage(closed, curves_[i]);
  }
}

void UsageCounter::setPayloadMass(double mass) {
  payload_mass_ = mass;
  if (last_from_this_count_ && std::isnan(lifts_.back().set_down)) lifts_.back().mass = mass;
}

double UsageCounter::hours() const {
  return hours_before_ + (std::isnan(t0_) ? 0.0 : (t_ - t0_) / 3600.0);
}

UsageReport UsageCounter::report() const {
  UsageReport r;
  r.hours = hours();
  r.lift_count = lift_count_;
  r.lifts.assign(lifts_.begin(), lifts_.end());
  if (lift_count_ > 0) r.k_q = massRatioCubedSum() / static_cast<double>(lift_count_);
  r.u_class = utilisationClass(static_cast<double>(lift_count_));
  r.q_class = loadSpectrumClass(r.k_q);
  r.design_hours = design_hours_;
  if (design_hours_ > 0.0 && r.hours > 0.0 && lift_count_ > 0) {
    r.lifts_in_design_life = static_cast<double>(lift_count_) / r.hours * design_hours_;
    r.u_class_in_design_life = utilisationClass(r.lifts_in_design_life);
  }
  for (std::size_t i = 0; i < names_.size(); ++i) {
    HotSpotUsage u;
    u.name = names_[i];
    u.damage = closed_damage_[i] + minerDamage(counters_[i].finish(), curves_[i]);
    if (r.hours > 0.0) {
      u.damage_per_hour = u.damage / r.hours;
      if (u.damage_per_hour > 0.0) u.hours_to_failure = 1.0 / u.damage_per_hour;
    }
    u.short_of_design_life = design_hours_ > 0.0 && u.hours_to_failure < design_hours_;
    r.hot_spots.push_back(u);
  }
  return r;
}

UsageState UsageCounter::state() const {
  UsageState s;
  s.hours = hours();
  s.lift_count = lift_count_;
  s.max_load = max_load_;
  s.mass_ratio_cubed_sum = massRatioCubedSum();
  s.recent_lifts.assign(lifts_.begin(), lifts_.end());
  for (std::size_t i = 0; i < names_.size(); ++i) {
    s.hot_spots.push_back(
        {names_[i], curves_[i].detail_category, closed_damage_[i], counters_[i].state()});
  }
  return s;
}

}  // namespace crane_twin
