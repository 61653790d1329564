// Checks of the ANCF cable element against docs/model.md: shape functions, mass, and the analytic
// force and tangent against finite differences of the energy.
#include "crane_twin/elements/ancf_cable_element.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>
#include <random>
#include <vector>

#include "crane_twin/elements/gauss_legendre.hpp"

using namespace crane_twin;

namespace {

AncfCableProperties ropeElement() {
  AncfCableProperties p;
  p.length = 0.5;
  p.mass_per_length = 3.8;
  p.axial_stiffness = 4.4e7;
  p.bending_stiffness = 157.0;
  return p;
}

// Straight reference element along direction d, starting at r0.
Vector12 straight(const Eigen::Vector3d& r0, const Eigen::Vector3d& d, double l) {
  Vector12 e;
  e << r0, d, r0 + l * d, d;
  return e;
}

Vector12 stretched() {
  Vector12 e = straight({1, 2, 3}, Eigen::Vector3d::UnitX(), 0.5);
  e(6) += 0.5 * 2e-3;   // 0.2 % strain
  e(3) = e(9) = 1.002;  // matching slopes
  return e;
}

Vector12 bent() {
  // In-plane arc: slopes rotated +-0.05 rad about z, small stretch.
  Vector12 e = straight({0, 0, 0}, Eigen::Vector3d::UnitX(), 0.5);
  e.segment<3>(3) = 1.001 * Eigen::Vector3d(std::cos(0.05), -std::sin(0.05), 0);
  e.segment<3>(9) = 1.0005 * Eigen::Vector3d(std::cos(0.05), std::sin(0.05), 0);
  e.segment<3>(6) = Eigen::Vector3d(0.5002, 0.0, 0.0);
  return e;
}

Vector12 curved3d() {
  // 3D-curved element with near-uniform stretch (r2 consistent with the end slopes), the state
  // a tensioned rope element is in.
  Vector12 e;
  e << 0.3, -0.2, 5.0, 0.04, 0.01, -1.0005, 0.305, -0.185, 4.50012, -0.02, 0.05, -0.999;
  return e;
}

Vector12 twisted() {
  // Out-of-plane (3D) bending: end slopes tilted in different planes.
  Vector12 e = straight({0.3, -0.2, 5.0}, Eigen::Vector3d(0, 0, -1), 0.5);
  e.segment<3>(3) = Eigen::Vector3d(0.04, 0.01, -1.0005);
  e.segment<3>(9) = Eigen::Vector3d(-0.02, 0.05, -0.999);
  e.segment<3>(6) += Eigen::Vector3d(0.003, -0.004, -0.0007);
  return e;
}

void expectForceIsEnergyGradient(const AncfCableProperties& p, const Vector12& e) {
  Vector12 Q;
  ancfElasticForce(p, e, Q);
  Vector12 fd;
  for (int i = 0; i < 12; ++i) {
    const double h = 1e-6 * std::max(1.0, std::abs(e(i)));
    Vector12 ep = e, em = e;
    ep(i) += h;
    em(i) -= h;
    fd(i) = (ancfElasticEnergy(p, ep) - ancfElasticEnergy(p, em)) / (2 * h);
  }
  EXPECT_LT((Q - fd).norm(), 1e-6 * Q.norm())
      << "Q = " << Q.transpose() << "\nfd = " << fd.transpose();
}

void expectTangentIsForceJacobian(const AncfCableProperties& p, const Vector12& e) {
  Vector12 Q;
  Matrix12 K;
  ancfElasticForce(p, e, Q, &K);
  Matrix12 fd;
  for (int i = 0; i < 12; ++i) {
    const double h = 1e-7;
    Vector12 ep = e, em = e, Qp, Qm;
    ep(i) += h;
    em(i) -= h;
    ancfElasticForce(p, ep, Qp);
    ancfElasticForce(p, em, Qm);
    fd.col(i) = (Qp - Qm) / (2 * h);
  }
  EXPECT_LT((K - fd).norm(), 1e-6 * K.norm());
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
}

}  // namespace

