// What the ROS node publishes, checked without ROS: the rope curve sampled from the ANCF shape
// functions, the crane frames at their deformed positions, the deformed structure segments
// (crane_snapshot), and the command checks and timeout (command_guard).
#include "crane_twin/analysis/crane_snapshot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "crane_twin/analysis/load_shapes.hpp"
#include "crane_twin/analysis/structure_group_poses.hpp"
#include "crane_twin/drives/command_guard.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/subdomain_reduced_simulation.hpp"
#include "crane_twin/structure/structure_support.hpp"

using namespace crane_twin;

namespace {
const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

CraneModel t8036(std::vector<std::string> sets) {
  sets.insert(sets.begin(),
              {"rope.model=full", "rope.elements=20", "time_step=0.01", "structure.modes=12"});
  return buildCraneModel(loadScene(kScenes + "t8036_combination1.yaml", sets));
}
}  // namespace

TEST(SampleRopeCurve, ReproducesACubicExactlyAndPassesThroughTheNodes) {
  // Hermite cubics interpolate any cubic space curve exactly from its nodal values and slopes:
  // r(x) = (x, 0.1 x^2, -0.01 x^3), three elements of 2 m.
  auto r = [](double x) { return Eigen::Vector3d(x, 0.1 * x * x, -0.01 * x * x * x); };
  auto rx = [](double x) { return Eigen::Vector3d(1.0, 0.2 * x, -0.03 * x * x); };
  const double l = 2.0;
  Eigen::VectorXd q(6 * 4);
  for (int j = 0; j < 4; ++j) {
    q.segment<3>(6 * j) = r(j * l);
    q.segment<3>(6 * j + 3) = rx(j * l);
  }
  const auto points = sampleRopeCurve(q, l, 5);
  ASSERT_EQ(points.size(), 3u * 5u + 1u);
  for (size_t i = 0; i < points.size(); ++i) {
    const double x = l * static_cast<double>(i) / 5.0;
    EXPECT_LT((points[i] - r(x)).norm(), 1e-12) << "sample " << i;
  }
  EXPECT_THROW(sampleRopeCurve(q, l, 0), std::invalid_argument);
}

TEST(CraneSnapshot, FramesSitWhereTheModelPutsThem) {
  // Slewed by 0.5 rad, modal structure: the trolley frame (slewing frame) turned to the world
  // is the rope's top node, the hook is the rope's end, and the payload hangs almost straight.
  CraneSimulation sim(t8036({"slewing.angle=0.5", "initial.swing_deg=2"}));
  sim.initialize();
  for (int k = 0; k < 30; ++k) sim.step();
  const CraneSnapshot s = snapshotOf(sim);
  ASSERT_TRUE(s.has_crane);
  EXPECT_NEAR(s.slew_angle, 0.5, 1e-15);
  const Eigen::Vector3d x_axis = s.slewing.orientation * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(x_axis.x(), std::cos(0.5), 1e-12);
  EXPECT_NEAR(x_axis.y(), std::sin(0.5), 1e-12);
  const Eigen::Vector3d top = sim.ropeNode(0);
  EXPECT_LT((s.slewing.orientation * s.trolley.position - top).norm(), 1e-9);
  // The trolley frame in the slewing frame: the rail point at radius 80 m, moved by the jib's
  // deflection, which is no larger than the jib tip's.
  const Eigen::Vector3d rail = trolleyPoint(*sim.support().structure(), 80.0);
  EXPECT_NEAR(rail.x(), 80.0, 1e-9);
  EXPECT_LE((s.trolley.position - rail).norm(), s.series.jib_tip.norm());
  EXPECT_GT((s.trolley.position - rail).norm(), 0.1);  // the soft structure does deflect
  EXPECT_LT((s.hook.position - sim.ropeNode(sim.ropeNodes() - 1)).norm(), 1e-12);
  EXPECT_LT((s.payload.position - s.series.payload).norm(), 1e-12);
  // Hook z axis along the rope's upward tangent: within a few degrees of the chord.
  const Eigen::Vector3d chord = (top - s.hook.position).normalized();
  EXPECT_GT((s.hook.orientation * Eigen::Vector3d::UnitZ()).dot(chord), std::cos(0.1));
  // The rope curve starts at the top node and ends at the hook.
  ASSERT_EQ(s.rope_curve.size(), 20u * 4u + 1u);
  EXPECT_LT((s.rope_curve.front() - top).norm(), 1e-12);
  EXPECT_LT((s.rope_curve.back() - s.hook.position).norm(), 1e-12);
  // Drives at rest: joint values are the scene's.
  EXPECT_NEAR(s.trolley_radius, 80.0, 1e-12);
  EXPECT_NEAR(s.rope_length, 60.0, 1e-12);
  EXPECT_EQ(s.slew_rate, 0.0);
}

