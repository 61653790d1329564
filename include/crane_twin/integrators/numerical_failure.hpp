// The error every integrator and solver throws when the numerics fail (Newton divergence, a
// singular matrix, a non-finite state). The CLI maps it to exit status 1 (docs/cli.md).
#pragma once

#include <stdexcept>

namespace crane_twin {

/// A failure of the numerics; the message names the time and the reason.
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace crane_twin
