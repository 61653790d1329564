// Full-order (F-ANCF) dynamics and statics of the rope held by its support (docs/model.md):
// a fixed anchor (crane: none) or the crane structure in modal or full coordinates z.
//
// Index-3 DAE:  M q'' + Q(q) - F_g - F_ext + C_q^T lambda = 0,
//               M_z z'' + C_z z' + K_z z - D^T lambda = 0,
//               C(q, z) = r_0 - r_p(z) = r_0 - (r_p0 + D z) = 0,
// integrated with generalized-alpha (integrators/generalized_alpha.hpp). The Newton iteration
// of a step (integrators/newton_step.hpp, shared with the pendulum solver) works on
// (Delta q, Delta z, Delta mu) with mu = beta h^2 lambda and the equations scaled by beta h^2
// (Bottasso, Bauchau & Cardona 2008), so the iteration matrix
//   [ a M + beta h^2 K_t    0      C_q^T ]      a = (1-alpha_m)/(1-alpha_f)
//   [ 0                     A_z    -D^T  ]      A_z = a M_z + gamma h C_z + beta h^2 K_z
//   [ C_q                   -D     0     ]
// has entries of the order of M whatever the step. The support block is eliminated by its
// Schur complement (RopeSupport): Delta z = A_z^-1 (r_z + D^T Delta mu), leaving the rope's
// KKT system with the 3 x 3 block -G = -D A_z^-1 D^T in the multiplier rows (zero for an
// anchor; constant while the step size is). The rope block is banded: the bordered band
// factorisation (bordered_band_factorization.hpp, LAPACK's band Cholesky) solves the whole
// system, with a sparse LDL^T in natural order (Eigen's SimplicialLDLT, the multiplier rows
// last) for an iteration whose rope block is not positive definite. The values are written
// into a fixed pattern every iteration and refactorised: this solver supplies that linear
// solve (RopeIncrement). Converged when max|Delta q| < position_tolerance (default
// 1e-10 m) and |C| < constraint_tolerance (1e-12 m). Failed steps are halved
// (integrators/step_halving.hpp).
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "crane_twin/elements/ground_contact.hpp"
#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/integrators/generalized_alpha.hpp"
#include "crane_twin/integrators/newton_step.hpp"
#include "crane_twin/integrators/numerical_failure.hpp"
#include "crane_twin/integrators/tension_only_step.hpp"
#include "crane_twin/rope/ancf_rope.hpp"
#include "crane_twin/rope/rope_support.hpp"
#include "crane_twin/solvers/bordered_band_factorization.hpp"
#include "crane_twin/solvers/rank_one_terms_solve.hpp"

namespace crane_twin {

/// Total mechanical energy of a state: 1/2 v^T M v + U(q) - F_g^T q (gravity potential, zero at
/// q = 0) plus the support's kinetic and strain energy [J].
double mechanicalEnergy(const AncfRope& rope, const RopeSupport& support, const CoupledState& s);
/// Rope top tension [N]: the force between rope and trolley, |lambda + m_top (r_0'' - g)| (the
/// support force less the trolley mass's weight and inertia).
double ropeTopTension(const AncfRope& rope, const CoupledState& s);

class FullOrderSolver {
 public:
  /// Rope and support are referenced, not copied: they must outlive the solver.
  FullOrderSolver(const AncfRope& rope, RopeSupport& support, const GeneralizedAlpha& scheme,
                  double time_step, NewtonSettings newton = {});

  /// Static equilibrium under gravity and a constant force on the end mass, damped Newton from
  /// (q_guess, z_guess) (q_guess must carry tension: see solveSwingEquilibrium). Returns the
  /// state at rest (v = 0); -lambda is the support force on the rope. The hanging rope's
  /// statics: the ground (setGround) takes no part.
  CoupledState solveStatic(const Eigen::VectorXd& q_guess, const Eigen::VectorXd& z_guess,
                           const Eigen::Vector3d& end_force);

