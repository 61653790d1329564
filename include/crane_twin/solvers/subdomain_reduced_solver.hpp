// Reduced-order (R-ANCF) dynamics of the rope on its support: the paper's method (Yu et al.
// 2024, eq. 6-17; docs/model.md).
//
// Subdomains. In the subdomain that starts at the rope state e_m the elastic force is
// linearised, Q(e) = Q_m + K_m (e - e_m) (paper eq. 8-9), and the rope moves in
//   e = e_m + Phi_c p_c + T u_b,
// Phi_c the lowest mass-normalised modes of (K_m, M) with the top node's position held
// (RopeModes), T the three rigid translations of the whole rope (unit vectors on every node's
// position, zero on slopes): u_b is the top node's displacement, K_m T = 0 and
// Phi_c^T K_m T = 0 exactly, so the reduced stiffness is diag(Omega^2, 0). With y = [p_c; u_b]:
//   M_r y'' + K_r y + E^T lambda = f_r,        M_r = [I  M_cb; M_cb^T  M_bb],
//   M_z z'' + C_z z' + K_z z - D^T lambda = 0, K_r = diag(Omega^2, 0),
//   r_top,m + u_b - r_p(z) = 0,                f_r = [Phi_c; T]^T (F_g - Q_m), E = [0 I3]
// (paper eq. 15-17 with the constraint Jacobian in principal coordinates: dC/dp_c = 0,
// dC/du_b = I). The subdomain's system is linear with constant matrices, so one linear solve
// per generalized-alpha step is exact (no Newton iterations). The solve eliminates p_c
// (diagonal plus a rank-3 mass coupling) and z (the support's Schur complement G) and ends in
// a 6 x 6 system for (u_b, lambda), factorised once per subdomain: O(r + k) work per step.
//
// A new subdomain starts after a step when max_j |r_j - r_j,m - u_b| > delta over the rope
// nodes: paper eq. (10) less the rigid translation of the whole rope, which the linearisation
// represents exactly (the elastic force is translation-invariant); in the chord's frame (below)
// less its rotation too. At the switch K_m and Q_m are rebuilt at the current e, the modes updated
// from the previous block (warm, RopeModes) or recomputed, and the state carried over: positions
// exactly (y = 0 at the new e_m), velocities and the generalized-alpha accelerations by the
// M-orthogonal projection onto the new basis, M_r w = B^T M x. The projection can only lose
// kinetic energy; the loss 1/2 (v^T M v - w^T M_r w) is summed in `projectionEnergyLoss`.
//
// Co-rotational subdomains (settings.corotational). The linear map moves a swinging
// rope along the tangent of its arc: after a chord rotation theta the payload sits L theta^2 / 2
// off the arc, a spurious stretch the next linearisation turns into an axial force of
// EA theta^2 / 2 (3.5 kN at delta = 0.5 m on the T8036's 60 m rope). The elastic force is
// rotation-invariant, Q(R e) = R Q(e) (the rope's M is block-diagonal in 3 x 3 identities, so
// R M R^T = M too), so the linearised force is right to first order in theta and the error is
// that of the map. The co-rotational map keeps the linear dynamics in y and maps it with the
// chord rotation: with D = Phi_c p_c (top rows zero), c = chord at e_m (last node - top),
// theta = c x D_last / |c|^2 (the chord's infinitesimal rotation), R = exp([theta]x), and per
// node block b (position relative to the top, or slope) of base_b = e_m,b (less the top):
//   e_b = top_m + u_b + R (base_b + D_b - theta x base_b)    (positions; slopes without top_m +
//   u_b)
// and its time derivatives (omega = J_l(theta) theta', J_l the left Jacobian of SO(3)). With
// theta = 0 it is the linear map. At a switch the state is carried in these coordinates and the
// basis rotated with the chord before its update: the modes of R e are R Phi
// (K(R e) = R K(e) R^T). The dynamics in the frame carry the frame's inertia and the rotation
// of gravity (.cpp, frameLoad), so the chord's rotation needs no new subdomain: the criterion
// reads the deformation in the frame, and a rotation past settings.max_chord_rotation starts
// one.
// Hoisting subdomains (a step each, BasisUpdate::modes_and_correction or ritz) keep the linear
// map: measured on the operator cycle, the frame there gave 5.0 m payload error (fixed: 5.6 mm).
//
// Hoisting: the full model's scheme, uniform rescaling (CraneSimulation::
// applyRopeLength), applied to the expanded state, then a new subdomain at it (every length
// change starts one). The fixed-top modes lack the shape a length change asks for: the rope's
// stretch along its length (a truncated basis can only represent it through the modes that
// happen to carry axial motion, and the projection at each switch then throws the winch's
// velocity field away). Such a subdomain gets a static-correction vector: psi solves
// K_ii psi = -dQ_i with the top position held, dQ = Q(e; L_new) - Q(e; L_old) the change of the
// elastic force the length change made at the rescaled state (the static response to the force
// it left unbalanced), M-orthogonalised against the modes, and a Rayleigh-Ritz
// step on [Phi_c psi] keeps the reduced stiffness diagonal. A length change of a millimetre
// hardly changes the rope's modes, so between such full updates a hoisting subdomain keeps the
// previous block [Phi_c psi] and only re-linearises: Rayleigh-Ritz of the block with the new
// K_m and M (BasisUpdate::ritz), which keeps Phi^T M Phi = I and Phi^T K_m Phi diagonal.
#pragma once

