// The dynamic factor of a lift-off (docs/model.md "Ground contact"; EN 13001-2 / ISO 8686-1
// phi_2): the peak rope top tension over the static one in the window after the load leaves the
// ground. Fed the output rows of a run (docs/cli.md), whatever the model.
//   lift-off  at the first row without ground contact after rows with it, counted once the load
//             has stayed off the ground for kConfirmation and the rope is by then kReelIn
//             shorter than the longest it was while the load lay (a load that lands again sooner
//             bounced, one the hoist did not lift was thrown up by the structure or its swing:
//             neither is a lift);
//   set-down  once the lifted load has lain on the ground for kConfirmation, dated at the row
//             it landed: a shorter touch (the jib's bounce lowering a load that had only just
//             left the ground onto it again while the hoist reels in) is part of the lift, not
//             a set-down and a second lift;
//   phi_2     = max T_top(t) / T_static over [t_lift, t_lift + window], T_static the hanging
//               weight at that row's rope length (staticTopTension);
// a landing inside the window ends it. T_top at a row is the largest top tension of the steps
// since the row before where the caller gives it (StepTensionPeak), else the row's own.
#pragma once

#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

struct CraneModel;

/// The top tension of the load hanging at rest on rope length L [m]: (m_hook + m_payload +
/// mu L) g [N] (the rope's weight hangs from the top as well).
double staticTopTension(const CraneModel& model, double rope_length);

class LiftOffMonitor {
 public:
  static constexpr double kConfirmation = 0.5;  ///< [s] off the ground to count as a lift
  static constexpr double kReelIn = 0.01;       ///< [m] the hoist reeled in to lift it
  /// window > kConfirmation [s] after each lift-off. Throws std::invalid_argument otherwise.
  explicit LiftOffMonitor(double window = 3.0);
  /// One output row, the static top tension for it [N] and the largest top tension of the steps
  /// since the row before, the row's own included [N] (StepTensionPeak::takeAtRow).
  void observe(const SeriesValues& row, double static_tension, double peak_tension);
  /// The same with the row's own top tension for the peak.
  void observe(const SeriesValues& row, double static_tension) {
    observe(row, static_tension, row.rope_top_tension);
  }
  /// Lift-offs seen so far.
  int liftOffs() const { return lift_offs_; }
  /// The largest phi_2 over the lift-offs so far (0: none yet).
  double factor() const { return factor_; }
  /// phi_2 of the last lift-off so far (0: none yet), and its time [s].
  double lastFactor() const { return last_factor_; }
  double lastLiftOffTime() const { return last_time_; }
  /// Within a lift-off's window now (from the load's leaving, confirmed or not).
  bool measuring() const { return measuring_; }
  /// A confirmed lift whose load has not been set down yet (touches included).
  bool liftInProgress() const { return lifted_; }
  /// Set-downs of lifted loads so far, and the time of the row the load landed on the ground
  /// now or last [s].
  int setDowns() const { return set_downs_; }
  double landingTime() const { return landing_time_; }
  /// Warning bit kLiftOffOverDesignFactor for the row just observed: within a lift-off's window
  /// and its factor so far above design_phi2 (0: no check).
  int warningFor(double design_phi2) const {
    return design_phi2 > 0.0 && measuring_ && confirmed_ && last_factor_ > design_phi2
               ? kLiftOffOverDesignFactor
               : 0;
  }

 private:
  double window_;
  bool was_landed_ = false, measuring_ = false, confirmed_ = false;
  bool lifted_ = false;        ///< a confirmed lift not yet set down
  double landing_time_ = 0.0;  ///< the current (or last) landing's first row [s]
  int set_downs_ = 0;
  /// The longest rope while the load lay on the ground since the last lift ended [m].
  double landed_length_ = 0.0;
  double candidate_time_ = 0.0, candidate_factor_ = 0.0;  ///< the window under way
  int lift_offs_ = 0;
  double factor_ = 0.0, last_factor_ = 0.0, last_time_ = 0.0;
};

}  // namespace crane_twin
