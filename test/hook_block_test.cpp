// Hook block on its own rigging (docs/model.md "Hook block"): the double
// pendulum's two swing frequencies against the linearised closed form, the
// static chain, frames, keys and the lumped case.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

#include "crane_twin/analysis/crane_snapshot.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/twin/sway_correction.hpp"
#include "period_estimate.hpp"

using namespace crane_twin;
using crane_twin_test::upCrossings;

namespace {
// Anchored at z = 0: 20 m of an almost massless, stiff hoist rope (1 fall, 1
// g/m, EA 2.2e9 N, no bending), a 2 t hook block and 3.6 t on 5 m of rigging
// (a bar of the same wire).
constexpr double kL1 = 20.0, kL2 = 5.0, kHook = 2000.0, kLoad = 3600.0, kG = 9.81, kEA = 2.2e9;

std::string hookScene() {
  const std::string path = testing::TempDir() + "hook_block.yaml";
  std::ofstream(path) << "crane: none\nanchor: [0, 0, 0]\nduration: 60.0\ntime_step: 0.005\n"
                         "integrator: {rho_inf: 1.0}\n"
                         "rope: {model: full, elements: 20, length: 20.0, falls: 1, "
                         "mass_per_length: 0.001, axial_stiffness: 2.2e9, bending: false}\n"
                         "payload: {mass: 3600.0}\nhook: {mass: 2000.0, rigging_length: 5.0}\n"
                         "initial: {swing_deg: 2.0}\n";
  return path;
}

// Linearised double pendulum (angles of the rope and the rigging from the
// vertical):
//   M = [[(m1 + m2) l1^2, m2 l1 l2], [m2 l1 l2, m2 l2^2]],  K = diag((m1 + m2)
//   g l1, m2 g l2),
// K phi = w^2 M phi; lengths stretched by their static tensions.
Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> doublePendulum() {
  const double l1 = kL1 * (1.0 + (kHook + kLoad) * kG / kEA), l2 = kL2 * (1.0 + kLoad * kG / kEA);
  Eigen::Matrix2d M, K;
  M << (kHook + kLoad) * l1 * l1, kLoad * l1 * l2, kLoad * l1 * l2, kLoad * l2 * l2;
  K << (kHook + kLoad) * kG * l1, 0.0, 0.0, kLoad * kG * l2;
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d>(K, M);
}
}  // namespace

TEST(HookBlock, DoublePendulumSwingsAtTheLinearisedClosedFormsFrequencies) {
  const auto dp = doublePendulum();
  const Eigen::Vector2d w = dp.eigenvalues().cwiseSqrt();
  const Eigen::Matrix2d Phi_inv = dp.eigenvectors().inverse();
  // The full ANCF rope, the default reduced rope (the payload point beside its
  // basis) and the pendulum.
  for (const char *model : {"full", "reduced", "pendulum"}) {
    SCOPED_TRACE(model);
    std::unique_ptr<Simulation> sim = makeSimulation(
        buildCraneModel(loadScene(hookScene(), {std::string("rope.model=") + model})));
    sim->initialize();
    ASSERT_EQ(sim->hookNode(), std::string(model) == "pendulum" ? 1 : 20);
    ASSERT_EQ(sim->ropeNodes(), std::string(model) == "pendulum" ? 3 : 22);
    std::vector<double> t, eta1, eta2;
    for (int k = 0; k < 12000; ++k) {
      sim->step();
      const Eigen::Vector3d top = sim->ropeNode(0), hook = sim->ropeNode(sim->hookNode()),
                            load = sim->ropeNode(sim->ropeNodes() - 1);
      // Angles in the swing plane (x), from the vertical; the modal coordinates
      // eta = Phi^-1 theta.
      const Eigen::Vector2d theta(std::atan2(hook.x() - top.x(), top.z() - hook.z()),
                                  std::atan2(load.x() - hook.x(), hook.z() - load.z()));
      const Eigen::Vector2d eta = Phi_inv * theta;
      t.push_back(sim->time());
      eta1.push_back(eta(0));
      eta2.push_back(eta(1));
    }
    for (int i = 0; i < 2; ++i) {
      const auto c = upCrossings(t, i == 0 ? eta1 : eta2);
      ASSERT_GE(c.size(), 4u) << "mode " << i;
      const double period = (c.back() - c.front()) / (c.size() - 1), closed = 2.0 * M_PI / w(i);
      std::printf("%s mode %d: period %.5f s, linearised double pendulum %.5f s\n", model, i + 1,
                  period, closed);
      EXPECT_NEAR(period, closed, 1e-3 * closed) << "mode " << i;
    }
  }
  // Lumped (no rigging) would swing at the simple pendulum's 2 pi sqrt((l1 +
  // l2) / g) or sqrt(l1 / g): neither is a double-pendulum frequency, so the
  // test tells them apart.
  EXPECT_GT(std::abs(2.0 * M_PI / w(0) - 2.0 * M_PI * std::sqrt(kL1 / kG)), 0.05);
}