TEST(CraneSnapshot, StructureSegmentsScaleTheDeformation) {
  CraneSimulation sim(t8036({"initial.swing_deg=0"}));
  sim.initialize();
  for (int k = 0; k < 5; ++k) sim.step();
  SnapshotOptions undeformed, true_scale, doubled;
  undeformed.displacement_scale = 0.0;
  doubled.displacement_scale = 2.0;
  const auto s0 = snapshotOf(sim, undeformed), s1 = snapshotOf(sim, true_scale),
             s2 = snapshotOf(sim, doubled);
  const TowerCraneStructure& st = *sim.support().structure();
  ASSERT_EQ(s1.structure_segments.size(), 2 * st.members.size());
  double moved = 0.0;
  for (size_t i = 0; i < s1.structure_segments.size(); ++i) {
    const Eigen::Vector3d d1 = s1.structure_segments[i] - s0.structure_segments[i];
    const Eigen::Vector3d d2 = s2.structure_segments[i] - s0.structure_segments[i];
    EXPECT_LT((d2 - 2.0 * d1).norm(), 1e-9);
    moved = std::max(moved, d1.norm());
  }
  // Undeformed segments are the mesh (slewing angle 0).
  EXPECT_LT((s0.structure_segments[0] - st.nodes[st.members[0].node1]).norm(), 1e-12);
  // The 3.6 t load bends the jib: the deformed jib tip matches the series' jib-tip
  // displacement, and the largest segment motion is at least that.
  EXPECT_LT(s1.series.jib_tip.z(), -0.5);
  Eigen::Vector3d tip = Eigen::Vector3d::Zero();
  for (size_t m = 0; m < st.members.size(); ++m)
    for (int end = 0; end < 2; ++end) {
      const int n = end ? st.members[m].node2 : st.members[m].node1;
      for (int t : st.jib_tip_nodes)
        if (n == t) tip = s1.structure_segments[2 * m + end] - st.nodes[n];
    }
  EXPECT_NEAR(tip.z(), s1.series.jib_tip.z(), 0.05);
  EXPECT_GE(moved, std::abs(s1.series.jib_tip.z()) - 1e-9);
  SnapshotOptions bad;
  bad.displacement_scale = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(snapshotOf(sim, bad), std::invalid_argument);
}

TEST(RigidFit, RecoversAKnownRigidMotion) {
  // Points moved by a known rotation and translation: the fit returns exactly that motion.
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()));
  const Eigen::Vector3d t(0.4, -1.5, 2.0);
  std::vector<Eigen::Vector3d> x = {{0, 0, 0}, {80, 0, 0}, {0, 2.45, 0}, {40, 1, 3.5}, {10, -1, 2}};
  std::vector<Eigen::Vector3d> y;
  for (const auto& p : x) y.push_back(q * p + t);
  const FramePose f = rigidFit(x, y);
  EXPECT_LT((f.position - t).norm(), 1e-10);
  EXPECT_LT(f.orientation.angularDistance(q), 1e-12);
  EXPECT_THROW(rigidFit({x[0], x[1]}, {y[0], y[1]}), std::invalid_argument);
  EXPECT_THROW(rigidFit(x, {y[0], y[1], y[2]}), std::invalid_argument);
}

