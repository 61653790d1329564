// The hanging hoist rope as a chain of ANCF cable elements (docs/model.md), with the hook block and
// payload as a point mass on the last node and the trolley (when the rope hangs from a crane)
// as a point mass on the first: the top node coincides with the trolley point through the
// constraint, so the trolley's inertia and weight act there.
//
// Coordinates q (6 per node, node 0 at the top): q = [r_0, r_0x, r_1, r_1x, ..., r_n, r_nx] in
// the world frame [m, -]. Element k spans nodes k and k+1 and uses q.segment(6k, 12).
//   M q'' + Q(q) = F_g,   M = sum_k int rho A S^T S dx + m_top (I at r_0) + m_end (I at r_n),
//   F_g = M g_field
// (constant: gravity is a uniform field), Q = dU/dq summed over elements.
//
// With a rigging (setRigging, docs/model.md "Hook block"): the payload point r_p hangs from the
// hook node r_n on a straight tension-only bar (PendulumRope's, hinged at both ends):
// q = [r_0, r_0x, ..., r_n, r_nx, r_p] (6 (n + 1) + 3). The hook block is a point mass m_hook
// at r_n; the bar's consistent mass and the payload m_end act on [r_n; r_p]. Hoisting
// (setLength) rescales the hoist rope's elements only.
#pragma once

#include <Eigen/Sparse>
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "crane_twin/elements/ancf_cable_element.hpp"
#include "crane_twin/elements/sparse_assembly.hpp"
#include "crane_twin/rope/pendulum_rope.hpp"

namespace crane_twin {

class AncfRope {
 public:
  /// elements >= 1 of equal unstretched length L / elements; material of the equivalent rope.
  AncfRope(int elements, double length, double mass_per_length, double axial_stiffness,
           double bending_stiffness, double end_mass, const Eigen::Vector3d& gravity,
           double top_mass = 0.0);

