// 3D gradient-deficient ANCF cable element (docs/model.md).
//
// Element coordinates e = [r1, r1_x, r2, r2_x] (12 values, world frame, m and -):
// nodal positions and axial slope vectors. With xi = x / l, l the unstretched length,
//   r(x) = S(x) e,  S = [S1 I, S2 I, S3 I, S4 I],
//   S1 = 1 - 3 xi^2 + 2 xi^3,  S2 = l (xi - 2 xi^2 + xi^3),
//   S3 = 3 xi^2 - 2 xi^3,      S4 = l (xi^3 - xi^2).
// Elastic energy (Euler-Bernoulli, exact curvature with |r_x|^3 in the denominator):
//   U = 1/2 int EA eps^2 dx + 1/2 int EI kappa^2 dx,
//   eps = |r_x| - 1,   kappa = |r_x x r_xx| / |r_x|^3.
// Q = dU/de and K = d2U/de2 are the exact analytic derivatives of U evaluated with the same
// Gauss rule (default 5 points; see docs/model.md for the quadrature study).
// Reference: Gerstmayr & Shabana, Nonlinear Dyn. 45 (2006); Yu et al. 2024, eq. (1)-(5).
#pragma once

#include <Eigen/Dense>

namespace crane_twin {

using Vector12 = Eigen::Matrix<double, 12, 1>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

/// Material and geometry of one cable element. Units: m, kg/m, N, N m^2.
struct AncfCableProperties {
  double length = 1.0;             ///< unstretched element length l [m]
  double mass_per_length = 1.0;    ///< rho A [kg/m]
  double axial_stiffness = 1.0;    ///< EA [N]
  double bending_stiffness = 0.0;  ///< EI [N m^2]; 0 turns bending off
  int gauss_points = 5;            ///< quadrature points per element (1..10)
  /// A wire rope takes no compression (`rope.tension_only`, docs/scenes.md): the axial energy
  /// is EA/2 max(eps, 0)^2, so neither force nor stiffness remain where eps < 0.
  bool tension_only = false;
};

/// Shape function values [S1, S2, S3, S4] at xi in [0, 1] for element length l.
Eigen::Vector4d ancfShape(double xi, double l);
/// d/dx of the shape functions (per metre).
Eigen::Vector4d ancfShapeDx(double xi, double l);
/// d2/dx2 of the shape functions (per square metre).
Eigen::Vector4d ancfShapeDxx(double xi, double l);

/// Tension-only rope: compressive strain taken without force, down to this guard [-] (below it
/// the axial energy is EA/2 (eps + guard)^2, so a slack element's slopes cannot collapse to
/// zero length, where the bending energy is singular; docs/model.md "Tension-only rope").
constexpr double kSlackGuardStrain = 0.2;
/// Half width of the strain band over which a tension-only rope's force rises from 0 to EA eps
/// with a continuous tangent (ancfAxialLaw) [-]: a kink there made Newton cycle between slack and
/// taut and the 60 deg swing gain energy without bound. Narrow (docs/model.md "The band's
/// width"): EA d / 4 at zero strain is a phantom force, and a rope whose points sit in the band
/// switches at every step; about 50 times the strain Newton's tolerance resolves.
constexpr double kSlackBand = 1e-8;

/// Axial force N(eps) [N] and its slope dN/deps of the rope's axial law (EA eps, or the
/// tension-only law of docs/model.md), and the energy density psi(eps) = int N [J/m].
void ancfAxialLaw(double EA, double eps, bool tension_only, double& N, double& dN);
double ancfAxialEnergy(double EA, double eps, bool tension_only);
/// A tension-only point with stretch g = |r_x| is slack (no axial force, no axial damping):
/// g - 1 <= -kSlackBand.
inline bool ancfAxialSlack(double g, bool tension_only) {
  return tension_only && g - 1.0 <= -kSlackBand;
}

/// Work error of the trapezoidal rule on a tension-only element's axial law over one time step
/// from e0 to e1 [J] (docs/model.md "Tension-only rope"):
///   err = sum_g w_g l | (N(eps0) + N(eps1)) / 2 (eps1 - eps0) - (psi(eps1) - psi(eps0)) |,
/// summed over the Gauss points where either end lies below the linear range (eps < kSlackBand).
/// For the linear law the trapezoid is exact (psi is quadratic), so this measures the energy
/// an implicit step creates or destroys where a point switches between slack and taut; the
/// solvers halve such steps (step-size control). 0 without tension_only.
double ancfSlackSwitchWorkError(const AncfCableProperties& p, const Vector12& e0,
                                const Vector12& e1);
/// The same from the axial strains eps = |r_x| - 1 at the element's Gauss points at both ends
/// (ancfAxialStrains), p.gauss_points values each.
double ancfSlackSwitchWorkError(const AncfCableProperties& p, const double* eps0,
                                const double* eps1);
/// The axial strains eps = |r_x(xi_g)| - 1 at the element's p.gauss_points Gauss points.
void ancfAxialStrains(const AncfCableProperties& p, const Vector12& e, double* eps);
/// The axial law's material share of Gauss point g's tangent as a rank-one term: the element's
/// tangent holds w_g l N'(eps_g) v v^T with v = S_x(xi_g)^T t, t = r_x / |r_x| (ancfCablePoint's
/// Paa = N' t t^T + (N / |r_x|) (I - t t^T)). Writes v and returns w_g l [m].
double ancfAxialTangentShape(const AncfCableProperties& p, const Vector12& e, int g, Vector12& v);

/// Position r(xi) = S(xi) e.
Eigen::Vector3d ancfPosition(const Vector12& e, double xi, double l);

/// Constant consistent mass matrix M = int rho A S^T S dx (exact, 4-point Gauss suffices).
Matrix12 ancfMassMatrix(const AncfCableProperties& p);

/// Generalised gravity force int rho A S^T g dx for a uniform field g [m/s^2].
Vector12 ancfGravityForce(const AncfCableProperties& p, const Eigen::Vector3d& g);

/// Elastic energy U(e) [J].
double ancfElasticEnergy(const AncfCableProperties& p, const Vector12& e);

/// Elastic force Q = dU/de and, if K != nullptr, tangent stiffness K = d2U/de2.
void ancfElasticForce(const AncfCableProperties& p, const Vector12& e, Vector12& Q,
                      Matrix12* K = nullptr);

/// Discrete gradient of the element's elastic energy over a step e0 -> e1 (docs/model.md
/// "Energy-consistent step", elements/discrete_gradient.hpp): Q with
///   Q . (e1 - e0) = U(e1) - U(e0)  to round-off,   Q(e, e) = dU/de (e),
/// summed over the Gauss points. At each point, a_k = S_x e_k, b_k = S_xx e_k, midpoint a_m, b_m:
///   axial    phi_a += 2 Sbar a_m,  Sbar the secant of W(s) = psi(sqrt(s) - 1) over s = |a|^2;
///   bending  Gonzalez in y = (a, l b):  grad phi_b(y_m) + c (da, l^2 db),
///            c = (phi_b(y1) - phi_b(y0) - grad phi_b(y_m) . dy) / (|da|^2 + l^2 |db|^2)
///            (c = 0 where |dy| <= 1e-8: the correction is then O(|dy|^2), below round-off).
/// K, when given, is a symmetric stand-in for 2 dQ/de1 (the Newton matrix of the step), equal
/// to the tangent stiffness K(e) for e1 = e0: axial 2 Sbar I + 8 kappa a_m a_m^T (kappa the
/// secant's curvature), bending the Hessian of phi_b at y_m.
void ancfElasticForceDiscreteGradient(const AncfCableProperties& p, const Vector12& e0,
                                      const Vector12& e1, Vector12& Q, Matrix12* K = nullptr);

/// The step's start at one Gauss point, the part of its discrete gradient that no Newton iterate
/// of the step changes: a0 = S_x e0 [-], b0 = S_xx e0 [1/m] and the densities there [J/m].
struct CablePointStepStart {
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();
  double axial_energy = 0.0;    ///< psi(|a0| - 1)
  double bending_energy = 0.0;  ///< EI/2 |a0 x b0|^2 / |a0|^6
};
/// The start of an element's step e0 at its p.gauss_points Gauss points, into start[0..].
void ancfElementStepStart(const AncfCableProperties& p, const Vector12& e0,
                          CablePointStepStart* start);
/// ancfElasticForceDiscreteGradient from the step's start at the Gauss points
/// (ancfElementStepStart of e0): the same Q and K, without re-evaluating the start at every
/// Newton iterate.
void ancfElasticForceDiscreteGradient(const AncfCableProperties& p,
                                      const CablePointStepStart* start, const Vector12& e1,
                                      Vector12& Q, Matrix12* K = nullptr);

/// Axial strain-rate damping (Kelvin-Voigt on the axial strain, `rope.damping` = c [s]):
///   Q_d = int c EA eps' (d eps / d e)^T dx,  eps' = t . r_x',  t = r_x / |r_x|,
/// dissipating int c EA eps'^2 dx >= 0 and zero for rigid motions. C_d = d Q_d / d e' =
/// int c EA S_x^T t t^T S_x dx into *C when given (the dependence on e through t is left out
/// of the iteration matrix). With tension_only the damper sits in parallel with the spring:
/// it acts only where eps > 0 (a slack rope carries no force).
void ancfAxialDampingForce(const AncfCableProperties& p, double c, const Vector12& e,
                           const Vector12& edot, Vector12& Q, Matrix12* C = nullptr);

/// The energy density phi(a, b) = EA/2 (|a| - 1)^2 + EI/2 |a x b|^2 / |a|^6 of one point of the
/// rope (EA/2 max(|a| - 1, 0)^2 for the axial part when tension_only), a = r_x [-], b = r_xx [1/m]
/// (the integrand of U above), and its derivatives: the gradient (fa, fb) = (d phi/da, d phi/db)
/// [N] and, when asked, the Hessian blocks Paa, Pab, Pbb (Pab = d2 phi / da db^T). The element and
/// the reduced rope (InvariantRopeBasis) both integrate this function, so they share one energy.
struct CablePointDerivatives {
  Eigen::Vector3d fa = Eigen::Vector3d::Zero(), fb = Eigen::Vector3d::Zero();
  Eigen::Matrix3d Paa = Eigen::Matrix3d::Zero(), Pab = Eigen::Matrix3d::Zero(),
                  Pbb = Eigen::Matrix3d::Zero();
};
void ancfCablePoint(double EA, double EI, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    bool hessian, CablePointDerivatives& d, bool tension_only = false);
/// ancfCablePoint's gradient (fa, fb), no Hessian, at many points at once: row g of `a` and `b`
/// (n x 3) holds r_x and r_xx of point g, the same rows of `fa` and `fb` receive its gradient.
/// One pass over the points' component columns (contiguous arrays, no 3-vector temporaries):
///   fa = c_a a + c_ab b,   fb = c_b b + c_ab a,
///   c_a = N / |a| + EI (bb h^-3 - 3 f h^-4),  c_ab = -EI ab h^-3,  c_b = EI h^-2,
/// with h = a.a, ab = a.b, bb = b.b, f = h bb - ab^2 and N the axial law at |a| - 1
/// (ancfAxialLaw; EA (|a| - 1) wherever the point is in the linear range).
using PointRows = Eigen::Matrix<double, Eigen::Dynamic, 3>;
void ancfCablePointGradients(double EA, double EI, const PointRows& a, const PointRows& b,
                             bool tension_only, PointRows& fa, PointRows& fb);
/// The density phi(a, b) itself [J/m] (what ancfCablePoint differentiates).
double ancfCableEnergyDensity(double EA, double EI, const Eigen::Vector3d& a,
                              const Eigen::Vector3d& b, bool tension_only = false);

/// The discrete gradient of phi at one point over a step (a0, b0) -> (a1, b1) (what
/// ancfElasticForceDiscreteGradient sums; the reduced rope's energy-consistent step uses it at
/// its own Gauss points): (fa, fb) with
///   fa . (a1 - a0) + fb . (b1 - b0) = phi(a1, b1) - phi(a0, b0)   to round-off,
/// axial: the secant in s = |a|^2; bending: Gonzalez's midpoint gradient corrected along
/// dy = (da, l db), l [m] the length that makes the two parts of dy commensurate (the element's).
/// With hessian, Paa, Pab, Pbb a symmetric stand-in for 2 d(fa, fb)/d(a1, b1): axial
/// 2 Sbar I + 8 kappa a_m a_m^T, bending the Hessian at the midpoint.
void ancfCablePointDiscreteGradient(double EA, double EI, double l, const Eigen::Vector3d& a0,
                                    const Eigen::Vector3d& b0, const Eigen::Vector3d& a1,
                                    const Eigen::Vector3d& b1, bool hessian,
                                    CablePointDerivatives& d, bool tension_only);
/// The same from the step's start at the point (ancfCablePointStepStart).
void ancfCablePointDiscreteGradient(double EA, double EI, double l,
                                    const CablePointStepStart& start, const Eigen::Vector3d& a1,
                                    const Eigen::Vector3d& b1, bool hessian,
                                    CablePointDerivatives& d, bool tension_only);
/// The step's start at a point (a0, b0).
CablePointStepStart ancfCablePointStepStart(double EA, double EI, const Eigen::Vector3d& a0,
                                            const Eigen::Vector3d& b0, bool tension_only);

/// The trapezoid's work error of the tension-only axial law at one point over eps0 -> eps1 [J/m]
/// (ancfSlackSwitchWorkError's integrand):
///   | (N(eps0) + N(eps1)) / 2 (eps1 - eps0) - (psi(eps1) - psi(eps0)) |,
/// exactly 0 where both ends lie in the linear range (eps >= kSlackBand).
double ancfAxialSwitchWorkError(double EA, double eps0, double eps1);

/// Axial strain eps and curvature kappa at xi (for output and tests).
void ancfStrainCurvature(const Vector12& e, double xi, double l, double& eps, double& kappa);

}  // namespace crane_twin