TEST(AncfShape, PartitionOfUnityAndInterpolation) {
  const double l = 0.7;
  for (double xi = 0.0; xi <= 1.0; xi += 0.05) {
    const Eigen::Vector4d s = ancfShape(xi, l);
    EXPECT_NEAR(s(0) + s(2), 1.0, 1e-15);
    // A straight line r = r0 + x d is reproduced exactly (S2 + S4 + l S3 = x).
    EXPECT_NEAR(s(1) + s(3) + l * s(2), xi * l, 1e-15);
  }
  Vector12 e;
  e.setRandom();
  EXPECT_LT((ancfPosition(e, 0.0, l) - e.segment<3>(0)).norm(), 1e-15);
  EXPECT_LT((ancfPosition(e, 1.0, l) - e.segment<3>(6)).norm(), 1e-15);
  // Derivative shape functions: central differences of S, S_x.
  for (double xi : {0.1, 0.3, 0.8, 0.95}) {
    const double h = 1e-5;
    const Eigen::Vector4d fd = (ancfShape(xi + h, l) - ancfShape(xi - h, l)) / (2 * h * l);
    EXPECT_LT((fd - ancfShapeDx(xi, l)).norm(), 1e-8);
    const Eigen::Vector4d fd2 = (ancfShapeDx(xi + h, l) - ancfShapeDx(xi - h, l)) / (2 * h * l);
    EXPECT_LT((fd2 - ancfShapeDxx(xi, l)).norm(), 1e-8);
  }
  // Nodal slopes.
  Eigen::Vector3d rx0 = Eigen::Vector3d::Zero(), rx1 = Eigen::Vector3d::Zero();
  const Eigen::Vector4d d0 = ancfShapeDx(0.0, l), d1 = ancfShapeDx(1.0, l);
  for (int k = 0; k < 4; ++k) {
    rx0 += d0(k) * e.segment<3>(3 * k);
    rx1 += d1(k) * e.segment<3>(3 * k);
  }
  EXPECT_LT((rx0 - e.segment<3>(3)).norm(), 1e-14);
  EXPECT_LT((rx1 - e.segment<3>(9)).norm(), 1e-14);
}

TEST(AncfShape, GaussRuleIntegratesPolynomialsExactly) {
  for (int n = 1; n <= 10; ++n) {
    Eigen::VectorXd x, w;
    gaussLegendre01(n, x, w);
    for (int deg = 0; deg <= 2 * n - 1; ++deg) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += w(i) * std::pow(x(i), deg);
      EXPECT_NEAR(sum, 1.0 / (deg + 1), 1e-14) << "n = " << n << " degree " << deg;
    }
  }
  Eigen::VectorXd x, w;
  EXPECT_THROW(gaussLegendre01(0, x, w), std::invalid_argument);
  EXPECT_THROW(gaussLegendre01(11, x, w), std::invalid_argument);
}

TEST(AncfMass, TotalMassAndGravityForce) {
  const AncfCableProperties p = ropeElement();
  const Matrix12 M = ancfMassMatrix(p);
  EXPECT_LT((M - M.transpose()).norm(), 1e-14 * M.norm());
  for (int d = 0; d < 3; ++d) {
    Vector12 t = Vector12::Zero();
    t(d) = t(6 + d) = 1.0;  // rigid translation along axis d
    EXPECT_NEAR(t.dot(M * t), p.mass_per_length * p.length, 1e-12);
  }
  // Positive definite.
  Eigen::SelfAdjointEigenSolver<Matrix12> es(M);
  EXPECT_GT(es.eigenvalues().minCoeff(), 0.0);
  // Generalised gravity = M times the rigid translation field with value g (S e_g = g).
  const Eigen::Vector3d g(0.1, -0.2, -9.81);
  Vector12 eg;
  eg << g, Eigen::Vector3d::Zero(), g, Eigen::Vector3d::Zero();
  EXPECT_LT((ancfGravityForce(p, g) - M * eg).norm(), 1e-12);
}

TEST(AncfForce, ForceIsGradientOfEnergy) {
  const AncfCableProperties p = ropeElement();
  expectForceIsEnergyGradient(p, stretched());
  expectForceIsEnergyGradient(p, bent());
  expectForceIsEnergyGradient(p, twisted());
  expectForceIsEnergyGradient(p, curved3d());
}

TEST(AncfForce, TangentIsJacobianOfForce) {
  const AncfCableProperties p = ropeElement();
  expectTangentIsForceJacobian(p, stretched());
  expectTangentIsForceJacobian(p, bent());
  expectTangentIsForceJacobian(p, twisted());
  AncfCableProperties noBend = p;
  noBend.bending_stiffness = 0.0;
  expectTangentIsForceJacobian(noBend, twisted());
}