TEST(CraneSnapshot, RigidPartsSitOnTheDeformedStructure) {
  // Slewed by 0.7 rad at static equilibrium: the structure sags under its weight and the 3.6 t
  // load (jib tip more than 1.5 m down). A rigid picture of the jib placed by its frame has its
  // tip on the deformed tip (the jib's own bending only, well under the rigid offset), the mast
  // top on the deformed mast top, and each fitted frame moves its part's nodes to within the
  // part's elastic bending of where the model has them.
  CraneSimulation sim(t8036({"slewing.angle=0.7", "initial.swing_deg=0"}));
  sim.initialize();
  const CraneSnapshot s = snapshotOf(sim);
  const TowerCraneStructure& st = *sim.support().structure();
  Eigen::Vector3d tip0 = Eigen::Vector3d::Zero();
  for (int n : st.jib_tip_nodes) tip0 += st.nodes[n];
  tip0 /= 2.0;
  const double rigid_offset = (s.jib_tip.position - tip0).norm();
  EXPECT_GT(rigid_offset, 1.5);
  const Eigen::Vector3d rigid_tip = s.jib.orientation * tip0 + s.jib.position;
  const double bending =
      std::abs(jibBendingTipDz(st, sim.support().structureDisplacement(sim.fullState().z)));
  EXPECT_LT((rigid_tip - s.jib_tip.position).norm(), 0.5 * bending + 0.05);
  EXPECT_LT((rigid_tip - s.jib_tip.position).norm(), 0.25 * rigid_offset);
  // The mast frame is in the world frame; the deformed mast top node turned by the slewing.
  const Eigen::Matrix3d R = s.slewing.orientation.toRotationMatrix();
  const Eigen::VectorXd u = sim.support().structureDisplacement(sim.fullState().z);
  int top = 0;
  for (size_t n = 0; n < st.nodes.size(); ++n)
    if (st.nodes[n].z() > st.nodes[top].z() && st.nodes[n].z() <= 65.0 + 1e-9) top = n;
  const Eigen::Vector3d top_world = R * (st.nodes[top] + st.nodeDisplacement(u, top));
  const Eigen::Vector3d top_rigid = s.mast.orientation * (R * st.nodes[top]) + s.mast.position;
  EXPECT_GT((top_world - R * st.nodes[top]).norm(), 0.2);
  // A straight line fitted to the mast's bending line under the jib's end moment, w = d xi^2,
  // misses its end by d / 6: the rigid mast's top is within that (plus 2 %) of the node.
  EXPECT_LT((top_rigid - top_world).norm(),
            (1.0 / 6.0 + 0.02) * (top_world - R * st.nodes[top]).norm());
  // Fits are small motions near identity: tilts of a few tenths of a degree.
  for (const FramePose* f : {&s.mast, &s.slewing_unit, &s.jib, &s.counter_jib})
    EXPECT_LT(f->orientation.angularDistance(Eigen::Quaterniond::Identity()), 0.05);
}

TEST(LoadShapes, SizedFromTheMassesAndHangingBelowTheRopesEnd) {
  // A rope end swung 0.2 rad about x: the hook block (2044 kg) and a 3600 kg payload lumped at
  // that point. Volumes: m_h / (0.5 * 7850) and m_p / 1000; the hook block's top face and the
  // payload's top face on the rope's line below the end point, one under the other.
  CraneSnapshot s;
  s.hook.position = Eigen::Vector3d(80.0, 1.0, 10.0);
  s.hook.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  s.payload = s.hook;
  const LoadShapes l = loadShapes(s, 2044.0, 3600.0);
  EXPECT_NEAR(l.hook_block.size.prod(), 2044.0 / (0.5 * 7850.0), 1e-12);
  EXPECT_NEAR(l.payload.size.prod(), 3.6, 1e-12);
  const Eigen::Vector3d up = s.hook.orientation * Eigen::Vector3d::UnitZ();
  const double h = l.hook_block.size.z(), e = l.payload.size.z();
  EXPECT_LT((l.hook_block.pose.position - (s.hook.position - 0.5 * h * up)).norm(), 1e-12);
  EXPECT_LT((l.payload.pose.position - (s.hook.position - (h + 0.5 * e) * up)).norm(), 1e-12);
  // A payload at its own point (rigging) hangs below that point instead.
  s.payload.position = s.hook.position - 3.0 * up;
  const LoadShapes r = loadShapes(s, 2044.0, 3600.0);
  EXPECT_LT((r.payload.pose.position - (s.payload.position - 0.5 * e * up)).norm(), 1e-12);
  EXPECT_THROW(loadShapes(s, -1.0, 3600.0), std::invalid_argument);
  EXPECT_THROW(loadShapes(s, 2044.0, std::nan("")), std::invalid_argument);
}

