// Pacer (include/crane_twin/simulation/pacer.hpp): the node's pacing rules without ROS.
#include "crane_twin/simulation/pacer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace crane_twin {
namespace {

constexpr double kNone = std::numeric_limits<double>::infinity();

PacerSettings settings(double factor, double period = 0.1, double step = 0.01) {
  PacerSettings s;
  s.real_time_factor = factor;
  s.publish_period = period;
  s.time_step = step;
  return s;
}

TEST(Pacer, AsFastAsPossibleStepsToTheNextPublicationAtOnce) {
  Pacer p(settings(0.0));
  p.restart(0.0, 0.0);
  const Pacer::Decision d = p.decide(5.0, 0.3, 0.4, kNone, 0.0);
  EXPECT_EQ(d.wait, Pacer::Wait::none);
  EXPECT_DOUBLE_EQ(d.target, 0.4);
}

TEST(Pacer, ARealTimeFactorFollowsTheWallClockFromItsAnchor) {
  for (double f : {0.5, 1.0, 4.0}) {
    Pacer p(settings(f));
    p.restart(10.0, 2.0);
    // 0.05 wall seconds later the run may reach 2 + 0.05 f, and no further than the publication.
    const Pacer::Decision d = p.decide(10.05, 2.0, 2.1, kNone, 0.0);
    EXPECT_EQ(d.wait, Pacer::Wait::none);
    EXPECT_DOUBLE_EQ(d.target, std::min(2.0 + 0.05 * f, 2.1)) << f;
    // At the paced time it waits until the next step is due: h / f of wall time.
    const Pacer::Decision w = p.decide(10.05, 2.0 + 0.05 * f, 2.0 + 0.05 * f + 0.1, kNone, 0.0);
    EXPECT_EQ(w.wait, Pacer::Wait::wall);
    EXPECT_NEAR(w.sleep, std::clamp(0.01 / f, 1e-4, 0.01), 1e-12) << f;
  }
  EXPECT_EQ(Pacer(settings(1.0)).overruns(), 0);
}

TEST(Pacer, ALagBeyondTheMarginReanchorsInsteadOfRacing) {
  Pacer p(settings(1.0, 0.1));
  p.restart(0.0, 0.0);
  // 0.34 s behind with a margin of 0.25 f + one period (0.35 s): keeps up, no overrun.
  Pacer::Decision d = p.decide(0.34, 0.0, 0.1, kNone, 0.0);
  EXPECT_EQ(p.overruns(), 0);
  EXPECT_DOUBLE_EQ(d.target, 0.1);
  // 0.36 s behind: an overrun; the anchor moves to the present, so nothing is due yet.
  d = p.decide(0.36, 0.0, 0.1, kNone, 0.0);
  EXPECT_EQ(p.overruns(), 1);
  EXPECT_EQ(d.wait, Pacer::Wait::wall);
  d = p.decide(0.41, 0.0, 0.1, kNone, 0.0);  // paced from the new anchor: 0.05 s
  EXPECT_DOUBLE_EQ(d.target, 0.05);
}

TEST(Pacer, WithACatchUpALagWithinItIsRacedBack) {
  // A twin's pacing (catch_up 5 s): 3 s behind, it steps at once to the next publication and
  // keeps doing so until it is on time; 5.5 s behind, it re-anchors.
  PacerSettings s = settings(1.0, 0.1);
  s.catch_up = 5.0;
  Pacer p(s);
  p.restart(0.0, 0.0);
  Pacer::Decision d = p.decide(3.0, 0.0, 0.1, kNone, 0.0);
  EXPECT_EQ(p.overruns(), 0);
  EXPECT_EQ(d.wait, Pacer::Wait::none);
  EXPECT_DOUBLE_EQ(d.target, 0.1);
  d = p.decide(3.01, 2.9, 3.0, kNone, 0.0);  // still behind the paced 3.01: on to 3.0
  EXPECT_DOUBLE_EQ(d.target, 3.0);
  d = p.decide(3.02, 3.02, 3.1, kNone, 0.0);  // on time: paced again
  EXPECT_EQ(d.wait, Pacer::Wait::wall);
  d = p.decide(8.6, 3.02, 3.1, kNone, 0.0);
  EXPECT_EQ(p.overruns(), 1);
  s.catch_up = -1.0;
  EXPECT_THROW(Pacer{s}, std::invalid_argument);
}

TEST(Pacer, TheClocksOwnerWaitsForItsSlowestFollower) {
  Pacer p(settings(0.0, 0.1));
  // A follower that has not reported yet holds the run.
  EXPECT_EQ(p.decide(0.0, 0.0, 0.1, -kNone, 0.0).wait, Pacer::Wait::followers);
  // At most 2.5 periods ahead of the slowest.
  Pacer::Decision d = p.decide(0.0, 1.0, 1.1, 0.8, 0.0);
  EXPECT_EQ(d.wait, Pacer::Wait::none);
  EXPECT_DOUBLE_EQ(d.target, 1.05);
  d = p.decide(0.0, 1.05, 1.1, 0.8, 0.0);
  EXPECT_EQ(d.wait, Pacer::Wait::followers);
}

TEST(Pacer, AFollowerOfTheClockStepsUpToIt) {
  PacerSettings s = settings(1.0);
  s.follow_clock = true;
  Pacer p(s);
  p.restart(0.0, 0.0);
  Pacer::Decision d = p.decide(100.0, 0.5, 0.6, kNone, 0.55);
  EXPECT_EQ(d.wait, Pacer::Wait::none);
  EXPECT_DOUBLE_EQ(d.target, 0.55);  // the wall clock plays no part
  d = p.decide(100.0, 0.55, 0.6, kNone, 0.55);
  EXPECT_EQ(d.wait, Pacer::Wait::clock);
  EXPECT_EQ(p.overruns(), 0);
}

TEST(Pacer, ALoopPacedByItKeepsTheRealTimeFactor) {
  // A loop that sleeps as told and steps instantly: over 10 s of wall time at f = 2 the run
  // reaches 20 s of simulated time, never more than one step ahead of the paced time.
  const double h = 0.005, f = 2.0, period = 1.0 / 30.0;
  Pacer p(settings(f, period, h));
  double wall = 0.0, sim = 0.0, next_publish = period;
  p.restart(wall, sim);
  while (wall < 10.0) {
    const Pacer::Decision d = p.decide(wall, sim, next_publish, kNone, 0.0);
    if (d.wait != Pacer::Wait::none) {
      wall += d.sleep;
      continue;
    }
    while (sim + 0.5 * h <= d.target) sim += h;
    EXPECT_LE(sim, f * wall + h + 1e-9);
    if (sim + 0.5 * h > next_publish) next_publish += period;
  }
  EXPECT_NEAR(sim, f * wall, 2 * h);
  EXPECT_EQ(p.overruns(), 0);
}

TEST(Pacer, BadSettingsAreRefused) {
  EXPECT_THROW(Pacer(settings(-1.0)), std::invalid_argument);
  EXPECT_THROW(Pacer(settings(std::nan(""))), std::invalid_argument);
  EXPECT_THROW(Pacer(settings(1.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(Pacer(settings(1.0, 0.1, -0.01)), std::invalid_argument);
}

}  // namespace
}  // namespace crane_twin
