// Recording a run whose latest steps a later step may replace (SpeculativeRun; docs/cli.md
// "Rows of a speculation"): the one place that follows a run's speculations for whatever
// records its steps (crane_sim run's rows and monitors, the sweep's samples). The recording
// says what to do at each event; the follower says when:
//  - record(k): step k's record (k = 0: the start), in order, the re-integrated steps of a
//    take-back included;
//  - hold(): a speculation opens, before the record of the step it opens at: what is recorded
//    from here on may be replaced;
//  - keep(): it is kept (its window passed, or the run ends with it open): what was held stands;
//  - drop(): it is taken back, before the re-integrated steps are recorded from the one it
//    opened at: what was recorded since hold() goes.
#pragma once

#include <functional>

#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"

namespace crane_twin {

class SpeculationFollower {
 public:
  struct Recording {
    std::function<void(long step)> record;
    std::function<void()> hold, keep, drop;  ///< may be empty: nothing to do
  };
  /// Follows `sim` (a run without the capability never speculates: record alone is called);
  /// registers itself as sim's replay observer until destroyed.
  SpeculationFollower(Simulation& sim, Recording recording);
  ~SpeculationFollower();
  SpeculationFollower(const SpeculationFollower&) = delete;
  SpeculationFollower& operator=(const SpeculationFollower&) = delete;

  /// After sim.initialize(): the start's record.
  void start() { follow(0); }
  /// After sim.step() of step k (1, 2, ...).
  void step(long k);
  /// At the run's end (also after a failure): an open speculation is kept as it is.
  void finish();
  /// A speculation is open and its records held.
  bool holding() const { return holding_; }

 private:
  // A speculation opening at step k (held from its record on), then step k's record.
  void follow(long k);
  // Within the step() that takes the speculation back (SpeculativeRun::ReplayObserver).
  void replayed(long replayed_steps);
  // The open speculation is kept: what was held stands.
  void keepHeld();
  static void call(const std::function<void()>& f) {
    if (f) f();
  }

  SpeculativeRun* speculative_;  ///< sim's capability, or null
  Recording recording_;
  bool holding_ = false;
  long checkpoint_step_ = 0;  ///< the step the open speculation began at
};

}  // namespace crane_twin
