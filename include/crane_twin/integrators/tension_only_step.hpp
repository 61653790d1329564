// The step of a tension-only rope (docs/model.md "Energy-consistent step"), one rule for the
// full-order and the reduced rope (FullOrderSolver, InvariantReducedSolver):
//  - outside a switching episode, a generalized-alpha step stands where the rope is taut at both
//    of its ends (the trapezoid work error of the axial law at the switching points is exactly
//    0), or where that error is within `tolerance` (not asked of a hoisting step, whose uniform
//    rescaling shifts every strain before it) and the run's created energy stays within it;
//  - any other step is taken energy-consistently (the discrete gradient in a scheme whose
//    energy can only fall, energyConsistentScheme); the episode goes on while such a step still
//    switches, hoisting or not, and generalized-alpha resumes from consistent accelerations once it
//    does not (a restart after every switching step of a hoisting run raised the energy at each,
//    which the hoist's pull on a bouncing rope fed: docs/model.md "Energy-consistent step").
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <string>

#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/integrators/generalized_alpha.hpp"

namespace crane_twin {

/// The rule's tolerance [-]: the switch error and created energy a generalized-alpha step may
/// carry, as a fraction of the hanging weight times the rope length (tensionOnlySwitchTolerance).
constexpr double kSwitchTolerance = 1e-10;

/// kSwitchTolerance times the hanging weight under standard gravity (so that g = 0 has one
/// too), hanging_mass [kg] the end mass plus the rope's, times the rope length [m]: [J].
inline double tensionOnlySwitchTolerance(double hanging_mass, double length) {
  const double weight = 9.80665 * hanging_mass;
  return kSwitchTolerance * weight * length;
}

/// What a rope's solver provides to the rule (states in its own coordinates).
struct TensionOnlyRope {
  /// One step of size h; false (s at the step's start, the reason in why) where Newton fails.
  std::function<bool(CoupledState& s, double h, std::string& why)> generalized_alpha_step;
  std::function<bool(CoupledState& s, double h, std::string& why)> energy_consistent_step;
  /// Trapezoid work error of the axial law over q0 -> q1 [J] (0 for a rope taut at both ends).
  std::function<double(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1)> switch_work_error;
  /// Energy a step start -> end adds to the rope beyond the top force's and the damper's [J].
  std::function<double(const CoupledState& start, const CoupledState& end)> energy_created;
  /// Consistent accelerations of a state (generalized-alpha's restart).
  std::function<void(CoupledState& s)> restart_accelerations;
};

/// The rule's memory over a run.
struct TensionOnlySwitching {
  bool switching = false;       ///< the last step was energy-consistent and switched
  double energy_created = 0.0;  ///< created by the accepted generalized-alpha steps [J]
  long energy_consistent_steps = 0;
  /// Workspace: the step's start, its storage reused from step to step (no allocation once
  /// sized; scratch between steps).
  CoupledState start;
};

/// One step of size h by the rule above. `tolerance` [J]: the switch error and created energy
/// a generalized-alpha step may carry. False, s at the step's start, where the step fails.
bool tensionOnlyStep(const TensionOnlyRope& rope, double tolerance, bool hoisting,
                     TensionOnlySwitching& memory, CoupledState& s, double h, std::string& why);

/// The energy-consistent step's decay rate kappa [1/s]: theta = kappa h (energyConsistentScheme;
/// 200 and 400 were no faster on the falling rope and further from its eighth step,
/// docs/accuracy-vs-time.md "Attempts").
constexpr double kEnergyDecayRate = 100.0;

/// The energy-consistent step's scheme (docs/model.md "Energy-consistent step"):
///   M (v1 - v0) / h = F - Qbar(q0, q1) - C_q^T lambda,
///   q1 - q0 = h ((1/2 + theta) v1 + (1/2 - theta) v0),   theta = kEnergyDecayRate h,
/// written as Newmark's gamma = 1, beta = 1/2 + theta from a start with q''_0 = a_0 = 0
/// (startEnergyConsistentStep), whose q''_1 is the step's mean acceleration (v1 - v0) / h; the
/// step's completion (newtonStep, alpha_m = alpha_f = 0) leaves a = q'' and za = z'', and lambda
/// is the step's mean constraint force (the reported tension).
/// With Qbar a discrete gradient, the energy changes by exactly -theta (v1 - v0)^T M (v1 - v0)
/// (and the support's likewise) beyond the dampers' dissipation: it never rises, and the velocity
/// jumps of the axial waves the step does not resolve decay, at second order in h.
GeneralizedAlpha energyConsistentScheme(double h);

/// The scheme's start: the acceleration-like variables set to 0 (its predictor q0 + h v0).
void startEnergyConsistentStep(CoupledState& s);

}  // namespace crane_twin
