// Drives follow rate commands within their limits (docs/model.md): final positions equal
// the closed form of the limited (trapezoidal) speed profile; position limits are never passed.
#include "crane_twin/drives/drive_axis.hpp"

#include <gtest/gtest.h>

using namespace crane_twin;

namespace {
DriveLimits limits(double v, double a) {
  DriveLimits l;
  l.max_speed = v;
  l.max_acceleration = a;
  return l;
}

// Hold `command` for `duration` at step dt; returns the flags of the last step.
DriveFlags hold(DriveAxis& d, double command, double duration, double dt) {
  DriveFlags f;
  const long n = std::lround(duration / dt);
  for (long k = 0; k < n; ++k) f = d.advance(command, dt);
  return f;
}
}  // namespace

TEST(DriveAxis, StepCommandFollowsTheTrapezoidalClosedForm) {
  // Trolley 1.0 m/s, 0.5 m/s^2: command 0.8 m/s for 10 s from rest, then 0 for 4 s.
  // Ramp 1.6 s: x(10) = 0.8 * 10 - 0.8^2 / (2 * 0.5); stop ramp adds 0.8^2 / (2 * 0.5).
  DriveAxis d(limits(1.0, 0.5), 30.0, 2.5, 80.0);
  hold(d, 0.8, 10.0, 0.01);
  EXPECT_NEAR(d.position(), 30.0 + 0.8 * 10.0 - 0.64, 1e-9);
  EXPECT_NEAR(d.speed(), 0.8, 1e-12);
  hold(d, 0.0, 4.0, 0.01);
  EXPECT_NEAR(d.position(), 30.0 + 0.8 * 10.0, 1e-9);
  EXPECT_NEAR(d.speed(), 0.0, 1e-12);
}

TEST(DriveAxis, ReversalPassesThroughZeroAtTheAccelerationLimit) {
  // Slewing 0.084 rad/s, 0.02 rad/s^2, no position limit: +0.05 rad/s for 10 s, then -0.05.
  DriveAxis d(limits(0.084, 0.02), 0.0);
  hold(d, 0.05, 10.0, 0.001);
  const double x1 = 0.05 * 10.0 - 0.05 * 0.05 / (2 * 0.02);
  EXPECT_NEAR(d.position(), x1, 1e-9);
  // -0.05 for 10 s: the speed goes from +0.05 to -0.05 in 5 s (distance 0), then 5 s at -0.05.
  hold(d, -0.05, 10.0, 0.001);
  EXPECT_NEAR(d.position(), x1 - 0.05 * 5.0, 1e-9);
}

TEST(DriveAxis, CommandAboveTheSpeedLimitIsLimitedAndFlagged) {
  DriveAxis d(limits(1.0, 0.5), 60.0, 2.0, 66.0);
  const DriveFlags f = d.advance(-3.0, 0.01);
  EXPECT_TRUE(f.speed_limited);
  hold(d, -3.0, 5.99, 0.01);
  // 6 s in all: 2 s ramp to -1 m/s (1 m), 4 s at -1 m/s.
  EXPECT_NEAR(d.position(), 60.0 - 1.0 - 4.0, 1e-9);
  EXPECT_NEAR(d.speed(), -1.0, 1e-12);
}

TEST(DriveAxis, PositionLimitStopsTheDriveAtTheLimit) {
  DriveAxis d(limits(1.0, 0.5), 70.0, 2.5, 80.0);
  DriveFlags f;
  double maxPos = 0.0;
  for (int k = 0; k < 3000; ++k) {
    f = d.advance(1.0, 0.01);
    maxPos = std::max(maxPos, d.position());
  }
  EXPECT_LE(maxPos, 80.0);
  EXPECT_NEAR(d.position(), 80.0, 1e-3);
  EXPECT_NEAR(d.speed(), 0.0, 1e-12);
  EXPECT_TRUE(f.at_position_limit);
  // Commanding away from the limit moves it again.
  hold(d, -0.5, 2.0, 0.01);
  EXPECT_LT(d.position(), 80.0 - 0.5);
}
