#include "crane_twin/rope/pendulum_rope.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "crane_twin/elements/discrete_gradient.hpp"

namespace crane_twin {

PendulumRope::PendulumRope(double length, double mass_per_length, double axial_stiffness,
                           double end_mass, const Eigen::Vector3d& gravity, double top_mass)
    : L_(length),
      mu_(mass_per_length),
      EA_(axial_stiffness),
      end_mass_(end_mass),
      top_mass_(top_mass),
      rope_axial_stiffness_(axial_stiffness),
      g_(gravity) {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("pendulum rope: ") + what);
  };
  require(std::isfinite(mu_) && mu_ >= 0.0, "mass per length must be finite and >= 0");
  require(std::isfinite(EA_) && EA_ > 0.0, "axial stiffness must be finite and > 0");
  require(std::isfinite(end_mass_) && end_mass_ >= 0.0, "end mass must be finite and >= 0");
  require(std::isfinite(top_mass_) && top_mass_ >= 0.0, "top mass must be finite and >= 0");
  require(g_.allFinite(), "gravity must be finite");
  setLength(length);
}

void PendulumRope::setLength(double length) {
  if (!(std::isfinite(length) && length > 0.0)) {
    throw std::invalid_argument("pendulum rope: length must be finite and > 0");
  }
  L_ = length;
  EA_ = rope_axial_stiffness_ * L_ / (L_ + reeving_length_);
  const double m = mu_ * L_;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  M_.setZero();
  M_.topLeftCorner<3, 3>() = (m / 3.0 + top_mass_) * I;
  M_.bottomRightCorner<3, 3>() = (m / 3.0 + end_mass_) * I;
  M_.topRightCorner<3, 3>() = M_.bottomLeftCorner<3, 3>() = (m / 6.0) * I;
  updateLoad();
}

void PendulumRope::setReevingLength(double equivalent_length) {
  if (!(std::isfinite(equivalent_length) && equivalent_length >= 0.0)) {
    throw std::invalid_argument("pendulum rope: reeving length must be finite and >= 0");
  }
  reeving_length_ = equivalent_length;
  EA_ = rope_axial_stiffness_ * L_ / (L_ + reeving_length_);
}

void PendulumRope::updateLoad() {
  Vector6 gg;
  gg << g_, g_;
  Fg_ = M_ * gg;
  Fg_.head<3>() += 0.5 * L_ * ext_per_length_;
  Fg_.tail<3>() += 0.5 * L_ * ext_per_length_ + ext_end_;
}

void PendulumRope::setExternalLoad(const Eigen::Vector3d& per_length,
                                   const Eigen::Vector3d& end_force) {
  if (!per_length.allFinite() || !end_force.allFinite()) {
    throw std::invalid_argument("pendulum rope: external load must be finite");
  }
  ext_per_length_ = per_length;
  ext_end_ = end_force;
  updateLoad();
}

double PendulumRope::tension(const Vector6& q) const {
  const double l = (q.tail<3>() - q.head<3>()).norm();
  return slack(l) ? 0.0 : EA_ * (l - L_) / L_;
}

void PendulumRope::elasticForce(const Vector6& q, Vector6& Q, Matrix6* K) const {
  const Eigen::Vector3d d = q.tail<3>() - q.head<3>();
  const double l = d.norm();
  Q.setZero();
  if (K) K->setZero();
  if (!(l > 0.0) || slack(l)) return;  // no force, no stiffness
  const Eigen::Vector3d u = d / l;
  const double T = EA_ * (l - L_) / L_;
  Q.head<3>() = -T * u;
  Q.tail<3>() = T * u;
  if (!K) return;
  const Eigen::Matrix3d uu = u * u.transpose();
  const Eigen::Matrix3d Kb = EA_ / L_ * uu + T / l * (Eigen::Matrix3d::Identity() - uu);
  K->topLeftCorner<3, 3>() = Kb;
  K->bottomRightCorner<3, 3>() = Kb;
  K->topRightCorner<3, 3>() = -Kb;
  K->bottomLeftCorner<3, 3>() = -Kb;
}

