#include "crane_twin/analysis/crane_classification.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace crane_twin {

std::string utilisationClass(double cycles) {
  if (!(std::isfinite(cycles) && cycles >= 0.0)) {
    throw std::invalid_argument("class U: the number of working cycles must be >= 0, got " +
                                std::to_string(cycles));
  }
  // ISO 4301-1:2016 Table 1, the upper bound of U0 .. U9.
  static constexpr std::array<double, 10> kUpper = {1.6e4, 3.15e4, 6.3e4, 1.25e5, 2.5e5,
                                                    5e5,   1e6,    2e6,   4e6,    8e6};
  for (std::size_t i = 0; i < kUpper.size(); ++i) {
    if (cycles <= kUpper[i]) return "U" + std::to_string(i);
  }
  return "above_U9";
}

std::string loadSpectrumClass(double k_q) {
  if (!(std::isfinite(k_q) && k_q >= 0.0)) {
    throw std::invalid_argument("class Q: the load spectrum factor must be >= 0, got " +
                                std::to_string(k_q));
  }
  // ISO 4301-1:2016 Table 2, the upper bound of Q0 .. Q5.
  static constexpr std::array<double, 6> kUpper = {0.0313, 0.0625, 0.125, 0.25, 0.5, 1.0};
  for (std::size_t i = 0; i < kUpper.size(); ++i) {
    if (k_q <= kUpper[i]) return "Q" + std::to_string(i);
  }
  return "above_Q5";
}

}  // namespace crane_twin
