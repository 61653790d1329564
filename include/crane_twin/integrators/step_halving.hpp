// Step-size control of the full-order, reduced and pendulum solvers: a step whose Newton
// iteration fails is retried as two half steps, each halved again where it fails.
#pragma once

#include <functional>
#include <string>

#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/rope/rope_support.hpp"

namespace crane_twin {

/// `try_step(s, h, why)` takes one step of size h from s; where Newton fails it leaves s at the
/// step's start, puts the reason in `why` and returns false.
using TryStep = std::function<bool(CoupledState&, double, std::string&)>;

/// One step of size h; a failed step is retried as two half steps, recursively down to
/// h / 2^max_halvings (the acceleration-like variable a carries over between step sizes,
/// Arnold & Bruls 2007, and 2^k half steps end exactly at t + h). Each half step holds the rope's
/// top at the drives' pose of its own end time, the fraction of the step it ends at
/// (RopeSupport::setStepFraction); the step's end pose is set again when the step returns or
/// throws. Counts the half steps taken in `halved`. Throws NumericalFailure naming the time and
/// the reason; s is then left at the step's start.
void stepWithHalving(CoupledState& s, double h, int max_halvings, RopeSupport& support,
                     const TryStep& try_step, long& halved);

}  // namespace crane_twin
