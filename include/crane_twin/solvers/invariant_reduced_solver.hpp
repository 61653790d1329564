// The reduced rope on the rotation-invariant Ritz basis (InvariantRopeBasis, docs/model.md
// "Reduced rope"): the Galerkin projection of the full-order equations onto q = B y,
// B = Psi (x) I3,
//   M_r y'' + Q_r(y, y') - F_r + E^T lambda = 0,   M_r = (Psi^T M_s Psi) (x) I3 = M_rs (x) I3,
//   M_z z'' + C_z z' + K_z z - D^T lambda = 0,      Q_r = B^T Q(B y),  F_r = B^T F_g,
//   a_0 - r_p(z) = 0                                 (E = [I3 0 ...]: psi_0 = 1, psi_k>0(0) = 0)
// integrated by the full model's generalized-alpha Newton step (integrators/newton_step.hpp).
//
// The elastic force is the exact one at the expanded state, integrated at Gauss points of the
// rope's elements (at least 2 per element, .cpp kQuadraturePoints) without expanding: with A = [a_0
// ... a_(m-1)] (3 x m), D1, D2 (m x n_g) the shapes' first and second xi-derivatives at the points
// and w_g their weights in xi,
//   r_x = A D1 / L,   r_xx = A D2 / L^2,   Q_A = sum_g w_g (phi_a,g D1_g^T + phi_b,g D2_g^T / L)
// (phi_a, phi_b the gradient of the energy density, ancfCablePoint): two 3 x m x n_g products
// and one density per point, O(m n_g), no assembly and no sparse factorisation. The
// axial damping force c EA eps' t is integrated the same way.
//
// Iteration matrix: the tangent of a straight rope along its chord d (unit vector from the top
// to the end node), per point phi_aa = (N / |r_x|) (I - d d^T) + EA d d^T, so
//   K_it = (1/L) [K_g (x) (I - d d^T) + K_a (x) d d^T] + (EI / L^3) K_b (x) (I - d d^T),
//   K_a = sum w_g N'(eps_g) D1_g D1_g^T,  K_g = sum w_g (N_g / |r_x,g|) D1_g D1_g^T,  K_b = sum w
//   D2 D2^T,
// and a M_r + gamma h C_it + beta h^2 K_it with the constraint rows, factorised (dense LU,
// 3m + 3) when the chord has turned, the length changed, the weights changed or the last step
// took many iterations. The residual is exact, so the converged step does not depend on this
// approximation; only the iteration count does. K_a weighs each point by the slope of its axial
// law (N'(eps) / EA: 0 where a tension-only point is slack).
//
// A tension-only rope (docs/model.md "Energy-consistent step"): full order's rule
// (integrators/tension_only_step.hpp). A step in which a Gauss point of the reduced rule crosses
// the slack edge with a work error above the switch tolerance, or that would create energy, is
// taken by the energy-consistent step (energyConsistentScheme, as at full order): Qbar the
// discrete gradient of U(B y) at the reduced Gauss points (ancfCablePointDiscreteGradient) plus
// the damper at the midpoint, so the elastic forces' work equals U(B y1) - U(B y0), a slack/taut
// switch creates no energy, and the step's velocity jumps lose theta dv^T M_r dv.
// Generalized-alpha resumes once a step no longer switches.
//
// With a rigging (AncfRope::setRigging, docs/model.md "Hook block"), y = [a; r_p]: the payload
// point r_p in its own 3 coordinates beside the basis, hung from the hook node r_n = psi(1) a by
// the tension-only bar. With T = [psi(1) (x) I3, 0; 0, I3] mapping y to the bar's [r_n; r_p],
// the bar adds T^T M_b T to the mass (its consistent mass and the payload), T^T Q_b to the
// force, T^T K_b T to the iteration matrix and its discrete gradient to the energy-consistent
// step, exactly as at full order; the hook block is the point mass at r_n, and the ground and
// the end force act on r_p. The basis is that of the rope with the rigging's masses lumped at
// its end (AncfRope::lumpedAtHook).
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <optional>
#include <string>

#include "crane_twin/elements/ground_contact.hpp"
#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/integrators/generalized_alpha.hpp"
#include "crane_twin/integrators/newton_step.hpp"
#include "crane_twin/integrators/tension_only_step.hpp"
#include "crane_twin/rope/ancf_rope.hpp"
#include "crane_twin/rope/invariant_rope_basis.hpp"
#include "crane_twin/rope/rope_support.hpp"

namespace crane_twin {

class InvariantReducedSolver {
 public:
  /// Rope (for its material, masses and current length), basis and support are referenced and
  /// must outlive the solver. States are in reduced coordinates: q = y (3 m), z as the support's.
  InvariantReducedSolver(const AncfRope& rope, const InvariantRopeBasis& basis,
                         RopeSupport& support, const GeneralizedAlpha& scheme, double time_step,
                         NewtonSettings newton = defaultNewton());

