// Full-order rope against closed form (docs/model.md): static stretch and tension, the
// modes of a hanging chain and of a heavy rope with a tip mass (Bessel functions), energy
// conservation, and the Project Chrono cross-code solution.
#include "crane_twin/solvers/full_order_solver.hpp"

#include <gtest/gtest.h>

#include <boost/math/special_functions/bessel.hpp>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>

#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/structure/modal_analysis.hpp"

using namespace crane_twin;

namespace {
const double g = 9.81;
const std::string kScenes = std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/";

CraneModel pendulumModel(const std::vector<std::string>& sets) {
  return buildCraneModel(loadScene(kScenes + "rope_pendulum_chrono.yaml", sets));
}

// Bisection root of f on [a, b] (f(a) f(b) < 0).
template <class F>
double bisect(F f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b), fm = f(m);
    if ((fm < 0) == (fa < 0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}
}  // namespace

TEST(AnchoredRope, StaticStretchAndTopTension) {
  // Hanging rope with tip mass: stretch (M g L + mu g L^2 / 2) / EA, tension (M + mu L) g.
  const double L = 60.0, mu = 1.9, EA = 2.2e7, M = 3600.0;
  AncfRope rope(40, L, mu, EA, 78.5, M, {0, 0, -g});
  FixedAnchor anchor({0, 0, 0});
  FullOrderSolver solver(rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 1e-3);
  const CoupledState s = solver.solveSwingEquilibrium(0.0, 0.0);
  const double stretch = (M * g * L + mu * g * L * L / 2) / EA;
  // The exact extensible-rope result differs from the linear formula by O(eps^2) ~ 3e-6 m.
  EXPECT_NEAR(-AncfRope::nodePosition(s.q, rope.nodes() - 1).z() - L, stretch, 1e-5);
  EXPECT_NEAR(solver.topTension(s), (M + mu * L) * g, 1e-6 * (M + mu * L) * g);
  EXPECT_NEAR(AncfRope::nodePosition(s.q, rope.nodes() - 1).x(), 0.0, 1e-12);
}

TEST(AnchoredRope, SwingEquilibriumHoldsTheChordAngle) {
  AncfRope rope(30, 60.0, 1.9, 2.2e7, 78.5, 3600.0, {0, 0, -g});
  FixedAnchor anchor({1, 2, 3});
  FullOrderSolver solver(rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 1e-3);
  Eigen::Vector3d H;
  const double th = 5.0 * M_PI / 180, az = 0.3;
  const CoupledState s = solver.solveSwingEquilibrium(th, az, &H);
  const Eigen::Vector3d c =
      AncfRope::nodePosition(s.q, rope.nodes() - 1) - Eigen::Vector3d(1, 2, 3);
  EXPECT_NEAR(std::atan2(std::hypot(c.x(), c.y()), -c.z()), th, 1e-9);
  EXPECT_NEAR(std::atan2(c.y(), c.x()), az, 1e-9);
  // Force balance of the whole rope: support force (-lambda) + weight + holding force = 0.
  const double W = (3600.0 + 1.9 * 60.0) * g;
  EXPECT_NEAR((-s.lambda - Eigen::Vector3d(0, 0, W) + H).norm(), 0.0, 1e-6 * W);
  EXPECT_NEAR(H.z(), 0.0, 1e-12);
}

TEST(AnchoredRope, HangingChainModesMatchBessel) {
  // No tip mass: w_n = (j0_n / 2) sqrt(g / L), j0 = 2.4048, 5.5201.
  const CraneModel m = pendulumModel({"payload.mass=0", "rope.elements=60", "rope.bending=false"});
  CraneSimulation sim(m);
  const ModalBasis b = sim.ropeModes(4);
  const double L = 60.0;
  const double w1 = 2.404826 / 2 * std::sqrt(g / L), w2 = 5.520078 / 2 * std::sqrt(g / L);
  // Planar modes come in pairs (x and y).
  EXPECT_NEAR(std::sqrt(b.omega2(0)), w1, 2e-3 * w1);
  EXPECT_NEAR(std::sqrt(b.omega2(1)), w1, 2e-3 * w1);
  EXPECT_NEAR(std::sqrt(b.omega2(2)), w2, 2e-3 * w2);
  EXPECT_NEAR(std::sqrt(b.omega2(3)), w2, 2e-3 * w2);
}

TEST(AnchoredRope, HeavyRopeWithTipMassModesMatchClosedForm) {
  // a = M / mu, xi(z) = 2 w sqrt(z / g), y = A J0 + B Y0 on z in [a, a + L];
  // y(a + L) = 0 and -w^2 y(a) = g y'(a) at the mass.
  const double L = 60.0, mu = 1.9, M = 3600.0, a = M / mu;
  using boost::math::cyl_bessel_j;
  using boost::math::cyl_neumann;
  auto det = [&](double w) {
    const double xa = 2 * w * std::sqrt(a / g), xt = 2 * w * std::sqrt((a + L) / g);
    const double dxdz = w / std::sqrt(g * a);  // d xi / dz at z = a
    // Rows: top condition [J0(xt), Y0(xt)]; mass condition w^2 y + g y' = 0.
    const double m11 = cyl_bessel_j(0, xt), m12 = cyl_neumann(0, xt);
    const double m21 = w * w * cyl_bessel_j(0, xa) - g * cyl_bessel_j(1, xa) * dxdz;
    const double m22 = w * w * cyl_neumann(0, xa) - g * cyl_neumann(1, xa) * dxdz;
    return m11 * m22 - m12 * m21;
  };
  // First root near the pendulum frequency sqrt(g / L_eff), second near the rope's string mode.
  std::vector<double> roots;
  double prev = det(0.05);
  for (double w = 0.05; w < 12.0 && roots.size() < 2; w += 0.002) {
    const double cur = det(w + 0.002);
    if ((cur < 0) != (prev < 0)) roots.push_back(bisect(det, w, w + 0.002));
    prev = cur;
  }
  ASSERT_EQ(roots.size(), 2u);
  const CraneModel m = pendulumModel({"rope.elements=120", "rope.bending=false"});
  CraneSimulation sim(m);
  const ModalBasis b = sim.ropeModes(4);
  EXPECT_NEAR(std::sqrt(b.omega2(0)), roots[0], 1e-3 * roots[0]);
  EXPECT_NEAR(std::sqrt(b.omega2(2)), roots[1], 1e-3 * roots[1]);
}

TEST(AnchoredRope, EnergyConservedWithRhoInfOneAndNeverGrowsWithDissipation) {
  // Undamped small swing, 20 s: with rho_inf = 1 (trapezoidal-like) the energy stays within
  // 0.5 % of the swing energy; with rho_inf = 0.7 it never grows.
  for (double rho : {1.0, 0.7}) {
    const CraneModel m =
        pendulumModel({"rope.elements=20", "time_step=0.01", "initial.mode=equilibrium",
                       "integrator.rho_inf=" + std::to_string(rho)});
    CraneSimulation sim(m);
    sim.initialize();
    const double E0 = sim.solver().energy(sim.state());
    // Swing energy: potential of the released swing above the hanging equilibrium.
    const CraneModel m0 = pendulumModel({"rope.elements=20", "initial.swing_deg=0"});
    CraneSimulation rest(m0);
    const CoupledState s0 = rest.staticState();
    const double Eswing = E0 - rest.solver().energy(s0);
    ASSERT_GT(Eswing, 0.0);
    double Eprev = E0, maxDev = 0.0;
    for (int k = 0; k < 2000; ++k) {
      sim.step();
      const double E = sim.solver().energy(sim.state());
      maxDev = std::max(maxDev, std::abs(E - E0));
      if (rho < 1.0) {
        EXPECT_LE(E, Eprev + 1e-9 * std::abs(E0)) << "t = " << sim.state().t;
      }
      Eprev = E;
      ASSERT_LT((AncfRope::nodePosition(sim.state().q, 0)).norm(), 1e-8);
    }
    if (rho == 1.0) {
      EXPECT_LT(maxDev, 0.005 * Eswing) << "max deviation " << maxDev << " J of " << Eswing;
    }
  }
}

TEST(AnchoredRope, TracksProjectChronoTipOverFirstTwoSeconds) {
  // test/data/chrono_rope_pendulum (its README): same rope, stress-free release at 2.3 deg.
  const std::string path =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/test/data/chrono_rope_pendulum/caseA_dt1e-3.csv";
  std::ifstream in(path);
  ASSERT_TRUE(in) << "missing reference data " << path;
  std::string line;
  std::getline(in, line);
  std::vector<std::array<double, 4>> ref;  // t, tip_x, tip_z, reaction
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::array<double, 9> v;
    char c;
    for (int i = 0; i < 9; ++i) ss >> v[i] >> c;
    ref.push_back({v[0], v[1], v[3], v[7]});
  }
  const CraneModel m = pendulumModel({"duration=2.0"});
  CraneSimulation sim(m);
  sim.initialize();
  std::size_t r = 1;
  double worstX = 0.0, worstZ = 0.0;
  while (sim.state().t < 2.0 - 1e-9) {
    sim.step();
    if (std::abs(sim.state().t - ref[r][0]) < 1e-9) {
      const Eigen::Vector3d p = AncfRope::nodePosition(sim.state().q, sim.rope().nodes() - 1);
      worstX = std::max(worstX, std::abs(p.x() - ref[r][1]));
      worstZ = std::max(worstZ, std::abs(p.z() - ref[r][2]));
      ++r;
    }
  }
  std::printf("Chrono, first 2 s: %zu common times, max tip difference x %.3g m, z %.3g m\n", r - 1,
              worstX, worstZ);
  EXPECT_GT(r, 40u);
  EXPECT_LT(worstX, 0.01);  // budget: within a centimetre or two of an independent code
  EXPECT_LT(worstZ, 0.02);
  // Sentinels: measured x 3.15e-4 m, z 4.15e-3 m (build/core/full_order_solver_test
  // --gtest_filter='*Chrono*'); z carries the undamped axial bounce's phase.
  EXPECT_LT(worstX, 1e-3);
  EXPECT_LT(worstZ, 1e-2);
}

