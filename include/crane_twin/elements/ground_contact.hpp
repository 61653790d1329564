// Contact of the payload with a horizontal ground (docs/model.md "Ground contact").
//
// The payload point r (the rope's end node, or the rigging's payload point: where the hook
// holds the load, on its top) carries a load of height h whose underside is at z - h. The
// ground is the plane z = z_g; the penetration is p = max(0, z_g + h - z) [m].
//   Normal force   N = max(0, k p - c v_z)  while p > 0, else 0:
//                  a penalty spring (potential U = k p^2 / 2) with a damper that never pulls
//                  (its part N - k p = max(-k p, -c v_z) always opposes v_z: it dissipates);
//   Friction       F_t = -mu N v_t / sqrt(|v_t|^2 + v_s^2):
//                  Coulomb's law regularised below the slip velocity v_s (|F_t| -> mu N when
//                  sliding; a viscous law of slope mu N / v_s about rest), F_t . v_t <= 0;
//   Force on r     f = F_t + N e_z   [N, world frame].
// Energy: U is the only stored part; the damper and friction only dissipate. Over a step
// r0 -> r1 the energy-consistent step (docs/model.md "Energy-consistent step") takes the
// discrete gradient of U (the secant of U in z) plus the dissipative part at the midpoint, so
// the contact's work equals -(U1 - U0) plus a dissipation <= 0, whether or not the payload
// touches down or lifts off inside the step.
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

struct GroundContactParameters {
  double height = 0.0;          ///< z_g: world height of the ground [m]
  double stiffness = 1e8;       ///< k [N/m] > 0
  double damping = 0.0;         ///< c [N s/m] >= 0
  double friction = 0.5;        ///< mu [-] >= 0
  double slip_velocity = 1e-3;  ///< v_s [m/s] > 0
  double payload_height = 1.0;  ///< h: from the payload point down to the load's underside [m]
};

/// The contact force at a state and its derivatives: f, df/dr, df/dv (the friction's coupling
/// of the tangential force with r_z and v_z left out, so both are symmetric: the iteration
/// matrices are factorised by a symmetric LDL^T; Newton then converges linearly in that part).
struct GroundContactForce {
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  Eigen::Matrix3d df_dr = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d df_dv = Eigen::Matrix3d::Zero();
};

class GroundContact {
 public:
  /// Throws std::invalid_argument for a non-finite value, k or v_s not positive, c, mu or h
  /// negative.
  explicit GroundContact(const GroundContactParameters& p);
  const GroundContactParameters& parameters() const { return p_; }

  /// p = max(0, z_g + h - z) [m].
  double penetration(const Eigen::Vector3d& r) const;
  /// z - h - z_g: the underside's height above the ground (negative: penetrating) [m].
  double clearance(const Eigen::Vector3d& r) const;
  /// U = k p^2 / 2 [J].
  double energy(const Eigen::Vector3d& r) const;
  /// The force at (r, v) and its derivatives.
  GroundContactForce force(const Eigen::Vector3d& r, const Eigen::Vector3d& v) const;
  /// The dissipative part alone (f - k p e_z) at (r, v).
  Eigen::Vector3d dissipativeForce(const Eigen::Vector3d& r, const Eigen::Vector3d& v) const;
  /// The energy-consistent step's mean force over r0 -> r1 with velocities v0 -> v1:
  /// f = -dU_bar e_z + f_d(r_m, v_m), dU_bar the secant of U in z (its limit U'(z_m) for a tiny
  /// step), so f . (r1 - r0) = -(U(r1) - U(r0)) + f_d(r_m, v_m) . (r1 - r0); with
  /// df_dr = d(2 f)/dr1 and df_dv = d(2 f)/dv1 (the step's Newton matrix, which works on twice
  /// the mean force).
  GroundContactForce stepMeanForce(const Eigen::Vector3d& r0, const Eigen::Vector3d& r1,
                                   const Eigen::Vector3d& v0, const Eigen::Vector3d& v1) const;
  /// Trapezoid work error of the spring over r0 -> r1: |(f_s(r0) + f_s(r1)) . (r1 - r0) / 2 +
  /// U(r1) - U(r0)| [J]; 0 when the payload touches at both ends or at neither (U quadratic),
  /// nonzero only for a step that lands or lifts off (integrators/tension_only_step.hpp).
  double switchWorkError(const Eigen::Vector3d& r0, const Eigen::Vector3d& r1) const;

 private:
  GroundContactParameters p_;
};

/// The damper c = 2 zeta sqrt(k m) of damping ratio zeta for a mass m [kg] on the spring k.
double groundDamping(double stiffness, double mass, double damping_ratio);

}  // namespace crane_twin
