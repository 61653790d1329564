// HandOverSimulation: the one hand-over mechanism every reduced rope plugs into (docs/model.md
// "Hand-over to full order"). It owns the full-order model of the scene (CraneSimulation: rope,
// support, drives, initial state), one clock, one sampling and output path, and the switch
// between the reduced rope and full order:
//  - reduced, each step: the drives advance, the reduced rope steps (reducedStep); the run hands
//    its state over to full order when that step fails or asks for it (Verdict), when the rope
//    is slack (slackened: by default the top tension under slack_tension_fraction of the
//    hanging weight or, every strain_check_steps steps, a Gauss point's or node's axial strain
//    under slack_strain_fraction of the static strain under the end mass; a reduced rope may
//    judge slack its own way), and when its error indicator says the basis no longer carries
//    the state (errorTooLarge);
//    and when the payload's underside comes down to within kGroundMargin of the ground (a
//    touchdown; docs/model.md "Ground contact"), or rests there under a rope that unloads off
//    its vertical (restingRopeUnloaded) or that the drives drag while it carries nothing of it
//    (restingRopeDragged);
//  - at full order: after hand_back_dwell of simulated time (quiet_hand_back_dwell after a quiet
//    hand-over: a start the basis does not hold that forecasts no slack) and then
//    every hand_back_steps steps (doubling after each refused trial once hand_back_dwell has
//    passed, up to max_hand_back_interval), a hand-back trial: the
//    rope taut (top tension above taut_tension_fraction of the weight, every node's strain above
//    taut_strain_fraction of the end mass's static strain less the slack band kSlackBand, the
//    payload at least 2 kGroundMargin above the ground) and the reduced rope takes the state over
//    (tryTakeOver: its own test that the projection loses nothing);
//  - a hand-back the reduced rope takes but cannot vouch for (handBackIsSpeculative: a rope
//    that rings towards slack) is speculative: the full-order state at the hand-back is kept as
//    a checkpoint, with the operator's commands and measured winds from then on. Where the run
//    would hand over within speculation_window of it (any cause), the hand-back is taken back
//    instead: full order re-integrates from the checkpoint to the present, replaying those
//    inputs at their steps, and continues the full-order run as if it had never handed back
//    (a caller that writes rows shows the re-integrated steps to its replay observer and
//    replaces the speculation's rows by theirs, SpeculativeRun; a node's published messages
//    stay as they went out). Past the window, or at a measured
//    motion (setMotion), the hand-back is kept and the checkpoint dropped. A guarded hand-back
//    (handBackGuarded: a reduced rope's after a snatch) keeps the same checkpoint but is taken
//    back only for a slack episode, a failed step or (guardTakesBackAtTheIndicator) the error
//    indicator within the window; any other hand-over keeps it.
// A start the reduced rope does not take over runs at full order from t = 0. The hanging weight
// W = (m_end + mu L) g and the end mass's static strain m_end g / EA are the scene's.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"

