// Segment distances against hand-computed cases and a brute-force search; crane parts on a site
// against the geometry of the crane file.
#include "crane_twin/analysis/site_clearance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "crane_twin/analysis/segment_distance.hpp"

using namespace crane_twin;
using V = Eigen::Vector3d;

namespace {
const std::string kCranes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/cranes/";

void expectClosest(const V& a0, const V& a1, const V& b0, const V& b1, double d, const V& pa,
                   const V& pb) {
  for (int swap = 0; swap < 2; ++swap) {  // the same answer with the segments exchanged
    const SegmentClosestPoints c =
        swap ? closestPointsOfSegments(b0, b1, a0, a1) : closestPointsOfSegments(a0, a1, b0, b1);
    EXPECT_NEAR(c.distance, d, 1e-12);
    EXPECT_LT(((swap ? c.point_b : c.point_a) - pa).norm(), 1e-12);
    EXPECT_LT(((swap ? c.point_a : c.point_b) - pb).norm(), 1e-12);
  }
}
}  // namespace

TEST(SegmentDistance, HandComputedCases) {
  // Skew, perpendicular: interior points, the common normal is z.
  expectClosest(V(0, 0, 0), V(2, 0, 0), V(1, -1, 3), V(1, 1, 3), 3.0, V(1, 0, 0), V(1, 0, 3));
  // Crossing: distance 0 at the crossing point.
  expectClosest(V(-1, 0, 0), V(1, 0, 0), V(0, -1, 0), V(0, 1, 0), 0.0, V(0, 0, 0), V(0, 0, 0));
  // Collinear, disjoint: end to end.
  expectClosest(V(0, 0, 0), V(1, 0, 0), V(3, 0, 0), V(5, 0, 0), 2.0, V(1, 0, 0), V(3, 0, 0));
  // End of one against the interior of the other: (0,0,1) to (0,2,5), sqrt(4 + 16).
  expectClosest(V(0, 0, 0), V(0, 0, 1), V(-1, 2, 5), V(1, 2, 5), std::sqrt(20.0), V(0, 0, 1),
                V(0, 2, 5));
  // A point against a segment, beyond its end: (3,1,0) to (2,0,0).
  expectClosest(V(3, 1, 0), V(3, 1, 0), V(0, 0, 0), V(2, 0, 0), std::sqrt(2.0), V(3, 1, 0),
                V(2, 0, 0));
  // Two points.
  expectClosest(V(1, 2, 3), V(1, 2, 3), V(4, 6, 3), V(4, 6, 3), 5.0, V(1, 2, 3), V(4, 6, 3));
}

TEST(SegmentDistance, ParallelOverlappingSegmentsAreAtTheirSpacing) {
  const SegmentClosestPoints c =
      closestPointsOfSegments(V(0, 0, 0), V(4, 0, 0), V(2, 1, 0), V(6, 1, 0));
  EXPECT_NEAR(c.distance, 1.0, 1e-12);
  EXPECT_NEAR((c.point_a - c.point_b).norm(), 1.0, 1e-12);
  EXPECT_GE(c.point_a.x(), 2.0 - 1e-12);  // within the overlap
  EXPECT_LE(c.point_a.x(), 4.0 + 1e-12);
}

TEST(SegmentDistance, NeverAboveABruteForceSearchAndAttained) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  for (int k = 0; k < 200; ++k) {
    const V a0(u(gen), u(gen), u(gen)), a1(u(gen), u(gen), u(gen));
    const V b0(u(gen), u(gen), u(gen)), b1(u(gen), u(gen), u(gen));
    const SegmentClosestPoints c = closestPointsOfSegments(a0, a1, b0, b1);
    double brute = 1e300;
    const int n = 400;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        brute = std::min(brute, ((a0 + (a1 - a0) * i / n) - (b0 + (b1 - b0) * j / n)).norm());
    EXPECT_LE(c.distance, brute + 1e-12) << k;
    EXPECT_GT(c.distance, brute - 0.05) << k;  // the grid's spacing bounds its error
    // The points lie on their segments and are c.distance apart.
    EXPECT_NEAR((c.point_a - c.point_b).norm(), c.distance, 1e-12);
    EXPECT_NEAR((c.point_a - a0).norm() + (a1 - c.point_a).norm(), (a1 - a0).norm(), 1e-9);
    EXPECT_NEAR((c.point_b - b0).norm() + (b1 - c.point_b).norm(), (b1 - b0).norm(), 1e-9);
  }
}

