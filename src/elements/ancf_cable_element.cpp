#include "crane_twin/elements/ancf_cable_element.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "crane_twin/elements/discrete_gradient.hpp"
#include "crane_twin/elements/gauss_legendre.hpp"

namespace crane_twin {

namespace {
// The most Gauss points an element may use (AncfCableProperties::gauss_points).
constexpr int kMaxGaussPoints = 10;

// Gauss rules are computed once per point count: the element routines run in the hot loop.
struct GaussRule {
  Eigen::VectorXd x, w;
};
const GaussRule& gaussRule(int n) {
  static const std::vector<GaussRule> rules = [] {
    std::vector<GaussRule> r(kMaxGaussPoints + 1);
    for (int k = 1; k <= kMaxGaussPoints; ++k) gaussLegendre01(k, r[k].x, r[k].w);
    return r;
  }();
  if (n < 1 || n > kMaxGaussPoints) {
    throw std::invalid_argument("gauss points must be in 1.." + std::to_string(kMaxGaussPoints) +
                                ", got " + std::to_string(n));
  }
  return rules[n];
}
}  // namespace

Eigen::Vector4d ancfShape(double xi, double l) {
  const double x2 = xi * xi, x3 = x2 * xi;
  return {1.0 - 3.0 * x2 + 2.0 * x3, l * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, l * (x3 - x2)};
}

Eigen::Vector4d ancfShapeDx(double xi, double l) {
  const double x2 = xi * xi;
  return {(-6.0 * xi + 6.0 * x2) / l, 1.0 - 4.0 * xi + 3.0 * x2, (6.0 * xi - 6.0 * x2) / l,
          3.0 * x2 - 2.0 * xi};
}

Eigen::Vector4d ancfShapeDxx(double xi, double l) {
  return {(-6.0 + 12.0 * xi) / (l * l), (-4.0 + 6.0 * xi) / l, (6.0 - 12.0 * xi) / (l * l),
          (6.0 * xi - 2.0) / l};
}

namespace {

// v = sum_k s(k) * e.segment<3>(3k)
Eigen::Vector3d combine(const Eigen::Vector4d& s, const Vector12& e) {
  return s(0) * e.segment<3>(0) + s(1) * e.segment<3>(3) + s(2) * e.segment<3>(6) +
         s(3) * e.segment<3>(9);
}

// K += w * Sa^T H Sb where Sa = [sa_k I], Sb = [sb_k I] and H is 3x3.
void addOuter(const Eigen::Vector4d& sa, const Eigen::Vector4d& sb, const Eigen::Matrix3d& H,
              double w, Matrix12& K) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) K.block<3, 3>(3 * i, 3 * j) += (w * sa(i) * sb(j)) * H;
}

// Q += w * Sa^T v
void addVec(const Eigen::Vector4d& sa, const Eigen::Vector3d& v, double w, Vector12& Q) {
  for (int i = 0; i < 4; ++i) Q.segment<3>(3 * i) += (w * sa(i)) * v;
}

// One Gauss point's share of the element force and tangent, from the point's derivatives d
// with weight w: Q += w (S_x^T fa + S_xx^T fb); block (i, j) of K gains
// w (sx_i sx_j Paa + sx_i sxx_j Pab + sxx_i sx_j Pab^T + sxx_i sxx_j Pbb), for j >= i only
// when bending (mirrorUpper completes it; the profiled hot spot was one 3 x 3 update per term
// and pair).
void addPoint(const Eigen::Vector4d& sx, const Eigen::Vector4d& sxx, const CablePointDerivatives& d,
              double w, bool bending, Vector12& Q, Matrix12* K) {
  addVec(sx, d.fa, w, Q);
  if (!bending) {
    if (K) addOuter(sx, sx, d.Paa, w, *K);
    return;
  }
  addVec(sxx, d.fb, w, Q);
  if (!K) return;
  // K_ij += w (sx_i sx_j Paa + sx_i sxx_j Pab + sxx_i sx_j Pab^T + sxx_i sxx_j Pbb) (upper
  // blocks, i <= j), as K_ij += sx_i Ta_j + sxx_i Tb_j with the column factors
  // Ta_j = w (sx_j Paa + sxx_j Pab), Tb_j = w (sx_j Pab^T + sxx_j Pbb): a quarter of the products.
  for (int j = 0; j < 4; ++j) {
    const Eigen::Matrix3d Ta = w * (sx(j) * d.Paa + sxx(j) * d.Pab);
    const Eigen::Matrix3d Tb = w * (sx(j) * d.Pab.transpose() + sxx(j) * d.Pbb);
    for (int i = 0; i <= j; ++i) K->block<3, 3>(3 * i, 3 * j) += sx(i) * Ta + sxx(i) * Tb;
  }
}