#include <chrono>

#include "crane_twin/rope/rope_modes.hpp"
#include "crane_twin/solvers/full_order_solver.hpp"

namespace crane_twin {

/// How the rope basis is renewed at a subdomain switch: cold (modes of the new tangent from
/// scratch, the paper's method as printed) or warm (subspace iteration from the previous block
/// plus Rayleigh-Ritz, RopeModes).
enum class ModeUpdate { cold, warm };

struct SubdomainSettings {
  int kept_modes = 10;  ///< fixed-top rope modes kept (plus the 3 translations)
  double delta = 0.05;  ///< subdomain criterion [m]
  ModeUpdate update = ModeUpdate::warm;
  /// Co-rotational subdomains (header): the chord's rotation within a subdomain is mapped to a
  /// finite rotation, and the basis rotated with the chord at a switch. false: the paper's
  /// linear map e = e_m + Phi_c p_c + T u_b as printed.
  bool corotational = false;
  /// Largest chord rotation within one subdomain [rad] (corotational): the frame leaves out
  /// terms of order theta times the frame's rates (.cpp), so a swing past this starts a new
  /// subdomain whatever the deformation. Measured on t8036_slew90 (docs/model.md): 0.1 rad
  /// 0.051 m, 0.03 rad 5.3e-3 m, 0.01 rad 3.4e-3 m; the paper scenes' 2.3 deg swing fits in 0.1.
  double max_chord_rotation = 0.1;
  /// Adaptive alternative to delta: > 0 starts a new subdomain when the linearisation
  /// residual |Q(e) - Q_m - K_m (e - e_m)| exceeds this force [N] at any node (checked every
  /// `residual_check_steps` steps); delta then only bounds the displacement as a backstop.
  double residual_tolerance = 0.0;
  int residual_check_steps = 5;
  RopeModeSettings modes;  ///< shift, guard, sweeps (kept is set from kept_modes)
};

struct SubdomainReducedState {
  double t = 0.0;
  Eigen::VectorXd y, yd, ydd, ya;  ///< [p_c; u_b] and its rates, generalized-alpha variable
  Eigen::VectorXd z, zd, zdd, za;  ///< support coordinates
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
};

struct SubdomainStatistics {
  int subdomains = 0;                   ///< subdomains started (the first one included)
  double mode_update_seconds = 0;       ///< wall time in mode updates (incl. K_m, Q_m rebuild)
  double setup_mode_seconds = 0;        ///< the first subdomain's (cold) modes
  double projection_energy_loss = 0.0;  ///< kinetic energy lost by the switch projections [J]
  double max_mode_residual = 0.0;       ///< worst relative residual of a kept mode after an update
  int cold_fallbacks = 0;               ///< warm updates that had to fall back to a cold solve
  int eigen_solves = 0;                 ///< mode computations after the first (warm or cold)
  int static_corrections = 0;           ///< subdomains given a static-correction vector (hoisting)
  int ritz_updates = 0;  ///< subdomains that only re-linearised their block (hoisting)
};

class SubdomainReducedSolver {
 public:
  /// Rope, support and scheme as the full-order solver's; `settings.kept_modes` in 1 .. n - 3.
  SubdomainReducedSolver(const AncfRope& rope, RopeSupport& support, const GeneralizedAlpha& scheme,
                         double time_step, const SubdomainSettings& settings);

