// What holds the rope's top node (docs/model.md): a fixed anchor (crane: none, or a rigid
// structure), or the flexible crane structure in modal or full FE coordinates z.
//
// The support point is linear in z (small-deformation structure, slewing angle and trolley
// radius fixed during a step):
//   r_p(z) = r_0 + D z                                             [m, world frame]
// and the support's own dynamics are linear:
//   M_z z'' + C_z z' + K_z z - D^T lambda = 0,
// with lambda the force the rope's top node exerts on the support point (the constraint
// C = r_top - r_p(z) = 0 acts on the rope with -lambda). The full-order solver eliminates z
// from every linear solve by its Schur complement: with A_z = a M_z + c C_z + k K_z,
//   G = D A_z^-1 D^T  (3 x 3 compliance of the support point),
// so the rope's KKT system only grows by the 3 x 3 block -G.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>

namespace crane_twin {

class TowerCraneStructure;

class RopeSupport {
 public:
  virtual ~RopeSupport() = default;
  /// Number of support coordinates z (0 for a fixed anchor).
  virtual int size() const = 0;
  /// r_p(z) [m].
  virtual Eigen::Vector3d point(const Eigen::VectorXd& z) const = 0;
  /// D dz: motion of the support point for a coordinate increment dz.
  virtual Eigen::Vector3d pointMotion(const Eigen::VectorXd& dz) const = 0;
  /// D^T f: generalised force of a point force f at the support point.
  virtual Eigen::VectorXd pointForceToCoordinates(const Eigen::Vector3d& f) const = 0;
  /// M_z z'' + C_z z' + K_z z - f_z(t), f_z the loads applied to the structure itself (the
  /// inertial loads of slewing when switched on; see setSlewMotion).
  virtual Eigen::VectorXd internalForce(const Eigen::VectorXd& z, const Eigen::VectorXd& zd,
                                        const Eigen::VectorXd& zdd) const = 0;
  /// Factorise A_z = a M_z + c C_z + k K_z (cached: only refactorised when (a, c, k) change)
  /// and return G = D A_z^-1 D^T.
  virtual Eigen::Matrix3d setIterationWeights(double a, double c, double k) = 0;
  /// A_z^-1 r for the weights last set.
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& r) const = 0;
  /// A_z^-1 D^T f for the weights last set (precomputed columns: no solve).
  virtual Eigen::VectorXd solvePointForce(const Eigen::Vector3d& f) const = 0;
  /// 1/2 z'^T M_z z' + 1/2 z^T K_z z [J] (strain energy measured from the self-weight state).
  virtual double energy(const Eigen::VectorXd& z, const Eigen::VectorXd& zd) const = 0;
  /// Move the support point with the drives: slewing angle theta [rad] and trolley radius [m]
  /// (docs/model.md). The constraint then holds the rope at the new point from the next step on
  /// (a rheonomic constraint). No effect on a fixed anchor.
  virtual void setPose(double /*theta*/, double /*radius*/) {}
  /// The drives' pose at the start (theta0, radius0) and end (theta1, radius1) of the step to
  /// come, the end's already set by setPose (SupportedRopeSimulation::advanceDrives); equal ends
  /// for a step without drive motion. A step the solver halves (stepWithHalving) holds the rope
  /// at the pose of each sub-step's end time (setStepFraction): held at the full step's end
  /// pose, a half step had to follow that step's whole motion in half the time, and the
  /// constraint force took the difference as an impulse (a slewing crane's trolley moves
  /// 0.3 mm in half a 1 ms step; the pendulum's top then rang at 7 MN, docs/model.md
  /// "Full-order solution").
  void setPoseStep(double theta0, double radius0, double theta1, double radius1);
  /// The pose at fraction f of the step (0 < f <= 1): theta0 + f (theta1 - theta0), radius
  /// likewise (the drives' ramps change a rate by at most a_max h within a step); f = 1 is the
  /// step's end pose again, exactly. Nothing to do on a step without drive motion.
  void setStepFraction(double f);
  /// Slewing rate theta' [rad/s] and acceleration theta'' [rad/s^2] of the step to come, for
  /// the inertial loads of slewing on the structure (docs/model.md, `slewing.inertial_loads`;
  /// StructureSupportBase). No effect on a support without structural coordinates.
  virtual void setSlewMotion(double /*rate*/, double /*acceleration*/) {}
  /// External load on the structure (wind, docs/model.md "Wind"): forces and moments on the
  /// structure's free DOFs, slewing frame [N, N m]; it enters f_z of internalForce. No effect
  /// on a support without structural coordinates (a rigid structure does not deform).
  virtual void setExternalLoad(const Eigen::VectorXd& /*free_dof_force*/) {}
  /// Scale s of that load (the gust: s = g(t)^2), so a load that only changes in size is not
  /// projected again.
  virtual void setExternalLoadScale(double /*s*/) {}
  /// The external load as a combination of fixed free-DOF load patterns (the columns of P,
  /// slewing frame): P is taken to the support's coordinates once here (structureWindPatterns),
  /// then setExternalLoadWeights(w) sets the load P w, a small product per change of w. An empty
  /// P removes the patterns. No effect without structural coordinates.
  virtual void setExternalLoadPatterns(const Eigen::SparseMatrix<double>& /*patterns*/) {}
  virtual void setExternalLoadWeights(const Eigen::VectorXd& /*w*/) {}
  /// Displacement of the cab and jib-tip reference points from the undeformed structure,
  /// slewing frame [m] (docs/cli.md cab_d*, jib_tip_d*); zero for an anchor.
  virtual Eigen::Vector3d cabDisplacement(const Eigen::VectorXd& z) const = 0;
  virtual Eigen::Vector3d jibTipDisplacement(const Eigen::VectorXd& z) const = 0;
  /// The structure mesh behind the support (nullptr for an anchor without a crane).
  virtual const TowerCraneStructure* structure() const { return nullptr; }
  /// Free-DOF displacement u = T z of that mesh, slewing frame [m, rad] (empty without one).
  virtual Eigen::VectorXd structureDisplacement(const Eigen::VectorXd& /*z*/) const {
    return Eigen::VectorXd();
  }