// The lower block triangle of K from the upper one.
void mirrorUpper(Matrix12& K) {
  for (int i = 1; i < 4; ++i)
    for (int j = 0; j < i; ++j)
      K.block<3, 3>(3 * i, 3 * j) = K.block<3, 3>(3 * j, 3 * i).transpose();
}

}  // namespace

// Tension-only axial law (docs/model.md "Tension-only rope"), with d = kSlackBand:
//   N = EA eps                        eps >= d
//   N = EA (eps + d)^2 / (4 d)        -d < eps < d   (C1 join: no jump in the tangent)
//   N = 0                             -g_c <= eps <= -d   (slack)
//   N = EA (eps + g_c)                eps < -g_c          (guard, g_c = kSlackGuardStrain)
// and its energy psi = int N d eps, psi(-d) = 0.
void ancfAxialLaw(double EA, double eps, bool tension_only, double& N, double& dN) {
  const double d = kSlackBand, gc = kSlackGuardStrain;
  if (!tension_only || eps >= d) {
    N = EA * eps;
    dN = EA;
  } else if (eps > -d) {
    N = EA * (eps + d) * (eps + d) / (4.0 * d);
    dN = EA * (eps + d) / (2.0 * d);
  } else if (eps >= -gc) {
    N = dN = 0.0;
  } else {
    N = EA * (eps + gc);
    dN = EA;
  }
}

double ancfAxialEnergy(double EA, double eps, bool tension_only) {
  const double d = kSlackBand, gc = kSlackGuardStrain;
  if (!tension_only) return 0.5 * EA * eps * eps;
  if (eps >= d) return 0.5 * EA * eps * eps + EA * d * d / 6.0;
  if (eps > -d) {
    const double x = eps + d;
    return EA * x * x * x / (12.0 * d);
  }
  if (eps >= -gc) return 0.0;
  return 0.5 * EA * (eps + gc) * (eps + gc);
}

Eigen::Vector3d ancfPosition(const Vector12& e, double xi, double l) {
  return combine(ancfShape(xi, l), e);
}

Matrix12 ancfMassMatrix(const AncfCableProperties& p) {
  const GaussRule& gr = gaussRule(4);  // S^T S is a degree-6 polynomial: exact
  const Eigen::VectorXd &xg = gr.x, &wg = gr.w;
  Matrix12 M = Matrix12::Zero();
  for (int g = 0; g < xg.size(); ++g) {
    const Eigen::Vector4d s = ancfShape(xg(g), p.length);
    addOuter(s, s, Eigen::Matrix3d::Identity(), wg(g) * p.length * p.mass_per_length, M);
  }
  return M;
}

Vector12 ancfGravityForce(const AncfCableProperties& p, const Eigen::Vector3d& g) {
  // int S dx = l [1/2, l/12, 1/2, -l/12]
  const double l = p.length, m = p.mass_per_length;
  Vector12 f;
  f << 0.5 * l * g, l * l / 12.0 * g, 0.5 * l * g, -l * l / 12.0 * g;
  return m * f;
}

void ancfStrainCurvature(const Vector12& e, double xi, double l, double& eps, double& kappa) {
  const Eigen::Vector3d a = combine(ancfShapeDx(xi, l), e);
  const Eigen::Vector3d b = combine(ancfShapeDxx(xi, l), e);
  const double g = a.norm();
  eps = g - 1.0;
  kappa = a.cross(b).norm() / (g * g * g);
}

