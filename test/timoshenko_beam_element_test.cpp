// Closed-form checks of the 3D Timoshenko beam element (docs/model.md): tip deflection with shear,
// Euler-Bernoulli cantilever frequencies, axial and torsional frequencies, rigid-body modes,
// and mesh convergence where shear matters. Eigenvalues here come from Eigen's dense solver,
// independent of the ARPACK path used for the crane.
#include "crane_twin/elements/timoshenko_beam_element.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "crane_twin/elements/sparse_assembly.hpp"

using namespace crane_twin;

namespace {

// Cantilever along the direction `axis`, n elements, node 0 clamped. Matrices over the free DOFs.
struct Cantilever {
  Eigen::MatrixXd K, M;
  int n;
};

Cantilever cantilever(const BeamSection& s, double L, int n,
                      const Eigen::Vector3d& axis = Eigen::Vector3d::UnitX(),
                      const Eigen::Vector3d& orient = Eigen::Vector3d::UnitY()) {
  const int free = 6 * n;
  SparseAssembler KA(free), MA(free);
  for (int e = 0; e < n; ++e) {
    const Eigen::Vector3d p1 = axis * (L * e / n), p2 = axis * (L * (e + 1) / n);
    const auto m = timoshenkoBeamGlobal(s, p1, p2, orient);
    std::vector<int> eq(12);
    for (int d = 0; d < 12; ++d) {
      const int node = e + d / 6;
      eq[d] = node == 0 ? -1 : 6 * (node - 1) + d % 6;
    }
    KA.add(m.K, eq);
    MA.add(m.M, eq);
  }
  return {Eigen::MatrixXd(KA.build()), Eigen::MatrixXd(MA.build()), n};
}

Eigen::VectorXd frequencies(const Cantilever& c) {
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(c.K, c.M);
  return es.eigenvalues().cwiseSqrt();
}

// Rectangular steel section; b along local y, h along local z.
BeamSection rect(double b, double h) { return BeamSection::rectangle(b, h, 2.1e11, 8.1e10, 7850); }

}  // namespace

TEST(TimoshenkoBeam, RigidBodyModesAndSymmetry) {
  const BeamSection s = BeamSection::circularTube(0.2, 0.01, 2.1e11, 8.1e10, 7850);
  const Eigen::Vector3d p1(1, 2, 3), p2(2.5, 1.0, 4.2);
  const auto m = timoshenkoBeamGlobal(s, p1, p2, Eigen::Vector3d(0, 0, 1));
  EXPECT_LT((m.K - m.K.transpose()).norm(), 1e-9 * m.K.norm());
  EXPECT_LT((m.M - m.M.transpose()).norm(), 1e-12 * m.M.norm());
  // Translations and small rotations (u = w x p at each node, theta = w) do no work.
  for (int k = 0; k < 6; ++k) {
    Eigen::Matrix<double, 12, 1> u = Eigen::Matrix<double, 12, 1>::Zero();
    if (k < 3) {
      u(k) = u(6 + k) = 1.0;
    } else {
      Eigen::Vector3d w = Eigen::Vector3d::Zero();
      w(k - 3) = 1.0;
      u.segment<3>(0) = w.cross(p1);
      u.segment<3>(3) = w;
      u.segment<3>(6) = w.cross(p2);
      u.segment<3>(9) = w;
    }
    EXPECT_LT((m.K * u).norm(), 1e-6 * m.K.norm()) << "rigid mode " << k;
  }
  // Total translational mass.
  Eigen::Matrix<double, 12, 1> t = Eigen::Matrix<double, 12, 1>::Zero();
  t(2) = t(8) = 1.0;
  EXPECT_NEAR(t.dot(m.M * t), s.density * s.area * (p2 - p1).norm(), 1e-9);
}

TEST(TimoshenkoBeam, LocalAxesRejectDegenerateInput) {
  EXPECT_THROW(beamLocalAxes({0, 0, 0}, {0, 0, 0}, {0, 0, 1}), std::invalid_argument);
  EXPECT_THROW(beamLocalAxes({0, 0, 0}, {0, 0, 2}, {0, 0, 1}), std::invalid_argument);
}

