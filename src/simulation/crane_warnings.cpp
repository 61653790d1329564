#include "crane_twin/simulation/crane_warnings.hpp"

namespace crane_twin {

namespace {
// The tension bits for a ratio of the top tension to the breaking force of all falls.
int tensionWarnings(const CraneModel& model, double ratio) {
  int bits = 0;
  if (ratio > 1.0) bits |= kTensionOverBreakingForce;
  if (ratio * model.scene.rope.safety_factor > 1.0) bits |= kTensionOverWorkingLoadLimit;
  return bits;
}
}  // namespace

void setCraneWarnings(const CraneModel& model, const CraneDrives& drives, SeriesValues& v) {
  const Scene& sc = model.scene;
  v.tension_ratio = v.rope_top_tension / model.rope.breaking_force;
  v.warnings |= tensionWarnings(model, v.tension_ratio);
  if (sc.crane) {
    v.load_chart_ratio = sc.payload_mass / allowedLoad(*sc.crane, drives.trolleyRadius());
    if (v.load_chart_ratio > 1.0 + 1e-12) v.warnings |= kOutsideLoadChart;
  }
  const DriveFlags &s = drives.slewFlags(), &t = drives.trolleyFlags(), &h = drives.hoistFlags();
  if (h.at_position_limit) v.warnings |= kRopeLengthAtLimit;
  if (t.at_position_limit) v.warnings |= kTrolleyAtLimit;
  if (s.speed_limited || t.speed_limited || h.speed_limited) v.warnings |= kCommandLimited;
}

void addStepPeakTensionWarnings(const CraneModel& model, double peak_tension, SeriesValues& v) {
  v.warnings |= tensionWarnings(model, peak_tension / model.rope.breaking_force);
}

}  // namespace crane_twin
