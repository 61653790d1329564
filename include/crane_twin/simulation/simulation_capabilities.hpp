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
#pragma once
#include <Eigen/Dense>

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