TEST(AncfForce, ZeroForceUnderRigidMotionOfReference) {
  const AncfCableProperties p = ropeElement();
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  const Eigen::Vector3d t(4.0, -1.0, 60.0);
  Vector12 e = straight(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), p.length);
  for (int k = 0; k < 4; ++k) {
    e.segment<3>(3 * k) = R * e.segment<3>(3 * k) + ((k % 2 == 0) ? t : Eigen::Vector3d::Zero());
  }
  Vector12 Q;
  ancfElasticForce(p, e, Q);
  EXPECT_LT(Q.norm(), 1e-9 * p.axial_stiffness);
  EXPECT_LT(ancfElasticEnergy(p, e), 1e-20 * p.axial_stiffness);
}

TEST(AncfForce, AxialForceOfUniformStretch) {
  // Uniform strain eps: nodal axial forces -/+ EA eps (closed form).
  const AncfCableProperties p = ropeElement();
  const double eps = 1e-3;
  Vector12 e = straight(Eigen::Vector3d::Zero(), (1 + eps) * Eigen::Vector3d::UnitX(), p.length);
  Vector12 Q;
  ancfElasticForce(p, e, Q);
  EXPECT_NEAR(Q(0), -p.axial_stiffness * eps, 1e-6 * p.axial_stiffness * eps);
  EXPECT_NEAR(Q(6), p.axial_stiffness * eps, 1e-6 * p.axial_stiffness * eps);
  const double U = 0.5 * p.axial_stiffness * eps * eps * p.length;
  EXPECT_NEAR(ancfElasticEnergy(p, e), U, 1e-10 * U);
}

TEST(AncfForce, CurvatureOfCircularArc) {
  // Nodes on a circle of radius R with tangent slopes: curvature close to 1/R everywhere.
  const double R = 10.0, l = 0.5, phi = l / R;
  Vector12 e;
  e << 0, 0, 0, 1, 0, 0, R * std::sin(phi), R * (1 - std::cos(phi)), 0, std::cos(phi),
      std::sin(phi), 0;
  for (double xi : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    double eps, kappa;
    ancfStrainCurvature(e, xi, l, eps, kappa);
    EXPECT_NEAR(kappa, 1.0 / R, 2e-3 / R);
    EXPECT_NEAR(eps, 0.0, 1e-4);
  }
}

TEST(AncfQuadrature, FivePointsConvergedTo1e10) {
  // docs/model.md: refining the Gauss rule must change nothing to 1e-10 relative at the default,
  // for the states a rope element is in (tensioned, bent, curved in 3D).
  AncfCableProperties p = ropeElement();
  EXPECT_EQ(p.gauss_points, 5);
  for (const Vector12& e : {stretched(), bent(), curved3d()}) {
    p.gauss_points = 5;
    Vector12 Q5, Q10;
    Matrix12 K5, K10;
    ancfElasticForce(p, e, Q5, &K5);
    const double U5 = ancfElasticEnergy(p, e);
    p.gauss_points = 10;
    ancfElasticForce(p, e, Q10, &K10);
    const double U10 = ancfElasticEnergy(p, e);
    EXPECT_LT(std::abs(U5 - U10), 1e-10 * U10);
    EXPECT_LT((Q5 - Q10).norm(), 1e-10 * Q10.norm());
    EXPECT_LT((K5 - K10).norm(), 1e-10 * K10.norm());
  }
}

TEST(AncfQuadrature, ElementWithStrainSignChangeNeedsMorePoints) {
  // docs/model.md: where the strain changes sign inside an element (a locally compressed,
  // kinked element of a slack rope) 5 points are only good to ~1e-5 and 9 reach 1e-10.
  AncfCableProperties p = ropeElement();
  const Vector12 e = twisted();
  p.gauss_points = 10;
  const double U10 = ancfElasticEnergy(p, e);
  p.gauss_points = 9;
  EXPECT_LT(std::abs(ancfElasticEnergy(p, e) - U10), 1e-10 * U10);
  p.gauss_points = 5;
  EXPECT_GT(std::abs(ancfElasticEnergy(p, e) - U10), 1e-8 * U10);
}

// ---- axial damping (rope.damping) -------------------------------------------------