  /// Newton settings of the reduced rope: increments converged below 1e-8 m (the full model's
  /// 1e-10 m is two orders under this basis's truncation error, 1e-7 to 1e-5 m against full
  /// order; the looser bound saves one force evaluation per step and moves the payload by under
  /// 1e-8 m on the operator cycle and the 30 deg swing, docs/accuracy-vs-time.md "Operation").
  /// Its generalized-alpha steps may end after one correction where the last measured rate of
  /// their corrections bounds the rest below that tolerance (NewtonSettings::
  /// accept_foreseen_first_correction; the rate is measured again at least every
  /// kMaxForeseenSteps + 1 steps and forgotten with every new iteration matrix).
  static NewtonSettings defaultNewton() {
    NewtonSettings s;
    s.position_tolerance = 1e-8;
    s.accept_foreseen_first_correction = true;
    return s;
  }

  /// Axial strain-rate damping c [s] (as FullOrderSolver::setRopeDamping).
  void setRopeDamping(double c);
  /// The ground under the payload (FullOrderSolver::setGround): the end point is linear in y,
  /// r_e = sum_k psi_k(1) a_k, so the contact's generalized force is psi_k(1) f on a_k and its
  /// tangent psi(1) psi(1)^T (x) df/dr; a step that lands or lifts off is energy-consistent.
  void setGround(std::optional<GroundContact> ground) { ground_ = std::move(ground); }
  const std::optional<GroundContact>& ground() const { return ground_; }
  /// The end point r_e (or its velocity, for y') of a reduced vector: the payload's, the hoist
  /// rope's end node or a rigging's payload point.
  Eigen::Vector3d endPoint(const Eigen::VectorXd& y) const;
  /// Re-read the rope's length after AncfRope::setLength (hoisting: y is kept, docs/model.md).
  void refreshLength() { setLength(rope_.length()); }
  /// Set the rope length L [m] the reduced model integrates at (mass and weight in xi-units,
  /// docs/model.md); the rope object itself is not touched, so a simulation that hoists at
  /// reduced order need not update the full rope every step.
  void setLength(double length);
  double length() const { return L_; }

  /// Consistent accelerations of a reduced state (y, y', z, z' given).
  void initializeAccelerations(CoupledState& s);
  /// One step of size h, halved where Newton fails (FullOrderSolver::step) unless halving is
  /// off (setHalvesFailedSteps). Throws NumericalFailure; s is then at the step's start.
  void step(CoupledState& s);
  long halvedSteps() const { return halved_steps_; }
  /// Whether a step whose Newton fails is halved (default) or refused at once. A run that hands
  /// over to full order refuses it: the basis does not carry a step it cannot take whole
  /// (InvariantReducedSimulation).
  void setHalvesFailedSteps(bool on) { halves_failed_steps_ = on; }
  /// Steps taken by the energy-consistent step, and the energy the accepted generalized-alpha
  /// steps created at slack/taut switches (each under the switch tolerance) [J].
  long energyConsistentSteps() const { return switching_.energy_consistent_steps; }
  double energyCreated() const { return switching_.energy_created; }
  /// A switching episode runs: the next step is energy-consistent too, and the state's
  /// accelerations are the last step's means.
  bool switching() const { return switching_.switching; }
  /// Carry the switching episode and the energy budget on from another solver's run.
  void continueSteppingOf(const InvariantReducedSolver& other);
  /// Restart the switching bookkeeping (a new run, or a take-over from full order).
  void resetSwitching();

  /// The reduced state of a full-coordinate state (M-orthogonal projection of q, v, q'', a with
  /// the top's and the hoist rope's end node's values held exactly,
  /// InvariantRopeBasis::Projection::withEndsHeld); and the full-coordinate state of a reduced one.
  CoupledState project(const CoupledState& full) const;
  CoupledState expand(const CoupledState& reduced) const;
  /// Largest node distance between full positions q and their projection's expansion (project's,
  /// the ends held) [m].
  double projectionError(const Eigen::VectorXd& q) const;

