// Discrete gradients of the rope's strain energies (docs/model.md "Energy-consistent step"):
// the defining identity G . (x1 - x0) = U(x1) - U(x0) across slack/taut switches, the limit
// G(x, x) = grad U(x), and the Newton matrix's stand-in against finite differences.
#include "crane_twin/elements/discrete_gradient.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "crane_twin/elements/ancf_cable_element.hpp"
#include "crane_twin/elements/gauss_legendre.hpp"
#include "crane_twin/rope/pendulum_rope.hpp"

using namespace crane_twin;

namespace {

// A curved element about the x axis: a circular arc of radius R and length l, stretched by
// 1 + eps (slopes of length 1 + eps), so that both bending and the axial law act.
Vector12 arc(double eps, double R, double l) {
  const double g = 1.0 + eps, phi = l / R;
  Vector12 e;
  e << 0.0, 0.0, 0.0, g, 0.0, 0.0,  //
      g * R * std::sin(phi), g * R * (1.0 - std::cos(phi)), 0.0, g * std::cos(phi),
      g * std::sin(phi), 0.0;
  return e;
}

AncfCableProperties cable(bool tension_only) {
  AncfCableProperties p;
  p.length = 0.5;
  p.mass_per_length = 1.2;
  p.axial_stiffness = 2.2e7;
  p.bending_stiffness = 40.0;
  p.tension_only = tension_only;
  return p;
}

// A random change of the coordinates of size `size` (slopes and positions alike).
Vector12 perturbation(std::mt19937& rng, double size) {
  std::normal_distribution<double> n(0.0, size);
  Vector12 d;
  for (int i = 0; i < 12; ++i) d(i) = n(rng);
  return d;
}

}  // namespace

TEST(DiscreteGradient, ElementWorkEqualsTheEnergyChangeAcrossSlackTautSwitches) {
  std::mt19937 rng(7);
  for (bool tension_only : {true, false}) {
    const AncfCableProperties p = cable(tension_only);
    // Taut to slack, slack to taut, within the smoothing band, deep slack, and the guard.
    const double strains[][2] = {{2e-3, -2e-3},  {-3e-3, 1e-3}, {4e-6, -6e-6},
                                 {-5e-2, -1e-2}, {-0.25, -0.1}, {1e-3, 1.5e-3}};
    for (const auto& st : strains) {
      for (int k = 0; k < 5; ++k) {
        const Vector12 e0 = arc(st[0], 30.0, p.length) + perturbation(rng, 1e-4);
        const Vector12 e1 = arc(st[1], 25.0, p.length) + perturbation(rng, 1e-4);
        Vector12 Q;
        ancfElasticForceDiscreteGradient(p, e0, e1, Q);
        const double dU = ancfElasticEnergy(p, e1) - ancfElasticEnergy(p, e0);
        // Round-off of U, which holds the axial energy of the larger strain: EA l eps^2 / 2.
        const double eps = std::max(std::abs(st[0]), std::abs(st[1]));
        const double scale = p.axial_stiffness * p.length * eps * eps + std::abs(dU);
        EXPECT_NEAR(Q.dot(e1 - e0), dU, 1e-12 * scale)
            << "tension_only " << tension_only << " eps " << st[0] << " -> " << st[1];
      }
    }
  }
}

TEST(DiscreteGradient, ElementLimitIsTheElasticForceAndTangent) {
  std::mt19937 rng(11);
  for (bool tension_only : {true, false}) {
    const AncfCableProperties p = cable(tension_only);
    for (double eps : {2e-3, 3e-6, -4e-6, -1e-2}) {
      const Vector12 e = arc(eps, 40.0, p.length) + perturbation(rng, 1e-5);
      Vector12 Q, Qdg;
      Matrix12 K, Kdg;
      ancfElasticForce(p, e, Q, &K);
      ancfElasticForceDiscreteGradient(p, e, e, Qdg, &Kdg);
      // Both paths round the axial force at about 1e-16 EA (N from |a| here, from |a|^2 there).
      EXPECT_LE((Qdg - Q).norm(), 1e-12 * Q.norm() + 1e-15 * p.axial_stiffness) << eps;
      EXPECT_LE((Kdg - K).norm(), 1e-10 * K.norm()) << eps;
    }
  }
}

