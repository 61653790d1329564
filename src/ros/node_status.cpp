#include "node_status.hpp"

#include "crane_twin/simulation/crane_warnings.hpp"
#include "ros_messages.hpp"

namespace crane_twin {

diagnostic_msgs::DiagnosticStatus simulationStatus(const NodeRunRecord& r) {
  diagnostic_msgs::DiagnosticStatus d;
  d.name = r.node_name + ": simulation";  // one per crane on a site
  d.hardware_id = r.scene_file;
  const bool slow = r.requested_real_time_factor > 0.0 && !r.paused && !r.finished &&
                    r.real_time_factor < 0.9 * r.requested_real_time_factor;
  if (!r.failure.empty()) {
    d.level = diagnostic_msgs::DiagnosticStatus::ERROR;
    d.message = "stopped: " + r.failure;
  } else if (slow) {
    d.level = diagnostic_msgs::DiagnosticStatus::WARN;
    d.message = "behind the requested real-time factor";
  } else {
    d.level = diagnostic_msgs::DiagnosticStatus::OK;
    d.message = r.paused ? "paused" : r.finished ? "end of scene reached" : "running";
  }
  addNumber(d, "sim_time_s", r.sim_time);
  addNumber(d, "real_time_factor", r.real_time_factor);
  addNumber(d, "requested_real_time_factor", r.requested_real_time_factor);
  addNumber(d, "step_cost_s", r.step_cost);
  addNumber(d, "steps", static_cast<double>(r.steps));
  if (r.statistics.subdomains > 0) {  // the subdomain reduction's count, shown where it runs
    addNumber(d, "subdomains", r.statistics.subdomains);
    addNumber(d, "mode_updates_s", r.statistics.mode_update_seconds);
  }
  addNumber(d, "hand_overs", static_cast<double>(r.statistics.hand_overs));
  addNumber(d, "full_order_steps", static_cast<double>(r.statistics.full_order_steps));
  addNumber(d, "hand_backs_taken_back", static_cast<double>(r.statistics.hand_backs_taken_back));
  addNumber(d, "rejected_commands", static_cast<double>(r.rejected_commands));
  addNumber(d, "pacing_overruns", static_cast<double>(r.pacing_overruns));
  addNumber(d, "warnings_seen", r.warnings_seen);
  std::string names;
  for (int bit = 1; bit <= kLastWarning; bit <<= 1)
    if (r.warnings_seen & bit) names += (names.empty() ? "" : "; ") + std::string(warningName(bit));
  addKeyValue(d, "warnings_seen_names", names.empty() ? "none" : names);
  addNumber(d, "wind_3s", r.wind_3s);
  addKeyValue(d, "rope_model", r.rope_model);
  return d;
}

}  // namespace crane_twin
