// A scene run with the reduced rope on the rotation-invariant basis (rope.model: reduced, the
// default rope.reduction: invariant; docs/model.md "Reduced rope"): the full-order model's rope,
// support, drives and initial state (CraneSimulation), the state projected onto the basis
// (InvariantRopeBasis) and integrated by InvariantReducedSolver. Swinging, slewing and trolley
// travel need nothing more: the basis carries any rigid rotation; hoisting keeps the reduced
// coordinates and rescales the matrices with the length.
//
// Hand-over to full order, where the basis cannot carry the state, and back (docs/model.md
// "Hand-over to full order"). The reduced rope integrates the tension-only law across its
// slack/taut switches energy-consistently (InvariantReducedSolver), so a rope that touches zero
// tension at the top of an axial bounce (a snatch, a stress-free release) stays reduced; the run
// hands over only
//  - for a slack interval itself: the rope's slack length (InvariantReducedSolver::slackLength,
//    the unstretched length by which its slack parts exceed their chord) above kSlackLength —
//    a slack rope sags and loops in shapes the basis does not hold;
//  - where a reduced step fails (Newton, even halved; a non-finite state);
//  - where the error indicator (every kCheckSteps steps, postponed while a switching episode
//    runs, whose accelerations are step means, and while a point of the rope is slack or
//    stretched under kIndicatorStrainFraction of the end mass's strain): the displacement a
//    static correction of the full equations' residual at the expanded state would add,
//    dq = (K + M)^-1 r (M in kg, K in N/m, so the shift is 1 s^-2) with the top held (what the
//    basis leaves out), exceeds kIndicatorTolerance at a node, and the basis cannot take the
//    state's own shapes (addShapesOf: up to kMaxAddedShapes over the basis the run started or
//    came back on; a hand-back returns to that basis).
// A start the basis does not carry (the hand-back criteria below fail on the scene's initial
// state: a velocity given to the payload alone) begins at full order. A release whose axial
// rebound will slacken the rope (releaseTensionLowPoint below zero: a load released from its
// held equilibrium past 45 deg), whose path after a slack episode is sensitive to the reduced
// steps before it, starts reduced on the snatch basis (below) but speculatively: full order's
// start is the checkpoint, and any hand-over within the speculation window (a slack interval, a
// failed step, an indicator over kIndicatorTolerance, or over kSnatchSpeculationTolerance where
// the state's own shapes cannot be added) takes the run back to full order's own run from the
// start; so does the same indicator within the window of any hand-back after a snatch (guarded,
// HandOverSimulation). Released at 45 to 52 deg the T8036's rope touches zero tension and stays
// reduced; at 55 and 60 deg the speculation is taken back within 0.3 s and the run is full order's,
// as before (docs/model.md "Hand-over to full order"). At full order, after kHandBackDwell
// (kQuietHandBackDwell after a start the basis does not hold that forecasts no slack) and then
// every kHandBackSteps steps (doubling after each refused trial once kHandBackDwell has passed, up
// to kMaxHandBackInterval), the run comes back as soon as the rope is taut (no node's strain and
// not the top tension below zero), the projection moves no node by more than kHandBackTolerance
// (kIndicatorTolerance on a firmly taut rope) and changes the rope's energy by less than
// kHandBackEnergy (a load not resting on the ground), and the indicator at the projected state is
// under kHandBackTolerance (neither test for a rope at rest without strain that the basis holds
// exactly, kRestEnergyFraction: a stress-free start, which therefore runs reduced from its first
// step); where these fail on the basis but its projection moves no node by more than
// kIndicatorTolerance, and the load is not on the ground, the same tests on the basis with full
// order's own shapes added (withShapesOf, kMaxAddedShapes). Where its tension's forecast low point
// (releaseTensionLowPoint) is under kIndicatorStrainFraction of the end weight (the rope rings
// towards slack, where the indicator does not look; a stress-free release on a rigid anchor,
// rope_pendulum_chrono, whose tension touches zero at every bounce, handed back for good 0.12 s
// in, parted from full order by 9.9 cm, rope RMS 21 cm), the hand-back is speculative
// (HandOverSimulation): taken back to full order, exactly, where the run would hand over within
// the speculation window, the indicator bounded by kSpeculationTolerance meanwhile. After a
// snatch (a ringing start, a slack hand-over) the hand-back projects onto the scene's basis with
// every axial mode the step resolves (snatchBasis, kResolvedAxialOmegaH). Hand-overs,
// the steps taken at full order and the hand-backs taken back are counted (summary line, CSV
// column `full_order_steps`, node diagnostics).
#pragma once