double ancfCableEnergyDensity(double EA, double EI, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, bool tension_only) {
  const double g = a.norm();
  const double kappa = a.cross(b).norm() / (g * g * g);
  return ancfAxialEnergy(EA, g - 1.0, tension_only) + 0.5 * EI * kappa * kappa;
}

double ancfElasticEnergy(const AncfCableProperties& p, const Vector12& e) {
  const GaussRule& gr = gaussRule(p.gauss_points);
  const Eigen::VectorXd &xg = gr.x, &wg = gr.w;
  double U = 0.0;
  for (int q = 0; q < xg.size(); ++q) {
    U += wg(q) * p.length *
         ancfCableEnergyDensity(p.axial_stiffness, p.bending_stiffness,
                                combine(ancfShapeDx(xg(q), p.length), e),
                                combine(ancfShapeDxx(xg(q), p.length), e), p.tension_only);
  }
  return U;
}

void ancfCablePoint(double EA, double EI, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    bool hessian, CablePointDerivatives& d, bool tension_only) {
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const double h = a.squaredNorm();
  const double g = std::sqrt(h);
  // Axial: phi = psi(eps), eps = g - 1, N = psi'(eps): phi_a = N a / g;
  // phi_aa = N' a a^T / g^2 + (N / g) (I - a a^T / g^2). Symmetric: N = EA eps.
  if (!tension_only || g >= 1.0 + kSlackBand) {
    d.fa = EA * (1.0 - 1.0 / g) * a;
    if (hessian) d.Paa = EA * ((1.0 - 1.0 / g) * I3 + a * a.transpose() / (h * g));
  } else {
    double N, dN;
    ancfAxialLaw(EA, g - 1.0, tension_only, N, dN);
    const Eigen::Vector3d t = a / g;
    d.fa = N * t;
    if (hessian) d.Paa = dN * t * t.transpose() + (N / g) * (I3 - t * t.transpose());
  }
  if (EI == 0.0) {
    d.fb.setZero();
    if (hessian) d.Pab.setZero(), d.Pbb.setZero();
    return;
  }
  // Bending: phi = EI/2 f h^-3, f = |a x b|^2 = (a.a)(b.b) - (a.b)^2, h = a.a.
  const double ab = a.dot(b), bb = b.dot(b);
  const double f = h * bb - ab * ab;
  const Eigen::Vector3d fa = 2.0 * bb * a - 2.0 * ab * b;
  const Eigen::Vector3d fb = 2.0 * h * b - 2.0 * ab * a;
  const Eigen::Vector3d ha = 2.0 * a;
  const double h3 = 1.0 / (h * h * h), h4 = h3 / h, h5 = h4 / h;
  const double c = 0.5 * EI;
  d.fa += c * (fa * h3 - 3.0 * f * h4 * ha);
  d.fb = c * fb * h3;
  if (!hessian) return;
  const Eigen::Matrix3d faa = 2.0 * bb * I3 - 2.0 * b * b.transpose();
  const Eigen::Matrix3d fbb = 2.0 * h * I3 - 2.0 * a * a.transpose();
  const Eigen::Matrix3d fab = 4.0 * a * b.transpose() - 2.0 * b * a.transpose() - 2.0 * ab * I3;
  d.Paa += c * (faa * h3 - 3.0 * h4 * (fa * ha.transpose() + ha * fa.transpose()) +
                12.0 * f * h5 * ha * ha.transpose() - 6.0 * f * h4 * I3);
  d.Pab = c * (fab * h3 - 3.0 * h4 * ha * fb.transpose());
  d.Pbb = c * fbb * h3;
}

