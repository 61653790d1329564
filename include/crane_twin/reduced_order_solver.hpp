// Reduced-order (R-ANCF) dynamics of the rope on its support: the paper's method (Yu et al.
// 2024, eq. 6-17; SPEC 1.6).
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
// represents exactly (the elastic force is translation-invariant). At the switch K_m and Q_m are rebuilt at the current e, the modes updated
// from the previous block (warm, RopeModes) or recomputed, and the state carried over: positions
// exactly (y = 0 at the new e_m), velocities and the generalized-alpha accelerations by the
// M-orthogonal projection onto the new basis, M_r w = B^T M x. The projection can only lose
// kinetic energy; the loss 1/2 (v^T M v - w^T M_r w) is summed in `projectionEnergyLoss`.
//
// Hoisting (issue 5): the full model's scheme, uniform rescaling (CraneSimulation::
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

#include "crane_twin/full_order_solver.hpp"
#include "crane_twin/rope_modes.hpp"

namespace crane_twin {

/// How the rope basis is renewed at a subdomain switch: cold (modes of the new tangent from
/// scratch, the paper's method as printed) or warm (subspace iteration from the previous block
/// plus Rayleigh-Ritz, RopeModes).
enum class ModeUpdate { cold, warm };

struct ReducedSettings {
  int kept_modes = 10;         ///< fixed-top rope modes kept (plus the 3 translations)
  double delta = 0.05;         ///< subdomain criterion [m]
  ModeUpdate update = ModeUpdate::warm;
  /// Adaptive alternative to delta (issue 4): > 0 starts a new subdomain when the linearisation
  /// residual |Q(e) - Q_m - K_m (e - e_m)| exceeds this force [N] at any node (checked every
  /// `residual_check_steps` steps); delta then only bounds the displacement as a backstop.
  double residual_tolerance = 0.0;
  int residual_check_steps = 5;
  RopeModeSettings modes;      ///< shift, guard, sweeps (kept is set from kept_modes)
};

struct ReducedState {
  double t = 0.0;
  Eigen::VectorXd y, yd, ydd, ya;  ///< [p_c; u_b] and its rates, generalized-alpha variable
  Eigen::VectorXd z, zd, zdd, za;  ///< support coordinates
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
};

struct ReducedStatistics {
  int subdomains = 0;              ///< subdomains started (the first one included)
  double mode_update_seconds = 0;  ///< wall time in mode updates (incl. K_m, Q_m rebuild)
  double setup_mode_seconds = 0;   ///< the first subdomain's (cold) modes
  double projection_energy_loss = 0.0;  ///< kinetic energy lost by the switch projections [J]
  double max_mode_residual = 0.0;  ///< worst relative residual of a kept mode after an update
  int cold_fallbacks = 0;          ///< warm updates that had to fall back to a cold solve
  int eigen_solves = 0;            ///< mode computations after the first (warm or cold)
  int static_corrections = 0;      ///< subdomains given a static-correction vector (hoisting)
  int ritz_updates = 0;            ///< subdomains that only re-linearised their block (hoisting)
};

class ReducedOrderSolver {
 public:
  /// Rope, support and scheme as the full-order solver's; `settings.kept_modes` in 1 .. n - 3.
  ReducedOrderSolver(const AncfRope& rope, RopeSupport& support, const GeneralizedAlpha& scheme,
                     double time_step, const ReducedSettings& settings);

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

  const ReducedState& state() const { return s_; }
  const ReducedStatistics& statistics() const { return stats_; }
  const RopeModes& modes() const { return modes_; }
  /// The state in full rope coordinates (e, e', e'' from y, y', y''); z, lambda copied.
  CoupledState fullState() const;
  /// Position of rope node j [m] (O(r) work).
  Eigen::Vector3d nodePosition(int j) const;
  Eigen::Vector3d nodeVelocity(int j) const;
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
  void addStaticCorrection(const SparseMatrix& K, const SparseMatrix& M, const Eigen::VectorXd& load);
  // Project a full rope vector x onto the basis (M-orthogonal): solves M_r w = B^T M x.
  Eigen::VectorXd project(const Eigen::VectorXd& x) const;
  Eigen::VectorXd expand(const Eigen::VectorXd& y) const;  // Phi_c p_c + T u_b
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
  ReducedSettings settings_;
  ReducedStatistics stats_;
  ReducedState s_;
  // Subdomain data.
  Eigen::VectorXd e_m_;
  RopeModes modes_;
  Eigen::MatrixXd phi_;                        ///< kept modes (n x r)
  Eigen::VectorXd omega2_;                     ///< kept eigenvalues
  Eigen::Matrix<double, Eigen::Dynamic, 3> Mcb_;  ///< Phi_c^T M T
  Eigen::Matrix3d Mbb_;                        ///< T^T M T (total mass I3)
  Eigen::VectorXd f_;                          ///< [Phi_c; T]^T (F_g - Q_m)
  Eigen::MatrixXd node_rows_;                  ///< 3 nodes x r: node positions of Phi_c
  Eigen::MatrixXd slope_rows_;                 ///< 3 nodes x r: node slopes of Phi_c
  Eigen::PartialPivLU<Eigen::Matrix<double, 6, 6>> kkt_lu_;  ///< the step's 6 x 6 system
  Eigen::Matrix3d G_step_;
  SparseMatrix K_m_;            ///< tangent at e_m (kept for the residual criterion)
  Eigen::VectorXd Q_m_;
  long steps_in_subdomain_ = 0;
  double linearisationResidual() const;
};

}  // namespace crane_twin
