// The cheapest rung of the rope ladder (docs/scenes.md, `rope.model: pendulum`): the hanging rope
// as one straight elastic bar from its top point r_0 to its end point r_1 (hook block and payload),
// with the rope's mass and no ANCF.
//
// Coordinates q = [r_0; r_1] [m, world frame] (6; the top point is held at the trolley by the
// same constraint as the ANCF rope's top node).
//   Mass:     M = mu L / 6 [[2 I, I], [I, 2 I]] + diag(m_top I, m_end I): the rope's mass
//             mu L spread uniformly along the chord (the linear bar's consistent mass), the
//             trolley at r_0, hook block and payload at r_1: rope mass exact, as in the ANCF
//             rope. Kinetic energy of a rigid swing about r_0: (m_end + mu L / 3) l^2 w^2 / 2.
//   Gravity:  F_g = M [g; g]: mu L g / 2 at each end plus the point masses' weights, so the
//             top force at rest is (m_end + mu L) g, the ANCF rope's.
//   Elastic:  l = |r_1 - r_0|, u = (r_1 - r_0) / l, tension T = EA (l - L) / L for l > L and
//             0 when slack (a rope takes no compression; with `rope.tension_only: false` the
//             bar also pushes, T < 0 for l < L, as the ANCF rope's symmetric energy does);
//             Q = T [-u; u],  K = dQ/dq = [[K_b, -K_b], [-K_b, K_b]],
//             K_b = EA / L u u^T + T / l (I - u u^T) (taut; 0 slack);
//             U = EA (l - L)^2 / (2 L) for l > L.
//   Damping:  Kelvin-Voigt on the axial strain rate, T_d = c EA / L (u . (v_1 - v_0)) while
//             taut, Q_d = T_d [-u; u] (dQ_d/dv = c EA / L [[u u^T, -u u^T], [-u u^T, u u^T]]).
// What it leaves out against the ANCF rope: bending, the rope's own transverse modes (its
// sag between the ends) and the tension's variation along the rope.
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

class PendulumRope {
 public:
  static constexpr int kDofs = 6;
  /// length > 0 [m] unstretched, mass_per_length >= 0 [kg/m], axial_stiffness EA > 0 [N], end
  /// and top masses >= 0 [kg]. Throws std::invalid_argument otherwise.
  PendulumRope(double length, double mass_per_length, double axial_stiffness, double end_mass,
               const Eigen::Vector3d& gravity, double top_mass = 0.0);

  double length() const { return L_; }
  double massPerLength() const { return mu_; }
  double axialStiffness() const { return EA_; }
  double endMass() const { return end_mass_; }
  double topMass() const { return top_mass_; }
  const Eigen::Vector3d& gravity() const { return g_; }
  /// `rope.reeving_length` as AncfRope::setReevingLength: EA = EA_rope L / (L + L_s), L_s =
  /// equivalent_length [m] >= 0, following setLength. axialStiffness() is the effective EA.
  void setReevingLength(double equivalent_length);
  /// `rope.tension_only` (default true here as in scenes): false lets the bar take compression.
  void setTensionOnly(bool on) { tension_only_ = on; }
  bool tensionOnly() const { return tension_only_; }
  const Matrix6& massMatrix() const { return M_; }
  /// The applied load: gravity M [g; g] plus the external loads (half the rope's at each end).
  const Vector6& gravityForce() const { return Fg_; }
  /// External loads (wind): a force per unit length of rope [N/m] and one at the end [N].
  void setExternalLoad(const Eigen::Vector3d& per_length, const Eigen::Vector3d& end_force);

  /// Hoisting: the unstretched length becomes `length`, M and F_g are rebuilt (rope mass
  /// mu L exactly); the geometry q is kept. Throws std::invalid_argument for length <= 0.
  void setLength(double length);

  /// T = EA (l - L) / L, or 0 when slack [N].
  double tension(const Vector6& q) const;
  /// Q(q); the tangent K(q) into *K when given.
  void elasticForce(const Vector6& q, Vector6& Q, Matrix6* K = nullptr) const;
  /// Discrete gradient of the elastic energy over a step q0 -> q1 (docs/model.md
  /// "Energy-consistent step"): Q . (q1 - q0) = U(q1) - U(q0), Q(q, q) = dU/dq. With d = r_1 - r_0
  /// and s = |d|^2: Q = 2 Sbar [-d_m; d_m], Sbar the secant of W(s) = U(sqrt(s))
  /// (elements/discrete_gradient.hpp). K, when given: [[K_b, -K_b], [-K_b, K_b]] with
  /// K_b = 2 Sbar I + 8 kappa d_m d_m^T, a symmetric stand-in for 2 dQ/dq1 equal to the tangent
  /// stiffness for q1 = q0.
  void discreteGradientForce(const Vector6& q0, const Vector6& q1, Vector6& Q,
                             Matrix6* K = nullptr) const;
  /// Axial damping force Q_d(q, v) with coefficient c [s]; dQ_d/dv into *C when given.
  void dampingForce(double c, const Vector6& q, const Vector6& v, Vector6& Q,
                    Matrix6* C = nullptr) const;
  double elasticEnergy(const Vector6& q) const;
  /// The trapezoid's work error over a step q0 -> q1 where the bar is not taut at both ends,
  /// |(T0 + T1) / 2 (l1 - l0) - (U1 - U0)| [J] (its tension is linear in its length while taut,
  /// so the trapezoid misses only where it switches); 0 where taut at both.
  double slackSwitchWorkError(const Vector6& q0, const Vector6& q1) const;
  /// The straight rope from `top` along the unit vector d with length l [m].
  static Vector6 straight(const Eigen::Vector3d& top, const Eigen::Vector3d& d, double l);

 private:
  double L_, mu_, EA_, end_mass_, top_mass_;
  double rope_axial_stiffness_, reeving_length_ = 0.0;
  bool tension_only_ = true;
  Eigen::Vector3d g_;
  Matrix6 M_;
  Vector6 Fg_;
  Eigen::Vector3d ext_per_length_ = Eigen::Vector3d::Zero(), ext_end_ = Eigen::Vector3d::Zero();
  void updateLoad();
  /// Slack at chord length l: no force, no stiffness, no damping (tension-only and l <= L).
  bool slack(double l) const { return tension_only_ && !(l > L_); }
};

}  // namespace crane_twin