TEST(CraneSnapshot, ReducedModelSnapshotEqualsItsExpandedState) {
  SubdomainReducedSimulation sim(t8036({"rope.model=reduced", "rope.mode_count=6"}));
  sim.initialize();
  for (int k = 0; k < 20; ++k) sim.step();
  const CraneSnapshot s = snapshotOf(sim);
  EXPECT_LT((s.hook.position - sim.ropeNode(sim.ropeNodes() - 1)).norm(), 1e-12);
  EXPECT_LT((s.rope_curve.front() - sim.ropeNode(0)).norm(), 1e-12);
}

TEST(CraneSnapshot, TheHoistsLengthIsWhatTheDrumPaidOutThePileOnALandedLoadIncluded) {
  // t8036_lift_off_slow: 3.6 t landed with about 1.2 m of slack rope (the scene's comment)
  // lying on it, reeled in at 0.3 m/s from t = 0. The hoist joint (what a drum encoder
  // measures, and what a twin's follower compares with its own drive) is the drive's length;
  // the hanging length stays while the pile is reeled in.
  CraneSimulation sim(buildCraneModel(
      loadScene(kScenes + "t8036_lift_off_slow.yaml", {"rope.model=full", "rope.elements=20"})));
  sim.initialize();
  const CraneSnapshot start = snapshotOf(sim);
  EXPECT_EQ(start.hoist_length, sim.drives().hoistLength());
  EXPECT_NEAR(start.hoist_length - start.rope_length, 1.2, 0.1);
  while (sim.time() < 1.0) sim.step();
  const CraneSnapshot later = snapshotOf(sim);
  EXPECT_EQ(later.hoist_length, sim.drives().hoistLength());
  EXPECT_LT(later.hoist_length, start.hoist_length - 0.15);  // 0.3 m/s after its ramp
  EXPECT_NEAR(later.rope_length, start.rope_length, 1e-3);
}

TEST(CraneSnapshot, AnchoredRopeHasNoStructure) {
  CraneSimulation sim(buildCraneModel(
      loadScene(kScenes + "rope_pendulum_chrono.yaml", {"rope.elements=10", "time_step=0.01"})));
  sim.initialize();
  const CraneSnapshot s = snapshotOf(sim);
  EXPECT_FALSE(s.has_crane);
  EXPECT_TRUE(s.structure_segments.empty());
  EXPECT_LT((s.trolley.position - sim.ropeNode(0)).norm(), 1e-12);
}

// ---- command_guard -----------------------------------------------------------------------

TEST(CheckCommand, RejectsNonFiniteAndAbsurdRatesNamingTheField) {
  const Scene scene = loadScene(kScenes + "t8036_combination1.yaml");
  const double vmax = scene.crane->trolley.max_speed;
  CommandEntry c;
  c.trolley_speed = std::numeric_limits<double>::quiet_NaN();
  CommandVerdict v = checkCommand(scene, c);
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("trolley_speed"), std::string::npos) << v.reason;
  c = CommandEntry{};
  c.slew_rate = std::numeric_limits<double>::infinity();
  v = checkCommand(scene, c);
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("slew_rate"), std::string::npos) << v.reason;
  c = CommandEntry{};
  c.hoist_speed = 1e9;
  v = checkCommand(scene, c);
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("hoist_speed"), std::string::npos) << v.reason;
  // Just above the limit: accepted, flagged (the drive limits it).
  c = CommandEntry{};
  c.trolley_speed = -1.5 * vmax;
  v = checkCommand(scene, c);
  EXPECT_TRUE(v.accepted);
  EXPECT_TRUE(v.over_limit);
  EXPECT_NE(v.reason.find("trolley_speed"), std::string::npos) << v.reason;
  c.trolley_speed = 0.5 * vmax;
  v = checkCommand(scene, c);
  EXPECT_TRUE(v.accepted);
  EXPECT_FALSE(v.over_limit);
  EXPECT_TRUE(v.reason.empty());
}

