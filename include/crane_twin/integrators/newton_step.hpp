// The Newton iteration of one generalized-alpha step of a rope held by its support, shared by
// the full-order (ANCF) and the pendulum solver; only the rope's linear solve differs.
//
// Index-3 DAE:  M q'' + Q(q, q') - F_g + C_q^T lambda = 0,      C_q = [I3 0 ...],
//               M_z z'' + C_z z' + K_z z - D^T lambda = 0,
//               C(q, z) = r_0 - r_p(z) = 0.
// Newton on (dq, dz, dmu) with mu = beta h^2 lambda and the equations scaled by beta h^2
// (Bottasso, Bauchau & Cardona 2008). The support is eliminated by its Schur complement
// (RopeSupport): dz = A_z^-1 (r_z + D^T dmu), A_z = a M_z + gamma h C_z + beta h^2 K_z, which
// leaves the rope's system
//   [ a M + beta h^2 K_t + gamma h C_d   C_q^T ] [dq ]   [ r_q                       ]
//   [ C_q                                -G    ] [dmu] = [ r_c + D A_z^-1 r_z        ],
// G = D A_z^-1 D^T, r_q = -beta h^2 (M q'' + Q - F_g + C_q^T lambda), r_c = -(r_0 - r_p(z)),
// r_z = -beta h^2 (M_z z'' + C_z z' + K_z z - D^T lambda).
// Converged when max |dq|, |D dz| < position_tolerance and |C| < constraint_tolerance.
// Once the iteration contracts quadratically (d_k / d_(k-1) <= kKeepMatrixContraction) and the
// next correction is foreseen below the tolerance (d_k^2 / d_(k-1) < position_tolerance), the
// last correction may reuse the previous iteration matrix (NewtonWeights::keep_matrix: the
// residual is assembled at the new iterate, the tangent and its factorisation are not). Its
// acceptance test is the same; where it misses, the next iteration is a full one again.
// With a NewtonMemory the first correction d_0 may be followed by such a correction too: Newton's
// quadratic constant C in d_k <= C d_(k-1)^2 varies little from one step to the next, so where the
// previous step's largest d_k / d_(k-1)^2 foresees the next correction below the tolerance
// (C d_0^2 < position_tolerance) the matrix the first correction factorised is kept. A taut
// rope's steps converge in one correction and a check: the check no longer assembles and
// factorises the tangent (docs/model.md "Full-order solution"). Where C grew (a slack point's
// kink, a snatch), the kept correction misses and costs one residual before a full iteration;
// the step's own ratios then set C for the next step. A solver whose law is piecewise refuses
// that keep where a branch changed since the matrix's iterate (NewtonWeights::
// keep_foreseen_from_last_step): a stale tangent stiffer than the law's branch at the iterate
// (a point gone slack) shrinks the correction below the tolerance before the state is there.
#pragma once

#include <functional>
#include <limits>
#include <string>

#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/integrators/generalized_alpha.hpp"
#include "crane_twin/rope/rope_support.hpp"

