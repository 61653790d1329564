// Geometric stiffness (docs/model.md "Geometric stiffness"): a cantilever column's buckling load
// and its exact sway under a compressive load (closed forms), and the T8036's mast-head sway
// amplified by 1 / (1 - 1 / lambda_cr) under its own weight.
#include "crane_twin/structure/geometric_stiffness.hpp"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>
#include <cmath>

#include "crane_twin/elements/beam_geometric_stiffness.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"

using namespace crane_twin;

namespace {

// A vertical cantilever of n Euler-Bernoulli elements (rigid in shear), clamped at z = 0: K and
// the geometric stiffness K_G for an axial force N in every element (free DOFs, dense).
struct Column {
  int n = 20;
  double L = 10.0;
  BeamSection s;
  Column() {
    s.E = 2.1e11;
    s.G = 8.1e10;
    s.area = 1e-3;
    s.Iy = s.Iz = 2e-6;
    s.J = 4e-6;
    s.shear_area_y = s.shear_area_z = 0.0;  // Euler-Bernoulli
  }
  void assemble(double N, Eigen::MatrixXd& K, Eigen::MatrixXd& KG) const {
    const int dofs = 6 * n;
    K = Eigen::MatrixXd::Zero(dofs, dofs);
    KG = Eigen::MatrixXd::Zero(dofs, dofs);
    const double h = L / n;
    for (int e = 0; e < n; ++e) {
      const Eigen::Vector3d p1(0, 0, e * h), p2(0, 0, (e + 1) * h), v(1, 0, 0);
      const auto m = timoshenkoBeamGlobal(s, p1, p2, v);
      const Matrix12d g = beamGeometricStiffnessGlobal(s, p1, p2, v, N);
      for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) {
          const int a = 6 * (e - 1) + i, b = 6 * (e - 1) + j;  // node 0 clamped
          if (a < 0 || b < 0) continue;
          K(a, b) += m.K(i, j);
          KG(a, b) += g(i, j);
        }
    }
  }
};

}  // namespace

TEST(GeometricStiffness, CantileverColumnBucklesAtPiSquaredEIOverFourLSquared) {
  const Column c;
  Eigen::MatrixXd K, KG;
  c.assemble(-1.0, K, KG);  // unit compression
  // K x = P (-K_G1) x: the largest eigenvalue of K^-1 (-K_G1) is 1 / P_cr.
  const Eigen::MatrixXd A = K.ldlt().solve(-KG);
  const double mu = A.eigenvalues().real().maxCoeff();
  const double Pcr = M_PI * M_PI * c.s.E * c.s.Iy / (4.0 * c.L * c.L);
  EXPECT_NEAR(1.0 / mu, Pcr, 1e-6 * Pcr);
}

TEST(GeometricStiffness, CompressedCantileverSwaysAsTheClosedForm) {
  // Tip force H across a cantilever under compression P: delta = H (tan kL - kL) / (P k),
  // k = sqrt(P / EI); without P, H L^3 / (3 EI).
  const Column c;
  const double EI = c.s.E * c.s.Iy, H = 100.0;
  const double Pcr = M_PI * M_PI * EI / (4.0 * c.L * c.L);
  for (double ratio : {0.0, 0.3, 0.6, 0.9}) {
    const double P = ratio * Pcr;
    Eigen::MatrixXd K, KG;
    c.assemble(-P, K, KG);
    Eigen::VectorXd f = Eigen::VectorXd::Zero(K.rows());
    f(6 * (c.n - 1)) = H;  // tip, along x
    const double delta = (K + KG).ldlt().solve(f)(6 * (c.n - 1));
    const double k = std::sqrt(P / EI);
    const double exact =
        P > 0.0 ? H * (std::tan(k * c.L) - k * c.L) / (P * k) : H * std::pow(c.L, 3) / (3.0 * EI);
    SCOPED_TRACE(ratio);
    EXPECT_NEAR(delta, exact, 1e-6 * exact);
  }
}