TEST(CheckCommand, NoCraneAcceptsOnlyRest) {
  const Scene scene = loadScene(kScenes + "rope_pendulum_chrono.yaml");
  EXPECT_TRUE(checkCommand(scene, CommandEntry{}).accepted);
  CommandEntry c;
  c.slew_rate = 0.01;
  const CommandVerdict v = checkCommand(scene, c);
  EXPECT_FALSE(v.accepted);
  EXPECT_NE(v.reason.find("no crane"), std::string::npos) << v.reason;
}

TEST(CommandWatchdog, ExpiresOnceAfterTheTimeout) {
  CommandWatchdog w(0.5);
  EXPECT_FALSE(w.expired(10.0));  // nothing received yet
  w.received(1.0);
  EXPECT_FALSE(w.expired(1.5));
  EXPECT_TRUE(w.expired(1.5001));
  EXPECT_FALSE(w.expired(2.0));  // once
  w.received(3.0);
  EXPECT_TRUE(w.expired(3.6));
  CommandWatchdog never(0.0);
  never.received(0.0);
  EXPECT_FALSE(never.expired(1e6));
  EXPECT_THROW(CommandWatchdog(-1.0), std::invalid_argument);
  EXPECT_THROW(CommandWatchdog(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(StructureGroupPoses, FitsFromMomentsEqualTheFitsOfTheDisplacedNodes) {
  // The groups' poses from their moments (linear in z) against rigidFit of the nodes displaced
  // by u = Phi z, for random large coordinates (rotations of several degrees) and scales.
  CraneSimulation sim(t8036({"initial.swing_deg=0"}));
  sim.initialize();
  const RopeSupport& support = sim.support();
  const TowerCraneStructure& st = *support.structure();
  const StructureGroupPoses poses(support);
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int trial = 0; trial < 4; ++trial) {
    Eigen::VectorXd z(support.size());
    for (int k = 0; k < z.size(); ++k) z(k) = 3.0 * normal(rng);
    const double scale = trial == 0 ? 0.0 : 0.5 * trial;
    const Eigen::VectorXd u = support.structureDisplacement(z);
    for (const std::string group : {"mast", "slewing", "jib", "counter_jib"}) {
      ASSERT_TRUE(poses.has(group)) << group;
      std::vector<Eigen::Vector3d> x, y;
      for (int n : st.groupNodes(group)) {
        x.push_back(st.nodes[n]);
        y.push_back(st.nodes[n] + scale * st.nodeDisplacement(u, n));
      }
      const FramePose a = poses.fit(group, z, scale), b = rigidFit(x, y);
      EXPECT_LT((a.position - b.position).norm(), 1e-9) << group;
      EXPECT_LT(a.orientation.angularDistance(b.orientation), 1e-10) << group;
    }
  }
  EXPECT_THROW(poses.fit("boom", Eigen::VectorXd::Zero(support.size()), 1.0),
               std::invalid_argument);
  EXPECT_THROW(poses.fit("jib", Eigen::VectorXd::Zero(3), 1.0), std::invalid_argument);
}

TEST(StructureGroupPoses, SnapshotWithThemEqualsTheSnapshotFromTheField) {
  CraneSimulation sim(t8036({"initial.swing_deg=5"}));
  sim.initialize();
  for (int k = 0; k < 20; ++k) sim.step();
  const StructureGroupPoses poses(sim.support());
  SnapshotOptions field, moments;
  field.displacement_scale = moments.displacement_scale = 50.0;
  moments.group_poses = &poses;
  moments.structure_segments = false;
  const CraneSnapshot a = snapshotOf(sim, field), b = snapshotOf(sim, moments);
  for (const auto& [pa, pb] :
       {std::pair(a.mast, b.mast), std::pair(a.jib, b.jib),
        std::pair(a.slewing_unit, b.slewing_unit), std::pair(a.counter_jib, b.counter_jib)}) {
    EXPECT_LT((pa.position - pb.position).norm(), 1e-9);
    EXPECT_LT(pa.orientation.angularDistance(pb.orientation), 1e-10);
  }
  EXPECT_TRUE(b.structure_segments.empty());
}
