// The torque-limited slewing drive (docs/model.md "Slewing drive") against its closed forms, and
// the scene keys that select it.
#include "crane_twin/drives/slew_torque_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "crane_twin/drives/crane_drives.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/structure/structure_support.hpp"

using namespace crane_twin;

namespace {
const std::string kScene = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_slew90.yaml";
}

TEST(SlewTorqueDrive, ConstantTorqueOnTheRigidPartGivesTheClosedFormAngle) {
  // Rigid gear, a reference far above what T_max can reach: theta = T t^2 / (2 J).
  const double J = 2.5e7, T = 1.0e6, dt = 1e-3;
  SlewTorqueDrive d(J, T, 0.0, 0.0, 0.3);
  for (int k = 1; k <= 5000; ++k) {
    d.advance(10.0, dt);
    const double t = k * dt;
    ASSERT_NEAR(d.angle(), 0.3 + 0.5 * T / J * t * t, 1e-12) << t;
    ASSERT_NEAR(d.rate(), T / J * t, 1e-12);
    ASSERT_TRUE(d.torqueLimited());
    ASSERT_NEAR(d.torque(), T, 1e-6);
  }
  // A reference it can follow is followed exactly, without the limit.
  SlewTorqueDrive f(J, T, 0.0, 0.0, 0.0);
  f.advance(1e-3 * 0.01, dt);
  EXPECT_FALSE(f.torqueLimited());
  EXPECT_NEAR(f.rate(), 1e-5, 1e-15);
}

TEST(SlewTorqueDrive, RateStepOnASpringInertiaPairIsTheDampedOscillatorsResponse) {
  // phi' = w from t = 0 (unlimited torque): x = theta - phi obeys J x'' + c x' + k x = 0 with
  // x(0) = 0, x'(0) = -w, so x = -(w / wd) exp(-zeta wn t) sin(wd t).
  const double J = 2.5e7, k = 4.0e8, c = 2.0e6, w = 0.05, dt = 1e-3;
  const double wn = std::sqrt(k / J), zeta = c / (2.0 * std::sqrt(k * J));
  const double wd = wn * std::sqrt(1.0 - zeta * zeta);
  SlewTorqueDrive d(J, std::numeric_limits<double>::infinity(), k, c, 0.0);
  double worst = 0.0;
  for (int n = 1; n <= 10000; ++n) {
    // The reference is linear over a step, so the first step ramps it from 0 to w: taken as
    // a step at t = dt / 2 (the closed form's time te below).
    d.advance(w, dt);
    const double t = n * dt;
    // Trapezoidal phi over the first step: phi = w (t - dt / 2) for t >= dt.
    const double phi = w * (t - 0.5 * dt);
    const double te = t - 0.5 * dt;  // the shifted closed form of the same ramp-to-step input
    const double x = -(w / wd) * std::exp(-zeta * wn * te) * std::sin(wd * te);
    worst = std::max(worst, std::abs((d.angle() - phi) - x));
  }
  // Amplitude w / wd = 12.5 mrad; the trapezoidal rule's phase error over 10 s at wn dt = 0.004.
  EXPECT_LT(worst, 2e-3 * w / wd) << "worst " << worst;
  EXPECT_FALSE(d.torqueLimited());
}

TEST(SlewTorqueDrive, AtItsTorqueLimitTheGearCarriesTheLimitAndNoWindUpRemains) {
  const double J = 2.5e7, T = 5e5, k = 4.0e8, c = 2.0e7, dt = 1e-3;  // zeta = 0.1
  SlewTorqueDrive d(J, T, k, c, 0.0);
  double peak = 0.0;
  for (int n = 0; n < 20000; ++n) {
    d.advance(0.05, dt);
    peak = std::max(peak, std::abs(d.torque()));
  }
  EXPECT_LE(peak, T * (1.0 + 1e-12));
  EXPECT_NEAR(d.rate(), 0.05, 1e-4);  // it reached the reference and holds it
  EXPECT_LT(std::abs(d.torque()), 0.01 * T);
}

TEST(SlewTorqueDrive, BadArgumentsAreRefused) {
  EXPECT_THROW(SlewTorqueDrive(0.0, 1.0, 0.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(SlewTorqueDrive(1.0, -1.0, 0.0, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(SlewTorqueDrive(1.0, 1.0, -1.0, 0.0, 0.0), std::invalid_argument);
  SlewTorqueDrive d(1.0, 1.0, 0.0, 0.0, 0.0);
  EXPECT_THROW(d.advance(std::nan(""), 1e-3), std::invalid_argument);
}

TEST(SlewDriveScene, TorqueDriveSlewsTheCraneWithinItsLimit) {
  const Scene s = loadScene(kScene, {"slewing.drive.model=torque", "slewing.drive.max_torque=2e6",
                                     "slewing.drive.stiffness=5e8", "slewing.drive.damping=1e6"});
  EXPECT_TRUE(s.slew_inertial_loads);  // default on: the structure is flexible
  const CraneModel m = buildCraneModel(s);
  const double J = slewingInertia(*m.structure, m.trolleyMass(), s.trolley_radius);
  EXPECT_GT(J, 1e6);
  CraneDrives drives(m.scene, J);
  const double dt = 1e-3;
  double worst = 0.0;
  for (int k = 0; k < 20000; ++k) {
    drives.advance(k * dt, dt);
    worst = std::max(worst, std::abs(drives.slewTorqueDrive()->torque()));
  }
  EXPECT_LE(worst, 2e6 * (1.0 + 1e-12));
  EXPECT_GT(drives.slewAngle(), 0.1);
  EXPECT_THROW(CraneDrives(m.scene, 0.0), InputError);
}

TEST(SlewDriveScene, KeysAreCheckedAndInertialLoadsDefaultWithTheStructure) {
  EXPECT_FALSE(loadScene(kScene, {"structure.model=rigid"}).slew_inertial_loads);
  EXPECT_TRUE(loadScene(kScene).slew_inertial_loads);
  EXPECT_THROW(loadScene(kScene, {"slewing.drive.model=torque"}), InputError);  // no max_torque
  EXPECT_THROW(loadScene(kScene, {"slewing.drive.model=kinematic", "slewing.drive.stiffness=1"}),
               InputError);
  EXPECT_THROW(loadScene(kScene, {"slewing.drive.model=fast"}), InputError);
}
