// One measured joint axis (slew angle, trolley radius or hoisted length) filtered into a
// position and a rate (docs/twin.md "Following the crane"): the Kalman filter of a motion at
// constant rate disturbed by white acceleration noise, sampled at irregular times t_k.
//
// State s = [x, v]; between samples (dt = t_k - t_{k-1})
//   s <- F s,  F = [1 dt; 0 1],   P <- F P F^T + q [dt^3/3  dt^2/2; dt^2/2  dt],
// and at a sample y (innovation e = y - x, the slew angle's wrapped to (-pi, pi])
//   K = P H^T / (H P H^T + r),  s <- s + K e,  P <- (I - K H) P,   H = [1 0].
// Only the ratio q / r sets the gains, so P is kept in units of r (r = 1) and q is chosen from
// one bandwidth omega [rad/s]: with samples every T, the filter is the continuous one with
// measurement noise density r T and q / (r T) = omega^4, whose poles are omega exp(+-3i pi/4)
// (gains sqrt(2) omega and omega^2). Its closed forms, which the tests check:
//   lag behind a constant acceleration a:  a / omega^2 (position), sqrt(2) a / omega (rate);
//   white noise sigma on a joint at rest:  variance 3 / (2 sqrt(2)) omega T sigma^2 (position),
//                                          omega^3 T sigma^2 / (2 sqrt(2)) (rate);
// and the rate moves by about omega^2 T sigma at each sample (its gain times the innovation):
// an acceleration of about omega^2 sigma for whoever follows it. Each interval's q takes
// T = dt, so the bandwidth holds at any sample rate, with jitter, and a sample after a gap
// counts for more.
//
// The first sample sets x = y, v = 0 and P to the steady state of that continuous filter for
// the next interval (P_xx = sqrt(2) omega T, P_xv = omega^2 T, P_vv = sqrt(2) omega^3 T): a
// twin starts beside a crane at rest, and a crane already moving is caught within about
// 2 / omega. restart() makes the next sample such a first one (the follower cleared).
#pragma once

namespace crane_twin {

class JointTrackingFilter {
 public:
  /// bandwidth omega [rad/s] > 0 (the caller checks it); `angle`: innovations wrapped.
  JointTrackingFilter(double bandwidth, bool angle) : omega_(bandwidth), angle_(angle) {}

  /// A sample y at time t (t >= the previous sample's; the caller refuses others).
  void add(double t, double y);
  /// Forget the history: the next sample starts the filter again.
  void restart() { started_ = false; }

  /// Filtered position and rate at the newest sample's time.
  double position() const { return x_; }
  double rate() const { return v_; }

 private:
  double omega_;
  bool angle_;
  bool started_ = false, steady_ = false;
  double t_ = 0.0, x_ = 0.0, v_ = 0.0;        ///< newest sample's time [s], position, rate
  double pxx_ = 0.0, pxv_ = 0.0, pvv_ = 0.0;  ///< covariance in units of r
};

}  // namespace crane_twin
