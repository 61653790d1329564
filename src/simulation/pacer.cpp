#include "crane_twin/simulation/pacer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace crane_twin {

Pacer::Pacer(const PacerSettings& s) : settings_(s) {
  if (!std::isfinite(s.real_time_factor) || s.real_time_factor < 0.0)
    throw std::invalid_argument("pacer: real_time_factor must be finite and >= 0, got " +
                                std::to_string(s.real_time_factor));
  if (!(s.publish_period > 0.0) || !std::isfinite(s.publish_period))
    throw std::invalid_argument("pacer: the publication period must be > 0");
  if (!(s.time_step > 0.0) || !std::isfinite(s.time_step))
    throw std::invalid_argument("pacer: the time step must be > 0");
  if (!std::isfinite(s.catch_up) || s.catch_up < 0.0)
    throw std::invalid_argument("pacer: catch_up must be finite and >= 0, got " +
                                std::to_string(s.catch_up));
}

void Pacer::restart(double wall, double sim) {
  anchor_wall_ = wall;
  anchor_sim_ = sim;
}

Pacer::Decision Pacer::decide(double wall, double sim, double next_publish, double slowest_follower,
                              double clock) {
  const double half = 0.5 * settings_.time_step, period = settings_.publish_period;
  Decision d;
  d.target = next_publish;
  // Lockstep: no further than kFollowerLead periods ahead of the slowest follower.
  if (slowest_follower != std::numeric_limits<double>::infinity()) {
    d.target = std::min(d.target, slowest_follower + kFollowerLead * period);
    if (sim + half > d.target) {
      d.wait = Wait::followers;
      d.sleep = 0.0005;
      return d;
    }
  }
  if (settings_.follow_clock) {
    d.target = std::min(d.target, clock);
    if (sim + half > d.target) {
      d.wait = Wait::clock;
      d.sleep = 0.001;
    }
    return d;
  }
  const double f = settings_.real_time_factor;
  if (f > 0.0) {
    double paced = anchor_sim_ + f * (wall - anchor_wall_);
    // Too far behind: re-anchor, do not race.
    if (paced - sim > std::max(0.25 * f + period, settings_.catch_up)) {
      ++overruns_;
      restart(wall, sim);
      paced = sim;
    }
    d.target = std::min(d.target, paced);
    if (sim + half > d.target) {
      d.wait = Wait::wall;
      // Until the next step (or publication) is due on the wall clock, within [0.1, 10] ms.
      d.sleep =
          std::clamp((std::min(next_publish, sim + settings_.time_step) - paced) / f, 1e-4, 0.01);
    }
  }
  return d;
}

}  // namespace crane_twin
