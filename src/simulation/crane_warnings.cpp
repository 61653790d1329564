#include "crane_twin/simulation/crane_warnings.hpp"

namespace crane_twin {

void setCraneWarnings(const CraneModel& model, const CraneDrives& drives, SeriesValues& v) {
  const Scene& sc = model.scene;
  v.tension_ratio = v.rope_top_tension / model.rope.breaking_force;
  if (v.tension_ratio > 1.0) v.warnings |= kTensionOverBreakingForce;
  if (v.tension_ratio * sc.rope.safety_factor > 1.0) v.warnings |= kTensionOverWorkingLoadLimit;
  if (sc.crane) {
    v.load_chart_ratio = sc.payload_mass / allowedLoad(*sc.crane, drives.trolleyRadius());
    if (v.load_chart_ratio > 1.0 + 1e-12) v.warnings |= kOutsideLoadChart;
  }
  const DriveFlags &s = drives.slewFlags(), &t = drives.trolleyFlags(), &h = drives.hoistFlags();
  if (h.at_position_limit) v.warnings |= kRopeLengthAtLimit;
  if (t.at_position_limit) v.warnings |= kTrolleyAtLimit;
  if (s.speed_limited || t.speed_limited || h.speed_limited) v.warnings |= kCommandLimited;
}

}  // namespace crane_twin