namespace crane_twin {

/// The largest contraction d_k / d_(k-1) of Newton's corrections at which the next correction may
/// reuse the iteration matrix (see above).
constexpr double kKeepMatrixContraction = 0.1;

struct NewtonSettings {
  double position_tolerance = 1e-10;    ///< [m] on max |dq| and |D dz|
  double constraint_tolerance = 1e-12;  ///< [m] on |C|
  int max_iterations = 30;
  /// Let the last correction reuse the iteration matrix (see above); false: every correction
  /// assembles and factorises it.
  bool reuse_matrix_near_convergence = true;
  /// With a NewtonMemory: accept a step after its first correction d_0 where the contraction
  /// rate rho of the corrections (d_k <= rho d_(k-1), the largest of the last step with two
  /// corrections or more) bounds what is left, rho / (1 - rho) d_0, below position_tolerance,
  /// the convergence test of DASSL (Brenan, Campbell and Petzold, "Numerical Solution of
  /// Initial-Value Problems in Differential-Algebraic Equations", 1996, sec. 5.2.2) for an
  /// iteration whose matrix is not the Jacobian: the step then costs one residual and one solve.
  /// At most kMaxForeseenSteps steps in a row, the next one measures rho again; and only where
  /// the solver reports its law's branches kept (NewtonMemory::first_correction_kept_branches).
  bool accept_foreseen_first_correction = false;
  /// Full order, tension-only law: a correction whose matrix differs from the factorised one
  /// only by the axial tangent of a few Gauss points that changed branch keeps the
  /// factorisation and adds those points as rank-one terms (FullOrderSolver; docs/model.md
  /// "Full-order solution"); false: such a correction assembles and factorises its matrix.
  bool rank_one_switch_updates = true;
};

/// Steps in a row a NewtonMemory's contraction rate may accept after their first correction
/// (NewtonSettings::accept_foreseen_first_correction).
constexpr int kMaxForeseenSteps = 4;

/// What a solver's Newton iteration carries from one step to the next (see above).
struct NewtonMemory {
  /// The largest d_k / d_(k-1)^2 of the last step with two corrections or more [1/m]; infinite
  /// before one (no first correction keeps the matrix then).
  double quadratic_constant = std::numeric_limits<double>::infinity();
  /// The largest d_k / d_(k-1) of the last step with two corrections or more; infinite before
  /// one, or after a solver's change of its iteration matrix (forget()).
  double contraction_rate = std::numeric_limits<double>::infinity();
  /// Steps accepted after their first correction since the rate was measured.
  int foreseen_steps = 0;
  /// Set by a solver's increment at each step's first correction: whether its law keeps its
  /// branches from the step's start to the corrected iterate (a piecewise law, a slack point or
  /// a contact, changes the rate within the step; the rate may then not end it).
  bool first_correction_kept_branches = true;
  /// A new iteration matrix or model: no rate is known.
  void forget() {
    quadratic_constant = contraction_rate = std::numeric_limits<double>::infinity();
    foreseen_steps = 0;
  }
};

/// The weights of the beta h^2-scaled iteration matrix of a step of size h.
struct NewtonWeights {
  double mass = 1.0;                            ///< a = (1 - alpha_m)/(1 - alpha_f)
  double damping = 0.0;                         ///< gamma h
  double stiffness = 0.0;                       ///< beta h^2
  Eigen::Matrix3d G = Eigen::Matrix3d::Zero();  ///< support compliance D A_z^-1 D^T
  /// The correction may reuse the previous iteration's factorised matrix (a solver that cannot
  /// ignores it): assemble only the residual.
  bool keep_matrix = false;
  /// keep_matrix was set after the step's first correction by the last step's constant
  /// (NewtonMemory), not by this step's own contraction: a solver whose law may have changed
  /// branch since the matrix's iterate (a slack point, a contact) assembles it afresh instead.
  bool keep_foreseen_from_last_step = false;
};

/// Storage a solver keeps for newtonStep from step to step, so that a step's copy of its start
/// reuses it instead of allocating (contents are scratch between calls).
struct NewtonWorkspace {
  CoupledState start;  ///< the step's start
};

/// The rope's linear solve at the iterate s: assemble its rows of the system above with the
/// weights w (r_q from s) and the condensed constraint residual rc = r_c + D A_z^-1 r_z, and
/// return dq and dmu. False, with the reason in `why`, where the matrix is singular.
using RopeIncrement =
    std::function<bool(const CoupledState& s, const NewtonWeights& w, const Eigen::Vector3d& rc,
                       Eigen::VectorXd& dq, Eigen::Vector3d& dmu, std::string& why)>;

/// One generalized-alpha step of size h from s: predictor, Newton corrections through
/// `increment`, and step completion. False, with s at the step's start and the reason (with the
/// time) in `why`, where the iteration fails (singular matrix, non-finite state, no
/// convergence in newton.max_iterations). With `support_means_z0` z_0, the start of an
/// energy-consistent step (gamma = 1 from z''_0 = 0, energyConsistentScheme), the support's
/// equation holds at the step's means instead of its end:
///   M_z z''_1 + C_z (z_1 - z_0) / h + K_z (z_0 + z_1) / 2 - f_z = D^T lambda,
/// z''_1 = (z'_1 - z'_0) / h and lambda the step's mean constraint force, so that with
/// K_z z_m the support's elastic work is its energy change and C_z at the step's own mean
/// velocity only dissipates (docs/model.md "Energy-consistent step"); its iteration matrix is
/// then M_z + beta h C_z + beta h^2 / 2 K_z. With `memory`, the first correction may keep its
/// matrix (see above) and the step's contraction is recorded there. `workspace` holds the step's
/// start meanwhile.
bool newtonStep(const GeneralizedAlpha& ga, RopeSupport& support, const NewtonSettings& newton,
                double h, const RopeIncrement& increment, CoupledState& s, std::string& why,
                NewtonWorkspace& workspace, const Eigen::VectorXd* support_means_z0 = nullptr,
                NewtonMemory* memory = nullptr);

/// The support's rows eliminated from a linear solve (its Schur complement): returns the
/// condensed constraint row rc + D A_z^-1 r_z and A_z^-1 r_z in Azr, for the weights last set
/// on the support; rc itself (and Azr untouched) for a support without coordinates.
Eigen::Vector3d condenseSupport(const RopeSupport& support, const Eigen::Vector3d& rc,
                                const Eigen::VectorXd& rz, Eigen::VectorXd& Azr);

/// The support part of a Newton correction: dz = A_z^-1 (r_z + D^T dmu) from the condensed
/// solve (Azr = A_z^-1 r_z), applied to (z, z', z''). Returns max |D dz|, the change at the
/// support point [m]. No-op returning 0 for a support without coordinates.
double correctSupport(const GeneralizedAlpha& ga, const RopeSupport& support, double h,
                      const Eigen::VectorXd& Azr, const Eigen::Vector3d& dmu, CoupledState& s);

/// Close a converged step of size h that started at `start`: the generalized-alpha variables a,
/// z_a, the time and the iteration count.
void completeStep(const GeneralizedAlpha& ga, const CoupledState& start, double h, int iterations,
                  CoupledState& s);

/// Before a consistent-acceleration solve: z and z' sized to the support (zero where unset), z''
/// zero.
void prepareSupportState(const RopeSupport& support, CoupledState& s);
/// After it: q'' and lambda from the solve, z'' = A_z^-1 (r_z + D^T lambda) from Azr = A_z^-1 r_z,
/// and the generalized-alpha variables a = q'', z_a = z'' of a start (Arnold & Bruls 2007).
void storeConsistentAccelerations(const RopeSupport& support, const Eigen::VectorXd& qdd,
                                  const Eigen::Vector3d& lambda, const Eigen::VectorXd& Azr,
                                  CoupledState& s);

/// |C| = |r_0 - r_p(z)| [m]: how far the rope's top node is from the support point.
double constraintError(const RopeSupport& support, const CoupledState& s);

}  // namespace crane_twin
