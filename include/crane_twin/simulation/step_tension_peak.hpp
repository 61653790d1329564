// The largest rope top tension of the steps between two output rows. Rows (docs/cli.md, every
// output_interval; the node's publications) sample an undamped snatch's ringing too coarsely for
// its crests: a 10 t lift-off thrown on four falls read a dynamic factor of 2.143 from rows every
// 10 ms and 2.348 from every step (docs/model.md "Ground contact"). The lift-off factor
// (LiftOffMonitor) and the tension warnings (addStepPeakTensionWarnings) read this peak.
#pragma once

#include <algorithm>
#include <limits>

namespace crane_twin {

class StepTensionPeak {
 public:
  /// The top tension after one step [N] (Simulation::topTension).
  void addStep(double top_tension) { peak_ = std::max(peak_, top_tension); }
  /// The peak over the steps since the previous row and the row's own tension [N]; the next
  /// interval starts empty.
  double takeAtRow(double row_tension) {
    const double p = std::max(peak_, row_tension);
    peak_ = -std::numeric_limits<double>::infinity();
    return p;
  }

 private:
  double peak_ = -std::numeric_limits<double>::infinity();
};

}  // namespace crane_twin
