// The static equilibrium of a rope hanging between two held points (docs/scenes.md "Initial
// state", initial.mode: landed): its top node and its end (the hook node; with a rigging the
// payload point, the hook block then free) stay where the guess puts them; every other
// coordinate settles under the chain's weight. It minimises the potential energy over the free
// coordinates f,
//   Pi(q) = U(q) - F_g^T q,      grad_f Pi = Q_f(q) - F_g,f = 0,
// by Newton on K_t,ff dq_f = F_g,f - Q_f(q) with a backtracking line search on Pi (a rope whose
// lower end carries almost no tension starts nearly without lateral stiffness there).
#pragma once

#include <Eigen/Dense>

#include "crane_twin/rope/ancf_rope.hpp"

namespace crane_twin {

struct HeldRopeSettings {
  double position_tolerance = 1e-10;  ///< [m] on max |dq_f|
  int max_iterations = 100;
};

/// Settle q (the rope's coordinates, a guess with both ends where they are held) into the
/// equilibrium above. Returns the Newton iterations taken (0: q was in equilibrium to the
/// tolerance); throws NumericalFailure, q unchanged, where it does not converge.
int settleBetweenHeldEnds(const AncfRope& rope, Eigen::VectorXd& q,
                          const HeldRopeSettings& settings = HeldRopeSettings());

}  // namespace crane_twin
