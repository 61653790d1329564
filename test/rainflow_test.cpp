// Rainflow counting and Miner's sum (include/crane_twin/analysis/rainflow.hpp): the ASTM
// E1049-85 example, two more sequences counted by hand, constant-amplitude closed forms.
#include "crane_twin/analysis/rainflow.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

namespace crane_twin {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Counts summed per range.
std::map<double, double> byRange(const std::vector<RainflowCycle>& cycles) {
  std::map<double, double> m;
  for (const RainflowCycle& c : cycles) m[c.range] += c.count;
  return m;
}

TEST(Rainflow, TheStandardsExampleGivesItsTable) {
  // ASTM E1049-85, the rainflow example: -2, 1, -3, 5, -1, 3, -4, 4, -2.
  const std::vector<RainflowCycle> c = rainflowCount({-2, 1, -3, 5, -1, 3, -4, 4, -2});
  const std::map<double, double> expected = {{3, 0.5}, {4, 1.5}, {6, 0.5}, {8, 1.0}, {9, 0.5}};
  EXPECT_EQ(byRange(c), expected);
  // The one closed cycle: -1 to 3, mean 1, closed when -4 arrives.
  ASSERT_FALSE(c.empty());
  EXPECT_EQ(c.front().range, 4.0);
  EXPECT_EQ(c.front().mean, 1.0);
  EXPECT_EQ(c.front().count, 1.0);
}

TEST(Rainflow, NestedCyclesInsideALargeExcursion) {
  // 0, 10, 2, 8, 4, 6, 0: 4-6 closes inside 2-8, which closes inside 0-10-0 (by hand: ranges
  // 2 and 6 full, mean 5 both; the residue 0, 10, 0 two half cycles of 10).
  const std::vector<RainflowCycle> c = rainflowCount({0, 10, 2, 8, 4, 6, 0});
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0].range, 2.0);
  EXPECT_EQ(c[0].mean, 5.0);
  EXPECT_EQ(c[0].count, 1.0);
  EXPECT_EQ(c[1].range, 6.0);
  EXPECT_EQ(c[1].mean, 5.0);
  EXPECT_EQ(c[1].count, 1.0);
  EXPECT_EQ(c[2].range, 10.0);
  EXPECT_EQ(c[2].count, 0.5);
  EXPECT_EQ(c[3].range, 10.0);
  EXPECT_EQ(c[3].count, 0.5);
}

TEST(Rainflow, TurningPointsDropPlateausAndMonotoneRuns) {
  EXPECT_EQ(turningPoints({1, 2, 3, 3, 2, 2, 5, 7}), (std::vector<double>{1, 3, 2, 7}));
  // A ramp is one half cycle; a constant none.
  const std::vector<RainflowCycle> ramp = rainflowCount({0, 1, 2, 3, 4});
  ASSERT_EQ(ramp.size(), 1u);
  EXPECT_EQ(ramp[0].range, 4.0);
  EXPECT_EQ(ramp[0].mean, 2.0);
  EXPECT_EQ(ramp[0].count, 0.5);
  EXPECT_TRUE(rainflowCount({3, 3, 3}).empty());
  EXPECT_TRUE(rainflowCount({}).empty());
  EXPECT_THROW(rainflowCount({0, std::nan(""), 1}), std::invalid_argument);
}

TEST(Rainflow, ConstantAmplitudeSineDamageIsTheClosedForm) {
  // N periods of A sin, 20 samples each, from 0 to 0: turning points 0, A, -A, ..., A, -A, 0.
  // N - 1 closed cycles of range 2A, and the residue 0, A, -A, 0: half cycles A, 2A, A. On
  // the S-N curve N_f(ds) = 2e6 (ds_c / (gamma ds))^3:
  //   D = (N - 1 + 0.5) / N_f(2A) + 2 x 0.5 / N_f(A).
  const double A = 40e6;  // [Pa]
  const int periods = 1000;
  std::vector<double> period;  // one period's samples, repeated exactly
  for (int k = 0; k < 20; ++k) period.push_back(A * std::sin(2.0 * kPi * k / 20.0));
  std::vector<double> h;
  for (int k = 0; k <= 20 * periods; ++k) h.push_back(period[k % 20]);
  const std::vector<RainflowCycle> c = rainflowCount(h);
  const std::map<double, double> counts = byRange(c);
  ASSERT_EQ(counts.size(), 2u);
  EXPECT_NEAR(counts.begin()->first, A, 1e-6);
  EXPECT_EQ(counts.begin()->second, 1.0);
  EXPECT_NEAR(counts.rbegin()->first, 2.0 * A, 1e-6);
  EXPECT_EQ(counts.rbegin()->second, periods - 1 + 0.5);
  for (double gamma : {1.0, 1.25}) {
    const SnCurve curve{71.0, gamma};
    auto nf = [&](double ds_mpa) { return 2e6 * std::pow(71.0 / (gamma * ds_mpa), 3); };
    const double closed = (periods - 0.5) / nf(80.0) + 1.0 / nf(40.0);
    EXPECT_NEAR(minerDamage(c, curve), closed, 1e-9 * closed) << gamma;
  }
  // One cycle at the category's range on gamma 1 is 1 / 2e6 of the life.
  EXPECT_NEAR(minerDamage({{71e6, 0.0, 1.0}}, SnCurve{71.0, 1.0}), 5e-7, 1e-21);
}

TEST(Rainflow, BadCurvesAreRefused) {
  EXPECT_THROW(minerDamage({}, SnCurve{0.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(minerDamage({}, SnCurve{71.0, 0.9}), std::invalid_argument);
  EXPECT_THROW(minerDamage({}, SnCurve{std::nan(""), 1.0}), std::invalid_argument);
  EXPECT_EQ(SnCurve({71.0, 1.0}).cyclesToFailure(0.0), INFINITY);
}

}  // namespace
}  // namespace crane_twin