 private:
  double theta0_ = 0.0, radius0_ = 0.0, theta1_ = 0.0, radius1_ = 0.0;
  double fraction_ = 1.0;    ///< the fraction of the step whose pose is set
  bool pose_moves_ = false;  ///< the step's ends differ
};

/// Rope top tension [N]: the force between the rope's top node and the support point less the
/// weight and inertia of the mass m_top that moves with that point (the trolley),
/// |lambda + m_top (r_0'' - g)|, with r_0'' the top node's acceleration [m/s^2].
inline double ropeTopTension(const Eigen::Vector3d& lambda, double top_mass,
                             const Eigen::Vector3d& top_acceleration,
                             const Eigen::Vector3d& gravity) {
  return (lambda + top_mass * (top_acceleration - gravity)).norm();
}

/// A fixed point in the world frame (no coordinates).
class FixedAnchor : public RopeSupport {
 public:
  explicit FixedAnchor(const Eigen::Vector3d& p) : p_(p) {}
  int size() const override { return 0; }
  Eigen::Vector3d point(const Eigen::VectorXd&) const override { return p_; }
  Eigen::Vector3d pointMotion(const Eigen::VectorXd&) const override {
    return Eigen::Vector3d::Zero();
  }
  Eigen::VectorXd pointForceToCoordinates(const Eigen::Vector3d&) const override {
    return Eigen::VectorXd();
  }
  Eigen::VectorXd internalForce(const Eigen::VectorXd&, const Eigen::VectorXd&,
                                const Eigen::VectorXd&) const override {
    return Eigen::VectorXd();
  }
  Eigen::Matrix3d setIterationWeights(double, double, double) override {
    return Eigen::Matrix3d::Zero();
  }
  Eigen::VectorXd solve(const Eigen::VectorXd&) const override { return Eigen::VectorXd(); }
  Eigen::VectorXd solvePointForce(const Eigen::Vector3d&) const override {
    return Eigen::VectorXd();
  }
  double energy(const Eigen::VectorXd&, const Eigen::VectorXd&) const override { return 0.0; }
  Eigen::Vector3d cabDisplacement(const Eigen::VectorXd&) const override {
    return Eigen::Vector3d::Zero();
  }
  Eigen::Vector3d jibTipDisplacement(const Eigen::VectorXd&) const override {
    return Eigen::Vector3d::Zero();
  }

 protected:
  Eigen::Vector3d p_;
};

}  // namespace crane_twin
