// The payload's ground contact law (elements/ground_contact.hpp, docs/model.md "Ground
// contact"): its derivatives against finite differences, the energy-consistent step's mean force
// (work equals the spring's energy change plus a dissipation, across a touchdown or a lift-off),
// the trapezoid error that picks such steps, and that the damper and friction only dissipate.
#include "crane_twin/elements/ground_contact.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

using namespace crane_twin;

namespace {

GroundContactParameters params() {
  GroundContactParameters p;
  p.height = 0.3;
  p.stiffness = 2e7;
  p.damping = 4e4;
  p.friction = 0.6;
  p.slip_velocity = 1e-2;
  p.payload_height = 1.5;
  return p;
}

}  // namespace

TEST(GroundContact, PenetrationEnergyAndStaticForceAreTheClosedForm) {
  const GroundContact g(params());
  // Underside at z - 1.5; ground at 0.3: the point at 1.79 penetrates 1 cm.
  const Eigen::Vector3d r(4.0, -2.0, 1.79);
  EXPECT_NEAR(g.penetration(r), 0.01, 1e-15);
  EXPECT_NEAR(g.clearance(r), -0.01, 1e-15);
  EXPECT_NEAR(g.energy(r), 0.5 * 2e7 * 1e-4, 1e-6);
  const GroundContactForce f = g.force(r, Eigen::Vector3d::Zero());
  EXPECT_NEAR(f.f.z(), 2e7 * 0.01, 1e-6);
  EXPECT_EQ(f.f.head<2>().norm(), 0.0);
  // Clear of the ground: nothing.
  const GroundContactForce none = g.force(Eigen::Vector3d(0, 0, 1.81), Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(none.f.norm(), 0.0);
  EXPECT_EQ(none.df_dr.norm(), 0.0);
  EXPECT_EQ(g.energy(Eigen::Vector3d(0, 0, 1.81)), 0.0);
  // Leaving fast enough that the damper would pull: no force (the contact never holds the load).
  EXPECT_EQ(g.force(r, Eigen::Vector3d(0, 0, 2e7 * 0.01 / 4e4 + 1e-3)).f.norm(), 0.0);
  // Sliding far above the slip velocity: friction mu N against the motion.
  const GroundContactForce s = g.force(r, Eigen::Vector3d(3.0, 4.0, 0.0));
  EXPECT_NEAR(s.f.head<2>().norm(), 0.6 * 2e5, 0.6 * 2e5 * 1e-5);
  EXPECT_NEAR(s.f.head<2>().normalized().dot(Eigen::Vector2d(0.6, 0.8)), -1.0, 1e-12);
  // The damper c = 2 zeta sqrt(k m).
  EXPECT_NEAR(groundDamping(1e8, 3600.0, 0.5), std::sqrt(1e8 * 3600.0), 1e-6);
}

TEST(GroundContact, DerivativesMatchFiniteDifferences) {
  const GroundContact g(params());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Vector3d r(u(rng), u(rng), 1.8 - 0.02 * std::abs(u(rng)));  // in contact
    const Eigen::Vector3d v(0.05 * u(rng), 0.05 * u(rng), 0.1 * u(rng));
    const GroundContactForce f = g.force(r, v);
    if (f.f.z() <= 1e3) continue;  // keep away from the damper's clip
    ++checked;
    const double hr = 1e-7, hv = 1e-7;
    Eigen::Matrix3d Dr, Dv;
    for (int j = 0; j < 3; ++j) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e(j) = 1.0;
      Dr.col(j) = (g.force(r + hr * e, v).f - g.force(r - hr * e, v).f) / (2 * hr);
      Dv.col(j) = (g.force(r, v + hv * e).f - g.force(r, v - hv * e).f) / (2 * hv);
    }
    // The normal law exactly; the friction's tangential block exactly; the friction's coupling
    // to r_z and v_z is left out of the matrices by design (symmetric LDL^T), so only the blocks
    // the matrices claim are compared.
    EXPECT_NEAR(f.df_dr(2, 2), Dr(2, 2), 1e-6 * 2e7);
    EXPECT_NEAR(f.df_dv(2, 2), Dv(2, 2), 1e-6 * 4e4);
    EXPECT_LT((f.df_dv.topLeftCorner<2, 2>() - Dv.topLeftCorner<2, 2>()).norm(),
              1e-6 * (1.0 + Dv.topLeftCorner<2, 2>().norm()));
    EXPECT_LT((f.df_dv.topLeftCorner<2, 2>() - f.df_dv.topLeftCorner<2, 2>().transpose()).norm(),
              1e-12 * (1.0 + Dv.norm()));
  }
  EXPECT_GT(checked, 50);
}

