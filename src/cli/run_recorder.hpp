// What `crane_sim run` makes of a run's steps (docs/cli.md "run"): the output rows (--out,
// --nodes), the physical warnings, the lift-off monitor, the steps' tension peak and the usage
// count; and the rows of a speculation (docs/cli.md "Rows of a speculation"): while a reduced
// rope's hand-back is speculative (SpeculationFollower), its rows, warnings and monitors'
// updates are held back; kept, they are written; taken back, they are dropped, the monitors
// return to where the speculation began, and full order's re-integrated steps are recorded in
// their place, so every row written is full order's wherever full order took the steps in the
// end.
#pragma once

#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "crane_twin/analysis/usage_counter.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/lift_off_monitor.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/speculation_follower.hpp"
#include "crane_twin/simulation/step_tension_peak.hpp"

namespace crane_twin {

class RunRecorder {
 public:
  /// Records `sim` (initialised, at t = 0) into `series` and `nodes` (either may be null), a row
  /// every `every` steps; `progress_bar` true when stderr shows a progress bar (a warning then
  /// starts on a new line). Follows sim's speculations until destroyed.
  RunRecorder(const CraneModel& model, Simulation& sim, std::ostream* series, std::ostream* nodes,
              long every, bool progress_bar);
  RunRecorder(const RunRecorder&) = delete;
  RunRecorder& operator=(const RunRecorder&) = delete;

  /// The start's row (step 0), after sim.initialize().
  void recordStart() { follower_.start(); }
  /// After sim.step() of step k (1, 2, ...): the step's tension and stresses, and its row.
  void recordStep(long k) { follower_.step(k); }
  /// At the run's end (also after a numerical failure): what a speculation still open holds
  /// is written as it is.
  void finish() { follower_.finish(); }

  /// The warning bits seen and, per bit, the rows that carried it.
  const std::map<int, long>& warned() const { return monitors_.warned; }
  const LiftOffMonitor& liftOff() const { return monitors_.lift_off; }
  double peakTension() const { return monitors_.peak_tension; }
  UsageReport usage() const { return monitors_.usage.report(); }

 private:
  // What the recorded steps have built up: copied where a speculation begins, put back where it
  // is taken back.
  struct Monitors {
    std::map<int, long> warned;
    LiftOffMonitor lift_off;
    StepTensionPeak tension_peak;
    double peak_tension = 0.0;  ///< the run's largest top tension, every step [N]
    UsageCounter usage;
  };
  // Step k's record (k = 0: the start's row alone).
  void record(long k);
  void emit();
  void warn(const std::string& message);
  // The follower's events (SpeculationFollower::Recording): a speculation opens; its held-back
  // rows and messages written out (kept, or the run's end); dropped (taken back).
  void hold();
  void release();
  void drop();

  const CraneModel& model_;
  Simulation& sim_;
  std::ostream* series_;
  std::ostream* nodes_;
  long every_;
  bool progress_bar_;
  Monitors monitors_;
  // An open speculation's: the monitors at its checkpoint (null: none open), its rows and
  // warnings held back.
  std::unique_ptr<Monitors> at_checkpoint_;
  std::ostringstream held_series_, held_nodes_;
  std::vector<std::string> held_messages_;
  SpeculationFollower follower_;  ///< (last: its events use the members above)
};

}  // namespace crane_twin