void ancfCablePointGradients(double EA, double EI, const PointRows& a, const PointRows& b,
                             bool tension_only, PointRows& fa, PointRows& fb) {
  // The terms of ancfCablePoint (header) as coefficients per point on a and b, one pass over the
  // points' component columns.
  const Eigen::Index n = a.rows();
  fa.resize(n, 3);
  fb.resize(n, 3);
  const bool bending = EI != 0.0;
  const double* __restrict ax = a.col(0).data();
  const double* __restrict ay = a.col(1).data();
  const double* __restrict az = a.col(2).data();
  const double* __restrict bx = bending ? b.col(0).data() : nullptr;
  const double* __restrict by = bending ? b.col(1).data() : nullptr;
  const double* __restrict bz = bending ? b.col(2).data() : nullptr;
  double* __restrict fax = fa.col(0).data();
  double* __restrict fay = fa.col(1).data();
  double* __restrict faz = fa.col(2).data();
  double* __restrict fbx = fb.col(0).data();
  double* __restrict fby = fb.col(1).data();
  double* __restrict fbz = fb.col(2).data();
  // One point, its axial coefficient N / |a| given (h = |a|^2, ih = 1 / h).
  const auto point = [&](Eigen::Index i, double h, double ih, double ca) {
    if (!bending) {
      fax[i] = ca * ax[i], fay[i] = ca * ay[i], faz[i] = ca * az[i];
      fbx[i] = fby[i] = fbz[i] = 0.0;
      return;
    }
    // Bending: phi = EI/2 f h^-3, f = h bb - ab^2.
    const double ab = ax[i] * bx[i] + ay[i] * by[i] + az[i] * bz[i];
    const double bb = bx[i] * bx[i] + by[i] * by[i] + bz[i] * bz[i];
    const double h3 = ih * ih * ih;
    const double f = h * bb - ab * ab;
    ca += EI * (bb - 3.0 * f * ih) * h3;
    const double cab = -EI * ab * h3, cb = EI * h * h3;
    fax[i] = ca * ax[i] + cab * bx[i], fay[i] = ca * ay[i] + cab * by[i],
    faz[i] = ca * az[i] + cab * bz[i];
    fbx[i] = cb * bx[i] + cab * ax[i], fby[i] = cb * by[i] + cab * ay[i],
    fbz[i] = cb * bz[i] + cab * az[i];
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    const double h = ax[i] * ax[i] + ay[i] * ay[i] + az[i] * az[i];
    const double g = std::sqrt(h), ih = 1.0 / h;
    double ca = EA * (1.0 - g * ih);  // N / |a| = EA (1 - 1 / |a|) in the linear range
    if (tension_only && g < 1.0 + kSlackBand) {
      double N, dN;
      ancfAxialLaw(EA, g - 1.0, true, N, dN);
      ca = N / g;
    }
    point(i, h, ih, ca);
  }
}

void ancfElasticForce(const AncfCableProperties& p, const Vector12& e, Vector12& Q, Matrix12* K) {
  const GaussRule& gr = gaussRule(p.gauss_points);
  const Eigen::VectorXd &xg = gr.x, &wg = gr.w;
  Q.setZero();
  if (K) K->setZero();
  const double EA = p.axial_stiffness, EI = p.bending_stiffness, l = p.length;
  CablePointDerivatives d;
  for (int q = 0; q < xg.size(); ++q) {
    const double w = wg(q) * l;
    const Eigen::Vector4d sx = ancfShapeDx(xg(q), l);
    const Eigen::Vector4d sxx = ancfShapeDxx(xg(q), l);
    // Q = int (S_x^T phi_a + S_xx^T phi_b) dx (addPoint).
    ancfCablePoint(EA, EI, combine(sx, e), combine(sxx, e), K != nullptr, d, p.tension_only);
    addPoint(sx, sxx, d, w, EI != 0.0, Q, K);
  }
  if (K && EI != 0.0) mirrorUpper(*K);
}

CablePointStepStart ancfCablePointStepStart(double EA, double EI, const Eigen::Vector3d& a0,
                                            const Eigen::Vector3d& b0, bool tension_only) {
  CablePointStepStart st;
  st.a = a0;
  st.b = b0;
  st.axial_energy = ancfAxialEnergy(EA, a0.norm() - 1.0, tension_only);
  if (EI != 0.0) st.bending_energy = ancfCableEnergyDensity(0.0, EI, a0, b0);
  return st;
}