  /// Equilibrium whose chord (top node to end node) makes swing_rad with the vertical at
  /// azimuth az_rad, held by a horizontal force on the end mass (secant on the force).
  /// docs/scenes.md.
  CoupledState solveSwingEquilibrium(double swing_rad, double az_rad,
                                     Eigen::Vector3d* holding_force = nullptr);

  /// Consistent accelerations of a state (q, v, z, zd given) at release: solves the KKT system
  /// with the constraint's second derivative r_0'' - D z'' = 0.
  void initializeAccelerations(CoupledState& s);

  /// One step of size h; where Newton fails, the step is halved (up to kMaxHalvings times).
  /// Throws NumericalFailure naming the time and the reason; s is then left at the step's start.
  /// With a tension-only rope (docs/model.md "Energy-consistent step"), a generalized-alpha step
  /// stands where the rope is taut at both of its ends; where some point is below the axial
  /// law's linear range, only if it switches no point between slack and taut
  /// (AncfRope::slackSwitchWorkError within kSwitchTolerance of the hanging weight times the
  /// rope length; not asked of a hoisting step, whose uniform rescaling shifts every strain
  /// before it) and keeps the run's sum of ropeEnergyCreated within that tolerance. Any other
  /// step is taken energy-consistently (energyConsistentScheme): the discrete gradient of the
  /// elastic energy, whose elastic work equals the energy change exactly, in a scheme whose
  /// energy falls by theta (v1 - v0)^T M (v1 - v0), theta = kEnergyDecayRate h. Such steps follow
  /// each other while the rope keeps switching; the first one without a switch restores consistent
  /// accelerations and hands back to generalized-alpha.
  void step(CoupledState& s);
  static constexpr int kMaxHalvings = 10;
  /// Axial strain-rate damping of the rope, c [s] (ancfAxialDampingForce; 0: none). Throws
  /// std::invalid_argument for a negative or non-finite c.
  void setRopeDamping(double c);
  /// The ground under the payload (docs/model.md "Ground contact"): its force acts on the
  /// payload point (the end node, or the rigging's payload point) in every step, its energy
  /// counts in energy(), and a step that lands or lifts off is taken energy-consistently (the
  /// tension-only rule then runs for a symmetric rope too). Empty: no ground.
  void setGround(std::optional<GroundContact> ground) { ground_ = std::move(ground); }
  const std::optional<GroundContact>& ground() const { return ground_; }
  /// Half steps taken so far in place of failed steps (0 in a smooth run).
  long halvedSteps() const { return halved_steps_; }
  /// Energy-consistent steps taken so far (slack/taut switches; 0 for a rope that stays taut).
  long energyConsistentSteps() const { return switching_.energy_consistent_steps; }
  /// Newton corrections so far that reused the factorised iteration matrix
  /// (NewtonSettings::reuse_matrix_near_convergence).
  long matrixReusingCorrections() const { return matrix_reusing_corrections_; }
  /// Corrections that kept the factorisation with rank-one terms for Gauss points whose axial
  /// law changed branch since (see rankOneTermsApply).
  long rankOneCorrections() const { return rank_one_corrections_; }
  /// Of those, the corrections whose terms include the ground contact's.
  long contactRankOneCorrections() const { return contact_rank_one_corrections_; }
  /// Factorisations of the iteration matrix so far.
  long factorizations() const { return factorizations_; }

  /// Continue another solver's run of the same scene and step: the memory of its stepping (an
  /// energy-consistent episode under way, the energy balance, the rope length of its last
  /// step), so that both take the same steps from the same state.
  void continueSteppingOf(const FullOrderSolver& other);

  /// Re-read the rope's mass matrix after AncfRope::setLength (same pattern).
  void refreshMass();

