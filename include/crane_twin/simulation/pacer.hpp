// Pacer: when a simulation run in a loop may take its next steps (docs/ros.md "Keeping real
// time"). The ROS node asks it on every turn of its loop; it owns no clock: the caller passes
// wall time, simulated time and the other clocks it follows, so the rules are tested without
// ROS (test/pacer_test.cpp).
//
// The simulated time the run may step to, target, is the next publication time t_pub limited by
//  - lockstep with followers (a site's other cranes, docs/site.md): at most
//    kFollowerLead publication periods ahead of the slowest follower's simulated time;
//  - following another node's /clock (follow_clock): the clock's time;
//  - real_time_factor f > 0: the paced time t_a + f (w - w_a) from an anchor (w_a, t_a); a lag
//    of more than max(0.25 f + one publication period, catch_up) re-anchors at the present (an
//    overrun, counted) instead of racing to catch up. Within it the run steps as fast as it can
//    until it is back on time: a twin (catch_up of seconds) keeps the crane's time through a
//    slow stretch; a plain run (catch_up 0) does not race after a stall.
// With f = 0 and nothing to follow the run steps from one publication to the next at once.
// A step of h is taken while t + h / 2 <= target.
#pragma once

namespace crane_twin {

struct PacerSettings {
  double real_time_factor = 1.0;       ///< simulated / wall seconds; 0: as fast as possible
  double publish_period = 1.0 / 30.0;  ///< simulated seconds between publications
  double time_step = 0.005;            ///< the simulation's step h [s]
  bool follow_clock = false;           ///< keep up with another node's /clock instead
  double catch_up = 0.0;  ///< a lag [simulated s] the run still races to catch up (>= 0)
};

class Pacer {
 public:
  /// Publication periods the clock's owner may run ahead of its slowest follower.
  static constexpr double kFollowerLead = 2.5;

  /// What holds the run back (none: step to target now).
  enum class Wait { none, followers, clock, wall };
  struct Decision {
    double target = 0.0;  ///< step while t + h / 2 <= target [s]
    Wait wait = Wait::none;
    double sleep = 0.0;  ///< suggested wall time to sleep before asking again [s]
  };

  /// Throws std::invalid_argument for a negative or non-finite factor or catch-up, a period or
  /// step not > 0.
  explicit Pacer(const PacerSettings& settings);

  /// (Re)start pacing at wall time `wall` and simulated time `sim` (after a pause or reset).
  void restart(double wall, double sim);
  /// The decision at wall time `wall` for a run at simulated time `sim` whose next publication
  /// is at `next_publish`; `slowest_follower` is the slowest follower's simulated time (pass
  /// +infinity without followers; -infinity while one has not reported), `clock` the followed
  /// /clock's time (ignored unless follow_clock).
  Decision decide(double wall, double sim, double next_publish, double slowest_follower,
                  double clock);
  /// Re-anchorings because the run lagged more than the margin behind the wall clock.
  long overruns() const { return overruns_; }
  const PacerSettings& settings() const { return settings_; }

 private:
  PacerSettings settings_;
  double anchor_wall_ = 0.0, anchor_sim_ = 0.0;
  long overruns_ = 0;
};

}  // namespace crane_twin
