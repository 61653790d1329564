// The flexible T8036 structure as the rope's support (docs/model.md).
//
// The generated geometry is taken as the structure's shape under its own weight (the jib and
// mast are fabricated with a camber that offsets the dead-load deflection, as built cranes
// are): z measures the motion about that self-weight equilibrium, so in the linear theory the
// self-weight drops out of the equations exactly. Free-DOF displacement u (slewing frame)
// = T z, with T = Phi (the lowest mass-normalised modes, `structure.model: modal`) or T = I
// (`full`):
//   modal:  z'' + 2 zeta Omega z' + Omega^2 z = Phi^T B^T R^T lambda
//   full:   M z'' + (alpha M + beta K) z' + K z = B^T R^T lambda,
// with Rayleigh damping alpha, beta matched to the modal damping ratio zeta at the first and
// the `structure.modes`-th natural frequencies (between them the damping ratio dips below zeta,
// above them it grows: the modes the modal model drops are damped out).
// The trolley point interpolates the rail nodes at the trolley radius s (weights B, docs/model.md):
//   r_p = R(theta) (X_p(s) + B T z),  R(theta) the slewing rotation about z.
// The trolley's own mass is not part of the structure: it rides on the rope's top node, which
// coincides with the trolley point through the constraint.
//
// Inertial loads of slewing (`slewing.inertial_loads: true`, docs/model.md): in the slewing frame,
// which turns with theta(t) about the tower axis z, every rotating node X (a node of the
// slewing unit, jib, counter-jib or cab) accelerates with the frame by
//   a(X) = theta'' e_z x X - theta'^2 (X_x, X_y, 0)        (Euler + centripetal),
// and its rotation DOFs by theta'' e_z; as nodal fields, a = theta'' r_theta + theta'^2 c with
// r_theta = [e_z x X; e_z] (the rigid slewing mode) and c = [-(X_x, X_y, 0); 0]. The
// structure's equations gain the d'Alembert load  f = -M (theta'' r_theta + theta'^2 c),
// T^T f in its coordinates. Neglected: the Coriolis load -2 theta' M (e_z x u') and the
// centrifugal change of stiffness, both of order theta' times the small deformation (at the
// 0.084 rad/s slewing limit, 2 theta' u' is under 1e-3 m/s^2 for u' < 5 mm/s); mast nodes do not
// turn (their field is 0), so mast elements at the slewing ring share a partial load.
#pragma once

#include <Eigen/CholmodSupport>
#include <memory>

#include "crane_twin/rope/rope_support.hpp"
#include "crane_twin/structure/modal_analysis.hpp"
#include "crane_twin/structure/tower_crane_structure.hpp"

namespace crane_twin {

/// Shared geometry of a flexible-structure support: rotation and the rows that pick the
/// trolley, cab and jib-tip translations out of u = T z.
class StructureSupportBase : public RopeSupport {
 public:
  void setPose(double theta, double radius) override;
  void setSlewMotion(double rate, double acceleration) override;
  /// Switch the inertial loads of slewing on (builds T^T M r_theta and T^T M c once).
  void enableSlewingLoads();
  bool slewingLoads() const { return euler_.size() > 0; }
  /// The d'Alembert load of slewing in the support's coordinates, T^T f (zero when off).
  Eigen::VectorXd slewingLoad() const;
  /// T^T f of an external free-DOF load f (an empty f removes it).
  void setExternalLoad(const Eigen::VectorXd& free_dof_force) override;
  void setExternalLoadScale(double s) override { external_scale_ = s; }
  /// T^T P, dense for modal coordinates (a few hundred numbers per pattern), P itself for T = I.
  void setExternalLoadPatterns(const Eigen::SparseMatrix<double>& patterns) override;
  /// external load = (T^T P) w. Throws std::invalid_argument for a w of another size than P's
  /// columns or not finite.
  void setExternalLoadWeights(const Eigen::VectorXd& w) override;
  /// The external load in the support's coordinates (empty when none).
  const Eigen::VectorXd& externalLoad() const { return external_; }
  Eigen::Vector3d point(const Eigen::VectorXd& z) const override { return r0_ + D_ * z; }
  Eigen::Vector3d pointMotion(const Eigen::VectorXd& dz) const override { return D_ * dz; }
  Eigen::VectorXd pointForceToCoordinates(const Eigen::Vector3d& f) const override {
    return D_.transpose() * f;
  }
  Eigen::Vector3d cabDisplacement(const Eigen::VectorXd& z) const override { return cab_ * z; }
  Eigen::Vector3d jibTipDisplacement(const Eigen::VectorXd& z) const override { return tip_ * z; }
  const TowerCraneStructure* structure() const override { return &structure_; }
  /// u = T z (T = Phi or I).
  Eigen::VectorXd structureDisplacement(const Eigen::VectorXd& z) const override {
    return modes_.size() > 0 ? Eigen::VectorXd(modes_ * z) : z;
  }