namespace crane_twin {

/// The thresholds and schedule of the hand-over (fractions of the hanging weight W and of the
/// end mass's static strain; see each reduced rope's values and why).
/// The payload's clearance above the ground under which a reduced run hands over to full order
/// [m] (twice that for a hand-back): a load moves far less in one step (1 cm at 10 m/s and 1 ms).
constexpr double kGroundMargin = 0.05;
/// A resting load's rope is loaded once its end carries this fraction of the end mass's weight
/// (its top tension less the hanging rope's weight), and unloaded again where its hook rests
/// (SupportedRopeSimulation::kRestingLoadFraction, a tenth of that weight, where the error
/// indicator no longer looks either).
constexpr double kRopeLoadedFraction = 0.2;
/// The end's horizontal offset from under the rope's top, as a fraction of the hanging length,
/// beyond which an unloading rope on a resting load hands over (restingRopeUnloaded): such a
/// rope sags into a catenary with a bending layer at the hook that the basis does not hold
/// (docs/model.md "Hand-over to full order"); a plumb one (a jib's rebound over a set-down load,
/// 0.16 m off under 61 m) stays reduced.
constexpr double kUnloadedOffsetFraction = 0.01;
/// How far the trolley or the slew may move the rope's top over a resting load whose rope does
/// not carry it (restingRopeDragged) before the run hands over [m]: the basis holds the sag of
/// the chord it took over, and the error indicator is blind at that rope's unloaded end. A
/// trolley dragging the top 1.2 m towards 6.8 t resting 2 m off on four falls of the rigid T8036
/// left the reduced rope 1.1 mm rope RMS from full order after 0.2 m and 2.0 cm after the whole
/// move, where full order at half the step is 5 mm from itself (docs/model.md "Hand-over to full
/// order").
constexpr double kDragTolerance = 0.05;
/// Round-off of a nodal strain |r_x| - 1 [-] (a few ulps of |r_x| near 1): the hand-back's strain
/// test allows it below the tension-only law's slack edge, where a stress-free rope sits.
constexpr double kStrainRoundOff = 1e-12;

struct HandOverSettings {
  double slack_tension_fraction = 0.1, taut_tension_fraction = 0.2;
  double slack_strain_fraction = 0.1, taut_strain_fraction = 0.2;
  int strain_check_steps = 10;   ///< reduced steps between strain checks
  double hand_back_dwell = 1.0;  ///< simulated time at full order before the first trial [s]
  /// The same after a quiet hand-over [s] (a start the basis does not hold that forecasts no
  /// slack: Start::outside_basis): trials every hand_back_steps from this dwell on, doubling
  /// only once hand_back_dwell has passed (at most the smaller of the two dwells).
  double quiet_hand_back_dwell = 0.1;
  int hand_back_steps = 20;          ///< full-order steps between trials at first
  int max_hand_back_interval = 640;  ///< the interval doubles after each refused trial up to this
  /// Simulated time a speculative hand-back may still be taken back [s]: the longest stretch
  /// full order re-integrates at once (a node's burst), and what a speculation must survive to
  /// be kept.
  double speculation_window = 10.0;
};

class HandOverSimulation : public Simulation, public SpeculativeRun {
 public:
  /// Why a run went to full order (counted per cause).
  enum class Cause { start, slack, failure, indicator, fast_hoist, ground };
  /// How a run starts (startReduced): the reduced rope takes the scene's initial state; or the
  /// run starts at full order, for a start the basis does not hold that forecasts no slack (a
  /// rope without a load released from rest: a quiet hand-over), or for one that rings (a
  /// release whose rebound will slacken the rope, a rigging's payload given its own velocity).
  /// Either is a Cause::start.
  enum class Start { reduced, outside_basis, ringing };
  /// What a reduced step reports: carried, or the full model must take the step just begun
  /// (the reduced state is still at its start: a failed step, a hoist too fast for the basis).
  enum class Verdict { carried, failed, fast_hoist };

  void initialize() override;
  void step() override;
  void setCommand(const CommandEntry& command) override;
  double time() const override { return full_order_ ? full_.time() : reducedTime(); }
  SeriesValues series() const override;
  double topTension() const override {
    return full_order_ ? full_.topTension() : reducedTopTension();
  }
  Eigen::VectorXd hotSpotStresses() const override {
    return full_order_ ? full_.hotSpotStresses() : full_.model().hotSpotStresses(reducedSupport());
  }
  void sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab,
              Eigen::Vector3d& jib_tip) const override;
  int ropeNodes() const override { return full_.ropeNodes(); }
  Eigen::Vector3d ropeNode(int j) const override {
    return full_order_ ? full_.ropeNode(j) : reducedNode(j);
  }
  CoupledState fullState() const override {
    return full_order_ ? full_.fullState() : expandReduced();
  }
  const CraneDrives& drives() const override { return full_.drives(); }
  const RopeSupport& support() const override { return full_.support(); }
  std::vector<Eigen::Vector3d> ropeCurve(int per_element) const override;
  int hookNode() const override { return full_.hookNode(); }
  /// The full model's (a rigging's payload point is a position without a slope).
  std::vector<bool> fullStatePositionBlocks() const override {
    return full_.fullStatePositionBlocks();
  }
  RunStatistics statistics() const override;
  /// Hand-overs to full order so far, the steps integrated at full order, and whether the
  /// current step runs at full order.
  long handOvers() const;
  long fullOrderSteps() const { return full_order_steps_; }
  bool integratingFullOrder() const { return full_order_; }
  /// Speculative hand-backs taken back so far (re-integrated at full order), whether the run is
  /// in one now, and whether that one rings towards slack (handBackIsSpeculative: taken back
  /// for any hand-over) rather than being guarded after a snatch (handBackGuarded: taken back
  /// for a slack episode or a failed step only).
  long handBacksTakenBack() const override { return taken_back_; }
  bool speculating() const override { return speculating_; }
  /// SpeculativeRun: the observer of a take-back's re-integration (takeBack).
  void setReplayObserver(ReplayObserver observer) override {
    replay_observer_ = std::move(observer);
  }
  bool speculationRingsTowardsSlack() const { return speculating_ && rings_towards_slack_; }

