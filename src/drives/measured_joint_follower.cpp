#include "crane_twin/drives/measured_joint_follower.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace crane_twin {

namespace {

double wrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

}  // namespace

void JointFollowerSettings::check() const {
  auto positive = [](double x, const char* name) {
    if (!std::isfinite(x) || !(x > 0.0)) {
      throw std::invalid_argument(std::string(name) + " must be finite and > 0, got " +
                                  std::to_string(x));
    }
  };
  positive(gain, "gain");
  positive(max_extrapolation, "max_extrapolation");
  positive(stale_after, "stale_after");
  positive(tracking_bandwidth, "tracking_bandwidth");
  positive(hold_window, "hold_window");
}

MeasuredJointFollower::MeasuredJointFollower(const JointFollowerSettings& settings)
    : settings_(settings),
      filters_{JointTrackingFilter(settings.tracking_bandwidth, true),
               JointTrackingFilter(settings.tracking_bandwidth, false),
               JointTrackingFilter(settings.tracking_bandwidth, false)} {
  settings_.check();
}

void MeasuredJointFollower::clear() {
  last_.reset();
  window_.clear();
  blend_time_ = 0.0;
  for (JointTrackingFilter& f : filters_) f.restart();
}

std::string MeasuredJointFollower::add(const JointSample& s, const CraneDescription& crane) {
  auto refuse = [&](const std::string& why) {
    ++refused_;
    return why;
  };
  if (!std::isfinite(s.t) || !s.position.allFinite() || (s.velocity && !s.velocity->allFinite())) {
    return refuse("non-finite joint value");
  }
  if (last_ && s.t < last_->t) return refuse("sample older than the newest one");
  // Sensor noise at a limit is normal: within kLimitMargin beyond it the sample is taken (the
  // drive stops the model at its limit and flags it); further out it is refused.
  const double m = MeasuredJointFollower::kLimitMargin;
  if (s.position.y() < crane.min_radius - m || s.position.y() > crane.max_radius + m) {
    return refuse("trolley radius " + std::to_string(s.position.y()) + " m outside [" +
                  std::to_string(crane.min_radius) + ", " + std::to_string(crane.max_radius) + "]");
  }
  if (s.position.z() < crane.min_rope_length - m || s.position.z() > crane.max_rope_length + m) {
    return refuse("rope length " + std::to_string(s.position.z()) + " m outside [" +
                  std::to_string(crane.min_rope_length) + ", " +
                  std::to_string(crane.max_rope_length) + "]");
  }
  // What the command followed at s.t, before this sample (a gap beyond max_extrapolation
  // is not bridged: then nothing to blend from).
  const bool blend = last_ && s.t - last_->t <= settings_.max_extrapolation;
  Estimate before;
  if (blend) before = estimate(s.t);
  if (last_ && s.t == last_->t && !window_.empty()) window_.pop_back();  // the newer wins
  for (int a = 0; a < 3; ++a) filters_[a].add(s.t, s.position[a]);
  const double previous = last_ ? last_->t : s.t;
  last_ = s;
  if (s.velocity) {
    position_ = s.position;
    rate_ = *s.velocity;
  } else {
    for (int a = 0; a < 3; ++a) {
      position_[a] = filters_[a].position();
      rate_[a] = filters_[a].rate();
    }
  }
  blend_offset_ = Eigen::Vector3d::Zero();
  blend_rate_ = Eigen::Vector3d::Zero();
  blend_time_ = 0.0;
  if (blend) {
    blend_offset_ = before.position - position_;
    blend_offset_.x() = wrapAngle(blend_offset_.x());
    blend_rate_ = before.rate - rate_;
    blend_time_ = std::min(s.t - previous, settings_.stale_after);
  }
  window_.push_back(s);
  const double keep = settings_.hold_window;
  while (window_.size() > 2 && window_.front().t < s.t - keep) {
    window_.pop_front();
  }
  return "";
}

double MeasuredJointFollower::age(double t) const {
  return last_ ? t - last_->t : std::numeric_limits<double>::infinity();
}

bool MeasuredJointFollower::stale(double t) const { return !(age(t) <= settings_.stale_after); }

MeasuredJointFollower::Estimate MeasuredJointFollower::estimate(double t) const {
  // x* = x_k + v_k a + w (dx + dv a), rate v_k + w dv, a = t - t_k (>= 0), the blend's weight
  // w = 1 - a / blend_time falling to 0 (the header); beyond max_extrapolation the last
  // position at rest.
  Estimate e;
  if (!last_) return e;
  const double ahead = std::max(t - last_->t, 0.0);
  if (!(ahead <= settings_.max_extrapolation)) {
    e.position = position_;
    return e;
  }
  const double w = ahead < blend_time_ ? 1.0 - ahead / blend_time_ : 0.0;
  e.rate = rate_ + w * blend_rate_;
  e.position = position_ + rate_ * ahead + w * (blend_offset_ + blend_rate_ * ahead);
  return e;
}

Eigen::Vector3d MeasuredJointFollower::rates(double t) const { return estimate(t).rate; }

Eigen::Vector3d MeasuredJointFollower::holdRates(double t) const {
  if (!last_ || !(age(t) <= settings_.max_extrapolation)) return Eigen::Vector3d::Zero();
  if (last_->velocity) return *last_->velocity;
  return slope(settings_.hold_window);
}

Eigen::Vector3d MeasuredJointFollower::slope(double window) const {
  // Least-squares slope v = sum (t_i - tm)(x_i - x_last) / sum (t_i - tm)^2, the slew angles
  // unwrapped against the newest.
  double tm = 0.0;
  int n = 0;
  for (const JointSample& w : window_) {
    if (w.t < last_->t - window) continue;
    tm += w.t;
    ++n;
  }
  if (n < 2) return Eigen::Vector3d::Zero();
  tm /= static_cast<double>(n);
  double stt = 0.0;
  Eigen::Vector3d stx = Eigen::Vector3d::Zero();
  for (const JointSample& w : window_) {
    if (w.t < last_->t - window) continue;
    Eigen::Vector3d d = w.position - last_->position;
    d.x() = wrapAngle(d.x());
    stt += (w.t - tm) * (w.t - tm);
    stx += (w.t - tm) * d;
  }
  return stt > 1e-9 ? Eigen::Vector3d(stx / stt) : Eigen::Vector3d::Zero();
}

CommandEntry MeasuredJointFollower::command(double t, const CraneDrives& drives,
                                            const CraneDescription& crane) const {
  CommandEntry c;
  c.t = t;
  if (!last_) return c;
  const Estimate target_now = estimate(t);
  const Eigen::Vector3d& v = target_now.rate;
  const Eigen::Vector3d& target = target_now.position;
  const Eigen::Vector3d model(drives.slewAngle(), drives.trolleyRadius(), drives.hoistLength());
  Eigen::Vector3d e = target - model;
  e.x() = wrapAngle(e.x());
  const double vmax[3] = {crane.slewing.max_speed, crane.trolley.max_speed, crane.hoist.max_speed};
  double rate[3];
  for (int a = 0; a < 3; ++a) {
    rate[a] = std::clamp(v[a] + settings_.gain * e[a], -vmax[a], vmax[a]);
  }
  c.slew_rate = rate[0];
  c.trolley_speed = rate[1];
  c.hoist_speed = rate[2];
  return c;
}

}  // namespace crane_twin