  /// Start the first subdomain at a full-order state (q, v, z, zd; accelerations recomputed).
  void initialize(const CoupledState& full);
  /// One step; starts a new subdomain after it when the criterion says so. Throws
  /// NumericalFailure on a non-finite state or a failed mode update.
  void step();

  /// Start a new subdomain at a full-coordinate state (the rope's positions, velocities and
  /// generalized-alpha accelerations; z and lambda stay): what a switch does, also used when
  /// the rope's length changed under it (hoisting).
  /// How a new subdomain renews its basis (header): the modes (warm or cold, per settings);
  /// the modes plus the static-correction vector; or Rayleigh-Ritz of the current block.
  enum class BasisUpdate { modes, modes_and_correction, ritz };
  /// `load` is the force the static correction responds to (-dQ, header).
  void restartAt(const CoupledState& full, bool consistent_accelerations = false,
                 BasisUpdate how = BasisUpdate::modes, const Eigen::VectorXd& load = {});

  /// The displacement criterion runs every max(1, r / kCheckedModesPerStep) steps (r kept modes).
  static constexpr int kCheckedModesPerStep = 40;

  const SubdomainReducedState& state() const { return s_; }
  const SubdomainStatistics& statistics() const { return stats_; }
  const RopeModes& modes() const { return modes_; }
  /// The state in full rope coordinates (e, e', e'' from y, y', y''); z, lambda copied.
  CoupledState fullState() const;
  /// The map of any reduced state of the current subdomain (the co-rotational map, header).
  CoupledState fullStateOf(const SubdomainReducedState& s) const;
  /// Position of rope node j [m] (O(r) work).
  Eigen::Vector3d nodePosition(int j) const;
  double constraintError() const;
  /// min over nodes of the axial strain |r_x| - 1 (a slack check: O(n r)).
  double minNodalStrain() const;
  /// Rope top tension as FullOrderSolver::topTension.
  double topTension() const;