  /// The rope length being integrated [m] (the full rope's while at full order).
  double ropeLength() const { return full_order_ ? full_.ropeLength() : reducedLength(); }
  /// The full-order setup behind the run (model, rope, support, drives; the full-order steps).
  const CraneSimulation& crane() const { return full_; }
  const HandOverSettings& handOverSettings() const { return settings_; }
  /// Hand-overs to full order for one cause.
  long handOvers(Cause c) const { return hand_overs_[static_cast<int>(c)]; }

 protected:
  HandOverSimulation(const CraneModel& model, const HandOverSettings& settings);

  // ---- what a reduced rope provides ------------------------------------------------------
  /// Start the reduced rope on the scene's initial state `full` (full_ holds it), or say why
  /// the run starts at full order (default: the hand-back trial, outside_basis where it fails).
  /// Resets the reduced rope's own counters.
  virtual Start startReduced(const CoupledState& full);
  /// One reduced step of h (the drives have advanced); throws nothing: a failure is a Verdict.
  virtual Verdict reducedStep() = 0;
  /// Take over a full-coordinate state (full_'s current); false, nothing changed, where the
  /// reduced rope cannot carry it.
  virtual bool tryTakeOver(const CoupledState& full) = 0;
  /// The full-coordinate state handed over to full order for cause c (the reduced state
  /// expanded; a reduced rope may relax what its basis held fixed, by cause).
  virtual CoupledState handOverState(Cause c) = 0;
  /// Whether full order restarts its accelerations from the handed-over positions and
  /// velocities (else it takes the expanded accelerations as they are).
  virtual bool restartsAtHandOver() const = 0;
  virtual double reducedTime() const = 0;
  virtual const Eigen::VectorXd& reducedSupport() const = 0;  ///< the support coordinates z
  virtual Eigen::Vector3d reducedNode(int j) const = 0;
  virtual CoupledState expandReduced() const = 0;
  virtual SeriesValues reducedSeries() const = 0;
  virtual double reducedLength() const = 0;
  virtual double reducedTopTension() const = 0;
  virtual double reducedMinStrain() const = 0;
  virtual long reducedHalvedSteps() const { return 0; }
  virtual long reducedEnergyConsistentSteps() const { return 0; }
  /// Times the reduced rope added a state's shapes to its basis (default: none).
  virtual long reducedBasisAdditions() const { return 0; }
  /// A hand-back tryTakeOver accepted that the reduced rope cannot vouch for beyond the present
  /// (default: none): it is speculative (header).
  virtual bool handBackIsSpeculative(const CoupledState& /*full*/) const { return false; }
  /// A hand-back that is not speculative but guarded (default: none): its checkpoint is kept as
  /// a speculative one's, and where the run hands over within speculation_window of it for a
  /// slack episode, a failed step or (guardTakesBackAtTheIndicator) the error indicator, the
  /// hand-back is taken back; any other hand-over (a fast hoist, the ground) keeps it. A reduced
  /// rope guards what it carries after a snatch, whose next slack episode would amplify the
  /// basis's small drift, and whose drift the indicator finds (header).
  virtual bool handBackGuarded() const { return false; }
  /// A guarded hand-back is taken back for the error indicator too (default: no).
  virtual bool guardTakesBackAtTheIndicator() const { return false; }
  /// Checked after every carried reduced step: the rope is slack and full order takes over.
  /// Default: the top tension under slack_tension_fraction of W or, every strain_check_steps
  /// steps, a point's strain under slack_strain_fraction of the end mass's static strain.
  virtual bool slackened() const;
  /// The reduced rope carries the ground's contact itself: a landed load and its lift-off stay
  /// reduced (a touchdown from the air still hands over). Default no: the run hands over
  /// within kGroundMargin of the ground and hands back 2 kGroundMargin clear.
  virtual bool carriesGround() const { return false; }
  /// Checked after every reduced step: the basis no longer carries the state (default: never).
  virtual bool errorTooLarge(long /*steps*/) { return false; }
  /// Subdomains of the run (the subdomain reduction's own count; 0 for every other reduced
  /// rope: the count is that reduction's output alone) and the wall time in its mode updates [s].
  virtual int reducedSubdomains() const { return 0; }
  virtual double reducedModeUpdateSeconds() const { return 0.0; }

