#include "run_recorder.hpp"

#include <algorithm>
#include <cstdio>

#include "crane_twin/simulation/crane_warnings.hpp"

namespace crane_twin {

RunRecorder::RunRecorder(const CraneModel& model, Simulation& sim, std::ostream* series,
                         std::ostream* nodes, long every, bool progress_bar)
    : model_(model),
      sim_(sim),
      series_(series),
      nodes_(nodes),
      every_(std::max(1L, every)),
      progress_bar_(progress_bar),
      monitors_{{}, LiftOffMonitor(), StepTensionPeak(), 0.0, UsageCounter(model)},
      follower_(sim, {[this](long k) { record(k); }, [this] { hold(); }, [this] { release(); },
                      [this] { drop(); }}) {}

void RunRecorder::hold() { at_checkpoint_ = std::make_unique<Monitors>(monitors_); }

void RunRecorder::drop() {
  // The held rows and warnings go, the monitors return to the checkpoint.
  if (at_checkpoint_) monitors_ = *at_checkpoint_;
  at_checkpoint_.reset();
  held_series_.str("");
  held_nodes_.str("");
  held_messages_.clear();
}

void RunRecorder::record(long k) {
  if (k > 0) {
    monitors_.tension_peak.addStep(sim_.topTension());
    monitors_.usage.observeStep(sim_.hotSpotStresses());  // the stresses' crests between rows
    if (k % every_ != 0) return;
  }
  emit();
}

void RunRecorder::emit() {
  Monitors& m = monitors_;
  SeriesValues v = sim_.series();
  const double peak = m.tension_peak.takeAtRow(v.rope_top_tension);
  m.peak_tension = std::max(m.peak_tension, peak);
  m.lift_off.observe(v, staticTopTension(model_, v.rope_length), peak);
  addStepPeakTensionWarnings(model_, peak, v);
  m.usage.observe(v, m.lift_off);
  v.warnings |= m.lift_off.warningFor(model_.scene.hoist_design_phi2);
  if (series_) writeSeriesRow(at_checkpoint_ ? held_series_ : *series_, v);
  if (nodes_) sim_.writeNodeRows(at_checkpoint_ ? held_nodes_ : *nodes_);
  for (int bit = 1; bit <= kLastWarning; bit <<= 1) {
    if (!(v.warnings & bit) || m.warned[bit]++ != 0) continue;
    char line[256];
    std::snprintf(line, sizeof line,
                  "warning: t = %.3f s: %s (tension_ratio %.3f, load_chart_ratio %.3f)\n", v.t,
                  warningName(bit), v.tension_ratio, v.load_chart_ratio);
    warn(line);
  }
}

void RunRecorder::warn(const std::string& message) {
  if (at_checkpoint_) {
    held_messages_.push_back(message);
    return;
  }
  if (progress_bar_) std::fputs("\n", stderr);
  std::fputs(message.c_str(), stderr);
}

void RunRecorder::release() {
  at_checkpoint_.reset();
  if (series_) *series_ << held_series_.str();
  if (nodes_) *nodes_ << held_nodes_.str();
  held_series_.str("");
  held_nodes_.str("");
  for (const std::string& message : held_messages_) warn(message);
  held_messages_.clear();
}

}  // namespace crane_twin