  /// Reduced elastic (and damping) force Q_r(y, y') and the elastic energy U(B y) [J].
  Eigen::VectorXd force(const Eigen::VectorXd& y, const Eigen::VectorXd& yd) const;
  double elasticEnergy(const Eigen::VectorXd& y) const;
  /// Discrete gradient of U(B y) over y0 -> y1 of a step of size h [s], plus the damper at the
  /// midpoint and the step's mean velocity (y1 - y0) / h, and the ground's step mean (v1 the
  /// end velocity): Qbar . (y1 - y0) = U(B y1) - U(B y0) + the damper's work.
  Eigen::VectorXd discreteGradientForce(const CoupledState& start, const Eigen::VectorXd& y1,
                                        const Eigen::VectorXd& v1, double h) const;
  /// Trapezoid work error of the tension-only axial law over y0 -> y1, summed over the reduced
  /// Gauss points (ancfAxialSwitchWorkError) [J]; 0 for a rope taut at both ends of the step.
  double slackSwitchWorkError(const Eigen::VectorXd& y0, const Eigen::VectorXd& y1) const;
  /// Smallest axial strain |r_x| - 1 over the Gauss points (a slack check).
  double minStrain(const Eigen::VectorXd& y) const;
  /// The rope's slack length [m]: int max(0, -eps) dx over the Gauss points, the unstretched
  /// length by which the slack parts exceed their stretched length.
  double slackLength(const Eigen::VectorXd& y) const;
  /// Total mechanical energy (FullOrderSolver::energy) and the top tension [N].
  double energy(const CoupledState& s) const;
  double topTension(const CoupledState& s) const;
  /// M_r x for a reduced vector x.
  Eigen::VectorXd appliedForce() const;
  Eigen::VectorXd massTimes(const Eigen::VectorXd& x) const;
  const Eigen::VectorXd& gravityForce() const { return gravity_; }
  /// Node j's position: the hoist rope's (j <= elements) from the basis, a rigging's payload
  /// point (j = elements + 1) its own coordinates.
  Eigen::Vector3d nodePosition(const Eigen::VectorXd& y, int j) const {
    return j <= rope_.elements() ? basis_.nodePosition(y, j) : Eigen::Vector3d(y.tail<3>());
  }
  /// Reduced coordinates: 3 m, and 3 more for a rigging's payload point.
  int coordinates() const { return n_; }
  /// A rigging's slack length at y: its unstretched length less the hook-payload distance, 0
  /// where taut or without a rigging [m].
  double barSlackLength(const Eigen::VectorXd& y) const {
    if (!rigged_) return 0.0;
    const Vector6 b = barCoordinates(y);
    return std::max(0.0, rope_.rigging().length() - (b.tail<3>() - b.head<3>()).norm());
  }
  /// Iteration matrices factorised, and the Newton iterations and steps taken so far.
  int factorizations() const { return factorizations_; }
  long newtonIterations() const { return newton_iterations_; }
  long steps() const { return steps_; }

 private:
  bool tryStep(CoupledState& s, double h, std::string& why);
  bool generalizedAlphaStep(CoupledState& s, double h, std::string& why);
  bool energyConsistentStep(CoupledState& s, double h, std::string& why);
  // Newton through the reduced iteration matrix; residual(x) the rope rows' force balance;
  // secant_from the step's start for an energy-consistent step's matrix.
  bool newton(const GeneralizedAlpha& scheme, double h,
              const std::function<Eigen::VectorXd(const CoupledState&)>& residual, CoupledState& s,
              std::string& why, const Eigen::VectorXd* support_means_z0,
              const Eigen::VectorXd* secant_from);
  // The work the rope gains over a step beyond the top force's and the damper's [J].
  double ropeEnergyCreated(const CoupledState& start, const CoupledState& s) const;
  Eigen::VectorXd dampingForce(const Eigen::VectorXd& y, const Eigen::VectorXd& yd) const;
  // Fill and factorise the iteration matrix for weights (a, c, k) and chord direction d.
  // With y0, the axial weights of an energy-consistent step from y0 (the secant's slope).
  bool factorize(double a, double c, double k, const Eigen::Matrix3d& G, const Eigen::VectorXd& y,
                 const Eigen::VectorXd* y0 = nullptr);
  Eigen::Vector3d chord(const Eigen::VectorXd& y) const;
  // The hoist rope's end node r_n = psi(1) a, the point mass there, the rigging bar's
  // coordinates [r_n; r_p], and T^T Qb added into Q (header: the rigging).
  Eigen::Vector3d hookPoint(const Eigen::VectorXd& y) const;
  double hookPointMass() const;
  Vector6 barCoordinates(const Eigen::VectorXd& y) const;
  void addBarForce(const Vector6& Qb, Eigen::VectorXd& Q) const;
  // The bar went slack or taut, or turned, since the last factorisation.
  bool barChanged(const Eigen::VectorXd& y) const;
  // -psi(1) (x) f: the ground's generalized force as an internal force (0 without ground).
  Eigen::VectorXd contactForce(const Eigen::Vector3d& f) const;
  // The ground's force at the state x (or the energy-consistent step's mean from ec_start_).
  GroundContactForce contactAt(const CoupledState& x) const;
  // The projection at the current length, set up on first use after a length change.
  const InvariantRopeBasis::Projection& projection() const;