TEST(HookBlock, HangsStraightWithEachMassOnItsPointAndItsOwnFrame) {
  for (const char *model : {"full", "pendulum"}) {
    SCOPED_TRACE(model);
    const CraneModel m = buildCraneModel(
        loadScene(hookScene(), {"initial.swing_deg=0", std::string("rope.model=") + model}));
    EXPECT_DOUBLE_EQ(m.end_mass, kLoad);
    EXPECT_DOUBLE_EQ(m.hook_mass, kHook);
    std::unique_ptr<Simulation> sim = makeSimulation(m);
    sim->initialize();
    const SeriesValues v = sim->series();
    // Top tension carries both point masses (and the rigging's 5 g); hook and
    // payload at the stretched lengths below the anchor.
    EXPECT_NEAR(v.rope_top_tension, (kHook + kLoad + 0.001 * 25.0) * kG,
                1e-6 * (kHook + kLoad) * kG);
    const double z_hook = -kL1 * (1.0 + (kHook + kLoad) * kG / kEA);
    EXPECT_NEAR(sim->ropeNode(sim->hookNode()).z(), z_hook, 1e-6);
    EXPECT_NEAR(v.payload.z(), z_hook - kL2 * (1.0 + kLoad * kG / kEA), 1e-6);
    const CraneSnapshot s = snapshotOf(*sim, SnapshotOptions{});
    EXPECT_NEAR((s.hook.position - sim->ropeNode(sim->hookNode())).norm(), 0.0, 1e-12);
    EXPECT_NEAR((s.payload.position - v.payload).norm(), 0.0, 1e-12);
    EXPECT_NEAR((s.hook.position - s.payload.position).norm(), kL2, 1e-3);
    // At rest: a step does not move it.
    sim->step();
    EXPECT_LT((sim->series().payload - v.payload).norm(), 1e-9);
  }
}

TEST(HookBlock, WithoutRiggingHookAndPayloadAreOneEndMassAndBadKeysAreRefused) {
  const std::string t8036 =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";
  const CraneModel lumped = buildCraneModel(loadScene(t8036));
  EXPECT_DOUBLE_EQ(lumped.end_mass,
                   lumped.scene.payload_mass + lumped.scene.crane->hook_block_mass);
  EXPECT_DOUBLE_EQ(lumped.hook_mass, 0.0);
  const CraneModel heavier = buildCraneModel(loadScene(t8036, {"hook.mass=3000"}));
  EXPECT_DOUBLE_EQ(heavier.end_mass, heavier.scene.payload_mass + 3000.0);
  EXPECT_THROW(loadScene(t8036, {"hook.rigging_length=-1"}), InputError);
  EXPECT_THROW(loadScene(t8036, {"hook.mass=0", "hook.rigging_length=4"}), InputError);
  EXPECT_THROW(loadScene(t8036, {"payload.mass=0", "hook.rigging_length=4"}), InputError);
  EXPECT_THROW(loadScene(t8036, {"hook.sling=4"}), InputError);
}

TEST(HookBlock, TwinSwayCorrectionTurnsTheWholeChainRigidly) {
  // The twin's correction (rotateRopeAboutTop with the model's position blocks)
  // on the chain with a rigging: the payload moves by dp across the chord (to
  // second order), every point keeps its distance to the top and the
  // hook-payload distance stays; the ANCF chain's strain energy is unchanged
  // (its slopes turned with it).
  const Eigen::Vector3d dp(0.3, -0.2, 0.0), dv(-0.05, 0.08, 0.0);
  for (const char *model : {"full", "reduced", "pendulum"}) {
    SCOPED_TRACE(model);
    std::unique_ptr<Simulation> sim = makeSimulation(
        buildCraneModel(loadScene(hookScene(), {std::string("rope.model=") + model})));
    sim->initialize();
    for (int k = 0; k < 50; ++k) sim->step();
    const CoupledState before = sim->fullState();
    const std::vector<bool> blocks = sim->fullStatePositionBlocks();
    ASSERT_EQ(3 * static_cast<int>(blocks.size()), before.q.size());
    CoupledState f = before;
    rotateRopeAboutTop(f.q, f.v, dp, dv, blocks);
    const bool pendulum = std::string(model) == "pendulum";
    const Eigen::Vector3d top = before.q.head<3>();
    const int end = static_cast<int>(before.q.size()) - 3;  // the payload: the last 3 in both
    const int hook = pendulum ? 3 : 6 * sim->hookNode();
    const Eigen::Vector3d rho = before.q.segment<3>(end) - top, n = rho.normalized();
    const Eigen::Vector3d moved = f.q.segment<3>(end) - before.q.segment<3>(end);
    EXPECT_LT((moved - (dp - dp.dot(n) * n)).norm(), dp.squaredNorm() / rho.norm() + 1e-9);
    EXPECT_NEAR((f.q.segment<3>(hook) - f.q.segment<3>(end)).norm(),
                (before.q.segment<3>(hook) - before.q.segment<3>(end)).norm(), 1e-9);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      if (blocks[b]) {
        EXPECT_NEAR((f.q.segment<3>(3 * b) - top).norm(), (before.q.segment<3>(3 * b) - top).norm(),
                    1e-9);
      }
    }
    if (std::string(model) == "full") {
      const AncfRope &rope = dynamic_cast<const CraneSimulation &>(*sim).rope();
      EXPECT_NEAR(rope.elasticEnergy(f.q), rope.elasticEnergy(before.q),
                  1e-9 * rope.elasticEnergy(before.q));
    }
  }
}
