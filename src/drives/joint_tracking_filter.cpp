#include "crane_twin/drives/joint_tracking_filter.hpp"

#include <cmath>

namespace crane_twin {

void JointTrackingFilter::add(double t, double y) {
  if (!started_) {
    started_ = true;
    steady_ = false;
    t_ = t;
    x_ = y;
    v_ = 0.0;
    return;
  }
  const double dt = t - t_;
  if (!steady_) {
    // The continuous filter's steady state for samples every dt (the file's comment), once the
    // first interval is known.
    steady_ = true;
    const double w = omega_, w2 = w * w, s2 = std::sqrt(2.0);
    pxx_ = s2 * w * dt;
    pxv_ = w2 * dt;
    pvv_ = s2 * w2 * w * dt;
  }
  // Predict: s <- F s, P <- F P F^T + q Q(dt), q = omega^4 dt (P in units of r).
  const double q = std::pow(omega_, 4) * dt;
  x_ += v_ * dt;
  const double pxx = pxx_ + 2.0 * dt * pxv_ + dt * dt * pvv_ + q * dt * dt * dt / 3.0;
  const double pxv = pxv_ + dt * pvv_ + q * dt * dt / 2.0;
  const double pvv = pvv_ + q * dt;
  // Update with y (r = 1).
  double e = y - x_;
  if (angle_) e = std::atan2(std::sin(e), std::cos(e));
  const double s = pxx + 1.0;
  const double kx = pxx / s, kv = pxv / s;
  x_ += kx * e;
  v_ += kv * e;
  pxx_ = (1.0 - kx) * pxx;
  pxv_ = (1.0 - kx) * pxv;
  pvv_ = pvv - kv * pxv;
  t_ = t;
}

}  // namespace crane_twin
