#include "crane_twin/integrators/step_halving.hpp"

#include "crane_twin/integrators/numerical_failure.hpp"

namespace crane_twin {

namespace {

// The step's end pose again when the step closes, also where it throws.
class EndPoseOnExit {
 public:
  explicit EndPoseOnExit(RopeSupport& support) : support_(support) {}
  ~EndPoseOnExit() { support_.setStepFraction(1.0); }
  EndPoseOnExit(const EndPoseOnExit&) = delete;
  EndPoseOnExit& operator=(const EndPoseOnExit&) = delete;

 private:
  RopeSupport& support_;
};

// Two steps of h / 2 over the fractions [f0, f0 + width] of the whole step, each halved again
// where it fails, down to depth max_halvings. (The fractions are sums of powers of 2: exact.)
bool stepHalved(CoupledState& s, double h, double f0, double width, int depth, int max_halvings,
                RopeSupport& support, const TryStep& try_step, long& halved, std::string& why) {
  const double half = 0.5 * h, half_width = 0.5 * width;
  for (int k = 0; k < 2; ++k) {
    const double from = f0 + k * half_width;
    const CoupledState start = s;
    support.setStepFraction(from + half_width);
    if (try_step(s, half, why)) {
      ++halved;
      continue;
    }
    s = start;
    if (depth >= max_halvings || !stepHalved(s, half, from, half_width, depth + 1, max_halvings,
                                             support, try_step, halved, why)) {
      return false;
    }
  }
  return true;
}

}  // namespace

void stepWithHalving(CoupledState& s, double h, int max_halvings, RopeSupport& support,
                     const TryStep& try_step, long& halved) {
  std::string why;
  if (try_step(s, h, why)) return;
  const EndPoseOnExit end_pose(support);
  const CoupledState start = s;
  if (!stepHalved(s, h, 0.0, 1.0, 1, max_halvings, support, try_step, halved, why)) {
    s = start;
    throw NumericalFailure(why + " (also with the step halved " + std::to_string(max_halvings) +
                           " times)");
  }
}

}  // namespace crane_twin
