#include "crane_twin/drives/crane_drives.hpp"

#include <cmath>
#include <stdexcept>

#include "crane_twin/io/config_reader.hpp"

namespace crane_twin {

namespace {
bool moves(const CommandEntry& c) {
  return c.slew_rate != 0.0 || c.trolley_speed != 0.0 || c.hoist_speed != 0.0;
}
}  // namespace

CraneDrives::CraneDrives(const Scene& scene, double slew_inertia)
    : scene_(scene), slew_inertia_(slew_inertia) {
  if (scene.slew_drive.model == SlewDriveModel::torque && !(slew_inertia > 0.0)) {
    throw InputError(scene.file +
                     ": key 'slewing.drive.model': the torque drive needs the "
                     "rotating part's inertia (a crane structure)");
  }
  for (const auto& c : scene.commands) {
    if (!moves(c)) continue;
    if (!scene.crane) {
      throw InputError(scene.file + ": key 'commands': drives need a crane (crane: none has none)");
    }
    active_ = true;
  }
  reset();
}

void CraneDrives::reset() {
  manual_.reset();
  slew_flags_ = trolley_flags_ = hoist_flags_ = DriveFlags{};
  if (!scene_.crane) return;
  const CraneDescription& c = *scene_.crane;
  slew_.emplace(c.slewing, scene_.slew_angle);
  trolley_.emplace(c.trolley, scene_.trolley_radius, c.min_radius, c.max_radius);
  hoist_.emplace(c.hoist, scene_.rope.length, c.min_rope_length, c.max_rope_length);
  slew_torque_.reset();
  const SlewDriveSettings& d = scene_.slew_drive;
  if (d.model == SlewDriveModel::torque) {
    slew_torque_.emplace(slew_inertia_, d.max_torque, d.stiffness, d.damping, scene_.slew_angle);
  }
}

void CraneDrives::assignStateFrom(const CraneDrives& o) {
  slew_ = o.slew_;
  slew_torque_ = o.slew_torque_;
  trolley_ = o.trolley_;
  hoist_ = o.hoist_;
  slew_flags_ = o.slew_flags_;
  trolley_flags_ = o.trolley_flags_;
  hoist_flags_ = o.hoist_flags_;
  active_ = o.active_;
  manual_ = o.manual_;
}

void CraneDrives::setCommand(const CommandEntry& c) {
  if (!std::isfinite(c.slew_rate) || !std::isfinite(c.trolley_speed) ||
      !std::isfinite(c.hoist_speed)) {
    throw std::invalid_argument("command with a non-finite rate");
  }
  if (!scene_.crane && moves(c)) {
    throw InputError("drives need a crane (crane: none has none)");
  }
  manual_ = c;
  active_ = true;
}

bool CraneDrives::hoists() const {
  if (manual_ && manual_->hoist_speed != 0.0) return true;
  for (const auto& c : scene_.commands)
    if (c.hoist_speed != 0.0) return true;
  return false;
}

CommandEntry CraneDrives::activeCommand(double t) const {
  if (manual_) return *manual_;
  CommandEntry active;
  for (const auto& c : scene_.commands) {
    if (c.t <= t + 1e-9) active = c;
  }
  return active;
}

bool CraneDrives::advance(double t, double dt) {
  if (!active_ || !slew_) return false;
  const CommandEntry c = activeCommand(t);
  slew_flags_ = slew_->advance(c.slew_rate, dt);
  if (slew_torque_) {
    slew_torque_->advance(slew_->speed(), dt);
    slew_flags_.torque_limited = slew_torque_->torqueLimited();
  }
  trolley_flags_ = trolley_->advance(c.trolley_speed, dt);
  hoist_flags_ = hoist_->advance(c.hoist_speed, dt);
  return true;
}

}  // namespace crane_twin