  /// Elements of the hoist rope (the rigging is a bar, not an element).
  int elements() const { return elements_; }
  /// Nodes with a position: the hoist rope's n + 1 and, with a rigging, the payload's.
  int nodes() const { return elements_ + (hasRigging() ? 2 : 1); }
  int dofs() const { return 6 * (elements_ + 1) + (hasRigging() ? 3 : 0); }
  /// Index of node j's position in q (6 j; the payload's, the last 3, with a rigging).
  int positionIndex(int j) const { return j <= elements_ ? 6 * j : dofs() - 3; }
  Eigen::Vector3d position(const Eigen::VectorXd& q, int j) const {
    return q.segment<3>(positionIndex(j));
  }
  /// Indices in q of the rigging bar's coordinates [r_n; r_p] (with a rigging).
  std::array<int, 6> riggingDofs() const;
  /// The rigging bar (hook to payload; its end mass the payload's). Only with a rigging.
  const PendulumRope& rigging() const { return *rigging_; }
  /// The hook block's mass at the hoist rope's end under a rigging [kg] (0 without).
  double hookMass() const { return hook_mass_; }
  /// The hoist rope's unstretched (hanging) length [m], without the rigging.
  double length() const { return element_.length * elements_; }
  /// The payload on a rigging of unstretched length `length` [m] > 0 under the hook block of mass
  /// `hook_mass` [kg] > 0 (docs/model.md "Hook block"): a tension-only bar of mass_per_length
  /// [kg/m] >= 0 and axial_stiffness EA [N] > 0. Rebuilds M and F_g. Throws
  /// std::invalid_argument otherwise.
  void setRigging(double length, double hook_mass, double mass_per_length, double axial_stiffness);
  bool hasRigging() const { return rigging_.has_value(); }
  /// This hoist rope without its rigging, the hook block, the bar's mass and the payload lumped
  /// on its end node (same length, material, reeving, law): the rope whose hanging shapes the
  /// reduced basis takes for a rope with a rigging (InvariantRopeBasis).
  AncfRope lumpedAtHook() const;
  /// The hook block's node: the hoist rope's last (the chain's end without a rigging).
  int hookNode() const { return elements_; }
  /// Points of the chain (sampleRopeCurve, then the rigging bar's straight line).
  /// element_length > 0: the hoist rope's elements at that length instead of their own (a
  /// reduced run that hoisted without updating this rope).
  std::vector<Eigen::Vector3d> sampleCurve(const Eigen::VectorXd& q, int per_element,
                                           double element_length = 0.0) const;
  double endMass() const { return end_mass_; }
  double topMass() const { return top_mass_; }
  const Eigen::Vector3d& gravity() const { return gravity_; }
  const AncfCableProperties& element() const { return element_; }
  /// `rope.reeving_length` (docs/model.md "Reeving"): the winch's line in series with the hanging
  /// rope, given as its length L_s = L_r / n along the equivalent cable [m] >= 0. The elements'
  /// EA becomes EA_rope L / (L + L_s) (and follows setLength): the hook's axial stiffness
  /// EA_rope / (L + L_s), the reeving's stretch smeared over the hanging length.
  void setReevingLength(double equivalent_length);
  double reevingLength() const { return reeving_length_; }
  /// The elements' EA at hanging length L: EA_rope L / (L + L_s) [N].
  double axialStiffnessAt(double L) const {
    return rope_axial_stiffness_ * L / (L + reeving_length_);
  }
  /// `rope.tension_only` (docs/scenes.md): no axial force in compression (AncfCableProperties).
  void setTensionOnly(bool on) {
    element_.tension_only = on;
    revision_ = nextRevision();
  }
  const SparseMatrix& massMatrix() const { return M_; }
  /// The applied load vector: gravity F_g = M g_field plus the external loads below.
  const Eigen::VectorXd& gravityForce() const { return Fg_; }
  /// External loads (wind, docs/model.md "Wind"): a force per unit length [N/m], uniform along
  /// the rope, and a force on the end node [N]; added to gravityForce() as
  /// int S^T f dx (per element [l/2 f, l^2/12 f, l/2 f, -l^2/12 f]) and at r_n.
  void setExternalLoad(const Eigen::Vector3d& per_length, const Eigen::Vector3d& end_force);
  const Eigen::Vector3d& externalPerLength() const { return ext_per_length_; }
  const Eigen::Vector3d& externalEndForce() const { return ext_end_; }

  /// Hoisting by uniform rescaling (docs/model.md): every element's reference length becomes
  /// length / elements; M and F_g are updated in place (rope mass mu L exactly, same pattern).
  /// Throws std::invalid_argument for a non-positive length.
  void setLength(double length);
  /// Rescale a coordinate-like vector (q, v, q'') so the rope's geometry is unchanged under a
  /// length change from `from` to `to`: positions stay, slopes r_x scale by from / to.
  static void rescaleSlopes(Eigen::VectorXd& x, double from, double to);
  /// rescaleSlopes on the hoist rope's nodes only (a rigging's payload point, after them, has no
  /// slope).
  void rescaleHoistSlopes(Eigen::VectorXd& x, double from, double to) const;