TEST(AncfDamping, VelocityJacobianMatchesFiniteDifferences) {
  // Q_d is linear in e', so central differences are exact up to round-off.
  const AncfCableProperties p = ropeElement();
  const double c = 0.01;
  for (const Vector12& e : {stretched(), bent(), twisted(), curved3d()}) {
    Vector12 edot;
    for (int i = 0; i < 12; ++i) edot(i) = 0.3 * std::sin(1.7 * i + 0.4);
    Vector12 Q0;
    Matrix12 C;
    ancfAxialDampingForce(p, c, e, edot, Q0, &C);
    const double h = 1e-4;
    for (int j = 0; j < 12; ++j) {
      Vector12 up = edot, dn = edot, Qu, Qd;
      up(j) += h;
      dn(j) -= h;
      ancfAxialDampingForce(p, c, e, up, Qu);
      ancfAxialDampingForce(p, c, e, dn, Qd);
      const Vector12 fd = (Qu - Qd) / (2 * h);
      EXPECT_LT((fd - C.col(j)).norm(), 1e-9 * (1.0 + C.col(j).norm())) << "column " << j;
    }
  }
}

TEST(AncfDamping, RigidMotionIsNotDampedAndStretchingDissipates) {
  const AncfCableProperties p = ropeElement();
  const double c = 0.02;
  const Vector12 e = curved3d();
  // Rigid velocity: translation v0 plus rotation w x r (positions) and w x r_x (slopes).
  const Eigen::Vector3d v0(0.3, -1.0, 2.0), w(0.2, 0.5, -0.1);
  Vector12 rigid;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d x = e.segment<3>(3 * k);
    rigid.segment<3>(3 * k) = w.cross(x) + ((k % 2 == 0) ? v0 : Eigen::Vector3d::Zero());
  }
  Vector12 Q;
  ancfAxialDampingForce(p, c, e, rigid, Q);
  EXPECT_LT(Q.norm(), 1e-9 * c * p.axial_stiffness);
  // Uniform stretching of a straight element at rate epsdot: power e'.Q_d = c EA epsdot^2 l.
  const Vector12 s = straight(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), p.length);
  const double epsdot = 0.003;
  Vector12 stretch = Vector12::Zero();
  stretch.segment<3>(6) = Eigen::Vector3d(epsdot * p.length, 0, 0);  // end node moves
  stretch.segment<3>(3) = Eigen::Vector3d(epsdot, 0, 0);             // slopes grow
  stretch.segment<3>(9) = Eigen::Vector3d(epsdot, 0, 0);
  ancfAxialDampingForce(p, c, s, stretch, Q);
  EXPECT_NEAR(stretch.dot(Q), c * p.axial_stiffness * epsdot * epsdot * p.length,
              1e-9 * c * p.axial_stiffness * epsdot * epsdot * p.length);
}

// Tension-only rope (docs/model.md "Tension-only rope"): no axial force in compression.
namespace {
AncfCableProperties tensionOnly() {
  AncfCableProperties p = ropeElement();
  p.tension_only = true;
  return p;
}
// The bent element shortened by the factor s (positions and slopes).
Vector12 shortened(double s) {
  Vector12 e = bent();
  for (int k : {3, 9}) e.segment<3>(k) *= s;
  e.segment<3>(6) = e.segment<3>(0) + s * (e.segment<3>(6) - e.segment<3>(0));
  return e;
}
}  // namespace

TEST(AncfTensionOnly, CompressedElementCarriesOnlyItsBendingForce) {
  // 2 % shorter: slack everywhere, so the force is the one of a rope without axial stiffness.
  const Vector12 e = shortened(0.98);
  AncfCableProperties bendingOnly = ropeElement();
  bendingOnly.axial_stiffness = 0.0;
  Vector12 Q, Qb;
  ancfElasticForce(tensionOnly(), e, Q);
  ancfElasticForce(bendingOnly, e, Qb);
  EXPECT_LT((Q - Qb).norm(), 1e-12 * Qb.norm() + 1e-9);
  EXPECT_NEAR(ancfElasticEnergy(tensionOnly(), e), ancfElasticEnergy(bendingOnly, e), 1e-12);
  // The symmetric law pushes back with about EA * 2 %.
  Vector12 Qs;
  ancfElasticForce(ropeElement(), e, Qs);
  EXPECT_GT((Qs - Qb).norm(), 0.01 * 4.4e7);
}

TEST(AncfTensionOnly, TautElementIsTheSymmetricOne) {
  Vector12 Q, Qs;
  Matrix12 K, Ks;
  ancfElasticForce(tensionOnly(), stretched(), Q, &K);
  ancfElasticForce(ropeElement(), stretched(), Qs, &Ks);
  EXPECT_LT((Q - Qs).norm(), 1e-12 * Qs.norm());
  EXPECT_LT((K - Ks).norm(), 1e-12 * Ks.norm());
}

