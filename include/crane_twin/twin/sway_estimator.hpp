// The twin's sway estimator (docs/twin.md): a linear Kalman filter on the error of the twin's
// payload sway, the rope's two rigid swing coordinates (horizontal payload offset and its rate,
// world frame), corrected into the running simulation by a rigid rotation of the rope about
// the trolley point.
//
// Error state e = [dx, dy, dvx, dvy] (twin minus truth, m and m/s). The simulation itself is the
// nonlinear predictor of the mean; the filter only carries the error's covariance P through
// the linearised pendulum of length l (w^2 = g / l), per horizontal axis
//   F(h) = [[cos wh, sin(wh) / w], [-w sin wh, cos wh]],
//   Q(h) = q [[h^3 / 3, h^2 / 2], [h^2 / 2, h]]   (white acceleration noise of density q),
// and a measured payload position z (noise sigma_z per axis) updates it:
//   nu = z - p_twin, S = H P H^T + R, K = P H^T S^-1, correction = K nu, P = (I - K H) P,
// H = [I 0]. A measurement whose normalised innovation nu^T S^-1 nu exceeds gate^2 is refused.
// Why a Kalman filter on the rigid coordinates: the payload's position sees the sway, not the
// rope's elastic modes (their amplitudes are millimetres, under any camera's noise), and the
// pendulum model of that error is linear, so the filter is optimal and costs nothing.
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

struct SwayEstimatorSettings {
  double measurement_noise = 0.05;     ///< sigma of each horizontal payload coordinate [m]
  double process_noise = 0.01;         ///< acceleration noise density q [m^2/s^3]
  double initial_position_sigma = 2.0; ///< [m]
  double initial_velocity_sigma = 0.5; ///< [m/s]
  double gate = 5.0;                   ///< refuse measurements beyond this many sigma
  /// Throws std::invalid_argument naming the field (non-finite, not > 0).
  void check() const;
};

struct SwayUpdate {
  bool accepted = false;
  Eigen::Vector2d innovation = Eigen::Vector2d::Zero();           ///< z - p_twin [m]
  double normalized = 0.0;                                         ///< nu^T S^-1 nu
  Eigen::Vector2d position_correction = Eigen::Vector2d::Zero();  ///< add to the twin [m]
  Eigen::Vector2d velocity_correction = Eigen::Vector2d::Zero();  ///< [m/s]
};

class SwayEstimator {
 public:
  explicit SwayEstimator(const SwayEstimatorSettings& settings = {});
  /// Back to the initial covariance.
  void reset();
  /// Propagate P over h [s] with the pendulum of length l [m] under gravity g [m/s^2].
  /// Throws std::invalid_argument for h < 0 or l, g not > 0.
  void predict(double h, double length, double gravity);
  /// A measured payload position (horizontal, world) against the twin's at the same time.
  SwayUpdate update(const Eigen::Vector2d& measured, const Eigen::Vector2d& twin);
  const Eigen::Matrix4d& covariance() const { return P_; }
  /// sqrt of the largest eigenvalue of the position block: the 1-sigma uncertainty radius [m].
  double positionSigma() const;
  const SwayEstimatorSettings& settings() const { return settings_; }

 private:
  SwayEstimatorSettings settings_;
  Eigen::Matrix4d P_;
};

}  // namespace crane_twin