  /// Hand the state `full` over to full order, for cause c; a quiet hand-over (a start outside
  /// the basis) tries the hand-back from quiet_hand_back_dwell on.
  void handOver(const CoupledState& full, Cause c, bool quiet = false);
  /// The hand-back trial (taut rope, then tryTakeOver).
  bool tryHandBack();
  /// A point (the payload's) lies within kGroundMargin of the ground; false without a ground.
  bool withinGroundMargin(const Eigen::Vector3d& point) const {
    return full_.ground() && full_.ground()->clearance(point) < kGroundMargin;
  }
  /// A load resting on the ground (pressed into it), off the rope top's vertical by more than
  /// kUnloadedOffsetFraction of the hanging length, whose rope, loaded since it came to rest
  /// there, has unloaded (kRopeLoadedFraction, kRestingLoadFraction): the jib's rebound after
  /// a drag, a pay-out onto a stalled off-centre lift. The rope sags and rings as it unloads,
  /// where the error indicator is blind. False without a ground; a landed start's rope, never
  /// loaded, is not.
  bool restingRopeUnloaded(const Eigen::Vector3d& end);
  /// A load resting on the ground (pressed into it) under a rope whose end carries under
  /// kRestingLoadFraction of the end mass's weight (the error indicator's floor), whose top the
  /// trolley or the slew moved by more than kDragTolerance since it came to rest so. False
  /// without a ground; a hoist alone, or the structure ringing, drags nothing.
  bool restingRopeDragged(const Eigen::Vector3d& end);
  /// The payload point presses into the ground (clearance below zero); false without a ground.
  bool pressedIntoGround(const Eigen::Vector3d& end) const;
  /// The reduced rope's top tension less its hanging rope's weight: what its end carries [N].
  double reducedEndTension() const;
  /// The end mass's weight m_end g [N] (the scale of the hand-over's tension tests).
  double endWeight() const;
  /// Continue the mechanism's state (clock, counters, schedule) of another run of this kind
  /// (a speculation of the other run is kept: its checkpoint stays with it).
  void continueHandOverFrom(const HandOverSimulation& other);
  /// A measured wind for the full model, kept for a replay while speculating.
  void setFullModelWind(const Eigen::Vector3d& velocity);
  /// Keep the speculative hand-back (if any): drop its checkpoint and inputs.
  void keepHandBack();

  CraneSimulation full_;
  HandOverSettings settings_;
  double weight_ = 0.0;      ///< hanging weight (m_end + mu L) g [N]
  double end_strain_ = 0.0;  ///< static axial strain under the end mass alone
  bool full_order_ = false;
  long steps_ = 0;  ///< reduced steps begun

 private:
  long full_order_steps_ = 0;
  std::array<long, static_cast<int>(Cause::ground) + 1> hand_overs_{};  ///< per Cause
  double full_since_ = 0.0;      ///< time of the last hand-over [s]
  double dwell_ = 0.0;           ///< its dwell before the first hand-back trial [s]
  bool clear_of_ground_ = true;  ///< the reduced payload was kGroundMargin clear at its last step
  bool loaded_on_ground_ =
      false;  ///< the resting load's rope has been loaded (restingRopeUnloaded)
  /// Where the drives held the rope's top (x, y) when the resting load's rope was first seen
  /// unloaded from a reduced step on (restingRopeDragged); none while it is loaded or in the air.
  std::optional<Eigen::Vector2d> unloaded_top_;
  int hand_back_interval_ = 0, hand_back_countdown_ = 0;

  // The hand-over for cause c at the end of a reduced step (its state `handOverState(c)`), or
  // the speculative hand-back taken back where one is open.
  void handOverOrTakeBack(Cause c);
  // An open speculation is taken back for a hand-over for cause c (header).
  bool takesBack(Cause c) const;
  // The full-order bookkeeping of a hand-over at the present (schedule, counters).
  void enterFullOrder(Cause c, bool quiet);
  // Re-integrate full order from the checkpoint over the speculative steps (header).
  void takeBack(Cause c);
  /// An operator's command or a measured wind given after `step` speculative steps.
  struct LoggedInput {
    long step = 0;
    std::optional<CommandEntry> command;
    std::optional<Eigen::Vector3d> wind;
  };
  std::unique_ptr<CraneSimulation> checkpoint_;  ///< full order at the speculative hand-back
  bool speculating_ = false;
  bool rings_towards_slack_ = false;  ///< the speculation is handBackIsSpeculative's
  long speculative_steps_ = 0;        ///< reduced steps since the checkpoint
  std::vector<LoggedInput> inputs_;
  long taken_back_ = 0;
  ReplayObserver replay_observer_;
};

}  // namespace crane_twin