void ancfCablePointDiscreteGradient(double EA, double EI, double l, const Eigen::Vector3d& a0,
                                    const Eigen::Vector3d& b0, const Eigen::Vector3d& a1,
                                    const Eigen::Vector3d& b1, bool hessian,
                                    CablePointDerivatives& d, bool tension_only) {
  ancfCablePointDiscreteGradient(EA, EI, l, ancfCablePointStepStart(EA, EI, a0, b0, tension_only),
                                 a1, b1, hessian, d, tension_only);
}

void ancfCablePointDiscreteGradient(double EA, double EI, double l,
                                    const CablePointStepStart& start, const Eigen::Vector3d& a1,
                                    const Eigen::Vector3d& b1, bool hessian,
                                    CablePointDerivatives& d, bool tension_only) {
  // The axial energy as a function of s = |a|^2: W(s) = psi(g - 1), W' = N / (2 g),
  // W'' = (N' g - N) / (4 g^3), g = sqrt(s).
  const auto W = [&](double s) { return ancfAxialEnergy(EA, std::sqrt(s) - 1.0, tension_only); };
  const auto dW = [&](double s) {
    const double g = std::sqrt(s);
    double N, dN;
    ancfAxialLaw(EA, g - 1.0, tension_only, N, dN);
    return N / (2.0 * g);
  };
  const auto ddW = [&](double s) {
    const double g = std::sqrt(s);
    double N, dN;
    ancfAxialLaw(EA, g - 1.0, tension_only, N, dN);
    return (dN * g - N) / (4.0 * g * g * g);
  };
  const Eigen::Vector3d &a0 = start.a, &b0 = start.b;
  const Eigen::Vector3d am = 0.5 * (a0 + a1), bm = 0.5 * (b0 + b1);
  // Bending: Gonzalez's midpoint gradient with its correction along dy = (da, l db).
  d = CablePointDerivatives();
  if (EI != 0.0) {
    ancfCablePoint(0.0, EI, am, bm, hessian, d, false);
    const Eigen::Vector3d da = a1 - a0, db = b1 - b0;
    const double dy2 = da.squaredNorm() + l * l * db.squaredNorm();
    if (dy2 > 1e-16) {
      const double c = (ancfCableEnergyDensity(0.0, EI, a1, b1) - start.bending_energy -
                        d.fa.dot(da) - d.fb.dot(db)) /
                       dy2;
      d.fa += c * da;
      d.fb += (c * l * l) * db;
    }
  }
  // Axial: the secant in s = |a|^2.
  const SquaredLengthSecant sec =
      squaredLengthSecant(a0.squaredNorm(), start.axial_energy, a1.squaredNorm(), W, dW, ddW);
  d.fa += (2.0 * sec.slope) * am;
  if (hessian) {
    d.Paa += (2.0 * sec.slope) * Eigen::Matrix3d::Identity() +
             (8.0 * sec.curvature) * am * am.transpose();
  }
}

void ancfElementStepStart(const AncfCableProperties& p, const Vector12& e0,
                          CablePointStepStart* start) {
  const GaussRule& gr = gaussRule(p.gauss_points);
  for (int q = 0; q < gr.x.size(); ++q) {
    start[q] = ancfCablePointStepStart(
        p.axial_stiffness, p.bending_stiffness, combine(ancfShapeDx(gr.x(q), p.length), e0),
        combine(ancfShapeDxx(gr.x(q), p.length), e0), p.tension_only);
  }
}

void ancfElasticForceDiscreteGradient(const AncfCableProperties& p, const Vector12& e0,
                                      const Vector12& e1, Vector12& Q, Matrix12* K) {
  CablePointStepStart start[kMaxGaussPoints];
  ancfElementStepStart(p, e0, start);
  ancfElasticForceDiscreteGradient(p, start, e1, Q, K);
}

