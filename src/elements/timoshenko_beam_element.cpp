#include "crane_twin/elements/timoshenko_beam_element.hpp"

#include <cmath>
#include <stdexcept>

#include "crane_twin/elements/gauss_legendre.hpp"

namespace crane_twin {

BeamSection BeamSection::circularTube(double D, double t, double E, double G, double density) {
  if (!(D > 0.0) || !(t > 0.0) || 2.0 * t > D) {
    throw std::invalid_argument("circular tube needs D > 0 and 0 < t <= D/2");
  }
  const double d = D - 2.0 * t;
  BeamSection s;
  s.E = E;
  s.G = G;
  s.density = density;
  s.area = M_PI / 4.0 * (D * D - d * d);
  s.outer_diameter = D;
  s.Iy = s.Iz = M_PI / 64.0 * (std::pow(D, 4) - std::pow(d, 4));
  s.J = 2.0 * s.Iy;
  s.shear_area_y = s.shear_area_z = 0.5 * s.area;  // thin-walled tube shear factor 1/2
  return s;
}

BeamSection BeamSection::rectangle(double b, double h, double E, double G, double density) {
  if (!(b > 0.0) || !(h > 0.0)) throw std::invalid_argument("rectangle needs b, h > 0");
  BeamSection s;
  s.E = E;
  s.G = G;
  s.density = density;
  s.area = b * h;
  s.Iz = h * b * b * b / 12.0;
  s.Iy = b * h * h * h / 12.0;
  const double a = std::max(b, h), c = std::min(b, h);
  s.J = a * c * c * c * (1.0 / 3.0 - 0.21 * c / a * (1.0 - std::pow(c / a, 4) / 12.0));
  s.shear_area_y = s.shear_area_z = 5.0 / 6.0 * s.area;
  return s;
}

Eigen::Matrix3d beamLocalAxes(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                              const Eigen::Vector3d& orientation) {
  const Eigen::Vector3d d = p2 - p1;
  const double L = d.norm();
  if (!(L > 0.0)) throw std::invalid_argument("beam element nodes coincide");
  const Eigen::Vector3d x1 = d / L;
  const Eigen::Vector3d zc = x1.cross(orientation);
  if (zc.norm() < 1e-9 * std::max(1.0, orientation.norm())) {
    throw std::invalid_argument("beam orientation vector is parallel to the element axis");
  }
  const Eigen::Vector3d z1 = zc.normalized();
  const Eigen::Vector3d y1 = z1.cross(x1);
  Eigen::Matrix3d R;
  R.row(0) = x1.transpose();
  R.row(1) = y1.transpose();
  R.row(2) = z1.transpose();
  return R;
}

namespace {

// In-plane bending matrices for DOFs (v1, psi1, v2, psi2), psi = dv/dx in the Euler-Bernoulli
// limit, built from the interdependent interpolation with shear parameter Phi.
void planeBending(double EI, double GAs, double rhoA, double rhoI, double L, Eigen::Matrix4d& K,
                  Eigen::Matrix4d& M) {
  const double Phi = (GAs > 0.0) ? 12.0 * EI / (GAs * L * L) : 0.0;
  const double c = 1.0 / (1.0 + Phi);
  Eigen::VectorXd xg, wg;
  gaussLegendre01(4, xg, wg);  // integrands are polynomials of degree <= 6: exact
  K.setZero();
  M.setZero();
  for (int q = 0; q < xg.size(); ++q) {
    const double x = xg(q), x2 = x * x, x3 = x2 * x, w = wg(q) * L;
    Eigen::Vector4d Nv, dNv, Np, dNp;
    Nv << c * (2 * x3 - 3 * x2 - Phi * x + 1 + Phi),
        c * L * (x3 - (2 + Phi / 2) * x2 + (1 + Phi / 2) * x), c * (-2 * x3 + 3 * x2 + Phi * x),
        c * L * (x3 - (1 - Phi / 2) * x2 - Phi / 2 * x);
    dNv << c * (6 * x2 - 6 * x - Phi) / L, c * (3 * x2 - (4 + Phi) * x + 1 + Phi / 2),
        c * (-6 * x2 + 6 * x + Phi) / L, c * (3 * x2 - (2 - Phi) * x - Phi / 2);
    Np << 6 * c / L * (x2 - x), c * (3 * x2 - (4 + Phi) * x + 1 + Phi), -6 * c / L * (x2 - x),
        c * (3 * x2 - (2 - Phi) * x);
    dNp << 6 * c / (L * L) * (2 * x - 1), c * (6 * x - (4 + Phi)) / L,
        -6 * c / (L * L) * (2 * x - 1), c * (6 * x - (2 - Phi)) / L;
    K += w * EI * dNp * dNp.transpose();
    if (GAs > 0.0) {
      const Eigen::Vector4d gam = dNv - Np;  // shear strain per unit DOF
      K += w * GAs * gam * gam.transpose();
    }
    M += w * (rhoA * Nv * Nv.transpose() + rhoI * Np * Np.transpose());
  }
}

}  // namespace

BeamElementMatrices timoshenkoBeamLocal(const BeamSection& s, double L) {
  if (!(L > 0.0)) throw std::invalid_argument("beam length must be positive");
  BeamElementMatrices m;
  m.K.setZero();
  m.M.setZero();
  const double rho = s.density;
  // Axial (0, 6) and torsion (3, 9): linear shape functions.
  const double ka = s.E * s.area / L, kt = s.G * s.J / L;
  const double ma = rho * s.area * L / 6.0, mt = rho * (s.Iy + s.Iz) * L / 6.0;
  const int ax[2] = {0, 6}, tr[2] = {3, 9};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      const double sgn = (i == j) ? 1.0 : -1.0;
      m.K(ax[i], ax[j]) = sgn * ka;
      m.K(tr[i], tr[j]) = sgn * kt;
      m.M(ax[i], ax[j]) = (i == j ? 2.0 : 1.0) * ma;
      m.M(tr[i], tr[j]) = (i == j ? 2.0 : 1.0) * mt;
    }
  Eigen::Matrix4d Kb, Mb;
  // x-y plane: v = u_y, psi = th_z.
  planeBending(s.E * s.Iz, s.G * s.shear_area_y, rho * s.area, rho * s.Iz, L, Kb, Mb);
  const int xy[4] = {1, 5, 7, 11};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      m.K(xy[i], xy[j]) += Kb(i, j);
      m.M(xy[i], xy[j]) += Mb(i, j);
    }
  // x-z plane: v = u_z, psi = -th_y (right-handed rotation about y tilts +x towards -z).
  planeBending(s.E * s.Iy, s.G * s.shear_area_z, rho * s.area, rho * s.Iy, L, Kb, Mb);
  const int xz[4] = {2, 4, 8, 10};
  const double sg[4] = {1.0, -1.0, 1.0, -1.0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      m.K(xz[i], xz[j]) += sg[i] * sg[j] * Kb(i, j);
      m.M(xz[i], xz[j]) += sg[i] * sg[j] * Mb(i, j);
    }
  return m;
}

BeamElementMatrices timoshenkoBeamGlobal(const BeamSection& s, const Eigen::Vector3d& p1,
                                         const Eigen::Vector3d& p2,
                                         const Eigen::Vector3d& orientation) {
  const Eigen::Matrix3d R = beamLocalAxes(p1, p2, orientation);
  BeamElementMatrices loc = timoshenkoBeamLocal(s, (p2 - p1).norm());
  Eigen::Matrix<double, 12, 12> T = Eigen::Matrix<double, 12, 12>::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  BeamElementMatrices g;
  g.K = T.transpose() * loc.K * T;
  g.M = T.transpose() * loc.M * T;
  return g;
}

}  // namespace crane_twin