  /// Total mechanical energy: 1/2 v^T M v + U(q) - F_g^T q (gravity potential, zero at q = 0)
  /// plus the support's kinetic and strain energy and the ground's spring energy.
  double energy(const CoupledState& s) const;
  /// Rope top tension [N]: the force between rope and trolley, |lambda + m_top (r_0'' - g)|
  /// (the support force less the trolley mass's weight and inertia).
  double topTension(const CoupledState& s) const;
  /// |C| = |r_0 - r_p(z)| [m].
  double constraintError(const CoupledState& s) const;

  const AncfRope& rope() const { return rope_; }
  const RopeSupport& support() const { return support_; }
  double timeStep() const { return h_; }

 private:
  // Every Gauss point in the axial law's linear range (and the payload clear of the ground) at
  // q and at matrix_q_: a kept matrix's tangent is then the law's own branch.
  bool lawBranchesAsAtMatrix(const Eigen::VectorXd& q) const;
  // Fill the values of A_ (fixed pattern, -G in the multiplier block) and the internal force Q:
  // elastic, plus the axial damping force at velocity v with dampWeight x C_d in A_. With
  // `from` (an energy-consistent step from that state to (q, v)): Q is the step's mean force,
  // the discrete gradient of the elastic energy plus the damping force at the midpoint, and A_
  // holds the derivative of twice that force (the start's share from step_start_, which
  // energyConsistentStep fills for `from`). With `matrix` false, Q alone (A_ untouched: a
  // Newton correction that reuses the factorised matrix, NewtonWeights::keep_matrix).
  void assemble(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double massWeight,
                double stiffWeight, double dampWeight, const Eigen::Matrix3d& G, Eigen::VectorXd& Q,
                const CoupledState* from = nullptr, bool matrix = true);
  // Recover (dq, dz, dy) from the reduced solution x = [dq; dy] of A_ x = [r_q; r_c + D A_z^-1
  // r_z].
  Eigen::VectorXd condensedRhs(const Eigen::VectorXd& rq, const Eigen::VectorXd& rz,
                               const Eigen::Vector3d& rc, Eigen::VectorXd& Azinv_rz) const;
  // Factorise A_; throws NumericalFailure with `what` on failure.
  void factorize(const std::string& what);
  // Factorise A_: the bordered band Cholesky, or the sparse LDL^T where the rope block is not
  // positive definite; false where neither succeeds. solveFactorized then solves with it.
  bool factorizeIterationMatrix();
  Eigen::VectorXd solveFactorized(const Eigen::VectorXd& rhs) const;
  // One step of size h from s; false (s unchanged, the reason in why) where Newton fails.
  bool tryStep(CoupledState& s, double h, std::string& why);
  // One generalized-alpha step, or one energy-consistent step (see step()).
  bool generalizedAlphaStep(CoupledState& s, double h, std::string& why);
  bool energyConsistentStep(CoupledState& s, double h, std::string& why);
  double ec_step_ = 0.0;  ///< the running energy-consistent step's size h [s] (assemble)
  // Factorise A_ (unless `refactorize` is false: the last factorisation) and solve it for rhs:
  // dq and dmu; false (reason set) where A_ is singular.
  bool solveIncrement(const Eigen::VectorXd& rhs, Eigen::VectorXd& dq, Eigen::Vector3d& dmu,
                      std::string& reason, bool refactorize = true);
  // The energy a step start -> s adds to the rope beyond the work of the top force and the
  // damper's dissipation [J] (<= 0 for a dissipative step; 0 to round-off for an
  // energy-consistent one).
  double ropeEnergyCreated(const CoupledState& start, const CoupledState& s) const;
  // The rope's own energy E_r = 1/2 v^T M v + U(q) - F_g^T q [J] at x, remembered for the last
  // state asked (ropeEnergyCreated asks a step's start, the step before's end, again).
  double ropeOwnEnergy(const CoupledState& x) const;
  struct RopeEnergyMemo {
    std::uint64_t revision = 0;  ///< AncfRope::revision() of the value (0: none)
    Eigen::VectorXd q, v;
    double value = 0.0;
  };
  mutable RopeEnergyMemo rope_energy_memo_;
  // The hoist rope's axial strains at q (AncfRope::axialStrains), remembered for the last two
  // states asked: a step's switch check asks its start (the step before's end) and its end.
  const Eigen::VectorXd& axialStrainsAt(const Eigen::VectorXd& q) const;
  struct StrainMemo {
    std::uint64_t revision = 0;  ///< AncfRope::revision() of the strains (0: none)
    Eigen::VectorXd q, eps;
  };
  mutable std::array<StrainMemo, 2> strain_memo_;
  mutable int strain_memo_last_ = 0;  ///< the entry asked last (the other is replaced first)
  long halved_steps_ = 0;
  long matrix_reusing_corrections_ = 0;
  /// An energy-consistent step's start at every Gauss point, element by element (the part of
  /// the discrete gradient no Newton iterate changes).
  std::vector<CablePointStepStart> step_start_;
  TensionOnlySwitching switching_;  ///< the tension-only rule's memory (episode, created energy)
  double last_step_length_ = -1.0;  ///< the rope's length at the previous step() or start
  bool hoisting_ = false;           ///< the length changed since: judged by energy alone
  double rope_damping_ = 0.0;
  std::optional<GroundContact> ground_;
  const AncfRope& rope_;
  RopeSupport& support_;
  GeneralizedAlpha ga_;
  double h_;
  NewtonSettings newton_;
  // The generalized-alpha steps' Newton constant (newton_step.hpp): a first correction keeps its
  // matrix where it foresees convergence and the law kept its branches (lawBranchesAsAtMatrix).
  // The energy-consistent steps, all across slack/taut switches, do not use it.
  NewtonMemory newton_memory_;
  NewtonWorkspace newton_workspace_;  ///< newtonStep's storage (scratch between steps)
  // The iterate at which a generalized-alpha step last assembled A_ (the matrix a first
  // correction keeps; the energy-consistent step's and the start's solves do not set it).
  Eigen::VectorXd matrix_q_;
  // A generalized-alpha correction whose matrix would be A_ at matrix_q_ but for the axial
  // tangent of a few Gauss points that changed branch since (a slack rope's Newton iterates):
  // the factorisation kept and those points' tangent changes added as rank-one terms
  // (rank_one_terms_solve.hpp; docs/model.md "Full-order solution"). axialTangentChanges
  // collects them: stiffWeight w_g l (N'(eps_g(q)) - N'(eps_g(matrix_q_))) v v^T with
  // v = S_x^T t at matrix_q_ (ancfAxialTangentShape); false where more than kMaxRankOneTerms points
  // changed. With a ground, the change of the contact's 3 x 3 block at the payload point joins
  // them (contactTangentChanges: a touchdown, a lift-off, the friction's slope). Only where
  // nothing else in A_ switches (no rigging, no rope damping) and A_'s factorisation is that
  // generalized-alpha matrix, of this step size and rope length.
  bool rankOneTermsApply(const Eigen::VectorXd& q, double h) const;
  // What rankOneTermsApply asks of the rope and the settings alone.
  bool rankOneTermsPossible() const;
  // The payload clear of the ground at matrix_q_ and at q (always, without a ground).
  bool payloadClearAtMatrixAnd(const Eigen::VectorXd& q) const;
  // The payload pressed into the ground at q (penetration > 0; never without a ground).
  bool payloadTouchesAt(const Eigen::VectorXd& q) const;
  // The payload point's penetration into the ground at q [m] (a ground must be set).
  double payloadPenetrationAt(const Eigen::VectorXd& q) const;
  // The ground's share of A_ at the payload point, -beta h^2 df/dr - gamma h df/dv, from the
  // contact's derivatives c and the two weights; and at a generalized-alpha iterate (q, v).
  static Eigen::Matrix3d contactMatrixPart(const GroundContactForce& c, double stiffWeight,
                                           double dampWeight);
  Eigen::Matrix3d contactMatrixPartAt(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                      const NewtonWeights& w) const;
  // Appends the change of the contact's share since matrix_q_ (matrix_contact_) as up to three
  // rank-one terms at the payload point (point id kContactPoint); false where the block's
  // eigen-decomposition fails.
  bool contactTangentChanges(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                             const NewtonWeights& w, std::vector<RankOneTerm>& terms,
                             std::vector<int>& points) const;
  static constexpr int kContactPoint = -10;  ///< rank_one_points_ id of a contact term
  /// A contact term's weight counts as zero below this fraction of the contact block's entries.
  static constexpr double kContactRoundOff = 1e-12;
  Eigen::Matrix3d matrix_contact_ = Eigen::Matrix3d::Zero();  ///< the contact's share at matrix_q_
  std::deque<Eigen::VectorXd> contact_columns_;  ///< this correction's contact-term columns
  // A generalized-alpha matrix assembled at q for step size h: matrix_q_ and what goes with it;
  // the strains at q taken from iterate_eps_ where strains_at_iterate (axialTangentChanges ran
  // at q), else computed when next asked.
  void assembledMatrixAt(const CoupledState& x, const NewtonWeights& w, double h,
                         bool strains_at_iterate);
  bool axialTangentChanges(const Eigen::VectorXd& q, double stiffWeight,
                           std::vector<RankOneTerm>& terms, std::vector<int>& points) const;
  // A^-1 u of the term at Gauss point `point`, from the columns kept for this factorisation.
  const Eigen::VectorXd& rankOneColumn(const RankOneTerm& term, int point);
  static constexpr int kMaxRankOneTerms = 12;
  long factorizations_ = 0;            ///< factorizeIterationMatrix calls
  long matrix_factorization_ = -1;     ///< factorizations_ of A_ at matrix_q_
  double matrix_h_ = 0.0;              ///< the step size of A_ at matrix_q_ [s]
  std::uint64_t matrix_revision_ = 0;  ///< the rope's revision() then (a new length: a new A_)
  long ga_steps_ = 0;                  ///< generalized-alpha steps begun
  /// The step's corrections look for switched points: at its start a Gauss point below the
  /// linear range, or the payload on the ground.
  bool step_looks_for_switches_ = false;
  long matrix_ga_step_ = -1;             ///< ga_steps_ when A_ was assembled at matrix_q_
  mutable Eigen::VectorXd matrix_eps_;   ///< axial strains at matrix_q_ (empty: not yet computed)
  mutable Eigen::VectorXd iterate_eps_;  ///< axial strains at the iterate last checked
  std::vector<RankOneTerm> rank_one_terms_;
  std::vector<int> rank_one_points_;  ///< the Gauss point (element-major index) of each term
  // A^-1 u of the terms' shapes for the factorisation matrix_factorization_, by Gauss point
  // (u = v at matrix_q_ does not change while the factorisation stands).
  long column_factorization_ = -1;
  std::vector<int> column_point_;
  std::deque<Eigen::VectorXd> column_;  // (push_back keeps references to the others)
  long rank_one_corrections_ = 0;
  long contact_rank_one_corrections_ = 0;
  SparseMatrix A_;               ///< KKT iteration matrix, pattern fixed at construction
  std::vector<int> mass_index_;  ///< value slot of each mass entry (in M's order)
  std::vector<double> mass_value_;
  std::vector<int> element_index_;  ///< 144 value slots per element, column-major 12 x 12
  std::vector<int> rigging_index_;  ///< 36 value slots of the rigging bar, column-major 6 x 6
  /// A_ solved by block elimination of its banded rope block (the usual case) ...
  std::optional<BorderedBandFactorization> band_;
  /// ... or, where that block is not positive definite, by a sparse LDL^T in natural order.
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt_;
  bool band_factorized_ = false;  ///< the last factorisation is band_'s
};

}  // namespace crane_twin