  const AncfRope& rope_;
  const InvariantRopeBasis& basis_;
  RopeSupport& support_;
  GeneralizedAlpha ga_;
  double h_;
  NewtonSettings newton_;
  double damping_ = 0.0;
  long halved_steps_ = 0;
  bool halves_failed_steps_ = true;
  int m_ = 0;            ///< shapes
  int n_ = 0;            ///< reduced rope coordinates: 3 m (+ 3 for a rigging's payload)
  bool rigged_ = false;  ///< a rigging bar hangs the payload point from the hook node
  Matrix6 bar_mass_ = Matrix6::Zero();  ///< the bar's consistent mass with the payload
  bool fact_bar_taut_ = false;
  Eigen::Vector3d fact_bar_dir_ = Eigen::Vector3d::Zero();
  Eigen::MatrixXd D1_, D2_;    ///< m x n_g shape xi-derivatives at the Gauss points
  Eigen::MatrixXd D1t_, D2t_;  ///< their transposes (n_g x m): force()'s point-major products
  // force()'s workspace: r_x, r_xx (and r_x') at the points and the density's gradient there.
  mutable PointRows ra_, rb_, rad_, fa_, fb_;
  Eigen::VectorXd w_;         ///< n_g weights in xi
  Eigen::MatrixXd Kb_;        ///< sum w D2 D2^T (m x m)
  Eigen::MatrixXd mass_hat_;  ///< Psi^T M_hat Psi of the rope alone per unit mu L
  Eigen::RowVectorXd psi_top_, psi_end_;
  // Length-dependent.
  double L_ = 0.0;
  Eigen::MatrixXd Mrs_;      ///< M_rs (m x m)
  Eigen::VectorXd gravity_;  ///< F_r (3 m)
  // Iteration matrix cache.
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  bool factored_ = false;
  std::optional<GroundContact> ground_;
  const CoupledState* ec_start_ = nullptr;  ///< an energy-consistent step's start, while it runs
  Eigen::Matrix3d contact_K_ = Eigen::Matrix3d::Zero(), contact_C_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d fact_contact_K_ = Eigen::Matrix3d::Zero(),
                  fact_contact_C_ = Eigen::Matrix3d::Zero();
  double fact_a_ = 0, fact_c_ = 0, fact_k_ = 0, fact_L_ = 0;
  Eigen::Matrix3d fact_G_ = Eigen::Matrix3d::Zero();
  Eigen::Vector3d fact_d_ = Eigen::Vector3d::Zero();
  int last_iterations_ = 0;
  int factorizations_ = 0;
  // The generalized-alpha steps' contraction rate (newton_step.hpp), forgotten with every
  // factorisation and after every energy-consistent step.
  NewtonMemory newton_memory_;
  NewtonWorkspace newton_workspace_;        ///< newtonStep's storage (scratch between steps)
  CoupledState step_start_;                 ///< step()'s copy of its start (scratch between steps)
  Eigen::VectorXd newton_rhs_, newton_dx_;  ///< a correction's system (scratch between calls)
  long newton_iterations_ = 0, steps_ = 0;
  // Tension-only stepping (as FullOrderSolver's).
  TensionOnlySwitching switching_;
  double last_step_length_ = 0.0;
  bool hoisting_ = false;  ///< the length changed since the last step: judged by energy alone
  // A field sum_k psi_k^(d)(xi_g) a_k at the Gauss points times `scale` (n_g x 3), for the
  // shapes' derivative values Dt = D1t_ or D2t_ and the coordinates A = y (or y').
  void pointRows(const Eigen::MatrixXd& Dt, const double* A, double scale, PointRows& r) const;
  // |r_x| at the Gauss points of the last two states asked for (stretches()).
  const Eigen::RowVectorXd& stretches(const Eigen::VectorXd& y) const;
  // A lower bound of min |r_x| over the points: for the end states of the last two converged
  // generalized-alpha steps, their Newton's last residual's less what the last correction can
  // change it by; else the exact one. A taut step's slack checks then cost O(m), not a pass
  // over the points.
  double minStretchLowerBound(const Eigen::VectorXd& y) const;
  double slope_sum_ = 0.0;                        ///< max over the points of sum_k |psi_k'(xi_g)|
  mutable double last_force_min_stretch_ = -1.0;  ///< min |r_x| of the last force() call
  struct StretchBound {
    Eigen::VectorXd y;
    double length = 0.0, bound = 0.0;
  };
  std::array<StretchBound, 2> stretch_bounds_;
  int next_stretch_bound_ = 0;
  struct StretchCache {
    Eigen::VectorXd y;
    double length = 0.0;
    Eigen::RowVectorXd g;
  };
  mutable std::array<StretchCache, 2> stretch_cache_;
  mutable int next_stretch_cache_ = 0;
  mutable std::optional<InvariantRopeBasis::Projection> projection_;
  mutable double projection_length_ = -1.0;
};

}  // namespace crane_twin
