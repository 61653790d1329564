// Inertial loads of slewing on the structure (slewing.inertial_loads, docs/model.md):
// the load vector against fields built here from the mesh, its modal projection, the rigid
// slewing mode's inertia against the rotating part's mass distribution, and the structure's
// response in a run against the static solution of the same load.
#include <gtest/gtest.h>

#include <Eigen/CholmodSupport>
#include <cmath>
#include <memory>

#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/pendulum_crane_simulation.hpp"
#include "crane_twin/structure/structure_support.hpp"

using namespace crane_twin;

namespace {
const std::string kScene =
    std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";

CraneModel t8036(std::vector<std::string> sets) { return buildCraneModel(loadScene(kScene, sets)); }
}  // namespace

TEST(SlewingLoads, LoadIsMinusMassTimesTheFramesAcceleration) {
  const CraneModel m = t8036({});
  const TowerCraneStructure& st = *m.structure;
  // The frame's acceleration field built here from the mesh: nodes of any non-mast member
  // turn; translation theta'' e_z x X - theta'^2 (X, Y, 0), rotation theta'' e_z.
  const double rate = 0.07, acc = 0.02;
  std::vector<bool> turns(st.nodes.size(), false);
  for (const auto& mem : st.members)
    if (mem.group != "mast") turns[mem.node1] = turns[mem.node2] = true;
  Eigen::VectorXd a = Eigen::VectorXd::Zero(st.free_dofs);
  for (size_t n = 0; n < st.nodes.size(); ++n) {
    if (!turns[n]) continue;
    const Eigen::Vector3d X = st.nodes[n];
    const Eigen::Vector3d t =
        acc * Eigen::Vector3d::UnitZ().cross(X) - rate * rate * Eigen::Vector3d(X.x(), X.y(), 0);
    for (int d = 0; d < 3; ++d)
      if (st.dof_equation[6 * n + d] >= 0) a(st.dof_equation[6 * n + d]) = t(d);
    if (st.dof_equation[6 * n + 5] >= 0) a(st.dof_equation[6 * n + 5]) = acc;
  }
  const Eigen::VectorXd f = -(st.M * a);

  FullStructureSupport full(st, 0.01, 1.0, 10.0, 80.0, 0.0);
  full.enableSlewingLoads();
  full.setSlewMotion(rate, acc);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(st.free_dofs);
  // internalForce = M z'' + C z' + K z - f: at rest, -f.
  EXPECT_LT((full.internalForce(zero, zero, zero) + f).norm(), 1e-9 * f.norm());

  ModalOptions o;
  o.count = 30;
  const ModalBasis b = lowestModes(st.K, st.M, o);
  ModalStructureSupport modal(st, b, 0.01, 80.0, 0.0);
  modal.enableSlewingLoads();
  modal.setSlewMotion(rate, acc);
  const Eigen::VectorXd z0 = Eigen::VectorXd::Zero(30);
  EXPECT_LT((modal.internalForce(z0, z0, z0) + b.phi.transpose() * f).norm(), 1e-9 * f.norm());
  // Off again: no load.
  modal.setSlewMotion(0.0, 0.0);
  EXPECT_LT(modal.internalForce(z0, z0, z0).norm(), 1e-12);
}

TEST(SlewingLoads, SlewingModeCarriesTheRotatingPartsInertia) {
  // r^T M r is the polar moment of inertia about the tower axis of what turns: the lumped
  // masses (counterweight, machinery, ...) m |X_xy|^2 plus the members. A uniform bar from A to
  // B has (m / 3)(|A|^2 + A.B + |B|^2) in the plane; members with one end on a mast node turn
  // only at that end, so they are bounded between 0 and their full value.
  const CraneModel m = t8036({});
  const TowerCraneStructure& st = *m.structure;
  Eigen::VectorXd r, c;
  slewingFields(st, r, c);
  const double Izz = r.dot(st.M * r);
  std::vector<bool> turns(st.nodes.size(), false);
  for (const auto& mem : st.members)
    if (mem.group != "mast") turns[mem.node1] = turns[mem.node2] = true;
  double lumped = 0.0, members = 0.0, mixed = 0.0;
  for (const auto& [node, mass] : st.lumped_masses)
    if (turns[node]) lumped += mass * st.nodes[node].head<2>().squaredNorm();
  for (const auto& mem : st.members) {
    const Eigen::Vector2d A = st.nodes[mem.node1].head<2>(), B = st.nodes[mem.node2].head<2>();
    const BeamSection& sec = st.sections[mem.section];
    const double mass = sec.density * sec.area * (st.nodes[mem.node1] - st.nodes[mem.node2]).norm();
    const double I = mass / 3.0 * (A.squaredNorm() + A.dot(B) + B.squaredNorm());
    if (turns[mem.node1] && turns[mem.node2])
      members += I;
    else if (turns[mem.node1] || turns[mem.node2])
      mixed += I;
  }
  std::printf("slewing inertia %.4g kg m^2: lumped %.4g, members %.4g, mixed members <= %.3g\n",
              Izz, lumped, members, mixed);
  EXPECT_GT(Izz, (lumped + members) * (1 - 1e-3));
  EXPECT_LT(Izz, (lumped + members + mixed) * (1 + 1e-3));
}