 private:
  void startSubdomain(const Eigen::VectorXd& e, BasisUpdate how = BasisUpdate::modes,
                      const Eigen::VectorXd& load = {});
  // phi_ <- phi_ X with B^T K B X = B^T M B X diag(omega2), B = phi_ (Rayleigh-Ritz).
  void ritz(const SparseMatrix& K, const SparseMatrix& M);
  // Append psi = K_ii^-1 load_i to phi_ and Rayleigh-Ritz the block (header).
  void addStaticCorrection(const SparseMatrix& K, const SparseMatrix& M,
                           const Eigen::VectorXd& load);
  // Project a full rope vector x onto the basis (M-orthogonal): solves M_r w = B^T M x.
  Eigen::VectorXd project(const Eigen::VectorXd& x) const;
  Eigen::VectorXd expand(const Eigen::VectorXd& y) const;  // Phi_c p_c + T u_b
  // The chord rotation of the subdomain's deformation Phi_c p_c (header).
  struct ChordRotation {
    Eigen::Vector3d theta = Eigen::Vector3d::Zero();  ///< rotation vector [rad]
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  ///< exp([theta]x)
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();  ///< left Jacobian: omega = J theta'
  };
  ChordRotation chordRotation(const Eigen::Vector3d& last_node_displacement) const;
  // theta = c x d_last / |c|^2 alone (zero outside the chord's frame): also the rate of theta
  // for a velocity, of its rate for an acceleration (linear in d_last).
  Eigen::Vector3d chordAngle(const Eigen::Vector3d& last_node_displacement) const;
  // The last node's displacement Phi_c x_c for reduced coordinates x (O(r)).
  Eigen::Vector3d lastNodeDisplacement(const Eigen::VectorXd& x) const;
  // Rotate every node's position and slope rows of `phi` by R (the rope's M is invariant).
  static void rotateBlocks(const Eigen::Matrix3d& R, Eigen::MatrixXd& phi);
  // The loads of the chord's frame (corotational, .cpp): tables per subdomain (Q = Q_m), the
  // load at reduced state (y, yd), a_c at a full-coordinate velocity v at the subdomain start.
  Eigen::Matrix<double, Eigen::Dynamic, 9> blockwiseTable(const Eigen::VectorXd& x) const;
  void prepareFrameLoads(const Eigen::VectorXd& Q);
  Eigen::VectorXd frameLoad(const Eigen::VectorXd& y, const Eigen::VectorXd& yd,
                            const Eigen::VectorXd& ydd) const;
  Eigen::VectorXd centripetalField(const Eigen::VectorXd& v) const;
  // Solve the eliminated system with weights (a on M, c on C, k on K) for right-hand sides
  // (r_y, r_z, r_c); returns dy, sets dz and dmu.
  Eigen::VectorXd solveWeighted(double a, double c, double k, const Eigen::VectorXd& ry,
                                const Eigen::VectorXd& rz, const Eigen::Vector3d& rc,
                                Eigen::VectorXd& dz, Eigen::Vector3d& dmu, bool cached);
  void initializeAccelerations();
  Eigen::Matrix<double, 6, 6> eliminatedMatrix(double a, double k, const Eigen::Matrix3d& G) const;
  double maxNodeIncrement() const;

  const AncfRope& rope_;
  RopeSupport& support_;
  GeneralizedAlpha ga_;
  double h_;
  SubdomainSettings settings_;
  SubdomainStatistics stats_;
  SubdomainReducedState s_;
  // Subdomain data.
  Eigen::VectorXd e_m_;
  Eigen::VectorXd base_;  ///< e_m with the top position taken from the node positions
  Eigen::Vector3d chord_ = Eigen::Vector3d::Zero();        ///< last node - top node at e_m
  Eigen::Vector3d basis_chord_ = Eigen::Vector3d::Zero();  ///< chord the basis belongs to
  bool frame_ = false;  ///< this subdomain runs in the chord's frame (not while hoisting)
  RopeModes modes_;
  Eigen::MatrixXd phi_;                           ///< kept modes (n x r)
  Eigen::VectorXd omega2_;                        ///< kept eigenvalues
  Eigen::Matrix<double, Eigen::Dynamic, 3> Mcb_;  ///< Phi_c^T M T
  Eigen::Matrix3d Mbb_;                           ///< T^T M T (total mass I3)
  Eigen::VectorXd f_;                             ///< [Phi_c; T]^T (F_g - Q_m)
  Eigen::Matrix<double, Eigen::Dynamic, 9> centrifugal_, gravity_rotation_, elastic_rotation_;
  Eigen::MatrixXd node_rows_;   ///< 3 nodes x r: node positions of Phi_c
  Eigen::MatrixXd slope_rows_;  ///< 3 nodes x r: node slopes of Phi_c
  Eigen::PartialPivLU<Eigen::Matrix<double, 6, 6>> kkt_lu_;  ///< the step's 6 x 6 system
  Eigen::Matrix3d G_step_;
  SparseMatrix K_m_;  ///< tangent at e_m (kept for the residual criterion)
  Eigen::VectorXd Q_m_;
  long steps_in_subdomain_ = 0;
  double linearisationResidual() const;
};

}  // namespace crane_twin