  /// Elastic force Q(q); appends the tangent K(q) as triplets when `tangent` is not null.
  void elasticForce(const Eigen::VectorXd& q, Eigen::VectorXd& Q,
                    std::vector<Eigen::Triplet<double>>* tangent = nullptr) const;
  /// Assembled tangent stiffness K(q) = dQ/dq (n x n); Q(q) into *force when given.
  SparseMatrix tangentStiffness(const Eigen::VectorXd& q, Eigen::VectorXd* force = nullptr) const;
  double elasticEnergy(const Eigen::VectorXd& q) const;
  /// The axial damping force of `rope.damping` = c [s] at (q, v) (n values): ancfAxialDampingForce
  /// over the hoist rope's elements plus the rigging bar's (PendulumRope::dampingForce), the
  /// force full order's equations add to Q(q) (zero for c = 0).
  Eigen::VectorXd axialDampingForce(double c, const Eigen::VectorXd& q,
                                    const Eigen::VectorXd& v) const;
  /// Sum of ancfSlackSwitchWorkError over the hoist rope's elements for a step q0 -> q1, plus the
  /// rigging bar's |(T0 + T1) / 2 (l1 - l0) - (U1 - U0)| where it is not taut at both ends [J]
  /// (0 unless tension_only; exactly 0 where the rope is taut at both ends).
  double slackSwitchWorkError(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) const;
  /// The same from the hoist rope's axial strains at both ends (axialStrains of q0 and q1, which
  /// a caller may keep from an earlier call) and, with a rigging, q0 and q1 for its bar.
  double slackSwitchWorkError(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1,
                              const Eigen::VectorXd& eps0, const Eigen::VectorXd& eps1) const;
  /// The hoist rope's axial strains eps = |r_x| - 1 at every Gauss point, element by element
  /// (elements() x gauss_points values; ancfAxialStrains).
  void axialStrains(const Eigen::VectorXd& q, Eigen::VectorXd& eps) const;
  bool tensionOnly() const { return element_.tension_only; }
  /// Which rope this is: a value that changes with every call that changes M, F_g or U(q) (the
  /// setters above), drawn from a process-wide counter, so two ropes that differ never share it
  /// (a copy shares its original's). A solver may keep values of the energy under it.
  std::uint64_t revision() const { return revision_; }

  /// Node `node`'s position in a chain without a rigging (position() in general).
  static Eigen::Vector3d nodePosition(const Eigen::VectorXd& q, int node) {
    return q.segment<3>(6 * node);
  }
  /// Smallest nodal axial strain min_j |r_j,x| - 1 over the hoist rope's nodes (a rigging's
  /// payload point, after them, has no slope): the slack checks of the reduced models.
  static double minNodalStrain(const Eigen::VectorXd& q);
  /// Kinetic energy of the velocities v relative to the top node's, 1/2 w^T M w with
  /// w_j = v_j - v_0 on every node position [J] (what a projection may drop).
  double kineticEnergyRelativeToTop(const Eigen::VectorXd& v) const;
  /// Straight, unstretched rope from `top` along unit direction d.
  /// (With tension_only: shortened to the law's slack edge, strain -kSlackBand, so that it carries
  /// no force.)
  Eigen::VectorXd straight(const Eigen::Vector3d& top, const Eigen::Vector3d& d) const;
  /// Straight rope from `top` along d, stretched by the tension profile
  /// T(x) = end_force + force_per_length (L - x) [N] (strain T / EA; node slopes at the nodes'
  /// tension, positions integrated with the elements' mid tension): the hanging rope's static
  /// shape along its chord, e.g. as a Newton start or a linearisation point.
  Eigen::VectorXd stretchedStraight(const Eigen::Vector3d& top, const Eigen::Vector3d& d,
                                    double end_force, double force_per_length) const;

 private:
  int elements_;
  AncfCableProperties element_;
  double end_mass_, top_mass_;
  double rope_axial_stiffness_, reeving_length_ = 0.0;
  std::optional<PendulumRope> rigging_;  ///< hook to payload; empty: no rigging
  double hook_mass_ = 0.0;
  Eigen::Vector3d gravity_;
  SparseMatrix M_;
  Eigen::VectorXd Fg_;
  Eigen::Vector3d ext_per_length_ = Eigen::Vector3d::Zero(), ext_end_ = Eigen::Vector3d::Zero();
  std::vector<double> unit_mass_, point_mass_;  ///< per entry of M_ (setLength)
  std::vector<int> mass_exponent_;              ///< s_i + s_j per entry (0: l, 1: l^2, 2: l^3)
  std::uint64_t revision_ = nextRevision();
  static std::uint64_t nextRevision();
  // The rigging bar's share of slackSwitchWorkError (0 without a rigging).
  double riggingSwitchWorkError(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) const;
  void assembleMass();
  void updateGravityForce();
};

/// Points r(x) of an ANCF rope with coordinates q (6 per node) and element length l, sampled
/// `per_element` times per element plus the end node (docs/model.md shape functions).
std::vector<Eigen::Vector3d> sampleRopeCurve(const Eigen::VectorXd& q, double l, int per_element);

}  // namespace crane_twin
