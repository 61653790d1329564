// Reeving (docs/model.md "Reeving"): the winch's line L_r in series with the n falls. The hook's
// axial stiffness is n EA / (L + L_r / n); checked against the spring chain's closed forms (static
// stretch, bounce period) in every rope model, and the stiffness following a hoisted length.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/rope/ancf_rope.hpp"
#include "crane_twin/rope/pendulum_rope.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "period_estimate.hpp"

using namespace crane_twin;
using crane_twin_test::upCrossings;

namespace {
// Anchored at z = 0; 2 falls of EA 2.2e7 N each, a light rope (10 g/m per fall) so the spring
// chain's Rayleigh mass correction is exact to 1e-7; 3.6 t; hanging 20 m.
constexpr double kEA = 2.2e7, kMu = 0.01, kMass = 3600.0, kL = 20.0, kG = 9.81;
constexpr int kFalls = 2;

std::string chainScene() {
  const std::string path = testing::TempDir() + "reeving_chain.yaml";
  std::ofstream(path) << "crane: none\nanchor: [0, 0, 0]\nduration: 2.0\ntime_step: 0.0002\n"
                         "integrator: {rho_inf: 1.0}\n"
                         "rope: {model: full, elements: 10, length: 20.0, falls: 2, "
                         "mass_per_length: 0.01, axial_stiffness: 2.2e7, bending: false}\n"
                         "payload: {mass: 3600.0}\ninitial: {swing_deg: 0}\n";
  return path;
}

// The chain's compliance: falls L / (n EA) in series with the line L_r / (n^2 EA).
double chainStiffness(double reeving) {
  return 1.0 / (kL / (kFalls * kEA) + reeving / (kFalls * kFalls * kEA));
}
}  // namespace

TEST(Reeving, ElementStiffnessFollowsTheHangingLengthNotTheReeving) {
  AncfRope rope(10, 30.0, 3.8, 4.4e7, 0.0, 3600.0, Eigen::Vector3d(0, 0, -9.81));
  EXPECT_DOUBLE_EQ(rope.element().axial_stiffness, 4.4e7);
  rope.setReevingLength(150.0);
  EXPECT_NEAR(rope.element().axial_stiffness, 4.4e7 * 30.0 / 180.0, 1e-6);
  rope.setLength(60.0);  // hoisting: the hanging length changes, the line does not
  EXPECT_NEAR(rope.element().axial_stiffness, 4.4e7 * 60.0 / 210.0, 1e-6);
  EXPECT_DOUBLE_EQ(rope.reevingLength(), 150.0);
  PendulumRope bar(30.0, 3.8, 4.4e7, 3600.0, Eigen::Vector3d(0, 0, -9.81));
  bar.setReevingLength(150.0);
  bar.setLength(60.0);
  EXPECT_NEAR(bar.axialStiffness(), 4.4e7 * 60.0 / 210.0, 1e-6);
  EXPECT_THROW(rope.setReevingLength(-1.0), std::invalid_argument);
  EXPECT_THROW(bar.setReevingLength(std::nan("")), std::invalid_argument);
}

TEST(Reeving, StaticStretchAndBouncePeriodAreTheSpringChainsInEveryRopeModel) {
  const double reeving = 200.0;  // a flat-top's line from the winch along the jib
  const double k = chainStiffness(reeving);
  const double m_rope = kFalls * kMu * kL;
  // Rayleigh: uniform strain along the falls, (m + m_rope / 3) on the chain's stiffness.
  const double period = 2.0 * M_PI * std::sqrt((kMass + m_rope / 3.0) / k);
  const double period_without =
      2.0 * M_PI * std::sqrt((kMass + m_rope / 3.0) / chainStiffness(0.0));
  ASSERT_GT(period / period_without, 1.5);  // the line matters: the test can tell
  for (const char* model : {"full", "pendulum", "reduced"}) {
    SCOPED_TRACE(model);
    const CraneModel cm = buildCraneModel(
        loadScene(chainScene(), {std::string("rope.model=") + model, "rope.reeving_length=200"}));
    EXPECT_DOUBLE_EQ(cm.rope.axialStiffnessAt(kL), kFalls * kEA * kL / (kL + reeving / kFalls));
    std::unique_ptr<Simulation> sim = makeSimulation(cm);
    sim->initialize();
    // At rest the hook hangs the chain's stretch below the unstretched falls: the payload's
    // weight on k, the falls' own weight (mean tension m_rope g / 2 over the falls) on k too.
    const double z0 = -kL - (kMass + m_rope / 2.0) * kG / k;
    EXPECT_NEAR(sim->series().payload.z(), z0, 1e-7);
    // A vertical kick: the bounce on the chain.
    std::unique_ptr<Simulation> kicked = makeSimulation(buildCraneModel(
        loadScene(chainScene(), {std::string("rope.model=") + model, "rope.reeving_length=200",
                                 "initial.payload_velocity=[0,0,0.05]"})));
    kicked->initialize();
    std::vector<double> t, x;
    for (int i = 0; i < 10000; ++i) {
      kicked->step();
      t.push_back(kicked->time());
      x.push_back(kicked->series().payload.z() - z0);
    }
    const auto c = upCrossings(t, x);
    ASSERT_GE(c.size(), 3u);
    const double measured = (c.back() - c.front()) / (c.size() - 1);
    std::printf("%s: bounce period %.6f s, spring chain %.6f s (without the line %.6f s)\n", model,
                measured, period, period_without);
    // The reduced rope adds its modes' truncation (measured 1.9e-4 of the period); the full and
    // pendulum ropes carry the chain exactly (the light rope's strain is uniform).
    const double tol = std::string(model) == "reduced" ? 5e-4 : 1e-5;
    EXPECT_NEAR(measured, period, tol * period);
  }
}

TEST(Reeving, TheLinesMassIsCarriedAtTheTrolleyAndBadValuesAreRefused) {
  const std::string t8036 =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";
  const CraneModel without = buildCraneModel(loadScene(t8036));
  const CraneModel with = buildCraneModel(loadScene(t8036, {"rope.reeving_length=300"}));
  EXPECT_NEAR(with.trolleyMass() - without.trolleyMass(), with.scene.rope.mass_per_length * 300.0,
              1e-9);
  EXPECT_DOUBLE_EQ(with.ropeMass(), without.ropeMass());  // the hanging mass is unchanged
  EXPECT_THROW(loadScene(t8036, {"rope.reeving_length=-5"}), InputError);
  EXPECT_THROW(loadScene(t8036, {"rope.reeving_length=abc"}), InputError);
}
