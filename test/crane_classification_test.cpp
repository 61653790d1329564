// Classes U and Q (include/crane_twin/analysis/crane_classification.hpp) at and beside each
// bound of ISO 4301-1:2016 Tables 1 and 2 (docs/fatigue.md "Classes").
#include "crane_twin/analysis/crane_classification.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace crane_twin {
namespace {

TEST(CraneClassification, EachUBoundBelongsToItsClass) {
  const std::vector<double> upper = {1.6e4, 3.15e4, 6.3e4, 1.25e5, 2.5e5, 5e5, 1e6, 2e6, 4e6, 8e6};
  EXPECT_EQ(utilisationClass(0.0), "U0");
  for (std::size_t i = 0; i < upper.size(); ++i) {
    EXPECT_EQ(utilisationClass(upper[i]), "U" + std::to_string(i));
    const std::string next = i + 1 < upper.size() ? "U" + std::to_string(i + 1) : "above_U9";
    EXPECT_EQ(utilisationClass(upper[i] + 1.0), next);
  }
}

TEST(CraneClassification, EachQBoundBelongsToItsClass) {
  const std::vector<double> upper = {0.0313, 0.0625, 0.125, 0.25, 0.5, 1.0};
  EXPECT_EQ(loadSpectrumClass(0.0), "Q0");
  for (std::size_t i = 0; i < upper.size(); ++i) {
    EXPECT_EQ(loadSpectrumClass(upper[i]), "Q" + std::to_string(i));
    const std::string next = i + 1 < upper.size() ? "Q" + std::to_string(i + 1) : "above_Q5";
    EXPECT_EQ(loadSpectrumClass(upper[i] * (1.0 + 1e-9)), next);
  }
  // Every lift at max_load: k_Q = 1, the heaviest class; a spectrum of m_i = m_max / 2: 1/8.
  EXPECT_EQ(loadSpectrumClass(std::pow(1.0, 3)), "Q5");
  EXPECT_EQ(loadSpectrumClass(std::pow(0.5, 3)), "Q2");
}

TEST(CraneClassification, ImpossibleCountsAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double x : {-1.0, nan, inf}) {
    EXPECT_THROW(utilisationClass(x), std::invalid_argument) << x;
    EXPECT_THROW(loadSpectrumClass(x), std::invalid_argument) << x;
  }
}

}  // namespace
}  // namespace crane_twin