void PendulumRope::discreteGradientForce(const Vector6& q0, const Vector6& q1, Vector6& Q,
                                         Matrix6* K) const {
  // W(s) = U(l), l = sqrt(s): W' = T / (2 l), W'' = (T' l - T) / (4 l^3), T' = EA / L taut.
  const auto W = [&](double s) {
    const double l = std::sqrt(s);
    return slack(l) ? 0.0 : 0.5 * EA_ / L_ * (l - L_) * (l - L_);
  };
  const auto dW = [&](double s) {
    const double l = std::sqrt(s);
    return slack(l) ? 0.0 : EA_ * (l - L_) / L_ / (2.0 * l);
  };
  const auto ddW = [&](double s) {
    const double l = std::sqrt(s);
    return slack(l) ? 0.0 : (EA_ / L_ * l - EA_ * (l - L_) / L_) / (4.0 * l * l * l);
  };
  const Eigen::Vector3d d0 = q0.tail<3>() - q0.head<3>(), d1 = q1.tail<3>() - q1.head<3>();
  const Eigen::Vector3d dm = 0.5 * (d0 + d1);
  const SquaredLengthSecant sec =
      squaredLengthSecant(d0.squaredNorm(), d1.squaredNorm(), W, dW, ddW);
  Q.head<3>() = -2.0 * sec.slope * dm;
  Q.tail<3>() = 2.0 * sec.slope * dm;
  if (!K) return;
  const Eigen::Matrix3d Kb =
      2.0 * sec.slope * Eigen::Matrix3d::Identity() + 8.0 * sec.curvature * dm * dm.transpose();
  K->topLeftCorner<3, 3>() = Kb;
  K->bottomRightCorner<3, 3>() = Kb;
  K->topRightCorner<3, 3>() = -Kb;
  K->bottomLeftCorner<3, 3>() = -Kb;
}

void PendulumRope::dampingForce(double c, const Vector6& q, const Vector6& v, Vector6& Q,
                                Matrix6* C) const {
  const Eigen::Vector3d d = q.tail<3>() - q.head<3>();
  const double l = d.norm();
  Q.setZero();
  if (C) C->setZero();
  if (c == 0.0 || !(l > 0.0) || slack(l)) return;
  const Eigen::Vector3d u = d / l;
  const double k = c * EA_ / L_;
  const double Td = k * u.dot(v.tail<3>() - v.head<3>());
  Q.head<3>() = -Td * u;
  Q.tail<3>() = Td * u;
  if (!C) return;
  const Eigen::Matrix3d Cb = k * u * u.transpose();
  C->topLeftCorner<3, 3>() = Cb;
  C->bottomRightCorner<3, 3>() = Cb;
  C->topRightCorner<3, 3>() = -Cb;
  C->bottomLeftCorner<3, 3>() = -Cb;
}

double PendulumRope::slackSwitchWorkError(const Vector6& q0, const Vector6& q1) const {
  const double T0 = tension(q0), T1 = tension(q1);
  if (T0 > 0.0 && T1 > 0.0) return 0.0;
  const double l0 = (q0.tail<3>() - q0.head<3>()).norm(), l1 = (q1.tail<3>() - q1.head<3>()).norm();
  return std::abs(0.5 * (T0 + T1) * (l1 - l0) - (elasticEnergy(q1) - elasticEnergy(q0)));
}

double PendulumRope::elasticEnergy(const Vector6& q) const {
  const double l = (q.tail<3>() - q.head<3>()).norm();
  return slack(l) ? 0.0 : 0.5 * EA_ / L_ * (l - L_) * (l - L_);
}

Vector6 PendulumRope::straight(const Eigen::Vector3d& top, const Eigen::Vector3d& d, double l) {
  Vector6 q;
  q << top, top + l * d;
  return q;
}

}  // namespace crane_twin
