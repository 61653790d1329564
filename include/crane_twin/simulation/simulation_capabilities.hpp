// What some rope models can do beyond the Simulation core (docs/architecture.md, "The
// concepts, one file each"). A model that can derives from the capability's interface; a caller
// asks for it by type (capabilityOf<C>(sim): nullptr where the model has none) or requires it
// (requireCapability<C>(sim): InputError naming the models that have it), at the boundary,
// instead of calling and catching a "not supported" throw.
//
//   capability            full  reduced (invariant)  reduced (subdomains)  pendulum
//   ContinuableRun         yes   yes                  no                    yes
//   CorrectableMotion      yes   yes                  no                    no
//   MeasuredWindInput      yes   yes                  no                    yes
//   SpeculativeRun         no    yes                  yes (never speculates) no
#pragma once
#include <Eigen/Dense>
#include <functional>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

/// Continue from another run's state: the forecaster's copy, a twin whose load changed.
class ContinuableRun {
 public:
  virtual ~ContinuableRun() = default;
  /// Continue from the state of another simulation of the same scene and rope model (its rope,
  /// support, drives and time), e.g. a forecast copy built with another time step: with the
  /// same step the two then run identically. Throws InputError for another model type or
  /// discretisation (docs/twin.md).
  virtual void continueFrom(const Simulation& other) = 0;
  static constexpr const char* kWhat =
      "continuing from another run's state (forecasts, a load change) needs rope.model full, "
      "pendulum or reduced (rope.reduction: invariant)";
};

/// Set the rope's and the support's motion: the twin's sway correction (docs/twin.md).
class CorrectableMotion {
 public:
  virtual ~CorrectableMotion() = default;
  /// Replace the positions and velocities of the rope and the support by s.q, s.v, s.z, s.zd
  /// (full coordinates, as Simulation::fullState() gives them; the rope's top node must stay on
  /// the support's point), keeping the drives and the time; accelerations are made consistent
  /// again. Throws std::invalid_argument for wrong sizes (Simulation::checkMotionSizes).
  virtual void setMotion(const CoupledState& s) = 0;
  static constexpr const char* kWhat =
      "setting the rope's motion (the twin's sway correction) needs rope.model full or reduced "
      "(rope.reduction: invariant)";
};

/// Take a measured wind instead of the scene's (docs/model.md "Wind"; the node's crane/wind).
class MeasuredWindInput {
 public:
  virtual ~MeasuredWindInput() = default;
  /// The wind at the jib's height [m/s, crane frame; its horizontal part] from now on. Throws
  /// std::invalid_argument for a non-finite value.
  virtual void setMeasuredWind(const Eigen::Vector3d& velocity) = 0;
  static constexpr const char* kWhat =
      "a measured wind needs rope.model full, pendulum or reduced (rope.reduction: invariant); "
      "the subdomain reduced rope takes no wind";
};

/// A run whose latest steps a later step may replace: a reduced rope's speculative hand-back
/// (docs/model.md "Hand-over to full order") is taken back where the run would hand over within
/// its window, and full order re-integrates every step since its checkpoint. A caller that writes
/// rows holds back those of an open speculation (speculating) and, where it is taken back,
/// writes the re-integrated steps' rows instead (setReplayObserver; docs/cli.md "Rows of a
/// speculation").
class SpeculativeRun {
 public:
  virtual ~SpeculativeRun() = default;
  /// A speculation is open: the state since its checkpoint may still be replaced.
  virtual bool speculating() const = 0;
  /// Speculations taken back so far.
  virtual long handBacksTakenBack() const = 0;
  /// Called within the step() that takes a speculation back: first with the run at the
  /// checkpoint's state (replayed_steps 0: the step the speculation began at, or the start), then
  /// after each re-integrated step but the last (replayed_steps 1 .. n - 1), which is the step()
  /// under way itself. The run reads full order's state throughout (series, topTension,
  /// hotSpotStresses, nodes). An empty observer: none.
  using ReplayObserver = std::function<void(long replayed_steps)>;
  virtual void setReplayObserver(ReplayObserver observer) = 0;
};

/// The capability C of `sim`, or nullptr where its model has none.
template <class C>
C* capabilityOf(Simulation& sim) {
  return dynamic_cast<C*>(&sim);
}
template <class C>
const C* capabilityOf(const Simulation& sim) {
  return dynamic_cast<const C*>(&sim);
}

/// The capability C of `sim`; InputError (C::kWhat) where its model has none.
template <class C>
C& requireCapability(Simulation& sim) {
  if (C* c = capabilityOf<C>(sim)) return *c;
  throw InputError(C::kWhat);
}

}  // namespace crane_twin
