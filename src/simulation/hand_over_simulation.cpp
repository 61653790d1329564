#include "crane_twin/simulation/hand_over_simulation.hpp"

#include <algorithm>
#include <cmath>

namespace crane_twin {

HandOverSimulation::HandOverSimulation(const CraneModel& model, const HandOverSettings& settings)
    : full_(model), settings_(settings) {}

void HandOverSimulation::initialize() {
  const CraneModel& m = full_.model();
  weight_ = (m.end_mass + m.ropeMass()) * m.scene.gravity;
  end_strain_ = m.end_mass * m.scene.gravity / m.rope.axialStiffnessAt(m.scene.rope.length);
  full_order_ = false;
  steps_ = full_order_steps_ = taken_back_ = 0;
  keepHandBack();
  clear_of_ground_ = true;
  loaded_on_ground_ = false;
  unloaded_top_.reset();
  std::fill(hand_overs_.begin(), hand_overs_.end(), 0);
  const CoupledState f = full_.initialState();  // the rope at the scene's length
  full_.setState(f);
  // A start the reduced rope cannot carry (a velocity given to a rigging's payload alone, a
  // release that will slacken) runs at full order until the hand-back criteria hold.
  const Start start = startReduced(f);
  if (start != Start::reduced) handOver(f, Cause::start, start == Start::outside_basis);
}

HandOverSimulation::Start HandOverSimulation::startReduced(const CoupledState&) {
  return tryHandBack() ? Start::reduced : Start::outside_basis;
}

void HandOverSimulation::handOver(const CoupledState& full, Cause c, bool quiet) {
  keepHandBack();
  if (restartsAtHandOver()) {
    full_.restartFrom(full);
  } else {
    full_.setState(full);
  }
  enterFullOrder(c, quiet);
}

void HandOverSimulation::enterFullOrder(Cause c, bool quiet) {
  full_since_ = full_.time();
  dwell_ = quiet ? std::min(settings_.quiet_hand_back_dwell, settings_.hand_back_dwell)
                 : settings_.hand_back_dwell;
  hand_back_interval_ = hand_back_countdown_ = settings_.hand_back_steps;
  full_order_ = true;
  ++hand_overs_[static_cast<int>(c)];
}

void HandOverSimulation::handOverOrTakeBack(Cause c) {
  if (takesBack(c)) return takeBack(c);
  handOver(handOverState(c), c);
}

bool HandOverSimulation::takesBack(Cause c) const {
  return speculating_ && (rings_towards_slack_ || c == Cause::slack || c == Cause::failure ||
                          (c == Cause::indicator && guardTakesBackAtTheIndicator()));
}

void HandOverSimulation::takeBack(Cause c) {
  // Full order from the checkpoint over the speculative steps, each input given where it was
  // given (before the step after `step` speculative steps), to the reduced run's present.
  // The run reads full order's state from here on, also for the observer (SpeculativeRun).
  full_.continueFrom(*checkpoint_);
  full_order_ = true;
  if (replay_observer_) replay_observer_(0);
  std::size_t next = 0;
  for (long k = 0; k < speculative_steps_; ++k) {
    for (; next < inputs_.size() && inputs_[next].step == k; ++next) {
      if (inputs_[next].command) full_.setCommand(*inputs_[next].command);
      if (inputs_[next].wind) full_.setMeasuredWind(*inputs_[next].wind);
    }
    full_.step();
    ++full_order_steps_;
    if (replay_observer_ && k + 1 < speculative_steps_) replay_observer_(k + 1);
  }
  keepHandBack();  // (the checkpoint and inputs are spent)
  ++taken_back_;
  enterFullOrder(c, false);
}

void HandOverSimulation::keepHandBack() {
  speculating_ = false;
  inputs_.clear();
}

void HandOverSimulation::setCommand(const CommandEntry& command) {
  if (speculating_) inputs_.push_back({speculative_steps_, command, std::nullopt});
  full_.setCommand(command);
}

void HandOverSimulation::setFullModelWind(const Eigen::Vector3d& velocity) {
  if (speculating_) inputs_.push_back({speculative_steps_, std::nullopt, velocity});
  full_.setMeasuredWind(velocity);
}

bool HandOverSimulation::tryHandBack() {
  const CoupledState& f = full_.state();
  if (weight_ > 0.0) {
    if (full_.solver().topTension(f) < settings_.taut_tension_fraction * weight_) return false;
    // (less the tension-only law's slack band and a strain's round-off: a stress-free rope sits
    // at the band's edge, AncfRope::straight, and |r_x| - 1 there reads -kSlackBand to a few
    // ulps either side)
    if (AncfRope::minNodalStrain(f.q) <
        settings_.taut_strain_fraction * end_strain_ - kSlackBand - kStrainRoundOff)
      return false;
  }
  double clearance = 0.0;
  if (full_.ground()) {
    clearance = full_.ground()->clearance(
        f.q.segment<3>(full_.rope().positionIndex(full_.rope().nodes() - 1)));
    if (!carriesGround() && clearance < 2.0 * kGroundMargin) return false;
  }
  // (Asked before tryTakeOver, which takes the state over.)
  const bool speculative = handBackIsSpeculative(f);
  if (!tryTakeOver(f)) return false;
  if (speculative || handBackGuarded()) {
    // The checkpoint: full order's state, drives and stepping at the hand-back (header).
    if (!checkpoint_) checkpoint_ = std::make_unique<CraneSimulation>(full_.model());
    checkpoint_->continueFrom(full_);
    speculating_ = true;  // (inputs_ is empty: every speculation's end clears it)
    rings_towards_slack_ = speculative;
    speculative_steps_ = 0;
  }
  full_order_ = false;
  clear_of_ground_ = clearance >= kGroundMargin;
  loaded_on_ground_ = false;
  unloaded_top_.reset();
  return true;
}

void HandOverSimulation::step() {
  if (full_order_) {
    full_.step();
    ++full_order_steps_;
    // Trials every hand_back_steps steps after the dwell, the interval doubling after each
    // refused trial once hand_back_dwell has passed, up to max_hand_back_interval (a scene that
    // stays violent costs little; a quiet one is tried often while its waves die out).
    const double since = full_.time() - full_since_;
    if (since >= dwell_ && --hand_back_countdown_ <= 0) {
      if (!tryHandBack()) {
        if (since >= settings_.hand_back_dwell) {
          hand_back_interval_ = std::min(2 * hand_back_interval_, settings_.max_hand_back_interval);
        }
        hand_back_countdown_ = hand_back_interval_;
      }
    }
    return;
  }
  // A speculation survived its window: the hand-back is kept.
  const double h = full_.model().scene.time_step;
  if (speculating_ && speculative_steps_ * h >= settings_.speculation_window - 0.5 * h) {
    keepHandBack();
  }
  full_.advanceDrives(reducedTime(), h, reducedSupport());
  ++steps_;
  if (speculating_) ++speculative_steps_;
  const Verdict verdict = reducedStep();
  if (verdict != Verdict::carried) {
    const Cause c = verdict == Verdict::failed ? Cause::failure : Cause::fast_hoist;
    if (takesBack(c)) return takeBack(c);  // (the replay takes this step too)
    // The reduced state is at the step's start: the full model takes the step.
    handOver(handOverState(c), c);
    full_.stepAfterDrives();
    ++full_order_steps_;
    return;
  }
  if (slackened()) return handOverOrTakeBack(Cause::slack);
  if (full_.ground()) {
    // A touchdown from the air goes to full order (a landing load sliding or tipping its rope
    // rings in shapes the basis does not hold); a rope that carries the ground stays reduced on
    // a landed load and through its lift-off.
    const Eigen::Vector3d end = reducedNode(full_.ropeNodes() - 1);
    const bool clear = !withinGroundMargin(end);
    const bool touchdown = !clear && (clear_of_ground_ || !carriesGround());
    clear_of_ground_ = clear;
    if (touchdown || (carriesGround() && (restingRopeUnloaded(end) || restingRopeDragged(end)))) {
      return handOverOrTakeBack(Cause::ground);
    }
  }
  if (errorTooLarge(steps_)) handOverOrTakeBack(Cause::indicator);
}

bool HandOverSimulation::pressedIntoGround(const Eigen::Vector3d& end) const {
  return full_.ground() && full_.ground()->clearance(end) < 0.0;
}

double HandOverSimulation::reducedEndTension() const {
  // The end's share of the top tension: what the hanging rope's weight leaves of it.
  const CraneModel& m = full_.model();
  return reducedTopTension() - m.rope.mass_per_length * reducedLength() * m.scene.gravity;
}

double HandOverSimulation::endWeight() const {
  return full_.model().end_mass * full_.model().scene.gravity;
}

bool HandOverSimulation::restingRopeUnloaded(const Eigen::Vector3d& end) {
  if (!pressedIntoGround(end)) {
    loaded_on_ground_ = false;  // in the air (a lift-off): a landing is a touchdown
    return false;
  }
  const double end_tension = reducedEndTension();
  if (end_tension >= kRopeLoadedFraction * endWeight()) {
    loaded_on_ground_ = true;
    return false;
  }
  if (!loaded_on_ground_ ||
      end_tension >= SupportedRopeSimulation::kRestingLoadFraction * endWeight()) {
    return false;
  }
  loaded_on_ground_ = false;
  const Eigen::Vector3d top = reducedNode(0);
  return (end - top).head<2>().norm() > kUnloadedOffsetFraction * reducedLength();
}

bool HandOverSimulation::restingRopeDragged(const Eigen::Vector3d& end) {
  if (!pressedIntoGround(end) ||
      reducedEndTension() >= SupportedRopeSimulation::kRestingLoadFraction * endWeight()) {
    unloaded_top_.reset();
    return false;
  }
  // The top where the drives put it, r (cos theta, sin theta): the structure's ringing under a
  // set-down (the shipped one's trolley point swings 16 cm) moves it and drags nothing.
  const CraneDrives& d = full_.drives();
  const Eigen::Vector2d top =
      d.trolleyRadius() * Eigen::Vector2d(std::cos(d.slewAngle()), std::sin(d.slewAngle()));
  if (!unloaded_top_) unloaded_top_ = top;
  return (top - *unloaded_top_).norm() > kDragTolerance;
}

bool HandOverSimulation::slackened() const {
  return weight_ > 0.0 && (reducedTopTension() < settings_.slack_tension_fraction * weight_ ||
                           (steps_ % settings_.strain_check_steps == 0 &&
                            reducedMinStrain() < settings_.slack_strain_fraction * end_strain_));
}

SeriesValues HandOverSimulation::series() const {
  SeriesValues v = full_order_ ? full_.series() : reducedSeries();
  v.subdomains = reducedSubdomains();
  v.full_order_steps = full_order_steps_;
  return v;
}

void HandOverSimulation::sample(Eigen::Vector3d& payload, Eigen::Vector3d& cab,
                                Eigen::Vector3d& jib_tip) const {
  if (full_order_) return full_.sample(payload, cab, jib_tip);
  payload = reducedNode(full_.ropeNodes() - 1);
  cab = full_.support().cabDisplacement(reducedSupport());
  jib_tip = full_.support().jibTipDisplacement(reducedSupport());
}

std::vector<Eigen::Vector3d> HandOverSimulation::ropeCurve(int per_element) const {
  return full_.rope().sampleCurve(fullState().q, per_element,
                                  ropeLength() / full_.rope().elements());
}

RunStatistics HandOverSimulation::statistics() const {
  const RunStatistics f = full_.statistics();
  RunStatistics r;
  r.subdomains = reducedSubdomains();
  r.mode_update_seconds = reducedModeUpdateSeconds();
  r.halved_steps = reducedHalvedSteps() + f.halved_steps;
  r.energy_consistent_steps = reducedEnergyConsistentSteps() + f.energy_consistent_steps;
  r.hand_overs = handOvers();
  r.hand_backs_taken_back = taken_back_;
  r.full_order_steps = full_order_steps_;
  r.integrating_full_order = full_order_;
  r.basis_additions = reducedBasisAdditions();
  return r;
}

long HandOverSimulation::handOvers() const {
  long n = 0;
  for (long k : hand_overs_) n += k;
  return n;
}

void HandOverSimulation::continueHandOverFrom(const HandOverSimulation& o) {
  weight_ = o.weight_;
  end_strain_ = o.end_strain_;
  full_order_ = o.full_order_;
  steps_ = o.steps_;
  full_since_ = o.full_since_;
  dwell_ = o.dwell_;
  hand_back_interval_ = o.hand_back_interval_;
  hand_back_countdown_ = o.hand_back_countdown_;
  clear_of_ground_ = o.clear_of_ground_;
  loaded_on_ground_ = o.loaded_on_ground_;
  unloaded_top_ = o.unloaded_top_;
  taken_back_ = o.taken_back_;
  // (The other run's checkpoint is its own: this run keeps the state it continues.)
  keepHandBack();
}

}  // namespace crane_twin
