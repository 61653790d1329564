// The twin's estimator (docs/twin.md "Correcting the sway"): a linear Kalman filter on the error
// of the twin's reduced coordinates that a payload position sees: the rope's rigid swing
// (payload offset s from the trolley point, horizontal, world frame, and its rate) and the
// structure's lowest modal coordinates eta_k (mass-normalised modes of the modal structure that
// move the trolley point sideways), both corrected into the running simulation
// (twin/sway_correction.hpp).
//
// Error state e = [eta (K), eta' (K), s (2), s' (2)] (twin minus truth). The simulation itself
// is the nonlinear predictor of the mean; the filter carries the error's covariance P through
// the linearised coupled system at the current pose:
//   eta'' = -Omega^2 eta - 2 zeta Omega eta' + (T / l) Phi^T s      (rope force on the trolley)
//   s''   = -(g / l) s - Phi eta''                                   (the pendulum on a moving
//   point)
// Phi (2 x K) the horizontal trolley-point motion per modal coordinate, l the hanging length,
// T the rope's top tension. Over dt: F = exp(A dt), Q by Van Loan's method from white
// acceleration noise of density q_s on s'' and q_eta_k on eta_k''. A measured payload position z
// (noise sigma_z per axis) updates it with H = [Phi 0 I 0]:
//   nu = z - p_twin, S = H P H^T + R, K = P H^T S^-1, correction = K nu, P = (I - K H) P (I - K
//   H)^T + K R K^T.
// A measurement whose normalised innovation nu^T S^-1 nu exceeds gate^2 is refused; after
// kReacquireAfter refusals in a row the filter returns to its prior and takes the next one.
// Why this filter: the payload's position sees the swing and the structure's sway at the
// trolley, not the rope's elastic modes (millimetres, under any camera's noise), and the error
// dynamics of these coordinates are linear, so a linear filter is optimal and costs nothing.
// Without structure modes (K = 0: a rigid structure) it is the pendulum filter alone.
#pragma once

#include <Eigen/Dense>
#include <vector>

namespace crane_twin {

struct SwayEstimatorSettings {
  double measurement_noise = 0.05;  ///< sigma of each horizontal payload coordinate [m]
  /// Acceleration noise density q_s [m^2/s^3] of the sway: the unmodelled accelerations (wind,
  /// a load mass off by 10 %), a velocity random walk of sqrt(q) = 3 cm/s per sqrt(s).
  double process_noise = 1e-3;
  double initial_position_sigma = 2.0;  ///< sway [m]
  double initial_velocity_sigma = 0.5;  ///< sway rate [m/s]
  /// Prior sigma of the trolley point's sideways motion from each structure mode [m], and the
  /// acceleration noise density of that motion [m^2/s^3].
  double structure_sigma = 0.5;
  double structure_process_noise = 1e-4;
  double gate = 5.0;  ///< refuse measurements beyond this many sigma
  /// Throws std::invalid_argument naming the field (non-finite, not > 0).
  void check() const;
};

/// The linearised model at the current pose.
struct SwayModel {
  double length = 0.0;              ///< hanging length l [m]
  double gravity = 9.81;            ///< [m/s^2]
  double tension = 0.0;             ///< rope top tension T [N] (0: no coupling to the structure)
  Eigen::VectorXd omega2, damping;  ///< Omega_k^2, 2 zeta Omega_k of the K modes
  Eigen::Matrix2Xd phi;             ///< horizontal trolley motion per modal coordinate (2 x K)
};

struct SwayUpdate {
  bool accepted = false;
  bool reacquired = false;  ///< the covariance was reset to the prior before this update
  Eigen::Vector2d innovation = Eigen::Vector2d::Zero();             ///< z - p_twin [m]
  double normalized = 0.0;                                          ///< nu^T S^-1 nu
  Eigen::Vector2d position_correction = Eigen::Vector2d::Zero();    ///< to the sway s [m]
  Eigen::Vector2d velocity_correction = Eigen::Vector2d::Zero();    ///< to s' [m/s]
  Eigen::VectorXd structure_correction, structure_rate_correction;  ///< to eta, eta' (K)
};

class SwayEstimator {
 public:
  static constexpr int kReacquireAfter = 10;
  /// K structure modes; `phi_norm` their |Phi_k| at the start (m per unit modal coordinate,
  /// > 0) to scale the priors. Throws std::invalid_argument for bad settings.
  explicit SwayEstimator(const SwayEstimatorSettings& settings = {},
                         const Eigen::VectorXd& phi_norm = Eigen::VectorXd());
  /// Back to the prior covariance.
  void reset();
  /// Let h [s] pass (accumulated; propagated at the next update or covariance()).
  /// Throws std::invalid_argument for h < 0.
  void predict(double h);
  /// A measured payload position (horizontal, world) against the twin's at the same time,
  /// with the model at the current pose. Throws std::invalid_argument for a model of another
  /// size or a length, gravity not > 0.
  SwayUpdate update(const Eigen::Vector2d& measured, const Eigen::Vector2d& twin,
                    const SwayModel& model);
  /// P propagated to now with `model` (n = 2 K + 4).
  const Eigen::MatrixXd& covariance(const SwayModel& model);
  /// The payload's horizontal covariance H P H^T, P propagated to now with `model`.
  Eigen::Matrix2d payloadCovariance(const SwayModel& model);
  /// sqrt of the largest eigenvalue of H P H^T: the 1-sigma radius of the payload [m] (as of
  /// the last propagation).
  double positionSigma() const;
  int modes() const { return K_; }
  const SwayEstimatorSettings& settings() const { return settings_; }

 private:
  void propagate(const SwayModel& model);
  /// H = [Phi 0 I 0] (2 x n).
  Eigen::MatrixXd observation(const Eigen::Matrix2Xd& phi) const;
  SwayEstimatorSettings settings_;
  Eigen::VectorXd phi_norm_;
  int K_ = 0;
  Eigen::MatrixXd P_;
  Eigen::Matrix2Xd last_phi_;
  double pending_ = 0.0;
  bool primed_ = false;
  int refused_in_a_row_ = 0;
};

}  // namespace crane_twin