TEST(AncfTensionOnly, ForceAndTangentAreTheEnergysDerivativesInEveryRegime) {
  // Slack (2 % short), in the guard (30 % short: the slopes are kept from collapsing) and taut.
  for (double s : {0.98, 0.7}) {
    SCOPED_TRACE(s);
    expectForceIsEnergyGradient(tensionOnly(), shortened(s));
    expectTangentIsForceJacobian(tensionOnly(), shortened(s));
  }
  expectForceIsEnergyGradient(tensionOnly(), stretched());
  expectTangentIsForceJacobian(tensionOnly(), stretched());
}

TEST(AncfTensionOnly, AxialLawIsContinuousWithAContinuousSlope) {
  const double EA = 4.4e7, d = kSlackBand, g = kSlackGuardStrain;
  double N, dN;
  for (double eps : {-0.5, -0.25, -g - 1e-7, -g + 1e-7, -0.01, -1.1 * d, -0.9 * d, -0.3 * d, 0.0,
                     0.7 * d, 0.9 * d, 1.1 * d, 1e-3}) {
    SCOPED_TRACE(eps);
    ancfAxialLaw(EA, eps, true, N, dN);
    // Central differences near the band take a step well under its width (the energy's error
    // is N'' h^2 / 6 = EA h^2 / (12 d) there).
    const double h = std::abs(eps) <= 2.0 * d ? 1e-3 * d : 1e-10;
    double Np, Nm, dNp, dNm;
    ancfAxialLaw(EA, eps + h, true, Np, dNp);
    ancfAxialLaw(EA, eps - h, true, Nm, dNm);
    EXPECT_NEAR((Np - Nm) / (2 * h), dN, 1e-3 * EA);  // N' (continuous: no jump at the joins)
    EXPECT_NEAR((ancfAxialEnergy(EA, eps + h, true) - ancfAxialEnergy(EA, eps - h, true)) / (2 * h),
                N, 1e-6 * EA * std::max(std::abs(eps), d));
    EXPECT_GE(N, eps < -g ? -EA : 0.0);
    if (eps > -g && eps <= -d) {
      EXPECT_EQ(N, 0.0);
    }
    if (eps >= d) {
      EXPECT_DOUBLE_EQ(N, EA * eps);
    }
  }
}

TEST(AncfForce, PointGradientsOverManyPointsAreEachPointsOwn) {
  // ancfCablePointGradients (the reduced rope's batch over its Gauss points) against
  // ancfCablePoint at every point: stretches across the taut range, the C1 band, slack and the
  // guard, random directions and curvatures; with and without bending, both laws.
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double EA = 4.4e7;
  const std::vector<double> stretches = {1.01,
                                         1.0 + 3 * kSlackBand,
                                         1.0 + 0.5 * kSlackBand,
                                         1.0,
                                         1.0 - 0.5 * kSlackBand,
                                         1.0 - 3 * kSlackBand,
                                         0.995,
                                         0.9,
                                         1.0 - kSlackGuardStrain - 0.05};
  const int n = static_cast<int>(stretches.size()) * 4;
  PointRows a(n, 3), b(n, 3);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d d = Eigen::Vector3d(u(gen), u(gen), u(gen)).normalized();
    a.row(i) = stretches[i % stretches.size()] * d.transpose();
    b.row(i) = 0.05 * Eigen::RowVector3d(u(gen), u(gen), u(gen));
  }
  for (double EI : {0.0, 157.0})
    for (bool tension_only : {false, true}) {
      SCOPED_TRACE(testing::Message() << "EI " << EI << " tension_only " << tension_only);
      PointRows fa, fb;
      ancfCablePointGradients(EA, EI, a, b, tension_only, fa, fb);
      for (int i = 0; i < n; ++i) {
        CablePointDerivatives d;
        ancfCablePoint(EA, EI, a.row(i).transpose(), b.row(i).transpose(), false, d, tension_only);
        // (EA (1 - 1 / |a|) near |a| = 1 is exact only to EA times the machine epsilon, in both)
        const double tol = 1e-12 * (d.fa.norm() + d.fb.norm()) +
                           10.0 * EA * std::numeric_limits<double>::epsilon();
        EXPECT_LT((fa.row(i).transpose() - d.fa).norm(), tol) << i;
        EXPECT_LT((fb.row(i).transpose() - d.fb).norm(), tol) << i;
      }
    }
}