TEST(SlewingLoads, StructureRespondsAsTheModalEquationsPredict) {
  // Slewing from rest at the 0.02 rad/s^2 limit; critically damped structure (zeta = 1 in each
  // of 30 modes), the pendulum rope with the trolley at 2.5 m, where the structure's twist
  // hardly moves the trolley point (at 80 m the swinging rope's changed pull would add ~15 % of
  // the response: the first mode, mast torsion at 0.10 Hz, is soft). The difference between
  // runs with the loads on and off is then the structure's response to the load alone.
  // Independently of the time integrator, each mode obeys z'' + 2 w z' + w^2 z = f(s) = -(alpha T^T
  // M r + (alpha s)^2 T^T M c), whose solution from rest is the Duhamel integral z(t) = int_0^t (t
  // - s) e^{-w (t - s)} f(s) ds (evaluated here by Simpson's rule); and at constant speed the
  // structure settles on the static response of the centrifugal load, K u = -theta'^2 M c, solved
  // here by CHOLMOD.
  const double alpha = 0.02;
  auto run = [](bool loads, double seconds) {
    const CraneModel m =
        t8036({"rope.model=pendulum", "structure.modes=30", "trolley.radius=2.5",
               "structure.damping_ratio=1", "initial.swing_deg=0", "time_step=0.005",
               std::string("slewing.inertial_loads=") + (loads ? "true" : "false"),
               "commands=[{t: 0, slew_rate: 0.084}]"});
    PendulumCraneSimulation sim(m);
    sim.initialize();
    for (long k = 0; k < std::lround(seconds / 0.005); ++k) sim.step();
    return sim.support().jibTipDisplacement(sim.state().z);
  };
  const CraneModel m = t8036({"structure.modes=30"});
  const TowerCraneStructure& st = *m.structure;
  ModalOptions o;
  o.count = 30;
  const ModalBasis b = lowestModes(st.K, st.M, o);
  ModalStructureSupport modal(st, b, 0.01, 2.5, 0.0);
  Eigen::VectorXd r, c;
  slewingFields(st, r, c);
  const Eigen::VectorXd er = b.phi.transpose() * (st.M * r), ec = b.phi.transpose() * (st.M * c);

  // While accelerating (t = 4 s, rate 0.08 rad/s).
  const double t = 4.0;
  Eigen::VectorXd z = Eigen::VectorXd::Zero(30);
  const int n = 4000;
  for (int i = 0; i < 30; ++i) {
    const double w = std::sqrt(b.omega2(i));
    double sum = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double sk = t * k / n;
      const double wgt = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
      sum += wgt * (t - sk) * std::exp(-w * (t - sk)) *
             -(alpha * er(i) + alpha * alpha * sk * sk * ec(i));
    }
    z(i) = sum * t / (3.0 * n);
  }
  const Eigen::Vector3d duhamel = modal.jibTipDisplacement(z);
  const Eigen::Vector3d d = run(true, t) - run(false, t);
  std::printf(
      "jib tip from the slewing loads at t = 4 s: run (%.4f, %.4f, %.4f) m, Duhamel "
      "(%.4f, %.4f, %.4f) m\n",
      d.x(), d.y(), d.z(), duhamel.x(), duhamel.y(), duhamel.z());
  // The Euler load bends the jib back against the slewing direction (-y for theta'' > 0).
  EXPECT_LT(d.y(), -0.1);
  EXPECT_NEAR(d.y(), duhamel.y(), 0.02 * std::abs(duhamel.y()));

  // At constant speed (0.084 rad/s from t = 4.2 s), 40 s on: the centrifugal load's statics.
  const double w = 0.084;
  const Eigen::Vector3d dc = run(true, 44.2) - run(false, 44.2);
  Eigen::CholmodSupernodalLLT<SparseMatrix> llt(st.K);
  const Eigen::Vector3d fe =
      jibTipDisplacement(st, llt.solve(Eigen::VectorXd(-(st.M * (w * w * c)))));
  std::printf(
      "jib tip at constant speed: run (%.5f, %.5f, %.5f) m, FE static (%.5f, %.5f, %.5f) m\n",
      dc.x(), dc.y(), dc.z(), fe.x(), fe.y(), fe.z());
  // Flung outwards (+x) and the jib tip dips: the radial-vertical plane of the centrifugal
  // load. Sideways (y) the run keeps ~0.7 mm from the swinging rope: the load-on run's trolley
  // point twisted 0.09 m further during the start, so its payload swings a little differently.
  EXPECT_GT(fe.x(), 0.0);
  EXPECT_NEAR(dc.x(), fe.x(), 0.05 * std::abs(fe.x()));
  EXPECT_NEAR(dc.z(), fe.z(), 0.05 * std::abs(fe.z()));
}