TEST(SiteClearance, FacingJibsAtDifferentHeightsAreTheirSpacingLessTheLatticeRadii) {
  const CraneDescription c = loadCraneDescription(kCranes + "t8036.yaml");
  // Crane b 100 m along x, turned to face crane a, its mast foot 10 m higher: the jibs overlap in
  // plan (81.2 m each) and pass 10 m apart in height, less both lattice radii.
  // a's load at 30 m, 20 m under the rail; b's trolley at 10 m so its rope hangs beyond a's
  // jib tip (at site x = 90 m).
  CraneClearanceState sa, sb;
  sa.trolley = V(30.0, 0.0, c.jibRailHeight());
  sa.payload = V(30.0, 0.0, c.jibRailHeight() - 20.0);
  sb.trolley = V(10.0, 0.0, c.jibRailHeight());
  sb.payload = V(10.0, 0.0, c.jibRailHeight() - 20.0);
  const SitePose pose_b{V(100, 0, 10), M_PI};
  const std::vector<CranePart> a = cranePartsOnSite(c, SitePose{V(0, 0, 0), 0.0}, sa);
  const std::vector<CranePart> b = cranePartsOnSite(c, pose_b, sb);
  ASSERT_EQ(b.size(), 5u);
  // Parts on the site: b's jib tip at 100 - 81.225 m, its payload at x = 90 m, 10 m higher.
  EXPECT_EQ(b[1].name, "jib");
  EXPECT_NEAR(b[1].b.x(), 100.0 - (c.mast_width / 2 + c.jib.length), 1e-9);
  EXPECT_EQ(b[4].name, "payload");
  EXPECT_LT((b[4].a - V(90.0, 0.0, c.jibRailHeight() - 10.0)).norm(), 1e-9);
  const PartClearance p = minimumClearance(a, b);
  const double r = 0.5 * std::hypot(c.jib.width, c.jib.height);
  EXPECT_EQ(p.part_a, "jib");
  EXPECT_EQ(p.part_b, "jib");
  EXPECT_NEAR(p.distance, 10.0 - 2.0 * r, 1e-9);
  EXPECT_NEAR((p.point_b - p.point_a).norm(), 10.0 - 2.0 * r, 1e-9);
  // Slewing crane b by 90 deg turns its jib to the site's -y: the closest parts are then a's
  // jib tip and b's mast, the horizontal 100 - 81.225 m less the lattice and mast radii (a's jib
  // at 69.75 m is within the span of b's mast, 10 to 78 m).
  CraneClearanceState turned = sb;
  turned.slew_angle = M_PI / 2;
  turned.trolley = V(0.0, 10.0, c.jibRailHeight());
  turned.payload = V(0.0, 10.0, c.jibRailHeight() - 20.0);
  const PartClearance q = minimumClearance(a, cranePartsOnSite(c, pose_b, turned));
  EXPECT_EQ(q.part_a, "jib");
  EXPECT_EQ(q.part_b, "mast");
  EXPECT_NEAR(q.distance,
              100.0 - (c.mast_width / 2 + c.jib.length) - r - c.mast_width / std::sqrt(2.0), 1e-9);
}

TEST(SiteClearance, ForecastClearanceIsTheClosestApproachAlongBothPaths) {
  // Crane b as above (100 m along x, facing a, 10 m higher) holds its load at 10 m; crane a's
  // forecast slews its load (radius 40 m, 20 m under the rail) from 90 deg to 0 deg in 3 s. The
  // jibs are apart in plan until a's points at b: then 10 m in height less both lattice radii,
  // at t = 3 s, jib against jib.
  const CraneDescription c = loadCraneDescription(kCranes + "t8036.yaml");
  const SitePose pose_a{V(0, 0, 0), 0.0}, pose_b{V(100, 0, 10), M_PI};
  CraneClearanceState now_a, now_b;
  now_b.trolley = V(10.0, 0.0, c.jibRailHeight());
  now_b.payload = V(10.0, 0.0, c.jibRailHeight() - 20.0);
  PayloadPath a, b;
  for (int i = 0; i <= 3; ++i) {
    const double az = M_PI / 2 * (1.0 - i / 3.0);
    a.t.push_back(i);
    a.payload.push_back(V(40.0 * std::cos(az), 40.0 * std::sin(az), c.jibRailHeight() - 20.0));
    b.t.push_back(i + 0.1);
    b.payload.push_back(pose_b.toSite(now_b.payload));
  }
  // The state a forecast payload implies: the jib turned to its azimuth, the trolley above it.
  const CraneClearanceState s1 = stateFromForecastPayload(c, pose_a, now_a, a.payload[1]);
  EXPECT_NEAR(s1.slew_angle, M_PI / 3, 1e-12);
  EXPECT_LT((s1.trolley - V(20.0, 40.0 * std::sin(M_PI / 3), c.jibRailHeight())).norm(), 1e-9);
  const CraneClearanceState sb = stateFromForecastPayload(c, pose_b, now_b, b.payload[0]);
  EXPECT_NEAR(std::cos(sb.slew_angle), 1.0, 1e-12);  // b's own frame: its jib along its x
  const double r = 0.5 * std::hypot(c.jib.width, c.jib.height);
  const ForecastClearance f = forecastClearance(c, pose_a, now_a, a, c, pose_b, now_b, b, {}, 0.2);
  ASSERT_TRUE(f.valid);
  EXPECT_EQ(f.t, 3.0);
  EXPECT_EQ(f.closest.part_a, "jib");
  EXPECT_EQ(f.closest.part_b, "jib");
  EXPECT_NEAR(f.closest.distance, 10.0 - 2.0 * r, 1e-9);
  // Paths that share no instant within the gap: no forecast clearance.
  EXPECT_FALSE(forecastClearance(c, pose_a, now_a, a, c, pose_b, now_b, b, {}, 0.05).valid);
}

TEST(SiteClearance, RejectsBadInput) {
  const CraneDescription c = loadCraneDescription(kCranes + "t8036.yaml");
  ClearanceSettings bad;
  bad.payload_radius = -1.0;
  EXPECT_THROW(cranePartsOnSite(c, SitePose{}, CraneClearanceState{}, bad), std::invalid_argument);
  EXPECT_THROW(minimumClearance({}, {CranePart{}}), std::invalid_argument);
}