TEST(TimoshenkoBeam, CantileverTipDeflectionWithShear) {
  // Deep beam: shear is 6 % (y) and 22 % (z) of the deflection. P L^3 / 3EI + P L / (k G A).
  const double L = 1.0, P = 1e5;
  const BeamSection s = rect(0.3, 0.6);
  for (int n : {1, 4}) {
    const Cantilever c = cantilever(s, L, n);
    for (int dir : {1, 2}) {  // load along local y (bending about z), then local z
      Eigen::VectorXd F = Eigen::VectorXd::Zero(6 * n);
      F(6 * (n - 1) + dir) = P;
      const Eigen::VectorXd u = c.K.ldlt().solve(F);
      const double EI = s.E * (dir == 1 ? s.Iz : s.Iy);
      const double GAs = s.G * (dir == 1 ? s.shear_area_y : s.shear_area_z);
      const double exact = P * L * L * L / (3 * EI) + P * L / GAs;
      EXPECT_NEAR(u(6 * (n - 1) + dir), exact, 1e-9 * exact) << "n = " << n << " dir " << dir;
      const double shearPart = P * L / GAs;
      EXPECT_GT(shearPart, 0.02 * exact);  // the case really tests shear
    }
  }
}

TEST(TimoshenkoBeam, EulerBernoulliCantileverFrequencies) {
  // Slender beam (L/h = 200): beta L = 1.8751, 4.6941, 7.8548 within 0.5 %.
  const double L = 20.0;
  const BeamSection s = rect(0.1, 0.2);  // Iz < Iy: y-bending modes come first
  const Cantilever c = cantilever(s, L, 40);
  const Eigen::VectorXd w = frequencies(c);
  const double EI = s.E * s.Iz, m = s.density * s.area;
  const double betaL[3] = {1.8751, 4.6941, 7.8548};
  // Collect the y-bending frequencies: the eigenvalues closest to the analytic ones.
  for (double bl : betaL) {
    const double exact = bl * bl / (L * L) * std::sqrt(EI / m);
    double best = 1e300;
    for (int i = 0; i < w.size(); ++i) best = std::min(best, std::abs(w(i) - exact) / exact);
    EXPECT_LT(best, 0.005) << "beta L = " << bl;
  }
  // The lowest mode is exactly the first y-bending mode.
  EXPECT_NEAR(w(0), 1.8751 * 1.8751 / (L * L) * std::sqrt(EI / m), 0.005 * w(0));
}

TEST(TimoshenkoBeam, AxialAndTorsionalFrequencies) {
  // Fixed-free rod: w_n = (2n - 1) pi / (2L) sqrt(E / rho); torsion with sqrt(G J / (rho Ip)).
  const double L = 10.0;
  const BeamSection s = BeamSection::circularTube(0.3, 0.02, 2.1e11, 8.1e10, 7850);
  const Cantilever c = cantilever(s, L, 60, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
  const Eigen::VectorXd w = frequencies(c);
  auto closest = [&](double target) {
    double best = 1e300;
    for (int i = 0; i < w.size(); ++i) best = std::min(best, std::abs(w(i) - target) / target);
    return best;
  };
  for (int n = 1; n <= 3; ++n) {
    const double wa = (2 * n - 1) * M_PI / (2 * L) * std::sqrt(s.E / s.density);
    const double wt =
        (2 * n - 1) * M_PI / (2 * L) * std::sqrt(s.G * s.J / (s.density * (s.Iy + s.Iz)));
    EXPECT_LT(closest(wa), 0.005) << "axial mode " << n;
    EXPECT_LT(closest(wt), 0.005) << "torsional mode " << n;
  }
}

TEST(TimoshenkoBeam, MeshConvergenceWhenShearMatters) {
  // Deep beam (L/b = 4 in the weak plane): coarse meshes converge to the fine one, and shear
  // with rotary inertia lowers the first frequency well below the Euler-Bernoulli value.
  const double L = 1.2;
  const BeamSection s = rect(0.3, 0.6);
  const double fine = frequencies(cantilever(s, L, 128))(0);
  double prevErr = 1e300;
  for (int n : {2, 4, 8, 16, 32}) {
    const double err = std::abs(frequencies(cantilever(s, L, n))(0) - fine) / fine;
    EXPECT_LT(err, prevErr) << "n = " << n;
    prevErr = err;
  }
  EXPECT_LT(prevErr, 1e-4);
  EXPECT_LT(std::abs(frequencies(cantilever(s, L, 8))(0) - fine) / fine, 0.01);
  const double EI = s.E * s.Iz, m = s.density * s.area;
  const double eb = 1.8751 * 1.8751 / (L * L) * std::sqrt(EI / m);
  EXPECT_LT(fine, 0.98 * eb);  // measured: 4.6 % below Euler-Bernoulli
}
