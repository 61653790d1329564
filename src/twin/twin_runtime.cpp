#include "crane_twin/twin/twin_runtime.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/twin/sway_correction.hpp"

namespace crane_twin {

TwinRuntime::TwinRuntime(const SwayEstimatorSettings& estimator,
                         const JointFollowerSettings& follower, const LoadCellSettings& load_cell)
    : estimator_settings_(estimator),
      follower_(follower),
      load_cell_settings_(load_cell),
      load_cell_(load_cell) {
  estimator_settings_.check();
}

void TwinRuntime::loadChanged(const CraneModel& model) {
  crane_ = model.scene.crane ? &*model.scene.crane : nullptr;
  end_mass_ = model.end_mass;
  hook_mass_ = model.scene.hookBlockMass();
  rigging_ = model.scene.hasRigging();
  rope_mass_per_length_ = model.rope.mass_per_length;
  gravity_ = model.scene.gravity;
}

void TwinRuntime::restart(const CraneModel& model, const Simulation& sim) {
  loadChanged(model);
  load_cell_ = LoadCellMonitor(load_cell_settings_);
  follower_.clear();
  modes_ = swayCouplingModes(sim);
  estimator_ = std::make_unique<SwayEstimator>(estimator_settings_, modeMotionNorms(sim, modes_));
  payload_in_.clear();
  tension_in_.clear();
  last_payload_t_ = -1e300;
  last_update_ = SwayUpdate{};
  tension_ratio_ = 1.0;
  tension_seen_ = false;
}

std::string TwinRuntime::addJoints(const JointSample& sample) {
  if (!crane_) return "the scene has no crane";
  return follower_.add(sample, *crane_);
}

void TwinRuntime::addPayload(double t, const Eigen::Vector3d& position) {
  payload_in_.emplace_back(t, position);
  if (payload_in_.size() > 100) payload_in_.pop_front();
}

void TwinRuntime::addTension(double tension) {
  tension_in_.push_back(tension);
  if (tension_in_.size() > 100) tension_in_.pop_front();
}

Eigen::Matrix2d TwinRuntime::payloadCovariance(const Simulation& sim, const SeriesValues& row) {
  return estimator_->payloadCovariance(swayModelAt(sim, row, modes_, gravity_));
}

void TwinRuntime::afterStep(Simulation& sim, double h,
                            const std::function<void(const std::string&)>& warn) {
  if (!estimator_) throw std::logic_error("TwinRuntime::afterStep before restart");
  const double now = sim.time();
  estimator_->predict(h);  // the error's covariance follows at the next update
  while (!payload_in_.empty()) {
    const double age = std::min(now - std::min(payload_in_.front().first, now), 1.0);
    const Eigen::Vector3d z = payload_in_.front().second;
    payload_in_.pop_front();
    // The twin's payload when the measurement was taken, p(t - age) = p - v age.
    const SeriesValues v = sim.series();
    // A load resting on the ground does not sway: nothing to correct.
    if (v.payload_landed) {
      ++payload_on_ground_;
      continue;
    }
    const Eigen::Vector3d p = v.payload - age * v.payload_velocity;
    const SwayUpdate u =
        estimator_->update(z.head<2>(), p.head<2>(), swayModelAt(sim, v, modes_, gravity_));
    if (u.reacquired) warn("sway estimator re-acquiring: 10 payload measurements refused in a row");
    last_update_ = u;
    last_payload_t_ = now;
    if (!u.accepted) {
      ++payload_refused_;
      warn("payload measurement beyond the innovation gate refused (" +
           std::to_string(u.innovation.norm()) + " m from the twin)");
      continue;
    }
    ++payload_updates_;
    try {
      applyTwinCorrection(sim, u, modes_);
    } catch (const std::exception& e) {
      ++correction_failures_;
      warn(std::string("sway correction not applied: ") + e.what());
    }
  }
  if (!tension_in_.empty()) {
    const SeriesValues v = sim.series();
    const double twin_tension = v.rope_top_tension;
    LoadCellSample sample;
    sample.t = now;
    sample.twin = twin_tension;
    // The masses that never land: the hanging rope and a hook block on a rigging.
    sample.unloaded =
        (rope_mass_per_length_ * v.rope_length + (rigging_ ? hook_mass_ : 0.0)) * gravity_;
    sample.end_mass = end_mass_;
    sample.gravity = gravity_;
    sample.twin_landed = v.payload_landed;
    sample.hoist_length = sim.drives().hoistLength();
    while (!tension_in_.empty()) {
      const double r = twin_tension > 0.0 ? tension_in_.front() / twin_tension : 1.0;
      sample.measured = tension_in_.front();
      if (end_mass_ > 0.0) load_cell_.add(sample);
      tension_in_.pop_front();
      // Exponential filter over about 10 measurements.
      tension_ratio_ = tension_seen_ ? tension_ratio_ + 0.1 * (r - tension_ratio_) : r;
      tension_seen_ = true;
    }
  }
}

double TwinRuntime::payloadMassEstimate() const {
  const double e = load_cell_.endMassEstimate();
  return (std::isnan(e) ? end_mass_ : e) - (rigging_ ? 0.0 : hook_mass_);
}

std::optional<double> TwinRuntime::takePayloadMass() {
  const std::optional<double> e = load_cell_.takeEndMass();
  if (!e) return std::nullopt;
  // The hook block stays what the crane file says; a load cell reading below it leaves no
  // payload.
  return std::max(*e - (rigging_ ? 0.0 : hook_mass_), 0.0);
}

}  // namespace crane_twin