TEST(DiscreteGradient, ElementNewtonMatrixIsTwiceTheDerivativeInTheLimit) {
  // The stand-in K of the step's Newton matrix against central differences of 2 Q(e0, e1) in
  // e1 along a fixed direction of steps: they differ by terms of the order of the step
  // |e1 - e0| (the stand-in is symmetric, the exact derivative is not), so the difference
  // shrinks in proportion to the step (measured: 5.3 x the step's size per coordinate).
  std::mt19937 rng(3);
  const Vector12 dir = perturbation(rng, 1.0);
  for (double EI : {0.0, 40.0}) {
    AncfCableProperties p = cable(true);
    p.bending_stiffness = EI;
    const Vector12 e0 = arc(1e-3, 30.0, p.length);
    double previous = 0.0;
    for (double step : {1e-3, 1e-4, 1e-5}) {
      const Vector12 e1 = e0 + step * dir;
      Vector12 Q;
      Matrix12 K;
      ancfElasticForceDiscreteGradient(p, e0, e1, Q, &K);
      Matrix12 fd;
      const double h = 1e-7;
      for (int j = 0; j < 12; ++j) {
        Vector12 ep = e1, em = e1, Qp, Qm;
        ep(j) += h;
        em(j) -= h;
        ancfElasticForceDiscreteGradient(p, e0, ep, Qp);
        ancfElasticForceDiscreteGradient(p, e0, em, Qm);
        fd.col(j) = (Qp - Qm) / h;  // 2 dQ/de1
      }
      const double rel = (fd - K).norm() / K.norm();
      EXPECT_LT(rel, 10.0 * step) << "EI " << EI << " step " << step;
      if (previous > 0.0) {
        EXPECT_LT(rel, 0.2 * previous) << "EI " << EI << " step " << step;
      }
      previous = rel;
    }
  }
}

TEST(DiscreteGradient, BarWorkEqualsTheEnergyChangeAndLimitIsTheForce) {
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  for (bool tension_only : {true, false}) {
    PendulumRope bar(5.0, 1.0, 2.0e7, 3000.0, g);
    bar.setTensionOnly(tension_only);
    const Eigen::Vector3d top(1.0, 2.0, 3.0);
    for (const auto& l01 : {std::pair{5.003, 4.99}, {4.98, 5.001}, {5.002, 5.004}, {4.9, 4.95}}) {
      const Vector6 q0 = PendulumRope::straight(top, Eigen::Vector3d(0.6, 0.0, -0.8), l01.first);
      const Vector6 q1 = PendulumRope::straight(top, Eigen::Vector3d(0.0, 0.6, -0.8), l01.second);
      Vector6 Q;
      bar.discreteGradientForce(q0, q1, Q);
      const double dU = bar.elasticEnergy(q1) - bar.elasticEnergy(q0);
      EXPECT_NEAR(Q.dot(q1 - q0), dU, 1e-12 * (2.0e7 / 5.0 * 0.01 * 0.01 + std::abs(dU)));
      Vector6 Qe, Qdg;
      Matrix6 Ke, Kdg;
      bar.elasticForce(q0, Qe, &Ke);
      bar.discreteGradientForce(q0, q0, Qdg, &Kdg);
      EXPECT_LE((Qdg - Qe).norm(), 1e-9 * (1.0 + Qe.norm()));
      EXPECT_LE((Kdg - Ke).norm(), 1e-9 * (1.0 + Ke.norm()));
    }
  }
}

TEST(DiscreteGradient, SquaredLengthSecantIsTheSecantAndItsLimit) {
  // W(s) = s^3: the secant (s1^3 - s0^3) / (s1 - s0) = s0^2 + s0 s1 + s1^2; its derivative in
  // s1 is s0 + 2 s1; the limit 3 s^2 and 3 s (W'' / 2).
  const auto W = [](double s) { return s * s * s; };
  const auto dW = [](double s) { return 3.0 * s * s; };
  const auto ddW = [](double s) { return 6.0 * s; };
  const SquaredLengthSecant a = squaredLengthSecant(1.0, 1.5, W, dW, ddW);
  EXPECT_NEAR(a.slope, 1.0 + 1.5 + 2.25, 1e-14);
  EXPECT_NEAR(a.curvature, (dW(1.5) - a.slope) / 0.5, 1e-14);
  EXPECT_NEAR(a.curvature, 1.0 + 2.0 * 1.5, 1e-12);  // d/ds1 (s0^2 + s0 s1 + s1^2) = s0 + 2 s1
  const SquaredLengthSecant b = squaredLengthSecant(1.2, 1.2 + 1e-10, W, dW, ddW);
  EXPECT_NEAR(b.slope, 3.0 * 1.2 * 1.2, 1e-9);
  EXPECT_NEAR(b.curvature, 3.0 * 1.2, 1e-9);
}