 protected:
  /// Build the rows for coordinates u = T z, T given by `modes` (nullptr: T = I).
  StructureSupportBase(const TowerCraneStructure& s, double trolley_radius, double slew_angle,
                       const Eigen::MatrixXd* modes);
  const TowerCraneStructure& structure_;
  Eigen::MatrixXd modes_;                        ///< T = Phi (modal), empty for T = I
  int pose_version_ = 0;                         ///< bumped by setPose (D changed)
  double pose_theta_ = 0.0, pose_radius_ = 0.0;  ///< [rad], [m] of the last setPose
  /// setIterationWeights' G = D A_z^-1 D^T where the weights (a, c, k) and the pose are those
  /// it was computed for (a run's steps share them), else nullptr; keepCompliance records a new
  /// one for the present pose and returns it.
  const Eigen::Matrix3d* keptCompliance(double a, double c, double k) const;
  const Eigen::Matrix3d& keepCompliance(double a, double c, double k, const Eigen::Matrix3d& G);
  Eigen::Vector3d r0_;
  Eigen::Matrix<double, 3, Eigen::Dynamic> D_, cab_, tip_;
  Eigen::VectorXd euler_, centrifugal_;  ///< T^T M r_theta, T^T M c (empty: loads off)
  Eigen::VectorXd external_;             ///< T^T f of the external load (empty: none)
  /// The load patterns in the coordinates: T^T P (modal) or P (T = I); none: 0 columns.
  Eigen::MatrixXd modal_patterns_;
  Eigen::SparseMatrix<double> patterns_;
  double external_scale_ = 1.0;
  double slew_rate_ = 0.0, slew_acceleration_ = 0.0;

 private:
  struct KeptCompliance {
    double a = -1.0, c = -1.0, k = -1.0;
    int pose_version = -1;
    Eigen::Matrix3d G = Eigen::Matrix3d::Zero();
  };
  KeptCompliance kept_compliance_;
};

/// The free-DOF fields of the slewing frame's motion (see above): r_theta = [e_z x X; e_z] and
/// c = [-(X_x, X_y, 0); 0] on the rotating nodes, 0 on the mast's.
void slewingFields(const TowerCraneStructure& s, Eigen::VectorXd& r_theta, Eigen::VectorXd& c);
/// Inertia of the rotating part about the slewing axis, J = r_theta^T M r_theta [kg m^2]
/// (r_theta of slewingFields: every node off the mast), plus a point mass m at radius r (the
/// trolley).
double slewingInertia(const TowerCraneStructure& s, double point_mass = 0.0, double radius = 0.0);

class ModalStructureSupport final : public StructureSupportBase {
 public:
  /// `modes` mass-normalised (phi^T M phi = I) modes of s; damping ratio zeta >= 0 per mode.
  ModalStructureSupport(const TowerCraneStructure& s, const ModalBasis& modes, double zeta,
                        double trolley_radius, double slew_angle);
  int size() const override { return static_cast<int>(omega2_.size()); }
  Eigen::VectorXd internalForce(const Eigen::VectorXd& z, const Eigen::VectorXd& zd,
                                const Eigen::VectorXd& zdd) const override;
  Eigen::Matrix3d setIterationWeights(double a, double c, double k) override;
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const override {
    return r.cwiseQuotient(diagonal_);
  }
  Eigen::VectorXd solvePointForce(const Eigen::Vector3d& f) const override {
    return (D_.transpose() * f).cwiseQuotient(diagonal_);
  }
  double energy(const Eigen::VectorXd& z, const Eigen::VectorXd& zd) const override;
  /// Omega_k^2 [rad^2/s^2] and 2 zeta Omega_k [1/s] of the modal coordinates z.
  const Eigen::VectorXd& omega2() const { return omega2_; }
  const Eigen::VectorXd& dampingTerms() const { return damping_; }

 private:
  Eigen::VectorXd omega2_, damping_;  ///< Omega^2, 2 zeta Omega
  Eigen::VectorXd diagonal_;          ///< A_z (diagonal)
};

class FullStructureSupport final : public StructureSupportBase {
 public:
  /// Rayleigh damping matched to zeta at omega_low and omega_high [rad/s].
  FullStructureSupport(const TowerCraneStructure& s, double zeta, double omega_low,
                       double omega_high, double trolley_radius, double slew_angle);
  int size() const override { return static_cast<int>(M_.rows()); }
  Eigen::VectorXd internalForce(const Eigen::VectorXd& z, const Eigen::VectorXd& zd,
                                const Eigen::VectorXd& zdd) const override;
  Eigen::Matrix3d setIterationWeights(double a, double c, double k) override;
  Eigen::VectorXd solve(const Eigen::VectorXd& r) const override { return llt_.solve(r); }
  Eigen::VectorXd solvePointForce(const Eigen::Vector3d& f) const override { return X_ * f; }
  double energy(const Eigen::VectorXd& z, const Eigen::VectorXd& zd) const override;
  double rayleighAlpha() const { return alpha_; }
  double rayleighBeta() const { return beta_; }

 private:
  SparseMatrix M_, K_, A_;
  double alpha_ = 0.0, beta_ = 0.0;
  double weight_m_ = -1.0, weight_k_ = -1.0;    ///< A_z = weight_m M + weight_k K, factorised
  Eigen::Matrix<double, Eigen::Dynamic, 3> X_;  ///< A_z^-1 D^T, of the kept compliance
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt_;
};

/// A rigid structure (`structure.model: rigid`): the rope hangs from the undeformed trolley
/// point R(theta) X_p(s); no structural coordinates.
class RigidTrolleySupport final : public FixedAnchor {
 public:
  RigidTrolleySupport(const TowerCraneStructure& s, double trolley_radius, double slew_angle);
  void setPose(double theta, double radius) override;
  const TowerCraneStructure* structure() const override { return &structure_; }
  /// Always zero: the structure does not deform.
  Eigen::VectorXd structureDisplacement(const Eigen::VectorXd&) const override;

 private:
  const TowerCraneStructure& structure_;
};

/// Rotation of the slewing frame about the world z axis by theta [rad].
Eigen::Matrix3d slewRotation(double theta);
/// Undeformed trolley point X_p(s) at radius s, slewing frame [m]. Throws std::out_of_range
/// outside the rail.
Eigen::Vector3d trolleyPoint(const TowerCraneStructure& s, double radius);

}  // namespace crane_twin
