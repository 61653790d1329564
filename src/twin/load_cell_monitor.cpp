#include "crane_twin/twin/load_cell_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace crane_twin {

// Sample times are sums of time steps: a hold of 0.2 s at 10 Hz is two samples, not three.
constexpr double kTimeTolerance = 1e-9;
constexpr double kPi = 3.14159265358979323846;

void LoadCellSettings::check() const {
  auto fail = [](const std::string& name, const std::string& what) {
    throw std::invalid_argument("load cell setting " + name + " " + what);
  };
  if (!(lift_fraction > 0.0 && lift_fraction < 1.0)) fail("lift_fraction", "must be in (0, 1)");
  if (!(set_down_fraction > 0.0 && set_down_fraction < lift_fraction)) {
    fail("set_down_fraction", "must be in (0, lift_fraction)");
  }
  for (auto [name, v] : {std::pair<const char*, double>{"lift_confirm", lift_confirm},
                         {"set_down_confirm", set_down_confirm},
                         {"lift_hoisting", lift_hoisting},
                         {"settle", settle},
                         {"change_threshold", change_threshold}}) {
    if (!(v >= 0.0 && std::isfinite(v))) fail(name, "must be a finite number >= 0");
  }
  if (!(window > 0.0 && std::isfinite(window))) fail("window", "must be a finite number > 0 [s]");
}

LoadCellMonitor::LoadCellMonitor(const LoadCellSettings& settings) : settings_(settings) {
  settings_.check();
}

void LoadCellMonitor::startWindow(double t) {
  window_start_ = t;
  sum_measured_ = sum_twin_ = 0.0;
}

void LoadCellMonitor::add(const LoadCellSample& s) {
  for (double v : {s.t, s.measured, s.twin, s.unloaded, s.end_mass, s.gravity, s.hoist_length}) {
    if (!std::isfinite(v)) throw std::invalid_argument("load cell sample: a value is not finite");
  }
  if (!(s.end_mass > 0.0)) throw std::invalid_argument("load cell sample: end mass must be > 0");
  const double weight = s.end_mass * s.gravity;
  const double e_measured = s.measured - s.unloaded, e_twin = s.twin - s.unloaded;
  if (!started_) {
    started_ = true;
    landed_ = e_measured < settings_.lift_fraction * weight;
    if (!landed_) windows_from_ = s.t;  // hanging from the start: windows at once
  }
  // The switch the end load asks for, confirmed after it held; a lift-off only by the hoist.
  if (landed_) longest_hoist_ = std::max(longest_hoist_, s.hoist_length);
  const bool crossing = landed_ ? e_measured > settings_.lift_fraction * weight &&
                                      s.hoist_length < longest_hoist_ - settings_.lift_hoisting
                                : e_measured < settings_.set_down_fraction * weight;
  if (!crossing) {
    switch_since_ = std::numeric_limits<double>::quiet_NaN();
  } else {
    if (std::isnan(switch_since_)) switch_since_ = s.t;
    // A hanging load's tension falls under a quarter of its weight while the hoist pays out
    // only when it lands: then at once (the jib springing back may pull the rope up again
    // within the confirmation time, for a period of the jib, about 2 s).
    const bool lowering = !std::isnan(last_hoist_) && s.hoist_length > last_hoist_;
    const double hold =
        landed_ ? settings_.lift_confirm : (lowering ? 0.0 : settings_.set_down_confirm);
    if (s.t - switch_since_ >= hold - kTimeTolerance) {
      landed_ = !landed_;
      if (landed_) {
        longest_hoist_ = s.hoist_length;
        ++set_downs_;
        last_set_down_ = switch_since_;
        windows_from_ = std::numeric_limits<double>::infinity();
      } else {
        ++lifts_;
        last_lift_off_ = switch_since_;
        windows_from_ = switch_since_ + settings_.settle;
      }
      window_start_ = std::numeric_limits<double>::quiet_NaN();
      switch_since_ = std::numeric_limits<double>::quiet_NaN();
    }
  }
  last_hoist_ = s.hoist_length;
  // The mass windows: the load hanging in both, the twin's end mass unchanged.
  if (landed_ || s.twin_landed || s.t < windows_from_) {
    window_start_ = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  if (std::isnan(window_start_) || s.end_mass != window_mass_) {
    window_mass_ = s.end_mass;
    startWindow(s.t);
  }
  // Hann weights: the rope's axial ringing after a lift-off (about 1 Hz, up to a third of the
  // weight, in the crane and in the twin at different frequencies and phases) leaks into a
  // window's mean as (pi f T)^-1 unweighted, as (pi f T)^-1 / ((f T)^2 - 1) with them.
  const double u = std::min((s.t - window_start_) / settings_.window, 1.0);
  const double w = std::pow(std::sin(kPi * u), 2);
  sum_measured_ += w * e_measured;
  sum_twin_ += w * e_twin;
  if (s.t - window_start_ < settings_.window - kTimeTolerance) return;
  if (sum_twin_ > 0.0 && sum_measured_ > 0.0) {
    estimate_ = window_mass_ * sum_measured_ / sum_twin_;
    if (std::abs(estimate_ - window_mass_) > settings_.change_threshold * window_mass_) {
      offered_ = estimate_;
    }
  }
  startWindow(s.t);
}

std::optional<double> LoadCellMonitor::takeEndMass() {
  std::optional<double> m = offered_;
  offered_.reset();
  return m;
}

}  // namespace crane_twin