TEST(GroundContact, StepMeanForceWorkIsTheEnergyChangePlusADissipation) {
  const GroundContact g(params());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int switching = 0;
  for (int trial = 0; trial < 300; ++trial) {
    // Steps that touch down, lift off, stay in contact or stay clear.
    const Eigen::Vector3d r0(u(rng), u(rng), 1.8 + 0.01 * u(rng));
    const Eigen::Vector3d r1 = r0 + Eigen::Vector3d(1e-3 * u(rng), 1e-3 * u(rng), 0.01 * u(rng));
    const Eigen::Vector3d v0(0.1 * u(rng), 0.1 * u(rng), 0.5 * u(rng));
    const Eigen::Vector3d v1(0.1 * u(rng), 0.1 * u(rng), 0.5 * u(rng));
    if ((g.penetration(r0) > 0.0) != (g.penetration(r1) > 0.0)) ++switching;
    const GroundContactForce m = g.stepMeanForce(r0, r1, v0, v1);
    const Eigen::Vector3d dr = r1 - r0;
    const Eigen::Vector3d fd = g.dissipativeForce(0.5 * (r0 + r1), 0.5 * (v0 + v1));
    // f . dr = -(U1 - U0) + f_d(mid) . dr, to round-off of the energies.
    EXPECT_NEAR(m.f.dot(dr), -(g.energy(r1) - g.energy(r0)) + fd.dot(dr),
                1e-12 * (1.0 + g.energy(r0) + g.energy(r1)));
    // The dissipative part opposes the mid velocity (it dissipates on the trapezoid's dr).
    EXPECT_LE(fd.dot(0.5 * (v0 + v1)), 1e-12);
    // d(2 f)/dr1 in z and d(2 f)/dv1 against finite differences (away from the kinks).
    const double h = 1e-8;
    const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
    const double Dz = (g.stepMeanForce(r0, r1 + h * ez, v0, v1).f.z() -
                       g.stepMeanForce(r0, r1 - h * ez, v0, v1).f.z()) /
                      h;  // = d(2 f_z)/dz1
    const Eigen::Vector3d rm = 0.5 * (r0 + r1);
    const double pm = g.penetration(rm);
    const bool near_kink = std::abs(g.clearance(r1)) < 1e-6 || std::abs(pm) < 1e-6 ||
                           std::abs(2e7 * pm - 4e4 * 0.5 * (v0 + v1).z()) < 1e2;
    if (!near_kink) {
      EXPECT_NEAR(m.df_dr(2, 2), Dz, 1e-5 * 2e7) << "trial " << trial;
    }
  }
  EXPECT_GT(switching, 20);
}

TEST(GroundContact, SwitchWorkErrorIsZeroUnlessTheStepLandsOrLiftsOff) {
  const GroundContact g(params());
  const Eigen::Vector3d in0(0, 0, 1.79), in1(0, 0, 1.785), out0(0, 0, 1.9), out1(0, 0, 1.85);
  EXPECT_NEAR(g.switchWorkError(in0, in1), 0.0, 1e-9);  // U quadratic: the trapezoid is exact
  EXPECT_EQ(g.switchWorkError(out0, out1), 0.0);
  // Landing from 1 cm above to 1 cm in: trapezoid work k (0 + 0.01) / 2 * 0.02 = 2000 J against
  // U = 1000 J: error 1000 J.
  EXPECT_NEAR(g.switchWorkError(Eigen::Vector3d(0, 0, 1.81), in0), 1000.0, 1e-6);
  EXPECT_NEAR(g.switchWorkError(in0, Eigen::Vector3d(0, 0, 1.81)), 1000.0, 1e-6);
}

TEST(GroundContact, RefusesNonPhysicalParameters) {
  auto with = [](auto set) {
    GroundContactParameters p = params();
    set(p);
    return p;
  };
  EXPECT_THROW(GroundContact(with([](auto& p) { p.stiffness = 0.0; })), std::invalid_argument);
  EXPECT_THROW(GroundContact(with([](auto& p) { p.damping = -1.0; })), std::invalid_argument);
  EXPECT_THROW(GroundContact(with([](auto& p) { p.friction = -0.1; })), std::invalid_argument);
  EXPECT_THROW(GroundContact(with([](auto& p) { p.slip_velocity = 0.0; })), std::invalid_argument);
  EXPECT_THROW(GroundContact(with([](auto& p) { p.height = NAN; })), std::invalid_argument);
  EXPECT_THROW(GroundContact(with([](auto& p) { p.payload_height = -1.0; })),
               std::invalid_argument);
}