TEST(GeometricStiffness, MastHeadSwayOfTheT8036IsAmplifiedByItsCriticalLoadFactor) {
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";
  const CraneModel plain = buildCraneModel(loadScene(scene));
  const CraneModel pdelta =
      buildCraneModel(loadScene(scene, {"structure.geometric_stiffness=true"}));
  const TowerCraneStructure& s0 = *plain.structure;
  const TowerCraneStructure& s1 = *pdelta.structure;
  // The mast's compression: the largest axial force in a mast member.
  double compression = 0.0;
  for (std::size_t k = 0; k < s1.members.size(); ++k)
    if (s1.members[k].group == "mast")
      compression = std::min(compression, pdelta.structure_axial_forces(k));
  EXPECT_LT(compression, -1e5);
  // lambda_cr: the smallest positive load factor with (K + lambda K_G) singular, 1 / mu for the
  // largest positive eigenvalue mu of K^-1 (-K_G), K_G = (K + K_G) - K. Tension members give
  // negative mu too (a reversed load's buckling): power iteration on K^-1 (-K_G) + sigma I,
  // sigma = |the most negative mu| (found first), makes the positive end dominant.
  const SparseMatrix KG = s1.K - s0.K;
  Eigen::SimplicialLDLT<SparseMatrix> K(s0.K);
  ASSERT_EQ(K.info(), Eigen::Success);
  auto power = [&](double sigma) {
    Eigen::VectorXd x = Eigen::VectorXd::Ones(s0.free_dofs);
    double m = 0.0, last = 1e300;
    for (int it = 0; it < 5000 && std::abs(m - last) > 1e-12 * std::abs(m); ++it) {
      const Eigen::VectorXd y = K.solve(-(KG * x)) + sigma * x;
      last = m;
      m = x.dot(y) / x.dot(x);
      x = y / y.norm();
    }
    return m - sigma;
  };
  const double most_negative = std::min(power(0.0), 0.0);
  const double mu = power(-most_negative);
  const double lambda = 1.0 / mu;
  EXPECT_GT(lambda, 1.0);  // it stands
  // A horizontal force across the jib at the cab (the slewing unit, on the mast head): sway
  // with and without K_G. Along its own linear sway shape u0 the structure is a one-DOF P-delta
  // system with critical factor lambda_s = u0^T K u0 / (-u0^T K_G u0) (Rayleigh-Ritz), so the
  // sway is amplified by 1 / (1 - 1 / lambda_s), bounded by the global 1 / (1 - 1 / lambda_cr).
  const Eigen::VectorXd f = s0.pointForce({{s0.cab_node, 1.0}}, Eigen::Vector3d(0.0, 1e4, 0.0));
  const Eigen::VectorXd u0 = staticDisplacement(s0, f);
  const double d0 = s0.nodeDisplacement(u0, s0.cab_node).y();
  const double d1 = s1.nodeDisplacement(staticDisplacement(s1, f), s1.cab_node).y();
  const double lambda_s = u0.dot(s0.K * u0) / -u0.dot(KG * u0);
  const double amplification = d1 / d0, expected = 1.0 / (1.0 - 1.0 / lambda_s);
  std::printf(
      "T8036 with the 3.6 t at 80 m: lambda_cr %.2f, largest mast compression %.0f kN; "
      "mast-head sway across the jib amplified %.4f, Rayleigh-Ritz 1 / (1 - 1 / %.2f) = "
      "%.4f\n",
      lambda, -compression / 1e3, amplification, lambda_s, expected);
  EXPECT_GT(lambda_s, lambda);
  EXPECT_GT(amplification, 1.0);
  EXPECT_LT(amplification, 1.0 / (1.0 - 1.0 / lambda));
  EXPECT_NEAR(amplification, expected, 0.05 * (expected - 1.0));
}

TEST(GeometricStiffness, KeyIsCheckedAndOffByDefault) {
  const std::string scene =
      std::string(CRANE_TWIN_SOURCE_DIR) + "/config/scenes/t8036_combination1.yaml";
  EXPECT_FALSE(loadScene(scene).structure_geometric_stiffness);
  EXPECT_THROW(loadScene(scene, {"structure.model=rigid", "structure.geometric_stiffness=true"}),
               InputError);
  EXPECT_THROW(loadScene(scene, {"structure.geometric_stiffness=maybe"}), InputError);
}