void ancfElasticForceDiscreteGradient(const AncfCableProperties& p,
                                      const CablePointStepStart* start, const Vector12& e1,
                                      Vector12& Q, Matrix12* K) {
  const GaussRule& gr = gaussRule(p.gauss_points);
  Q.setZero();
  if (K) K->setZero();
  const double l = p.length;
  CablePointDerivatives d;
  for (int q = 0; q < gr.x.size(); ++q) {
    const double w = gr.w(q) * l;
    const Eigen::Vector4d sx = ancfShapeDx(gr.x(q), l);
    const Eigen::Vector4d sxx = ancfShapeDxx(gr.x(q), l);
    ancfCablePointDiscreteGradient(p.axial_stiffness, p.bending_stiffness, l, start[q],
                                   combine(sx, e1), combine(sxx, e1), K != nullptr, d,
                                   p.tension_only);
    addPoint(sx, sxx, d, w, p.bending_stiffness != 0.0, Q, K);
  }
  if (K && p.bending_stiffness != 0.0) mirrorUpper(*K);
}

double ancfAxialSwitchWorkError(double EA, double eps0, double eps1) {
  if (eps0 >= kSlackBand && eps1 >= kSlackBand) return 0.0;  // linear law: trapezoid exact
  double N0, N1, dN;
  ancfAxialLaw(EA, eps0, true, N0, dN);
  ancfAxialLaw(EA, eps1, true, N1, dN);
  const double trapezoid = 0.5 * (N0 + N1) * (eps1 - eps0);
  const double exact = ancfAxialEnergy(EA, eps1, true) - ancfAxialEnergy(EA, eps0, true);
  return std::abs(trapezoid - exact);
}

double ancfSlackSwitchWorkError(const AncfCableProperties& p, const Vector12& e0,
                                const Vector12& e1) {
  if (!p.tension_only) return 0.0;
  double eps0[kMaxGaussPoints], eps1[kMaxGaussPoints];
  ancfAxialStrains(p, e0, eps0);
  ancfAxialStrains(p, e1, eps1);
  return ancfSlackSwitchWorkError(p, eps0, eps1);
}

double ancfSlackSwitchWorkError(const AncfCableProperties& p, const double* eps0,
                                const double* eps1) {
  if (!p.tension_only) return 0.0;
  const GaussRule& gr = gaussRule(p.gauss_points);
  double err = 0.0;
  for (int q = 0; q < gr.x.size(); ++q)
    err += gr.w(q) * p.length * ancfAxialSwitchWorkError(p.axial_stiffness, eps0[q], eps1[q]);
  return err;
}

void ancfAxialStrains(const AncfCableProperties& p, const Vector12& e, double* eps) {
  const GaussRule& gr = gaussRule(p.gauss_points);
  for (int q = 0; q < gr.x.size(); ++q)
    eps[q] = combine(ancfShapeDx(gr.x(q), p.length), e).norm() - 1.0;
}

double ancfAxialTangentShape(const AncfCableProperties& p, const Vector12& e, int g, Vector12& v) {
  const GaussRule& gr = gaussRule(p.gauss_points);
  const Eigen::Vector4d sx = ancfShapeDx(gr.x(g), p.length);
  const Eigen::Vector3d t = combine(sx, e).normalized();
  for (int i = 0; i < 4; ++i) v.segment<3>(3 * i) = sx(i) * t;
  return gr.w(g) * p.length;
}

void ancfAxialDampingForce(const AncfCableProperties& p, double c, const Vector12& e,
                           const Vector12& edot, Vector12& Q, Matrix12* C) {
  const GaussRule& gr = gaussRule(p.gauss_points);
  Q.setZero();
  if (C) C->setZero();
  const double cEA = c * p.axial_stiffness, l = p.length;
  for (int q = 0; q < gr.x.size(); ++q) {
    const double w = gr.w(q) * l;
    const Eigen::Vector4d sx = ancfShapeDx(gr.x(q), l);
    const Eigen::Vector3d a = combine(sx, e);
    if (ancfAxialSlack(a.norm(), p.tension_only)) continue;  // slack: no damper force
    const Eigen::Vector3d t = a.normalized();
    const double epsDot = t.dot(combine(sx, edot));
    addVec(sx, cEA * epsDot * t, w, Q);
    if (C) addOuter(sx, sx, cEA * t * t.transpose(), w, *C);
  }
}

}  // namespace crane_twin
