#include "crane_twin/integrators/step_halving.hpp"

#include "crane_twin/integrators/numerical_failure.hpp"

namespace crane_twin {

namespace {
// Two steps of h / 2, each halved again where it fails, down to depth max_halvings.
bool stepHalved(CoupledState& s, double h, int depth, int max_halvings, const TryStep& try_step,
                long& halved, std::string& why) {
  const double half = 0.5 * h;
  for (int k = 0; k < 2; ++k) {
    const CoupledState start = s;
    if (try_step(s, half, why)) {
      ++halved;
      continue;
    }
    s = start;
    if (depth >= max_halvings ||
        !stepHalved(s, half, depth + 1, max_halvings, try_step, halved, why)) {
      return false;
    }
  }
  return true;
}
}  // namespace

void stepWithHalving(CoupledState& s, double h, int max_halvings, const TryStep& try_step,
                     long& halved) {
  std::string why;
  if (try_step(s, h, why)) return;
  const CoupledState start = s;
  if (!stepHalved(s, h, 1, max_halvings, try_step, halved, why)) {
    s = start;
    throw NumericalFailure(why + " (also with the step halved " + std::to_string(max_halvings) +
                           " times)");
  }
}

}  // namespace crane_twin