TEST(DiscreteGradient, PointWorkEqualsTheDensityChangeAndLimitIsTheGradient) {
  // One point of the rope (what the reduced rope integrates at its own Gauss points): the work
  // fa . da + fb . db equals phi(a1, b1) - phi(a0, b0) across the slack edge, and for a1 = a0,
  // b1 = b0 it is the density's gradient (ancfCablePoint).
  const double EA = 2.2e7, EI = 40.0, l = 0.5;
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto vec = [&](double s) { return Eigen::Vector3d(s * n(rng), s * n(rng), s * n(rng)); };
  int switches = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // Stretches either side of the slack edge: |a| - 1 from -2e-4 to 2e-4.
    const Eigen::Vector3d t0 = vec(1.0).normalized(), t1 = (t0 + vec(0.05)).normalized();
    const double eps0 = 2e-4 * (2.0 * (trial % 7) / 6.0 - 1.0);
    const double eps1 = 2e-4 * (2.0 * ((trial / 7) % 5) / 4.0 - 1.0);
    const Eigen::Vector3d a0 = (1.0 + eps0) * t0, a1 = (1.0 + eps1) * t1;
    const Eigen::Vector3d b0 = vec(0.3), b1 = b0 + vec(0.01);
    if ((eps0 < -kSlackBand) != (eps1 < -kSlackBand)) ++switches;
    CablePointDerivatives d;
    ancfCablePointDiscreteGradient(EA, EI, l, a0, b0, a1, b1, false, d, true);
    const double dU =
        ancfCableEnergyDensity(EA, EI, a1, b1, true) - ancfCableEnergyDensity(EA, EI, a0, b0, true);
    const double scale = std::abs(ancfCableEnergyDensity(EA, EI, a0, b0, true)) +
                         std::abs(ancfCableEnergyDensity(EA, EI, a1, b1, true)) + 1e-3;
    EXPECT_NEAR(d.fa.dot(a1 - a0) + d.fb.dot(b1 - b0), dU, 1e-9 * scale) << "trial " << trial;
    // The limit: the gradient at the point.
    CablePointDerivatives g, lim;
    ancfCablePoint(EA, EI, a1, b1, false, g, true);
    ancfCablePointDiscreteGradient(EA, EI, l, a1, b1, a1, b1, false, lim, true);
    EXPECT_LT((lim.fa - g.fa).norm(), 1e-9 * (g.fa.norm() + 1.0)) << "trial " << trial;
    EXPECT_LT((lim.fb - g.fb).norm(), 1e-9 * (g.fb.norm() + 1.0)) << "trial " << trial;
  }
  EXPECT_GT(switches, 20);  // the sample crosses the slack edge
}

TEST(DiscreteGradient, AxialSwitchWorkErrorIsTheTrapezoidsError) {
  // Zero where both ends are in the linear range (the trapezoid is exact for a quadratic
  // energy); across the edge, the closed form of a step from slack (-1e-3) to taut (eps1):
  // trapezoid (N1 / 2) (eps1 + 1e-3) against the energy psi(eps1) = EA eps1^2 / 2 + EA d^2 / 6.
  const double EA = 2.2e7, d = kSlackBand;
  EXPECT_EQ(ancfAxialSwitchWorkError(EA, 1e-4, 3e-4), 0.0);
  for (const double eps1 : {1e-4, 5e-4, 2e-3}) {
    const double trapezoid = 0.5 * EA * eps1 * (eps1 + 1e-3);
    const double exact = 0.5 * EA * eps1 * eps1 + EA * d * d / 6.0;
    EXPECT_NEAR(ancfAxialSwitchWorkError(EA, -1e-3, eps1), std::abs(trapezoid - exact),
                1e-12 * exact);
  }
}

TEST(DiscreteGradient, StepStartAtTheGaussPointsIsThePointsOwnStateAndEnergies) {
  // The full-order step evaluates the start of its step once (ancfElementStepStart) for all its
  // Newton iterates: each point's share must be S_x e0, S_xx e0 and the densities there, and the
  // element's discrete gradient from it the one from e0, to the last bit.
  std::mt19937 rng(11);
  for (bool tension_only : {true, false}) {
    AncfCableProperties p = cable(tension_only);
    for (int points : {3, 5}) {
      p.gauss_points = points;
      // Taut at the start, slack at the end (for tension_only).
      const Vector12 e0 = arc(2e-3, 30.0, p.length) + perturbation(rng, 1e-5);
      const Vector12 e1 = arc(-1e-3, 25.0, p.length) + perturbation(rng, 1e-5);
      std::vector<CablePointStepStart> start(points);
      ancfElementStepStart(p, e0, start.data());
      Eigen::VectorXd x, w;
      gaussLegendre01(points, x, w);
      for (int q = 0; q < points; ++q) {
        const Eigen::Vector4d sx = ancfShapeDx(x(q), p.length), sxx = ancfShapeDxx(x(q), p.length);
        Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
        for (int k = 0; k < 4; ++k) {
          a += sx(k) * e0.segment<3>(3 * k);
          b += sxx(k) * e0.segment<3>(3 * k);
        }
        EXPECT_LT((start[q].a - a).norm(), 1e-15);
        EXPECT_LT((start[q].b - b).norm(), 1e-12);
        // The two densities add up to the point's energy density.
        EXPECT_NEAR(
            start[q].axial_energy + start[q].bending_energy,
            ancfCableEnergyDensity(p.axial_stiffness, p.bending_stiffness, a, b, tension_only),
            1e-9 * (start[q].axial_energy + start[q].bending_energy));
        EXPECT_GT(start[q].axial_energy, 0.0);
        EXPECT_GT(start[q].bending_energy, 0.0);
      }
      Vector12 Qa, Qb;
      Matrix12 Ka, Kb;
      ancfElasticForceDiscreteGradient(p, e0, e1, Qa, &Ka);
      ancfElasticForceDiscreteGradient(p, start.data(), e1, Qb, &Kb);
      EXPECT_EQ((Qa - Qb).cwiseAbs().maxCoeff(), 0.0);
      EXPECT_EQ((Ka - Kb).cwiseAbs().maxCoeff(), 0.0);
    }
  }
}
