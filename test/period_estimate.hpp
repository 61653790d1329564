// Period of a sampled oscillation for the unit tests: the times where x crosses zero upwards,
// linearly interpolated between samples, and their mean spacing.
#pragma once

#include <cstddef>
#include <vector>

namespace crane_twin_test {

inline std::vector<double> upCrossings(const std::vector<double>& t, const std::vector<double>& x) {
  std::vector<double> c;
  for (std::size_t k = 1; k < x.size(); ++k)
    if (x[k - 1] < 0.0 && x[k] >= 0.0)
      c.push_back(t[k - 1] + (t[k] - t[k - 1]) * -x[k - 1] / (x[k] - x[k - 1]));
  return c;
}

}  // namespace crane_twin_test