// A sub-step of a halved step holds the rope at the drives' pose of its own end time
// (RopeSupport::setStepFraction): the trolley point at fraction f of a step that slews from
// theta0 to theta1 and moves the trolley from R0 to R1 is the point of the pose
// (theta0 + f (theta1 - theta0), R0 + f (R1 - R0)), computed here by setPose itself; f = 1 is the
// step's end pose again, and a step without drive motion keeps its pose.
TEST(SlewingLoads, AStepFractionHoldsTheSupportAtThePoseOfThatTime) {
  const CraneModel m = t8036({});
  const TowerCraneStructure& st = *m.structure;
  const double th0 = 0.30, th1 = 0.3001, r0 = 40.0, r1 = 40.001;
  for (const bool rigid : {false, true}) {
    SCOPED_TRACE(rigid ? "rigid" : "modal");
    ModalOptions o;
    o.count = 10;
    const ModalBasis b = lowestModes(st.K, st.M, o);
    std::unique_ptr<RopeSupport> s, probe;
    if (rigid) {
      s = std::make_unique<RigidTrolleySupport>(st, r1, th1);
      probe = std::make_unique<RigidTrolleySupport>(st, r1, th1);
    } else {
      s = std::make_unique<ModalStructureSupport>(st, b, 0.01, r1, th1);
      probe = std::make_unique<ModalStructureSupport>(st, b, 0.01, r1, th1);
    }
    Eigen::VectorXd z = Eigen::VectorXd::Zero(s->size());
    for (int k = 0; k < z.size(); ++k) z(k) = 0.01 * (k + 1);
    const Eigen::Vector3d end = s->point(z);
    s->setPoseStep(th0, r0, th1, r1);
    EXPECT_EQ((s->point(z) - end).norm(), 0.0);
    for (const double f : {0.5, 0.25, 0.75}) {
      s->setStepFraction(f);
      probe->setPose(th0 + f * (th1 - th0), r0 + f * (r1 - r0));
      EXPECT_LT((s->point(z) - probe->point(z)).norm(), 1e-12);
      EXPECT_GT((s->point(z) - end).norm(), 1e-4 * (1.0 - f));
    }
    s->setStepFraction(1.0);
    EXPECT_LT((s->point(z) - end).norm(), 1e-12);
    s->setPoseStep(th1, r1, th1, r1);
    s->setStepFraction(0.5);
    EXPECT_LT((s->point(z) - end).norm(), 1e-12);
  }
}

TEST(SlewingLoads, IterationWeightsFollowTheWeightsAndThePose) {
  // The modal support keeps G = D A_z^-1 D^T (A_z = a I + c 2 zeta Omega + k Omega^2) while the
  // weights and the pose are those it was computed for: every answer must be the one computed
  // here from the support's point rows (pointMotion of unit coordinates) and its frequencies,
  // whatever came before it, a repeated pose or weight set included.
  const CraneModel m = t8036({});
  const TowerCraneStructure& st = *m.structure;
  ModalOptions o;
  o.count = 10;
  const ModalBasis b = lowestModes(st.K, st.M, o);
  ModalStructureSupport s(st, b, 0.01, 40.0, 0.3);
  const auto expected = [&](double a, double c, double k, Eigen::VectorXd& diag) {
    diag = Eigen::VectorXd::Constant(s.size(), a) + c * s.dampingTerms() + k * s.omega2();
    Eigen::Matrix<double, 3, Eigen::Dynamic> D(3, s.size());
    for (int j = 0; j < s.size(); ++j) D.col(j) = s.pointMotion(Eigen::VectorXd::Unit(s.size(), j));
    return Eigen::Matrix3d(D * diag.cwiseInverse().asDiagonal() * D.transpose());
  };
  struct Case {
    double a, c, k, theta, radius;
  };
  const double h = 1e-3;
  const std::vector<Case> cases = {{1.0, 0.5 * h, 0.25 * h * h, 0.3, 40.0},
                                   {1.0, 0.5 * h, 0.25 * h * h, 0.3, 40.0},
                                   {1.2, 0.6 * h, 0.3 * h * h, 0.3, 40.0},
                                   {1.2, 0.6 * h, 0.3 * h * h, 1.1, 25.0},
                                   {1.0, 0.5 * h, 0.25 * h * h, 1.1, 25.0},
                                   {1.0, 0.5 * h, 0.25 * h * h, 0.3, 40.0},
                                   {1.0, 0.0, 0.0, 0.3, 40.0},
                                   {1.0, 0.0, 0.0, 0.3, 40.0}};
  const Eigen::VectorXd r = Eigen::VectorXd::LinSpaced(s.size(), 1.0, 2.0);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    s.setPose(c.theta, c.radius);
    const Eigen::Matrix3d G = s.setIterationWeights(c.a, c.c, c.k);
    Eigen::VectorXd diag;
    const Eigen::Matrix3d G0 = expected(c.a, c.c, c.k, diag);
    EXPECT_LT((G - G0).norm(), 1e-12 * G0.norm()) << "case " << i;
    EXPECT_LT((s.solve(r) - r.cwiseQuotient(diag)).norm(), 1e-12 * r.norm()) << "case " << i;
  }
}