TEST(AnchoredRope, SwingPeriodFromIntegrationMatchesRopeMode) {
  // Small swing (0.5 deg) released from equilibrium: the period measured from the payload's
  // x zero crossings equals 2 pi / w1 of the linearised rope (itself checked against the
  // Bessel closed form above), here for a 30-element rope at 10 ms steps with rho_inf = 1.
  const CraneModel m =
      pendulumModel({"rope.elements=30", "time_step=0.01", "initial.mode=equilibrium",
                     "initial.swing_deg=0.5", "integrator.rho_inf=1.0"});
  CraneSimulation sim(m);
  const double w1 = std::sqrt(sim.ropeModes(2).omega2(0));
  sim.initialize();
  std::vector<double> crossings;
  double prevX = AncfRope::nodePosition(sim.state().q, sim.rope().nodes() - 1).x(), prevT = 0.0;
  while (sim.state().t < 40.0) {
    sim.step();
    const double x = AncfRope::nodePosition(sim.state().q, sim.rope().nodes() - 1).x();
    if ((x < 0) != (prevX < 0)) {
      crossings.push_back(prevT + (sim.state().t - prevT) * prevX / (prevX - x));
    }
    prevX = x;
    prevT = sim.state().t;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double period = 2.0 * (crossings.back() - crossings.front()) / (crossings.size() - 1);
  EXPECT_NEAR(period, 2 * M_PI / w1, 1e-3 * 2 * M_PI / w1);
}

TEST(AnchoredRope, AxialDampingDampsTheBounceNotTheSwing) {
  // Stress-free release at 2.3 deg: the end mass bounces on the rope's stretch (axial mode,
  // ~1 Hz) while it swings (15.5 s). With rope.damping = 0.005 s the bounce, measured as the
  // top tension's spread over 8 s..10 s, decays, the swing (payload x at its first turning
  // point, ~7.8 s) stays, and the energy never grows.
  auto run = [](double c, double* spread, double* x_min, bool* energy_ok) {
    CraneSimulation sim(
        pendulumModel({"rope.elements=20", "time_step=0.002", "integrator.rho_inf=1",
                       "rope.damping=" + std::to_string(c)}));
    sim.initialize();
    double Eprev = sim.solver().energy(sim.state()), lo = 1e300, hi = -1e300;
    *x_min = 1e300;
    *energy_ok = true;
    for (int k = 1; k <= 5000; ++k) {
      sim.step();
      const double E = sim.solver().energy(sim.state());
      if (c > 0.0 && E > Eprev + 1e-9 * std::abs(Eprev)) *energy_ok = false;
      Eprev = E;
      const SeriesValues v = sim.series();
      *x_min = std::min(*x_min, v.payload.x());
      if (v.t >= 8.0) {
        lo = std::min(lo, v.rope_top_tension);
        hi = std::max(hi, v.rope_top_tension);
      }
    }
    *spread = hi - lo;
  };
  double spread0, spread1, x0, x1;
  bool ok0, ok1;
  run(0.0, &spread0, &x0, &ok0);
  run(0.005, &spread1, &x1, &ok1);
  EXPECT_TRUE(ok1);
  EXPECT_LT(spread1, 0.2 * spread0) << spread1 << " N against " << spread0 << " N undamped";
  EXPECT_NEAR(x1, x0, 0.01 * std::abs(x0) + 1e-3);
}

TEST(AncfRopeLength, InPlaceLengthChangeEqualsAFreshRope) {
  // Hoisting updates M and F_g in place (entry scaling l^(1 + s_i + s_j)); they must equal the
  // matrices of a rope built at the new length, point masses included.
  AncfRope hoisted(7, 60.0, 3.8, 4.4e7, 157.0, 3600.0, Eigen::Vector3d(0, 0, -9.81), 850.0);
  for (const double L : {42.0, 3.0, 75.5}) {
    hoisted.setLength(L);
    const AncfRope fresh(7, L, 3.8, 4.4e7, 157.0, 3600.0, Eigen::Vector3d(0, 0, -9.81), 850.0);
    const Eigen::MatrixXd d =
        Eigen::MatrixXd(hoisted.massMatrix()) - Eigen::MatrixXd(fresh.massMatrix());
    EXPECT_LT(d.cwiseAbs().maxCoeff(),
              1e-10 * Eigen::MatrixXd(fresh.massMatrix()).cwiseAbs().maxCoeff())
        << "L = " << L;
    EXPECT_LT((hoisted.gravityForce() - fresh.gravityForce()).cwiseAbs().maxCoeff(),
              1e-10 * fresh.gravityForce().cwiseAbs().maxCoeff());
  }
}

namespace {
// A 10 m tension-only rope under 100 kg from an anchor, stepped by a solver whose corrections
// may reuse the iteration matrix and by one that factorises it in every correction.
AncfRope tensionOnlyTestRope() {
  AncfRope rope(12, 10.0, 1.9, 2.2e7, 78.5, 100.0, {0, 0, -g});
  rope.setTensionOnly(true);
  return rope;
}

NewtonSettings withoutRankOneTerms() {
  NewtonSettings newton;
  newton.rank_one_switch_updates = false;
  return newton;
}

NewtonSettings freshMatrixNewton() {
  NewtonSettings newton;
  newton.reuse_matrix_near_convergence = false;
  return newton;
}

struct NewtonVariants {
  AncfRope rope = tensionOnlyTestRope();
  FixedAnchor anchor{Eigen::Vector3d(0, 0, 0)};
  FullOrderSolver reusing{rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 1e-3};
  FullOrderSolver fresh{rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 1e-3, freshMatrixNewton()};
};
}  // namespace

TEST(AnchoredRope, ATautStepChecksItsFirstCorrectionWithTheSameMatrix) {
  // A taut step converges in one correction and a check (integrators/newton_step.hpp): the
  // previous step's quadratic constant foresees the check below the tolerance, so the check
  // reuses the first correction's matrix. A tension-only rope swinging from 30 deg (taut
  // throughout) against the same steps with a fresh matrix in every correction.
  NewtonVariants v;
  FullOrderSolver &reusing = v.reusing, &fresh = v.fresh;
  CoupledState a = fresh.solveSwingEquilibrium(30.0 * M_PI / 180.0, 0.0);
  a.v.setZero();
  fresh.initializeAccelerations(a);
  CoupledState b = a;
  const int steps = 1000;
  double largest = 0.0;
  for (int k = 0; k < steps; ++k) {
    reusing.step(a);
    fresh.step(b);
    largest = std::max(largest, (a.q - b.q).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(largest, 1e-9) << "m between the two Newton variants' states";
  EXPECT_EQ(fresh.energyConsistentSteps(), 0) << "the rope went slack";
  // Every step but the first (which has no constant yet) and those converged in one correction.
  EXPECT_GT(reusing.matrixReusingCorrections(), steps * 9 / 10);
  std::printf("largest state difference %.3g m, %ld matrix-reusing corrections in %d steps\n",
              largest, reusing.matrixReusingCorrections(), steps);
}

TEST(AnchoredRope, LastCorrectionReusingTheMatrixReachesTheFullNewtonState) {
  // Newton's last correction may reuse the factorised iteration matrix once the corrections
  // contract quadratically (integrators/newton_step.hpp): every step must then end where the
  // same step with a fresh matrix in every correction ends (both meet the same tolerance). A
  // tension-only rope with an axial damper swings 40 deg down onto the ground and bounces, so
  // generalized-alpha steps, energy-consistent steps, the damper and the contact all take part.
  NewtonVariants v;
  const AncfRope& rope = v.rope;
  FullOrderSolver &reusing = v.reusing, &fresh = v.fresh;
  GroundContactParameters ground;
  ground.payload_height = 1.0;
  ground.height = -10.0 - ground.payload_height + 0.3;  // 5 cm above the lowest pass
  ground.damping = 2.0e3;
  for (FullOrderSolver* s : {&reusing, &fresh}) {
    s->setRopeDamping(1e-4);
    s->setGround(GroundContact(ground));
  }
  CoupledState s = fresh.solveSwingEquilibrium(40.0 * M_PI / 180.0, 0.0);
  s.v.setZero();
  fresh.initializeAccelerations(s);
  const int e = rope.positionIndex(rope.nodes() - 1);
  double largest = 0.0, deepest = -1.0;
  for (int k = 0; k < 2500; ++k) {
    CoupledState a = s, b = s;
    reusing.continueSteppingOf(fresh);
    reusing.step(a);
    fresh.step(b);
    largest = std::max(largest, (a.q - b.q).cwiseAbs().maxCoeff());
    deepest = std::max(deepest, ground.height + ground.payload_height - b.q(e + 2));
    s = b;
  }
  EXPECT_LT(largest, 1e-9) << "m between the two Newton variants' states";
  EXPECT_GT(deepest, 0.0) << "the payload never reached the ground";
  EXPECT_GT(fresh.energyConsistentSteps(), 0);
  EXPECT_EQ(fresh.matrixReusingCorrections(), 0);
  EXPECT_GT(reusing.matrixReusingCorrections(), 250) << "of 2500 steps";
  std::printf(
      "largest state difference %.3g m, %ld matrix-reusing corrections, %ld "
      "energy-consistent steps\n",
      largest, reusing.matrixReusingCorrections(), fresh.energyConsistentSteps());
}

TEST(AnchoredRope, TheContactsTangentChangesAsRankOneTermsReachTheFreshMatrixState) {
  // A payload on the ground changes the iteration matrix's contact block at every iterate (the
  // friction's slope about rest, a touchdown, a lift-off); with a slack rope the step keeps its
  // factorisation and adds that block's change, by its eigenvectors, as rank-one terms beside
  // the switched Gauss points' (FullOrderSolver::contactTangentChanges). Every step must end
  // where the same step assembled and factorised afresh ends, where both take the same kind of
  // step: the tension-only rule's choice between the generalized-alpha and the energy-consistent
  // step (integrators/tension_only_step.hpp) turns on the contact's sign at the step's end,
  // which a touchdown's 1e-10 m of Newton tolerance may flip. A tension-only rope swings 40 deg
  // down onto a ground 0.3 m above its lowest pass: the load lands, slides under friction,
  // bounces and comes to rest, its rope slackening and snatching.
  AncfRope rope = tensionOnlyTestRope();
  FixedAnchor anchor{Eigen::Vector3d(0, 0, 0)};
  FullOrderSolver updating{rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 1e-3};
  FullOrderSolver fresh{rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 1e-3,
                        withoutRankOneTerms()};
  GroundContactParameters ground;
  ground.payload_height = 1.0;
  ground.height = -10.0 - ground.payload_height + 0.3;
  ground.damping = 1.0e5;  // (half the critical 2 sqrt(k m) of the 100 kg load)
  ground.friction = 0.5;
  const GroundContact contact(ground);
  for (FullOrderSolver* x : {&updating, &fresh}) x->setGround(contact);
  CoupledState s = fresh.solveSwingEquilibrium(40.0 * M_PI / 180.0, 0.0);
  s.v.setZero();
  fresh.initializeAccelerations(s);
  const int e = rope.positionIndex(rope.nodes() - 1);
  double largest = 0.0;
  int touching = 0, other_kind = 0;
  for (int k = 0; k < 3000; ++k) {
    CoupledState a = s, b = s;
    updating.continueSteppingOf(fresh);
    const long ec_a = updating.energyConsistentSteps(), ec_b = fresh.energyConsistentSteps();
    updating.step(a);
    fresh.step(b);
    if (updating.energyConsistentSteps() - ec_a != fresh.energyConsistentSteps() - ec_b) {
      ++other_kind;
    } else {
      largest = std::max(largest, (a.q - b.q).cwiseAbs().maxCoeff());
    }
    if (contact.penetration(b.q.segment<3>(e)) > 0.0) ++touching;
    s = b;
  }
  EXPECT_LT(largest, 1e-9) << "m between the two Newton variants' states";
  EXPECT_LT(other_kind, 30) << "steps of another kind, of 3000";
  EXPECT_GT(touching, 1000) << "steps with the payload on the ground, of 3000";
  EXPECT_GT(updating.contactRankOneCorrections(), 300);
  EXPECT_EQ(fresh.rankOneCorrections(), 0);
  EXPECT_LT(updating.factorizations(), fresh.factorizations());
  std::printf(
      "largest state difference %.3g m (%d steps of another kind); %d steps on the ground; "
      "rank-one corrections %ld (%ld with the contact's terms), factorisations %ld against %ld, "
      "%ld energy-consistent steps\n",
      largest, other_kind, touching, updating.rankOneCorrections(),
      updating.contactRankOneCorrections(), updating.factorizations(), fresh.factorizations(),
      fresh.energyConsistentSteps());
}

TEST(AnchoredRope, AnEnergyConsistentStepLosesThetaTimesItsVelocityJumpAndNoMore) {
  // energyConsistentScheme (integrators/tension_only_step.hpp): with the discrete gradient and no
  // damper, the step's energy change is exactly -theta (v1 - v0)^T M (v1 - v0), theta =
  // kEnergyDecayRate h, and its positions move by h ((1/2 + theta) v1 + (1/2 - theta) v0). A
  // payload thrown up at 3 m/s on 10 m of tension-only rope: the rope goes slack and snatches.
  const double h = 1e-3, theta = kEnergyDecayRate * h;
  const AncfRope rope = tensionOnlyTestRope();
  FixedAnchor anchor{Eigen::Vector3d(0, 0, 0)};
  FullOrderSolver solver(rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), h);
  CoupledState s = solver.solveSwingEquilibrium(0.0, 0.0);
  s.v.segment<3>(rope.positionIndex(rope.nodes() - 1)) = Eigen::Vector3d(0.0, 0.0, 3.0);
  solver.initializeAccelerations(s);
  const SparseMatrix& M = rope.massMatrix();
  long checked = 0;
  double dissipated = 0.0, worst = 0.0, worst_move = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const CoupledState a = s;
    const long before = solver.energyConsistentSteps();
    solver.step(s);
    if (solver.energyConsistentSteps() == before) continue;
    ++checked;
    const Eigen::VectorXd dv = s.v - a.v;
    const double loss = theta * dv.dot(M * dv);
    const double dE = solver.energy(s) - solver.energy(a);
    dissipated += loss;
    // Round-off of energies of about 1e4 J (the payload's potential energy).
    worst = std::max(worst, std::abs(dE + loss) / (1e-12 * std::abs(solver.energy(a)) + 1e-9));
    const Eigen::VectorXd move = s.q - a.q - h * ((0.5 + theta) * s.v + (0.5 - theta) * a.v);
    worst_move = std::max(worst_move, move.cwiseAbs().maxCoeff());
  }
  std::printf(
      "%ld energy-consistent steps dissipated %.3g J; worst energy error %.3g of its "
      "bound, position update %.3g m\n",
      checked, dissipated, worst, worst_move);
  EXPECT_GT(checked, 10) << "the rope never switched: it tests nothing";
  EXPECT_GT(dissipated, 0.0);
  EXPECT_LT(worst, 1.0);
  EXPECT_LT(worst_move, 1e-12);
}

namespace {
// A tension-only step's checks take what they need of the step's start from the step before,
// which computed it (FullOrderSolver: the start's energy E_r = 1/2 v^T M v + U - F_g^T q and its
// Gauss points' axial strains); a change of the rope in between must be seen. A payload thrown up
// at 3 m/s on 10 m of tension-only rope (slack, then a snatch), the rope changed by
// `change(k, rope, solver)` before step k, stepped by one solver and by a run whose every step
// is taken by a solver built afresh (continuing the last one's stepping), which remembers
// nothing: the two must take the same decisions (which step is energy-consistent, which episode
// goes on) and so the same path.
void expectTheSamePathAsFreshSolvers(
    const std::function<void(int, AncfRope&, FullOrderSolver&)>& change) {
  const double h = 1e-3;
  AncfRope rope = tensionOnlyTestRope();
  FixedAnchor anchor{Eigen::Vector3d(0, 0, 0)};
  const GeneralizedAlpha ga = GeneralizedAlpha::fromRhoInf(0.9);
  FullOrderSolver stepping(rope, anchor, ga, h);
  CoupledState s = stepping.solveSwingEquilibrium(0.0, 0.0);
  s.v.segment<3>(rope.positionIndex(rope.nodes() - 1)) = Eigen::Vector3d(0.0, 0.0, 3.0);
  stepping.initializeAccelerations(s);
  CoupledState b = s;
  auto last = std::make_unique<FullOrderSolver>(rope, anchor, ga, h);
  last->continueSteppingOf(stepping);
  long fresh_energy_consistent = 0;
  double largest = 0.0;
  for (int k = 0; k < 1500; ++k) {
    change(k, rope, stepping);
    auto fresh = std::make_unique<FullOrderSolver>(rope, anchor, ga, h);
    fresh->continueSteppingOf(*last);
    stepping.step(s);
    fresh->step(b);
    fresh_energy_consistent += fresh->energyConsistentSteps();
    largest = std::max(largest, (s.q - b.q).cwiseAbs().maxCoeff());
    last = std::move(fresh);
  }
  EXPECT_GT(stepping.energyConsistentSteps(), 10) << "the rope never switched: it tests nothing";
  EXPECT_EQ(stepping.energyConsistentSteps(), fresh_energy_consistent);
  EXPECT_LT(largest, 1e-9) << "m between the remembering and the fresh solvers' paths";
  std::printf("largest path difference %.3g m, %ld and %ld energy-consistent steps\n", largest,
              stepping.energyConsistentSteps(), fresh_energy_consistent);
}
}  // namespace

TEST(AnchoredRope, TheRememberedStartEnergyFollowsTheRope) {
  // The end force changes every step (a new F_g): +-300 N on the 100 kg payload moves F_g^T q
  // by kJ, the energy check's tolerance is uJ.
  expectTheSamePathAsFreshSolvers([](int k, AncfRope& rope, FullOrderSolver&) {
    rope.setExternalLoad(Eigen::Vector3d::Zero(),
                         Eigen::Vector3d(0.0, 0.0, k % 2 ? 300.0 : -300.0));
  });
}

TEST(AnchoredRope, TheRememberedStrainsFollowTheRopesLength) {
  // A hoist rescales every element, and so every strain at the same coordinates: the rope
  // 10 m +- 1 cm every third step.
  expectTheSamePathAsFreshSolvers([](int k, AncfRope& rope, FullOrderSolver& solver) {
    if (k % 3 != 0) return;
    rope.setLength(k % 2 ? 10.01 : 9.99);
    solver.refreshMass();
  });
}

TEST(AnchoredRope, SwitchedPointsAsRankOneTermsReachTheFreshMatrixState) {
  // A slack step whose Gauss points change branch between iterates keeps its factorisation and
  // adds those points' axial tangents as rank-one terms (NewtonSettings::
  // rank_one_switch_updates): every step must end where the same step assembled and factorised
  // afresh ends (both meet the same tolerance). A rope without payload released horizontal and
  // unstretched: it falls slack almost everywhere and its points switch at every step.
  AncfRope rope(12, 10.0, 1.9, 2.2e7, 78.5, 0.0, {0, 0, -g});
  rope.setTensionOnly(true);
  FixedAnchor anchor{Eigen::Vector3d(0, 0, 0)};
  FullOrderSolver updating{rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 5e-4};
  FullOrderSolver fresh{rope, anchor, GeneralizedAlpha::fromRhoInf(0.9), 5e-4,
                        withoutRankOneTerms()};
  CoupledState s;
  s.q = rope.stretchedStraight(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0.0, 0.0);
  s.v = Eigen::VectorXd::Zero(s.q.size());
  fresh.initializeAccelerations(s);
  double largest = 0.0;
  for (int k = 0; k < 2000; ++k) {
    CoupledState a = s, b = s;
    updating.continueSteppingOf(fresh);
    updating.step(a);
    fresh.step(b);
    largest = std::max(largest, (a.q - b.q).cwiseAbs().maxCoeff());
    s = b;
  }
  EXPECT_LT(largest, 1e-9) << "m between the two Newton variants' states";
  EXPECT_EQ(fresh.rankOneCorrections(), 0);
  EXPECT_GT(updating.rankOneCorrections(), 500) << "of 2000 steps";
  EXPECT_LT(updating.factorizations(), fresh.factorizations());
  std::printf(
      "largest state difference %.3g m; rank-one corrections %ld, factorisations %ld "
      "against %ld\n",
      largest, updating.rankOneCorrections(), updating.factorizations(), fresh.factorizations());
}
