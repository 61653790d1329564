// The position controller on the rate drives against the drives' own limits and the
// time-optimal trapezoid (v_max, a_max): goals reached within tolerance, no overshoot beyond
// it, points in order and not before their time; bad trajectories refused with the reason.
#include "crane_twin/drives/trajectory_follower.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "crane_twin/io/scene.hpp"

using namespace crane_twin;

namespace {
const std::string kScene =
    std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";

TrajectoryPoint point(double t, std::optional<double> slew, std::optional<double> trolley,
                      std::optional<double> hoist) {
  TrajectoryPoint p;
  p.time_from_start = t;
  p.target = {slew, trolley, hoist};
  return p;
}

struct FollowRun {
  double done_at = -1.0;  // [s], -1: not reached
  double min_trolley = 1e9, max_slew = -1e9, max_hoist = -1e9;
  double end_slew = 0, end_trolley = 0, end_hoist = 0;
};

FollowRun follow(const Scene& scene, const std::vector<TrajectoryPoint>& points, double t_end,
                 double dt = 0.005) {
  CraneDrives drives(scene);
  TrajectoryFollower f;
  f.start(points, 0.0);
  FollowRun r;
  for (double t = 0.0; t < t_end; t += dt) {
    const bool was_active = f.active();
    drives.setCommand(f.command(t, drives, *scene.crane));
    if (was_active && f.reached() && r.done_at < 0.0) r.done_at = t;
    drives.advance(t, dt);
    r.min_trolley = std::min(r.min_trolley, drives.trolleyRadius());
    r.max_slew = std::max(r.max_slew, drives.slewAngle());
    r.max_hoist = std::max(r.max_hoist, drives.hoistLength());
  }
  r.end_slew = drives.slewAngle();
  r.end_trolley = drives.trolleyRadius();
  r.end_hoist = drives.hoistLength();
  return r;
}

// Time-optimal rest-to-rest move of distance d: d / v + v / a when v_max is reached.
double trapezoid(double d, const DriveLimits& l) {
  const double d_acc = l.max_speed * l.max_speed / l.max_acceleration;
  return d >= d_acc ? d / l.max_speed + l.max_speed / l.max_acceleration
                    : 2.0 * std::sqrt(d / l.max_acceleration);
}
}  // namespace

TEST(TrajectoryFollower, ReachesEachAxisWithoutOvershootNearTheTimeOptimalMove) {
  const Scene s = loadScene(kScene);
  const CraneDescription& c = *s.crane;
  // Trolley 80 -> 30 m, slew 0 -> 1 rad, rope 60 -> 40 m in one point.
  const FollowRun r = follow(s, {point(0.0, 1.0, 30.0, 40.0)}, 120.0);
  ASSERT_GT(r.done_at, 0.0) << "not reached";
  EXPECT_NEAR(r.end_slew, 1.0, TrajectoryFollower::kTolerance[0]);
  EXPECT_NEAR(r.end_trolley, 30.0, TrajectoryFollower::kTolerance[1]);
  EXPECT_NEAR(r.end_hoist, 40.0, TrajectoryFollower::kTolerance[2]);
  // No overshoot beyond the tolerance (the trolley and rope only shrink, the slew only grows).
  EXPECT_GE(r.min_trolley, 30.0 - TrajectoryFollower::kTolerance[1]);
  EXPECT_LE(r.max_slew, 1.0 + TrajectoryFollower::kTolerance[0]);
  EXPECT_LE(r.max_hoist, 60.0 + 1e-12);
  // The slowest axis decides; braking at 0.8 a_max costs a little over the trapezoid.
  const double t_opt =
      std::max({trapezoid(1.0, c.slewing), trapezoid(50.0, c.trolley), trapezoid(20.0, c.hoist)});
  std::printf("reached after %.2f s, time-optimal %.2f s\n", r.done_at, t_opt);
  EXPECT_GE(r.done_at, t_opt - 1e-9);
  EXPECT_LT(r.done_at, 1.1 * t_opt);
}

TEST(TrajectoryFollower, PointsInOrderAndNeverBeforeTheirTime) {
  const Scene s = loadScene(kScene);
  // Out to 70 m, then back to 50 m; the second point not before 40 s (the move itself needs
  // about 12 + 22 s).
  const FollowRun r = follow(
      s,
      {point(0.0, std::nullopt, 70.0, std::nullopt), point(40.0, std::nullopt, 50.0, std::nullopt)},
      80.0);
  ASSERT_GT(r.done_at, 0.0);
  EXPECT_GE(r.done_at, 40.0);
  EXPECT_NEAR(r.end_trolley, 50.0, TrajectoryFollower::kTolerance[1]);
  EXPECT_LE(r.min_trolley, 70.0 + TrajectoryFollower::kTolerance[1]);  // went out to 70 first
  EXPECT_GE(r.min_trolley, 50.0 - TrajectoryFollower::kTolerance[1]);
}

TEST(TrajectoryFollower, BadTrajectoriesAreRefusedWithTheReason) {
  const CraneDescription c = *loadScene(kScene).crane;
  auto why = [&](std::vector<TrajectoryPoint> p) { return TrajectoryFollower::validate(p, c); };
  EXPECT_EQ(why({point(0.0, 0.5, 40.0, 30.0)}), "");
  EXPECT_NE(why({}).find("at least one point"), std::string::npos);
  EXPECT_NE(
      why({point(0.0, std::nan(""), std::nullopt, std::nullopt)}).find("slew is not a finite"),
      std::string::npos);
  EXPECT_NE(why({point(5.0, 0.1, std::nullopt, std::nullopt),
                 point(2.0, 0.2, std::nullopt, std::nullopt)})
                .find("point 1: time_from_start 2"),
            std::string::npos);
  EXPECT_NE(why({point(-1.0, 0.1, std::nullopt, std::nullopt)}).find("time_from_start -1"),
            std::string::npos);
  EXPECT_NE(why({point(0.0, std::nullopt, c.max_radius + 1.0, std::nullopt)}).find("radius limits"),
            std::string::npos);
  EXPECT_NE(why({point(0.0, std::nullopt, std::nullopt, c.min_rope_length - 0.5)})
                .find("rope length limits"),
            std::string::npos);
}