#include <Eigen/SparseCholesky>
#include <functional>
#include <memory>

#include "crane_twin/rope/invariant_rope_basis.hpp"
#include "crane_twin/simulation/hand_over_simulation.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"
#include "crane_twin/solvers/invariant_reduced_solver.hpp"

namespace crane_twin {

/// Basis sizes of a scene: rope.mode_count transverse modes when > 0, else the default
/// (InvariantBasisSettings).
InvariantBasisSettings invariantBasisSettings(const Scene& scene);
/// Reduced coordinates (3 per shape, 3 more for a rigging's payload point) a run of the scene
/// integrates: the scene's basis, or one a landed start adapted (initialises a run to see).
int invariantRopeCoordinates(const CraneModel& model);

class InvariantReducedSimulation final : public HandOverSimulation,
                                         public ContinuableRun,
                                         public CorrectableMotion,
                                         public MeasuredWindInput {
 public:
  /// Throws InputError for what the full-order model refuses, naming the key.
  explicit InvariantReducedSimulation(const CraneModel& model);
  /// The wind acts through the full model's rope loads, which the reduced solver projects.
  void setMeasuredWind(const Eigen::Vector3d& v) override { setFullModelWind(v); }
  void continueFrom(const Simulation& other) override;
  /// Reduced: the motion projected onto the basis (exact for a rigid rotation of a state the
  /// basis carries); at full order: the full model's.
  void setMotion(const CoupledState& s) override;

  /// The basis integrated on: the scene's, or one a landed start adapted (kStartShapeTolerance).
  const InvariantRopeBasis& basis() const { return *basis_; }
  const InvariantReducedSolver& solver() const { return *solver_; }
  /// The reduced state (y, z) while integrating reduced.
  const CoupledState& reducedState() const { return state_; }
  /// The error indicator at a full-coordinate state: max node |dq| [m] (header).
  double errorIndicator(const CoupledState& full) const;
  /// The full-coordinate state `full` (an expansion of this run's basis) with what the basis
  /// held fixed relaxed to the full model's quasi-static shape at full's accelerations: the
  /// static correction iterated in the basis's M-orthogonal complement,
  ///   q <- q + dq,  (K(q) + M) dq + M B mu = F_g - M q'' - Q(q, q'),  B^T M dq = 0
  /// (the top's position held; B without the top's translation), so that its projection onto
  /// the basis is unchanged; velocities and accelerations kept. Until max node |dq| <
  /// kQuasiStaticTolerance or kQuasiStaticIterations corrections; `full` unchanged where the
  /// iteration does not settle (its last correction not below its first).
  CoupledState quasiStaticallyRelaxed(const CoupledState& full) const;
  /// Hand-overs by cause: slack, failed step, error indicator.
  long slackHandOvers() const { return handOvers(Cause::slack); }
  long failureHandOvers() const { return handOvers(Cause::failure); }
  long indicatorHandOvers() const { return handOvers(Cause::indicator); }
  /// 1 where the scene's start was not carried by the basis and the run began at full order.
  long startHandOvers() const { return handOvers(Cause::start); }
  /// Largest indicator value seen on a reduced step [m].
  double maxIndicator() const { return max_indicator_; }
  /// The end tension's forecast low point [N] at the start of a release (startReduced): the end
  /// mass m on the rope's axial spring k = EA / L about the quasi-static pendulum tension
  ///   T_qs = m (g . e + |v_perp|^2 / l) + F_ext . e   (e the unit chord from the top to the end)
  /// rings with the axial energy E = (T - T_qs)^2 / (2 k) + m s'^2 / 2 (T the rope's pull on the
  /// end now, from m (a - g) - F_ext; s' the chord's stretch rate) down to T_qs - sqrt(2 k E).
  /// Released from its held equilibrium at theta: W (2 cos theta - 1 / cos theta), below zero
  /// past 45 deg. +infinity without an end mass and for a load on (or within kGroundMargin of)
  /// the ground, which is no release.
  double releaseTensionLowPoint(const CoupledState& full) const;

  /// The hand-over's thresholds for this rope (HandOverSettings): taut again where no node's
  /// strain and not the top tension is below zero; hand-back trials after a 1 s dwell (the
  /// waves of a slack episode ring for about a second on a 60 m rope; 0.1 s after a quiet
  /// hand-over), every 20 steps, doubling up to 640. Slack is the slack length's test (slackened:
  /// the rope's, and a rigging's in the air), not the settings' fractions.
  static HandOverSettings handOverSettingsFor();
  /// Slack length [m] above which the rope counts as slack. Measured on the stress-free
  /// release (rope_pendulum_chrono: 60 m, 3.6 t), whose rope touches zero tension at the top of
  /// each 0.63 s axial bounce: at most 2.0 mm in the first 5 s; the 60 deg release's rope, which
  /// sags as it falls, 0.17 m in its first 0.5 s; a payload thrown up by h slackens ~h.
  static constexpr double kSlackLength = 0.01;
  /// Steps between the error indicator's evaluations (a tangent assembly and a sparse LDL^T
  /// of the full rope: 1.4 ms at 120 elements, from the benchmark's 27.5 us a step with it every
  /// 50 steps; 5.6 us a step averaged over 250).
  static constexpr int kCheckSteps = 250;
  static constexpr int kHandBackSteps = 20, kMaxHandBackInterval = 640;
  static constexpr double kIndicatorTolerance = 2e-3;  ///< [m]
  /// The indicator's bound while a hand-back is speculative [m] (HandOverSimulation): a rope
  /// ringing towards slack drifts from full order by far more than the indicator reads. On
  /// Chrono's stress-free release (rope_pendulum_chrono) it read 0.15 to 0.48 mm in the 3 s
  /// after the hand-back while the rope drifted to 1.1 cm RMS from full order (0.4 mm when it
  /// first read 0.25 mm); on 12.5 t released stress-free from a rigid anchor (60 elements),
  /// which stays within 0.11 mm RMS of full order, it read at most 1.1e-5 m in 12 s.
  static constexpr double kSpeculationTolerance = 1e-4;
  /// The indicator's bound while a speculation after a snatch is open [m] (a release's start,
  /// startReduced; a guarded hand-back, handBackGuarded): a reading over it adds the state's
  /// shapes (addShapesOf), one over kIndicatorTolerance or one whose shapes cannot be added
  /// takes the speculation back. Guarded hand-backs used to hand over at kIndicatorTolerance
  /// from the drifted state: three releases of light loads on four falls came back after their
  /// slack episode and drifted 1.1 to 1.3 cm rope RMS from full order in 20 s, where full order
  /// is within 1 mm of itself; taken back, 4.8 to 6.9 mm. Measured on 53 releases from 45 to
  /// 60 deg (the T8036 at 120 elements, other loads, lengths, falls and riggings, seeded draws;
  /// docs/accuracy-vs-time.md "Releases that start reduced"): at 2 mm, no additions, a release
  /// on four falls read 1.95 mm and ended 1.1 cm rope RMS from full order (7.5 mm started at
  /// full order); at 0.5 mm (kHandBackTolerance) each run over 1 cm was over it at 1 mm too, and
  /// shapes were added where the path needed none (two drawn releases 4.6x and 6.0x faster than
  /// full order against 9.2x and 12x at 1 mm, all four runs within 4 mm rope RMS).
  static constexpr double kSnatchSpeculationTolerance = 1e-3;
  /// The indicator waits while a point of the rope is stretched less than this fraction of the
  /// end mass's static strain (carries under a tenth of its weight): there the rope's tangent
  /// stiffness (EA's slope in the slack band, the tension's geometric stiffness) nears zero and
  /// the static correction (K + M)^-1 r grows with 1 / N, not with the state's error. Measured
  /// on t8036_set_down, whose landed load's rope nearly unloads at each low point of the jib's
  /// rebound: the indicator read 3.3 to 8.5 mm where the lowest strain was 0.1 to 1 % of the
  /// end strain and 0.04 to 1.1 mm where it was 3 to 6 %; the three hand-overs it made there
  /// in 20 s moved the rope's path against full order by 0.1 mm (9.2 mm RMS either way).
  static constexpr double kIndicatorStrainFraction = 0.1;
  /// Hand-back: largest node distance between the full state and its projection [m] (the
  /// waves a slack episode leaves on the rope that the basis drops), and the indicator bound.
  static constexpr double kHandBackTolerance = 5e-4;
  /// Hand-back of a firmly taut rope (every node's strain at least kFirmlyTautStrain of the end
  /// mass's static strain: an axial ringing, if any, within 20 % of the static tension, far
  /// from slack): the projection may drop up to kIndicatorTolerance, what a reduced run would
  /// hand over for. Waves dropped from a rope that stays taut ring down as they do at full
  /// order; a rope ringing near slack would grow them at its next snatch. Measured on the
  /// shipped scenes (scripts/reduced_vs_full.sh): with 0.5 t8036_set_down came back while its
  /// load, lifted by the jib's rebound, rang at over 20 % and ended 1.1 cm rope RMS from full
  /// order (0.92 cm strict); with 0.65 and 0.8 it ran as strict; with 0.95 the off-centre
  /// lift-off (0.8 to 3 mm of waves from the sideways drag on its swinging rope) no longer came
  /// back; with 0.8 it comes back after 2.3 s instead of running 20 s at full order.
  static constexpr double kFirmlyTautStrain = 0.8;
  /// Hand-back: energy the projection changes (kinetic relative to the top plus strain) against
  /// the rope's own (kinetic relative to the top, strain and the swing's potential energy).
  /// Not asked where the payload rests on the ground (within kGroundMargin of it): it has no
  /// swing, and its unloaded rope's few joules made 1e-4 of them a bound that the waves of a
  /// set-down kept failing (1.6 t set down at 44.6 m on the rigid structure: 3.8 s more at full
  /// order; its rope RMS against full order 2.8e-5 m without the bound, 2.4e-5 m with it); the
  /// projection's and the indicator's 0.5 mm still hold.
  static constexpr double kHandBackEnergy = 1e-4;
  /// A rope whose kinetic energy relative to its top and strain energy together stay under this
  /// fraction of the hanging weight times the rope's length counts as at rest and unloaded
  /// (round-off: a stress-free start reads 1e-26 J of 3e6 J), whatever its swing: a hand-back onto
  /// a basis that holds it exactly needs neither the energy test nor the indicator (tryTakeOver),
  /// and, its forecast low point being zero, is speculative. Measured (docs/model.md "Hand-over to
  /// full order"): the stress-free starts of hard_stress_free_heavy and of six seeded draws run
  /// reduced from their first step, within the same errors as after the 119 full-order steps
  /// before.
  static constexpr double kRestEnergyFraction = 1e-12;
  /// A landed start whose projection onto the scene's basis moves a node by more than this [m]
  /// adds its own shapes to the basis (InvariantRopeBasis::withShapesOf) and starts reduced on
  /// it, in equilibrium as full order's start is. The basis holds the rope hanging from the
  /// trolley with its load at the end; a load landed under the trolley leaves the rope so
  /// (4.6e-8 m on the shipped lift-offs, pick-and-place and set-down), but a load landed off the
  /// trolley's vertical settles the rope into the catenary between the trolley and the load,
  /// with a bending layer at the hook where it carries almost nothing (6.3e-5 m on
  /// t8036_off_centre_lift): on the scene's basis that start's equilibrium was lost (its reduced
  /// top tension 2.6 % under full order's, ringing by 5.6 % within 0.2 s), and its error
  /// indicator (1.3 to 1.6 mm where the rope is that unloaded) kept such lifts at full order
  /// until the load hung from a firmly taut rope, 3 to 7 s (docs/model.md "Hand-over to full
  /// order").
  static constexpr double kStartShapeTolerance = 1e-6;
  /// Simulated time a hand-over stays at full order before the first hand-back trial [s]: the
  /// waves of a snatch or a slack episode ring for about a second on a 60 m rope.
  static constexpr double kHandBackDwell = 1.0;
  /// The same after a quiet hand-over [s] (a start the basis does not hold with no slack
  /// forecast: a rope without a load released from rest; the hand-back's tests decide). Measured
  /// when a stress-free start still began at full order (docs/model.md "Hand-over to full
  /// order"): hard_stress_free_heavy came back after 139 full-order steps instead of 1019, errors
  /// unchanged; with 0.02 s after 139 too (seeded draws: 59 to 99 instead of 119 to 139). A
  /// touchdown is not quiet: the pick-and-place on a 4 m rigging came back 0.12 s after its
  /// touchdown, went back 3.3 s later as the jib's rebound slackened the rope, and ended 1.04 cm
  /// rope RMS from full order (0.50 cm with the second's dwell).
  static constexpr double kQuietHandBackDwell = 0.1;
  /// A rigging's payload moving against the hook at the start [m/s] (startReduced): a velocity
  /// given to the payload alone; an equilibrium start's is 0 to round-off.
  static constexpr double kStartVelocityTolerance = 1e-9;
  /// A release's forecast low point counts as slack below -kLowPointRoundOff of the end weight
  /// (releaseTensionLowPoint; a stress-free start's is zero up to its accelerations' round-off).
  static constexpr double kLowPointRoundOff = 1e-6;
  /// A rigging shorter than its unstretched length by more than this [m] is slack (tryTakeOver:
  /// a landed start's rigging is straight and unstretched, to round-off).
  static constexpr double kSlackRigging = 1e-3;
  /// After a snatch (a start whose release rings towards slack, or a slack hand-over), the
  /// hand-back projects onto a basis that also holds every axial mode full order's step resolves,
  /// omega h <= kResolvedAxialOmegaH (at least 2 pi steps a period), up to kMaxSnatchAxialModes:
  /// the rope rings axially far beyond the scene basis's two modes. Measured on the T8036 released
  /// from its held equilibrium at 50 deg (t8036_combination1, 120 elements, 1 ms: the modes at
  /// 11, 179, 357, ... rad/s, six with omega h <= 1): on two axial modes it came back 2.26 s in and
  /// drifted to 1.14 cm rope RMS from full order in 20 s (full order within 0.64 mm of itself at
  /// an eighth of the step); on six, 2.2 mm (docs/model.md "Hand-over to full order").
  static constexpr double kResolvedAxialOmegaH = 1.0;
  static constexpr int kMaxSnatchAxialModes = 16;
  /// An indicator hand-over (errorTooLarge) hands over the expanded state relaxed by
  /// quasiStaticallyRelaxed to kQuasiStaticTolerance (a fiftieth of the hand-back's 0.5 mm), in
  /// at most kQuasiStaticIterations corrections: the components the basis held fixed, released
  /// as they are, spring back and ring on at full order. Measured on the T8036 released at
  /// 48 deg with 1.2 t on 30 m (60 elements; the hand-over 5.76 s in): full order's
  /// accelerations outside the basis 888 m/s^2 at the plain expansion, 0.087 relaxed; its top
  /// tension within 2.5 kN of full order's own run after the hand-over, 0.50 kN relaxed (the
  /// reduced run's own 0.44 kN before it; docs/model.md "Hand-over to full order").
  static constexpr double kQuasiStaticTolerance = 1e-5;  ///< [m]
  static constexpr int kQuasiStaticIterations = 5;
  /// The basis takes a state's own shapes (InvariantRopeBasis::withShapesOf: at most three
  /// scalar shapes, one per direction) twice over:
  ///  - an indicator miss outside a speculation that rings towards slack first adds the shapes
  ///    of the state relaxed by quasiStaticallyRelaxed and stays reduced on the state's
  ///    projection onto the new basis, which is the relaxed state itself;
  ///  - a hand-back trial whose tests fail on the basis, where the projection drops at most
  ///    kIndicatorTolerance of full order's rope and the load is not on the ground (a landing's
  ///    waves on a rigging passed the tests on the added shapes and then left them: a pick and
  ///    place on a 4 m rigging came back 1 s after its touchdown, 0.91 cm rope RMS and 2.3 %
  ///    top tension from full order, 0.29 cm and 1.1 % staying there), repeats them on the
  ///    basis with full order's shapes added, which holds its positions exactly (the
  ///    velocities and accelerations are still weighed).
  /// Up to kMaxAddedShapes shapes over the basis the run started or came back on; then a miss
  /// hands over and a trial fails. Measured on the releases past 45 deg and the drawn lift-offs
  /// (docs/model.md "Hand-over to full order", "Shapes added to the basis").
  static constexpr int kMaxAddedShapes = 9;
  /// Shapes a run may add (kMaxAddedShapes; 0: none, as a comparison: every miss hands over,
  /// every hand-back on the basis alone).
  void setMaxAddedShapes(int shapes);
  /// Whether a release whose rebound slackens the rope starts reduced as a speculation (true,
  /// the default; header) or at full order, coming back after the dwell (false, as a
  /// comparison: the hand-back after a snatch). Asked at initialize().
  void setSpeculativeReleaseStart(bool speculative) { speculative_release_start_ = speculative; }
  /// Whether the error indicator holds a guarded hand-back (after a snatch) to
  /// kSnatchSpeculationTolerance and takes it back over kIndicatorTolerance (true, the default;
  /// header) or hands over from it as from any reduced state (false, as a comparison).
  void setSnatchIndicatorGuard(bool guard) { snatch_indicator_guard_ = guard; }
  /// Shapes added so far, by indicator misses and hand-backs.
  long basisAdditions() const { return basis_additions_; }

 protected:
  Start startReduced(const CoupledState& full) override;
  Verdict reducedStep() override;
  bool tryTakeOver(const CoupledState& full) override;
  bool handBackIsSpeculative(const CoupledState& full) const override;
  /// After a snatch (hasSnatched): every hand-back is guarded (HandOverSimulation, docs/model.md
  /// "Hand-over to full order": a guarded hand-back).
  bool handBackGuarded() const override { return hasSnatched(); }
  bool guardTakesBackAtTheIndicator() const override { return snatch_indicator_guard_; }
  CoupledState handOverState(Cause c) override;
  bool restartsAtHandOver() const override { return true; }
  double reducedTime() const override { return state_.t; }
  const Eigen::VectorXd& reducedSupport() const override { return state_.z; }
  Eigen::Vector3d reducedNode(int j) const override { return solver_->nodePosition(state_.q, j); }
  CoupledState expandReduced() const override { return solver_->expand(state_); }
  SeriesValues reducedSeries() const override;
  double reducedLength() const override { return solver_->length(); }
  double reducedTopTension() const override { return solver_->topTension(state_); }
  double reducedMinStrain() const override { return solver_->minStrain(state_.q); }
  long reducedHalvedSteps() const override {
    return retired_halved_steps_ + solver_->halvedSteps();
  }
  long reducedEnergyConsistentSteps() const override {
    return retired_energy_consistent_steps_ + solver_->energyConsistentSteps();
  }
  long reducedBasisAdditions() const override { return basis_additions_; }
  bool slackened() const override;
  bool errorTooLarge(long steps) override;
  bool carriesGround() const override { return true; }

 private:
  void syncFullRope();
  bool riggingSlackInTheAir() const;
  // The static correction dq = (K + M)^-1 r at a full-coordinate state, the top's position held
  // (errorIndicator, header), into dq (the rope's coordinates less the top's position); returns
  // its largest node |dq| [m], infinity where the matrix is singular.
  double staticCorrection(const CoupledState& full, Eigen::VectorXd& dq) const;
  // Largest node position |dq_j| of a correction over the rope's coordinates less the top's
  // position [m] (infinity where it is not finite).
  double largestNodeCorrection(const Eigen::VectorXd& dq) const;
  // Potential energy of the swing of a full-coordinate state above the hanging rope [J].
  double swingEnergy(const CoupledState& full) const;

  // Integrate on `basis` from now on: a new solver with the scene's settings (the old one's step
  // counts kept for the run's statistics).
  void useBasis(std::shared_ptr<const InvariantRopeBasis> basis);
  // At an indicator miss on the reduced state expanded to `full`: the basis with the shapes of
  // full relaxed (withShapesOf), the reduced state its projection there. False, nothing
  // changed, where the shapes would pass the cap, the relaxation does not settle, or the
  // indicator at the new state still misses.
  bool addShapesOf(const CoupledState& full);
  // The hand-back's tests on the present basis (tryTakeOver): the state taken over where they
  // pass.
  bool takeOverOnBasis(const CoupledState& full);
  // The basis with the shapes of full coordinates q added (InvariantRopeBasis::withShapesOf), a
  // new solver on it continuing the old one's stepping, kept where `attempt` (on the new
  // basis) succeeds; else the old basis and solver, unchanged. False where !mayAddShapes() or
  // the basis holds q already.
  bool withShapesOf(const Eigen::VectorXd& q, const std::function<bool()>& attempt);
  // Three more shapes stay within max_added_shapes_ over base_basis_ (asked before the work
  // that would find them).
  bool mayAddShapes() const;
  // A replaced solver's step counts, kept for the run's statistics.
  void retireCounts(const InvariantReducedSolver& replaced);
  // The scene's basis with the axial modes the step resolves (kResolvedAxialOmegaH), at the
  // rope's present length; built once, at the first hand-back trial after a snatch.
  std::shared_ptr<const InvariantRopeBasis> snatchBasis();
  // A ringing start, a continued run's snatch or a slack hand-over of this run.
  bool hasSnatched() const { return snatched_ || handOvers(Cause::slack) > 0; }

  std::shared_ptr<const InvariantRopeBasis> scene_basis_;  ///< the scene's, shared by copies
  std::shared_ptr<const InvariantRopeBasis> basis_;        ///< base_basis_, with added shapes
  /// The scene's, a start's or the snatch basis: what the run started or came back on.
  std::shared_ptr<const InvariantRopeBasis> base_basis_;
  std::shared_ptr<const InvariantRopeBasis> snatch_basis_;  ///< snatchBasis, once built
  /// The run has snatched before: a release start whose rebound slackens the rope, or a run
  /// continued from one that handed over for slack (this run's own slack hand-overs count too).
  bool snatched_ = false;
  /// The open speculation is the release start's (startReduced): though it rings towards
  /// slack, the indicator holds it to kSnatchSpeculationTolerance, adding shapes up to
  /// kIndicatorTolerance, instead of kSpeculationTolerance; cleared by any later hand-back.
  bool release_speculation_ = false;
  std::unique_ptr<InvariantReducedSolver> solver_;
  CoupledState state_;
  double max_indicator_ = 0.0;
  int max_added_shapes_ = kMaxAddedShapes;
  bool speculative_release_start_ = true;
  bool snatch_indicator_guard_ = true;
  long basis_additions_ = 0;
  long retired_halved_steps_ = 0, retired_energy_consistent_steps_ = 0;  ///< replaced solvers'
  bool indicator_due_ = false;  ///< an indicator check postponed by a switching episode
  mutable Eigen::SimplicialLDLT<SparseMatrix> indicator_ldlt_;
  mutable bool indicator_pattern_ = false;
};

}  // namespace crane_twin
