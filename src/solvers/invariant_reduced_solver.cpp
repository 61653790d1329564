#include "crane_twin/solvers/invariant_reduced_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "crane_twin/elements/gauss_legendre.hpp"
#include "crane_twin/integrators/numerical_failure.hpp"
#include "crane_twin/integrators/step_halving.hpp"
#include "crane_twin/rope/rope_support.hpp"

namespace crane_twin {

namespace {
using Matrix3X = Eigen::Matrix<double, 3, Eigen::Dynamic>;

// (S (x) I3) x as a 3 x m matrix product: vec(X S) for x = vec(X), S symmetric m x m.
Eigen::VectorXd kronTimes(const Eigen::MatrixXd& S, const Eigen::VectorXd& x) {
  const Eigen::Map<const Matrix3X> X(x.data(), 3, S.rows());
  Eigen::VectorXd y(3 * S.rows());
  Eigen::Map<Matrix3X>(y.data(), 3, S.rows()).noalias() = X * S;  // (into y: one allocation)
  return y;
}

constexpr int kMaxHalvings = 6;
// Refactorise the iteration matrix when the chord turned by more than this [rad] or the length
// changed by this fraction since the last factorisation, or the last step took this many
// Newton iterations.
constexpr double kChordTurn = 0.02;
constexpr double kLengthChange = 1e-3;
constexpr int kSlowIterations = 4;
// A rope whose points' tangents leave its chord by more than this [rad] (bowed by wind on the
// rope, or lagging behind a slewing trolley) takes its tension and axial stiffness along each
// point's own tangent in the iteration matrix (factorize): along the chord, the axial stiffness
// EA sin^2(alpha) leaks across it, and Newton on a wind draw (4 falls, 23.5 m/s with 30 % gusts,
// the tangents up to 0.064 rad off the chord) contracted by 0.79 per iteration, took 6.6
// iterations a step and failed at 30 ten times in 30 s. A straighter rope keeps the cheaper
// chord form (the T8036's combination 1: 8e-4 rad).
constexpr double kBowedTangent = 1e-3;
// Gauss points for the reduced force: at least kMinPointsPerElement per element and about
// kQuadraturePoints on the whole rope, at most the full model's rule. Measured on
// t8036_combination1 (120 elements, 5 s, against full order): 1 point per element left a
// 2.6 % top-tension error (the static stretch under the coarser rule differs, and the release
// rings axially) and 9e-6 m payload error; 2 points 9e-6 relative tension error and 2e-7 m, at
// the same wall time within the machine's noise (scripts/reduced_vs_full.sh). On 60 elements
// 2 points per element (120) instead of 4 (240) halved the force's cost at the same error
// against full order on the hoisting, lift-off and pick-and-place scenes (docs/model.md).
constexpr int kQuadraturePoints = 120;
constexpr int kMinPointsPerElement = 2;
// The support's compliance G turns with the slewing angle: refactorise past this relative change.
constexpr double kSupportChange = 1e-2;
// The ground's tangent (df/dr, df/dv at the payload point) in the iteration matrix: refactorise
// where it moved by this fraction of the factored one. A touchdown or a lift-off moves it by all
// of it, a sticking load that starts to slide as its speed outgrows v_s. On a resting load the
// sticking friction's slope mu N / v_s follows N, which the rope's tension moves a little every
// step: at 1e-3 the shipped set-down refactorised more than once a step while its load rested
// (4172 dense LU factorisations in 4000 steps; 0.90 s reduced against 0.51 s at this bound over
// its 20 s, the payload's path the same to 1e-8 m and the rope's to 2.6e-7 m RMS, within
// Newton's tolerance). The residual is exact, so a stale slope costs at most a linear
// contraction of 0.1 a correction in it.
constexpr double kContactTangentChange = 0.1;
}  // namespace

InvariantReducedSolver::InvariantReducedSolver(const AncfRope& rope,
                                               const InvariantRopeBasis& basis,
                                               RopeSupport& support, const GeneralizedAlpha& scheme,
                                               double time_step, NewtonSettings newton)
    : rope_(rope), basis_(basis), support_(support), ga_(scheme), h_(time_step), newton_(newton) {
  if (!(time_step > 0.0)) throw std::invalid_argument("time step must be positive");
  if (basis.nodes() != rope.elements() + 1)
    throw std::invalid_argument("basis and rope differ in nodes");
  m_ = basis.shapes();
  rigged_ = rope.hasRigging();
  n_ = 3 * m_ + (rigged_ ? 3 : 0);
  if (rigged_) bar_mass_ = rope.rigging().massMatrix();
  const int N = rope.elements();
  Eigen::VectorXd xg, wg;
  // The reduced quadrature (docs/model.md, and kQuadraturePoints above).
  const int per_element =
      std::clamp(std::max(kMinPointsPerElement, (kQuadraturePoints + N - 1) / N), 1,
                 rope.element().gauss_points);
  gaussLegendre01(per_element, xg, wg);
  const int ng = static_cast<int>(xg.size());
  D1_.resize(m_, N * ng);
  D2_.resize(m_, N * ng);
  w_.resize(N * ng);
  const double le = 1.0 / N;  // element length in xi
  const Eigen::MatrixXd& P = basis.positionRows();
  const Eigen::MatrixXd& S = basis.slopeRows();
  for (int e = 0; e < N; ++e)
    for (int g = 0; g < ng; ++g) {
      const int c = e * ng + g;
      const Eigen::Vector4d sx = ancfShapeDx(xg(g), le), sxx = ancfShapeDxx(xg(g), le);
      for (int k = 0; k < m_; ++k) {
        const Eigen::Vector4d nodal(P(e, k), S(e, k), P(e + 1, k), S(e + 1, k));
        D1_(k, c) = sx.dot(nodal);
        D2_(k, c) = sxx.dot(nodal);
      }
      w_(c) = wg(g) * le;
    }
  D1t_ = D1_.transpose();
  D2t_ = D2_.transpose();
  Kb_ = D2_ * w_.asDiagonal() * D2_.transpose();
  slope_sum_ = D1_.cwiseAbs().colwise().sum().maxCoeff();
  psi_top_ = P.row(0);
  psi_end_ = P.row(N);
  // The rope's own mass in xi-units is mu L times a constant matrix (docs/model.md); the hook
  // node's point mass (the end mass, or the hook block and the bar's share of a rigging) apart.
  const double L = rope.length(), mu = rope.element().mass_per_length;
  mass_hat_ =
      (InvariantRopeBasis::Projection(basis, rope.massMatrix(), L).scalarMass() -
       rope.topMass() * psi_top_.transpose() * psi_top_ -
       (hookPointMass() + (rigged_ ? bar_mass_(0, 0) : 0.0)) * psi_end_.transpose() * psi_end_) /
      (mu * L);
  refreshLength();
}

void InvariantReducedSolver::setRopeDamping(double c) {
  if (!std::isfinite(c) || c < 0.0) throw std::invalid_argument("rope damping must be >= 0");
  damping_ = c;
}

void InvariantReducedSolver::setLength(double length) {
  if (!(length > 0.0)) throw std::invalid_argument("rope length must be positive");
  L_ = length;
  Mrs_ = rope_.element().mass_per_length * L_ * mass_hat_ +
         rope_.topMass() * psi_top_.transpose() * psi_top_ +
         hookPointMass() * psi_end_.transpose() * psi_end_;
  Mrs_ = 0.5 * (Mrs_ + Mrs_.transpose()).eval();
  // F_r = B^T M (1 (x) g) = M_r u_g: psi_0 = 1 (and the payload point) is the uniform field, u_g
  // the translation by g.
  Eigen::VectorXd ug = Eigen::VectorXd::Zero(n_);
  ug.head<3>() = rope_.gravity();
  if (rigged_) ug.tail<3>() = rope_.gravity();
  gravity_ = massTimes(ug);
}

double InvariantReducedSolver::hookPointMass() const {
  return rigged_ ? rope_.hookMass() : rope_.endMass();
}

Eigen::Vector3d InvariantReducedSolver::hookPoint(const Eigen::VectorXd& y) const {
  return Eigen::Map<const Matrix3X>(y.data(), 3, m_) * psi_end_.transpose();
}

Vector6 InvariantReducedSolver::barCoordinates(const Eigen::VectorXd& y) const {
  Vector6 b;
  b << hookPoint(y), y.tail<3>();
  return b;
}

// T^T Qb, T = [psi(1) (x) I3, 0; 0, I3]: a force on [r_n; r_p] as reduced rows.
void InvariantReducedSolver::addBarForce(const Vector6& Qb, Eigen::VectorXd& Q) const {
  for (int k = 0; k < m_; ++k) Q.segment<3>(3 * k) += psi_end_(k) * Qb.head<3>();
  Q.tail<3>() += Qb.tail<3>();
}

// F_r = B^T F = gravity_ + sum_k [L int psi_k dxi f + psi_k(1) F_end] (x) e_k: the rope's external
// load per length f and end force F_end (AncfRope::setExternalLoad), int psi_k = mass_hat(k, 0);
// with a rigging F_end acts on the payload point's rows instead (as at full order).
Eigen::VectorXd InvariantReducedSolver::appliedForce() const {
  const Eigen::Vector3d& f = rope_.externalPerLength();
  const Eigen::Vector3d& fe = rope_.externalEndForce();
  if (f.isZero() && fe.isZero()) return gravity_;
  Eigen::VectorXd F = gravity_;
  for (int k = 0; k < m_; ++k) F.segment<3>(3 * k) += L_ * mass_hat_(k, 0) * f;
  F -= contactForce(fe);  // the end force acts where the ground does: the payload point
  return F;
}

Eigen::Vector3d InvariantReducedSolver::endPoint(const Eigen::VectorXd& y) const {
  return rigged_ ? Eigen::Vector3d(y.tail<3>()) : hookPoint(y);
}

Eigen::VectorXd InvariantReducedSolver::contactForce(const Eigen::Vector3d& f) const {
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(n_);
  if (rigged_) {
    Q.tail<3>() = -f;
  } else {
    for (int k = 0; k < m_; ++k) Q.segment<3>(3 * k) = -psi_end_(k) * f;
  }
  return Q;
}

GroundContactForce InvariantReducedSolver::contactAt(const CoupledState& x) const {
  if (!ground_) return {};
  if (ec_start_) {
    return ground_->stepMeanForce(endPoint(ec_start_->q), endPoint(x.q), endPoint(ec_start_->v),
                                  endPoint(x.v));
  }
  return ground_->force(endPoint(x.q), endPoint(x.v));
}

Eigen::VectorXd InvariantReducedSolver::massTimes(const Eigen::VectorXd& x) const {
  if (!rigged_) return kronTimes(Mrs_, x);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n_);
  out.head(3 * m_) = kronTimes(Mrs_, x);
  addBarForce(bar_mass_ * barCoordinates(x), out);
  return out;
}

void InvariantReducedSolver::pointRows(const Eigen::MatrixXd& Dt, const double* A, double scale,
                                       PointRows& r) const {
  // Component c of the field at the points: scale Dt a^(c), a^(c) the c-components of the
  // shapes' amplitudes (every third coordinate from c).
  r.resize(Dt.rows(), 3);
  for (int c = 0; c < 3; ++c) {
    const Eigen::Map<const Eigen::VectorXd, 0, Eigen::InnerStride<3>> Ac(A + c, m_);
    r.col(c).noalias() = scale * (Dt * Ac);
  }
}

Eigen::VectorXd InvariantReducedSolver::force(const Eigen::VectorXd& y,
                                              const Eigen::VectorXd& yd) const {
  // r_x = A D1 / L and r_xx = A D2 / L^2 at all points (n_g x 3, one column per component: the
  // matrix-vector product D1^T a^(c) of the shapes' derivatives with component c of the shapes'
  // amplitudes), the density's gradient there (ancfCablePointGradients), then
  // Q_A = (w phi_a)^T D1^T + (w phi_b / L)^T D2^T, component c as D1 (w phi_a)^(c) and likewise.
  const double EA = rope_.axialStiffnessAt(L_), EI = rope_.element().bending_stiffness;
  const double c1 = 1.0 / L_, c2 = 1.0 / (L_ * L_), cEA = damping_ * EA;
  const bool damped = cEA > 0.0 && yd.size() == y.size();
  const bool tension_only = rope_.element().tension_only;
  pointRows(D1t_, y.data(), c1, ra_);
  if (EI != 0.0) pointRows(D2t_, y.data(), c2, rb_);
  ancfCablePointGradients(EA, EI, ra_, rb_, tension_only, fa_, fb_);
  const Eigen::ArrayXd h = ra_.rowwise().squaredNorm().array();
  if (damped) {
    // c EA eps' t with eps' = t . r_x', t = r_x / |r_x|: c EA (a . a') / h a, where not slack.
    pointRows(D1t_, yd.data(), c1, rad_);
    const Eigen::ArrayXd rate = (ra_.array() * rad_.array()).rowwise().sum();
    for (Eigen::Index g = 0; g < h.size(); ++g) {
      if (ancfAxialSlack(std::sqrt(h(g)), tension_only)) continue;
      fa_.row(g) += (cEA * rate(g) / h(g)) * ra_.row(g);
    }
  }
  fa_.array().colwise() *= w_.array();
  fb_.array().colwise() *= c1 * w_.array();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n_);
  for (int c = 0; c < 3; ++c) {
    Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<3>> Qc(out.data() + c, m_);
    Qc.noalias() = D1t_.transpose() * fa_.col(c);
    if (EI != 0.0) Qc.noalias() += D2t_.transpose() * fb_.col(c);
  }
  const double min_stretch2 = h.minCoeff();
  last_force_min_stretch_ = std::sqrt(min_stretch2);
  if (rigged_) {
    // The rigging bar on [r_n; r_p] (AncfRope::setRigging), its axial damping as the rope's.
    const Vector6 b = barCoordinates(y);
    Vector6 Qb;
    rope_.rigging().elasticForce(b, Qb);
    if (damped) {
      Vector6 Qd;
      rope_.rigging().dampingForce(damping_, b, barCoordinates(yd), Qd);
      Qb += Qd;
    }
    addBarForce(Qb, out);
  }
  return out;
}

double InvariantReducedSolver::elasticEnergy(const Eigen::VectorXd& y) const {
  const double EA = rope_.axialStiffnessAt(L_), EI = rope_.element().bending_stiffness;
  const Eigen::Map<const Matrix3X> A(y.data(), 3, m_);
  const Matrix3X Rx = A * D1_ / L_;
  const Matrix3X Rxx = A * D2_ / (L_ * L_);
  double U = 0.0;
  for (int g = 0; g < w_.size(); ++g)
    U += w_(g) * L_ *
         ancfCableEnergyDensity(EA, EI, Rx.col(g), Rxx.col(g), rope_.element().tension_only);
  if (rigged_) U += rope_.rigging().elasticEnergy(barCoordinates(y));
  return U;
}

const Eigen::RowVectorXd& InvariantReducedSolver::stretches(const Eigen::VectorXd& y) const {
  // The slack checks of a step ask for the stretches of its start (the previous step's end) and
  // of its end, then the run's slack test for the end again: two entries serve them all.
  for (StretchCache& c : stretch_cache_)
    if (c.length == L_ && c.y.size() == y.size() && c.y == y) return c.g;
  StretchCache& c = stretch_cache_[next_stretch_cache_];
  next_stretch_cache_ = 1 - next_stretch_cache_;
  c.y = y;
  c.length = L_;
  // |r_x| = |A D1_g| / L per point, r_x at the points as force() forms it.
  PointRows rx;
  pointRows(D1t_, y.data(), 1.0 / L_, rx);
  c.g = rx.rowwise().norm().transpose();
  return c.g;
}

double InvariantReducedSolver::minStretchLowerBound(const Eigen::VectorXd& y) const {
  for (const StretchBound& b : stretch_bounds_)
    if (b.length == L_ && b.y.size() == y.size() && b.y == y) return b.bound;
  return stretches(y).minCoeff();
}

double InvariantReducedSolver::minStrain(const Eigen::VectorXd& y) const {
  return stretches(y).minCoeff() - 1.0;
}

double InvariantReducedSolver::slackLength(const Eigen::VectorXd& y) const {
  if (minStretchLowerBound(y) >= 1.0) return 0.0;
  const Eigen::RowVectorXd& g = stretches(y);
  double slack = 0.0;
  for (int k = 0; k < w_.size(); ++k) slack += w_(k) * L_ * std::max(0.0, 1.0 - g(k));
  return slack;
}

Eigen::Vector3d InvariantReducedSolver::chord(const Eigen::VectorXd& y) const {
  const Eigen::Vector3d c = hookPoint(y) - y.head<3>();
  const double n = c.norm();
  return n > 0.0 ? Eigen::Vector3d(c / n) : Eigen::Vector3d(0.0, 0.0, -1.0);
}

bool InvariantReducedSolver::factorize(double a, double c, double k, const Eigen::Matrix3d& G,
                                       const Eigen::VectorXd& y, const Eigen::VectorXd* y0) {
  const double EA = rope_.axialStiffnessAt(L_), EI = rope_.element().bending_stiffness;
  const Eigen::Vector3d d = chord(y);
  const Eigen::Matrix3d dd = d * d.transpose(), tr = Eigen::Matrix3d::Identity() - dd;
  // Tension-weighted K_g at the current state (N / |r_x| per point).
  const Eigen::Map<const Matrix3X> A(y.data(), 3, m_);
  const Matrix3X Rx = A * D1_ / L_;
  // and the axial law's slope N'(eps) per point (0 where a tension-only point is slack); in an
  // energy-consistent step from y0, the slope of twice the secant force Nbar = (psi(eps) -
  // psi(eps0)) / (eps - eps0) in eps, 2 (N(eps) - Nbar) / (eps - eps0) (N' at the midpoint where
  // the strains are that close), which is what that step's residual changes by.
  const bool tension_only = rope_.element().tension_only;
  Eigen::RowVectorXd g0;
  if (y0) g0 = (Eigen::Map<const Matrix3X>(y0->data(), 3, m_) * D1_ / L_).colwise().norm();
  Eigen::VectorXd wt(w_.size()), wa(w_.size());
  for (int g = 0; g < w_.size(); ++g) {
    const double gx = Rx.col(g).norm(), eps = gx - 1.0;
    double N, dN;
    ancfAxialLaw(EA, eps, tension_only, N, dN);
    wt(g) = w_(g) * std::max(0.0, N / gx);
    if (y0) {
      const double eps0 = g0(g) - 1.0, de = eps - eps0;
      if (std::abs(de) > 1e-9) {
        const double Nbar =
            (ancfAxialEnergy(EA, eps, tension_only) - ancfAxialEnergy(EA, eps0, tension_only)) / de;
        dN = 2.0 * (N - Nbar) / de;
      } else {
        double Nm;
        ancfAxialLaw(EA, 0.5 * (eps + eps0), tension_only, Nm, dN);
      }
    }
    wa(g) = w_(g) * dN;
  }
  const Eigen::MatrixXd Kg = D1_ * wt.asDiagonal() * D1_.transpose();
  const Eigen::MatrixXd Ktr = Kg / L_ + (EI / (L_ * L_ * L_)) * Kb_;           // on I - d d^T
  const Eigen::MatrixXd Kax = (D1_ * wa.asDiagonal() * D1_.transpose()) / L_;  // on d d^T
  const int n = n_;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + 3, n + 3);
  // The tension's and the axial law's 3 x 3 blocks: on the chord's projectors, or, for a bowed
  // rope (kBowedTangent), along each point's tangent t_g:
  //   sum_g D1_g D1_g^T (wt_g (I - t_g t_g^T) + wa_g t_g t_g^T) / L
  //   = Kg / L (x) I + sum_ab P_ab (x) e_a e_b^T,  P_ab = D1 diag((wa - wt) t_a t_b) D1^T / L,
  // and the damper's sum_ab Q_ab (x) e_a e_b^T, Q_ab = D1 diag(wa t_a t_b) D1^T / L; bending
  // stays across the chord, (EI / L^3) K_b (x) (I - d d^T), in either form.
  const Matrix3X T = Rx.colwise().normalized();  // t_g
  double bow = 0.0;
  for (int g = 0; g < w_.size(); ++g) bow = std::max(bow, T.col(g).cross(d).norm());
  std::vector<Eigen::Matrix3d> along, damped;  // per (i, j), row-major, when bowed
  if (bow > kBowedTangent) {
    static constexpr int pa[6] = {0, 0, 0, 1, 1, 2}, pb[6] = {0, 1, 2, 1, 2, 2};
    along.assign(static_cast<std::size_t>(m_ * m_), Eigen::Matrix3d::Zero());
    damped = along;
    Eigen::VectorXd cp(w_.size()), cq(w_.size());
    for (int q = 0; q < 6; ++q) {
      for (int g = 0; g < w_.size(); ++g) {
        const double tt = T(pa[q], g) * T(pb[q], g);
        cp(g) = (wa(g) - wt(g)) * tt;
        cq(g) = wa(g) * tt;
      }
      const Eigen::MatrixXd P = D1_ * cp.asDiagonal() * D1_.transpose() / L_;
      const Eigen::MatrixXd Q = damping_ != 0.0
                                    ? Eigen::MatrixXd(D1_ * cq.asDiagonal() * D1_.transpose() / L_)
                                    : Eigen::MatrixXd::Zero(m_, m_);
      for (int i = 0; i < m_; ++i)
        for (int j = 0; j < m_; ++j) {
          Eigen::Matrix3d& A = along[static_cast<std::size_t>(i * m_ + j)];
          Eigen::Matrix3d& C = damped[static_cast<std::size_t>(i * m_ + j)];
          A(pa[q], pb[q]) = A(pb[q], pa[q]) = P(i, j);
          C(pa[q], pb[q]) = C(pb[q], pa[q]) = Q(i, j);
        }
    }
    for (int i = 0; i < m_; ++i)
      for (int j = 0; j < m_; ++j)
        along[static_cast<std::size_t>(i * m_ + j)] +=
            (Kg(i, j) / L_) * Eigen::Matrix3d::Identity() + (EI / (L_ * L_ * L_)) * Kb_(i, j) * tr;
  }
  for (int i = 0; i < m_; ++i)
    for (int j = 0; j < m_; ++j) {
      const std::size_t ij = static_cast<std::size_t>(i * m_ + j);
      J.block<3, 3>(3 * i, 3 * j) =
          a * Mrs_(i, j) * Eigen::Matrix3d::Identity() +
          (along.empty() ? Eigen::Matrix3d(k * (Ktr(i, j) * tr + Kax(i, j) * dd) +
                                           c * damping_ * Kax(i, j) * dd)
                         : Eigen::Matrix3d(k * along[ij] + c * damping_ * damped[ij]));
      // The ground at the end point: psi_i(1) psi_j(1) (k K_c + c C_c).
      if (ground_ && !rigged_)
        J.block<3, 3>(3 * i, 3 * j) +=
            psi_end_(i) * psi_end_(j) * (k * contact_K_ + c * contact_C_);
    }
  if (rigged_) {
    // The bar's a M_b + c C_b + k K_b on [r_n; r_p] as T^T A_b T (T as addBarForce); in an
    // energy-consistent step K_b is its discrete gradient's stand-in (PendulumRope). The ground
    // acts on r_p.
    const Vector6 b = barCoordinates(y);
    Vector6 Qb;
    Matrix6 Kb, Cb;
    if (y0) {
      rope_.rigging().discreteGradientForce(barCoordinates(*y0), b, Qb, &Kb);
    } else {
      rope_.rigging().elasticForce(b, Qb, &Kb);
    }
    rope_.rigging().dampingForce(damping_, b, Vector6::Zero(), Qb, &Cb);
    Matrix6 Ab = a * bar_mass_ + c * Cb + k * Kb;
    if (ground_) Ab.bottomRightCorner<3, 3>() += k * contact_K_ + c * contact_C_;
    const int p = 3 * m_;
    for (int i = 0; i < m_; ++i) {
      for (int j = 0; j < m_; ++j)
        J.block<3, 3>(3 * i, 3 * j) += psi_end_(i) * psi_end_(j) * Ab.topLeftCorner<3, 3>();
      J.block<3, 3>(3 * i, p) += psi_end_(i) * Ab.topRightCorner<3, 3>();
      J.block<3, 3>(p, 3 * i) += psi_end_(i) * Ab.bottomLeftCorner<3, 3>();
    }
    J.block<3, 3>(p, p) += Ab.bottomRightCorner<3, 3>();
    fact_bar_taut_ = rope_.rigging().tension(b) > 0.0;
    fact_bar_dir_ = (b.tail<3>() - b.head<3>()).normalized();
  }
  J.block<3, 3>(n, 0).setIdentity();
  J.block<3, 3>(0, n).setIdentity();
  J.block<3, 3>(n, n) = -G;
  lu_.compute(J);
  ++factorizations_;
  newton_memory_.forget();  // its rate was the old matrix's
  factored_ = std::isfinite(lu_.rcond()) && lu_.rcond() > 1e-300;
  fact_a_ = a, fact_c_ = c, fact_k_ = k, fact_L_ = L_, fact_G_ = G, fact_d_ = d;
  fact_contact_K_ = contact_K_;
  fact_contact_C_ = contact_C_;
  return factored_;
}

void InvariantReducedSolver::initializeAccelerations(CoupledState& s) {
  prepareSupportState(support_, s);
  const int n = n_;
  Eigen::VectorXd Azr, rz;
  const Eigen::Matrix3d G = support_.setIterationWeights(1.0, 0.0, 0.0);
  if (!factorize(1.0, 0.0, 0.0, G, s.q))
    throw NumericalFailure("initial accelerations: singular mass");
  factored_ = false;  // the step's weights differ
  if (support_.size() > 0) rz = -support_.internalForce(s.z, s.zd, s.zdd);
  Eigen::VectorXd rhs(n + 3);
  rhs.head(n) = appliedForce() - force(s.q, s.v);
  if (ground_) rhs.head(n) -= contactForce(ground_->force(endPoint(s.q), endPoint(s.v)).f);
  rhs.tail<3>() = condenseSupport(support_, Eigen::Vector3d::Zero(), rz, Azr);
  const Eigen::VectorXd x = lu_.solve(rhs);
  storeConsistentAccelerations(support_, x.head(n), x.tail<3>(), Azr, s);
  last_step_length_ = L_;        // a start, not a hoist
  switching_.switching = false;  // consistent accelerations: generalized-alpha's start
}

void InvariantReducedSolver::step(CoupledState& s) {
  hoisting_ = L_ != last_step_length_;
  last_step_length_ = L_;
  if (!halves_failed_steps_) {
    std::string why;
    step_start_ = s;  // (into the member's storage: no allocation once sized)
    if (tryStep(s, h_, why)) return;
    s = step_start_;
    throw NumericalFailure(why);
  }
  stepWithHalving(
      s, h_, kMaxHalvings, support_,
      [this](CoupledState& x, double h, std::string& why) { return tryStep(x, h, why); },
      halved_steps_);
}

void InvariantReducedSolver::resetSwitching() {
  switching_.switching = false;
  switching_.energy_created = 0.0;
  last_step_length_ = L_;
}

void InvariantReducedSolver::continueSteppingOf(const InvariantReducedSolver& o) {
  switching_.switching = o.switching_.switching;
  switching_.energy_created = o.switching_.energy_created;
  last_step_length_ = o.last_step_length_;
}

// A tension-only rope (header): the rule of integrators/tension_only_step.hpp.
bool InvariantReducedSolver::tryStep(CoupledState& s, double h, std::string& why) {
  if (!rope_.element().tension_only && !ground_) return generalizedAlphaStep(s, h, why);
  TensionOnlyRope rope;
  rope.generalized_alpha_step = [this](CoupledState& x, double dt, std::string& w) {
    return generalizedAlphaStep(x, dt, w);
  };
  rope.energy_consistent_step = [this](CoupledState& x, double dt, std::string& w) {
    return energyConsistentStep(x, dt, w);
  };
  rope.switch_work_error = [this](const Eigen::VectorXd& y0, const Eigen::VectorXd& y1) {
    return slackSwitchWorkError(y0, y1) +
           (ground_ ? ground_->switchWorkError(endPoint(y0), endPoint(y1)) : 0.0);
  };
  rope.energy_created = [this](const CoupledState& a, const CoupledState& b) {
    return ropeEnergyCreated(a, b);
  };
  rope.restart_accelerations = [this](CoupledState& x) {
    const double length = last_step_length_;  // within a step: not a start
    initializeAccelerations(x);
    last_step_length_ = length;
  };
  const double tolerance =
      tensionOnlySwitchTolerance(rope_.endMass() + rope_.element().mass_per_length * L_, L_);
  return tensionOnlyStep(rope, tolerance, hoisting_, switching_, s, h, why);
}

bool InvariantReducedSolver::newton(
    const GeneralizedAlpha& scheme, double h,
    const std::function<Eigen::VectorXd(const CoupledState&)>& residual, CoupledState& s,
    std::string& why, const Eigen::VectorXd* support_means_z0, const Eigen::VectorXd* secant_from) {
  const int n = n_;
  int iterations = 0;
  double residual_min_stretch = -1.0, last_correction = 0.0;
  // The law's branches kept from the step's start to its first corrected iterate (NewtonMemory,
  // asked only of generalized-alpha steps that may end there): every point in the axial law's
  // linear range (the start's bound, and the residual's less what the correction can change), a
  // rigging's bar taut and the load clear of the ground, at the start, the iterate and the
  // corrected one. The start's part here, the iterates' in the first correction.
  const auto taut_bar = [&](const Eigen::VectorXd& y) {
    return !rigged_ || rope_.rigging().tension(barCoordinates(y)) > 0.0;
  };
  const auto clear = [&](const Eigen::VectorXd& y) {
    return !ground_ || ground_->penetration(endPoint(y)) <= 0.0;
  };
  const bool foresee = !secant_from && newton_.accept_foreseen_first_correction;
  const bool start_kept =
      foresee && clear(s.q) && taut_bar(s.q) &&
      (!rope_.element().tension_only || minStretchLowerBound(s.q) - 1.0 >= kSlackBand);
  const RopeIncrement increment = [&](const CoupledState& x, const NewtonWeights& w,
                                      const Eigen::Vector3d& rc, Eigen::VectorXd& dq,
                                      Eigen::Vector3d& dmu, std::string& reason) {
    bool contact_changed = false;
    if (ground_) {
      // The ground's tangent at this iterate: a touchdown, a lift-off or a change of the
      // friction's slope refactorises.
      const GroundContactForce cf = contactAt(x);
      contact_K_ = -cf.df_dr;
      contact_C_ = -cf.df_dv;
      const double scale = std::max({contact_K_.norm(), fact_contact_K_.norm(), 1e-300});
      const double cscale = std::max({contact_C_.norm(), fact_contact_C_.norm(), 1e-300});
      contact_changed = (contact_K_ - fact_contact_K_).norm() > kContactTangentChange * scale ||
                        (contact_C_ - fact_contact_C_).norm() > kContactTangentChange * cscale;
    }
    // An energy-consistent step's d Qbar / dy1 is half the stand-in (twice the secant's slope).
    const double ks = secant_from ? 0.5 : 1.0;
    const bool stale =
        contact_changed || !factored_ || w.mass != fact_a_ || ks * w.damping != fact_c_ ||
        ks * w.stiffness != fact_k_ || (w.G - fact_G_).norm() > kSupportChange * fact_G_.norm() ||
        std::abs(L_ - fact_L_) > kLengthChange * L_ || (chord(x.q) - fact_d_).norm() > kChordTurn ||
        (iterations == 0 && last_iterations_ >= kSlowIterations) ||
        (iterations > 0 && iterations % kSlowIterations == 0) || barChanged(x.q);
    if (stale && !factorize(w.mass, ks * w.damping, ks * w.stiffness, w.G, x.q, secant_from)) {
      reason = "singular reduced iteration matrix";
      return false;
    }
    ++iterations;
    // (the right-hand side and the solution in members' storage: no allocation once sized)
    Eigen::VectorXd& rhs = newton_rhs_;
    Eigen::VectorXd& dx = newton_dx_;
    rhs.resize(n + 3);
    rhs.head(n) = -w.stiffness * residual(x);
    rhs.head<3>() -= w.stiffness * x.lambda;
    rhs.tail<3>() = rc;
    dx = lu_.solve(rhs);
    dq = dx.head(n);
    dmu = dx.tail<3>();
    residual_min_stretch = last_force_min_stretch_;
    last_correction = dq.cwiseAbs().maxCoeff();
    if (foresee && iterations == 1) {
      bool kept = start_kept;
      if (kept) {
        const double moved = std::sqrt(3.0) * slope_sum_ * last_correction / L_;
        const Eigen::VectorXd corrected = x.q + dq;
        kept =
            (!rope_.element().tension_only || residual_min_stretch - moved - 1.0 >= kSlackBand) &&
            clear(x.q) && clear(corrected) && taut_bar(x.q) && taut_bar(corrected);
      }
      newton_memory_.first_correction_kept_branches = kept;
    }
    return true;
  };
  last_force_min_stretch_ = -1.0;  // set by force(): a residual without it records no bound
  // (the energy-consistent steps, secant_from set, neither use nor set the rate)
  const bool ok = newtonStep(scheme, support_, newton_, h, increment, s, why, newton_workspace_,
                             support_means_z0, secant_from ? nullptr : &newton_memory_);
  // A lower bound of the end state's smallest stretch: the last residual's, less what the last
  // correction can change it by (|dr_x| <= sum_k |psi_k'| |da_k| / L <= sqrt(3) S |dq|_inf / L).
  if (ok && residual_min_stretch > 0.0) {
    StretchBound& b = stretch_bounds_[next_stretch_bound_];
    next_stretch_bound_ = 1 - next_stretch_bound_;
    b.y = s.q;
    b.length = L_;
    b.bound = residual_min_stretch - std::sqrt(3.0) * slope_sum_ * last_correction / L_;
  }
  last_iterations_ = ok ? s.newton_iterations : kSlowIterations;
  if (ok) newton_iterations_ += s.newton_iterations, ++steps_;
  if (!ok) factored_ = false;
  return ok;
}

bool InvariantReducedSolver::generalizedAlphaStep(CoupledState& s, double h, std::string& why) {
  const Eigen::VectorXd applied = appliedForce();  // constant over the step
  const auto residual = [&](const CoupledState& x) -> Eigen::VectorXd {
    Eigen::VectorXd r = massTimes(x.qdd) + force(x.q, x.v) - applied;
    if (ground_) r += contactForce(ground_->force(endPoint(x.q), endPoint(x.v)).f);
    return r;
  };
  return newton(ga_, h, residual, s, why, nullptr, nullptr);
}

// The energy-consistent step (header; FullOrderSolver::energyConsistentStep at full order),
// energyConsistentScheme:
//   M_r (v1 - v0) / h = F_r - Qbar(y0, y1) - E^T lambda,
//   y1 - y0 = h ((1/2 + theta) v1 + (1/2 - theta) v0),
// lambda the step's mean constraint force and the support at the step's means (newtonStep).
bool InvariantReducedSolver::energyConsistentStep(CoupledState& s, double h, std::string& why) {
  const CoupledState start = s;
  startEnergyConsistentStep(s);
  const Eigen::VectorXd applied = appliedForce();
  const auto residual = [&](const CoupledState& x) -> Eigen::VectorXd {
    return massTimes(x.qdd) + discreteGradientForce(start, x.q, x.v, h) - applied;
  };
  ec_start_ = &start;
  const bool ok = newton(energyConsistentScheme(h), h, residual, s, why, &start.z, &start.q);
  ec_start_ = nullptr;
  newton_memory_.forget();  // the generalized-alpha steps after a switch measure their rate anew
  if (!ok) {
    s = start;
    return false;
  }
  return true;
}

Eigen::VectorXd InvariantReducedSolver::discreteGradientForce(const CoupledState& start,
                                                              const Eigen::VectorXd& y1,
                                                              const Eigen::VectorXd& v1,
                                                              double h) const {
  const double EA = rope_.axialStiffnessAt(L_), EI = rope_.element().bending_stiffness;
  const bool tension_only = rope_.element().tension_only;
  const double le = L_ / rope_.elements();  // the element length weighs Gonzalez's correction
  const Eigen::Map<const Matrix3X> A0(start.q.data(), 3, m_), A1(y1.data(), 3, m_);
  const Matrix3X Rx0 = A0 * D1_ / L_, Rx1 = A1 * D1_ / L_;
  const Matrix3X Rxx0 = A0 * D2_ / (L_ * L_), Rxx1 = A1 * D2_ / (L_ * L_);
  Matrix3X Fa(3, w_.size()), Fb(3, w_.size());
  CablePointDerivatives d;
  for (int g = 0; g < w_.size(); ++g) {
    ancfCablePointDiscreteGradient(EA, EI, le, Rx0.col(g), Rxx0.col(g), Rx1.col(g), Rxx1.col(g),
                                   false, d, tension_only);
    Fa.col(g) = w_(g) * d.fa;
    Fb.col(g) = (w_(g) / L_) * d.fb;
  }
  const Matrix3X QA = Fa * D1_.transpose() + Fb * D2_.transpose();
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(n_);
  Q.head(3 * m_) = Eigen::Map<const Eigen::VectorXd>(QA.data(), QA.size());
  if (rigged_) {
    Vector6 Qb;
    rope_.rigging().discreteGradientForce(barCoordinates(start.q), barCoordinates(y1), Qb);
    addBarForce(Qb, Q);
  }
  // The damper at the midpoint and the step's own mean velocity (y1 - y0) / h (a dissipation).
  if (damping_ > 0.0) Q += dampingForce(0.5 * (start.q + y1), (y1 - start.q) / h);
  if (ground_) {
    Q += contactForce(
        ground_->stepMeanForce(endPoint(start.q), endPoint(y1), endPoint(start.v), endPoint(v1)).f);
  }
  return Q;
}

Eigen::VectorXd InvariantReducedSolver::dampingForce(const Eigen::VectorXd& y,
                                                     const Eigen::VectorXd& yd) const {
  // c EA eps' t at the points where the rope is not slack (ancfAxialDampingForce).
  const double cEA = damping_ * rope_.axialStiffnessAt(L_);
  const bool tension_only = rope_.element().tension_only;
  const Eigen::Map<const Matrix3X> A(y.data(), 3, m_), Ad(yd.data(), 3, m_);
  const Matrix3X Rx = A * D1_ / L_, Rxd = Ad * D1_ / L_;
  Matrix3X Fa = Matrix3X::Zero(3, w_.size());
  for (int g = 0; g < w_.size(); ++g) {
    const double gx = Rx.col(g).norm();
    if (ancfAxialSlack(gx, tension_only)) continue;
    const Eigen::Vector3d t = Rx.col(g) / gx;
    Fa.col(g) = (w_(g) * cEA * t.dot(Rxd.col(g))) * t;
  }
  const Matrix3X QA = Fa * D1_.transpose();
  Eigen::VectorXd Q = Eigen::VectorXd::Zero(n_);
  Q.head(3 * m_) = Eigen::Map<const Eigen::VectorXd>(QA.data(), QA.size());
  if (rigged_) {
    Vector6 Qb;
    rope_.rigging().dampingForce(damping_, barCoordinates(y), barCoordinates(yd), Qb);
    addBarForce(Qb, Q);
  }
  return Q;
}

double InvariantReducedSolver::slackSwitchWorkError(const Eigen::VectorXd& y0,
                                                    const Eigen::VectorXd& y1) const {
  double err =
      rigged_ ? rope_.rigging().slackSwitchWorkError(barCoordinates(y0), barCoordinates(y1)) : 0.0;
  // Both ends in the linear range: the trapezoid is exact (ancfAxialSwitchWorkError).
  if (minStretchLowerBound(y0) - 1.0 >= kSlackBand && minStretchLowerBound(y1) - 1.0 >= kSlackBand)
    return err;
  const double EA = rope_.axialStiffnessAt(L_);
  const Eigen::RowVectorXd g0 = stretches(y0);
  const Eigen::RowVectorXd& g1 = stretches(y1);
  for (int g = 0; g < w_.size(); ++g)
    err += w_(g) * L_ * ancfAxialSwitchWorkError(EA, g0(g) - 1.0, g1(g) - 1.0);
  return err;
}

bool InvariantReducedSolver::barChanged(const Eigen::VectorXd& y) const {
  if (!rigged_) return false;
  const Vector6 b = barCoordinates(y);
  const Eigen::Vector3d d = b.tail<3>() - b.head<3>();
  return (rope_.rigging().tension(b) > 0.0) != fact_bar_taut_ ||
         (d.normalized() - fact_bar_dir_).norm() > kChordTurn;
}

double InvariantReducedSolver::ropeEnergyCreated(const CoupledState& start,
                                                 const CoupledState& s) const {
  // FullOrderSolver::ropeEnergyCreated in reduced coordinates: the rope's own energy
  // 1/2 v^T M_r v + U(B y) - F_r^T y changes by the top force's work -lambda . dy_top (E = [I3 0
  // ...], trapezoid in time) less the damper's dissipation at the midpoint.
  const Eigen::VectorXd F = appliedForce();
  const auto ropeEnergy = [&](const CoupledState& x) {
    const double ground = ground_ ? ground_->energy(endPoint(x.q)) : 0.0;
    return 0.5 * x.v.dot(massTimes(x.v)) + elasticEnergy(x.q) - F.dot(x.q) + ground;
  };
  const Eigen::VectorXd dq = s.q - start.q;
  double created =
      ropeEnergy(s) - ropeEnergy(start) + 0.5 * (start.lambda + s.lambda).dot(dq.head<3>());
  if (ground_) {
    // Less the work of the ground's damper and friction (at the midpoint, <= 0).
    created -=
        ground_->dissipativeForce(endPoint(0.5 * (start.q + s.q)), endPoint(0.5 * (start.v + s.v)))
            .dot(endPoint(dq));
  }
  if (damping_ > 0.0) {
    created += dampingForce(0.5 * (start.q + s.q), 0.5 * (start.v + s.v)).dot(dq);
  }
  return created;
}

const InvariantRopeBasis::Projection& InvariantReducedSolver::projection() const {
  if (rope_.length() != L_)
    throw std::logic_error("reduced projection: rope and solver lengths differ");
  if (!projection_ || projection_length_ != L_) {
    projection_.emplace(basis_, rope_.massMatrix(), L_);
    projection_length_ = L_;
  }
  return *projection_;
}

CoupledState InvariantReducedSolver::project(const CoupledState& full) const {
  const InvariantRopeBasis::Projection& P = projection();
  // The hoist rope's part projected with its top and end node held (a_0 is the top node: psi_k(0)
  // = delta_k0), a rigging's payload point kept as it is. With the end mass's velocity held, a
  // hand-back keeps the swing's momentum: the plain projection of Chrono's stress-free release at
  // 0.139 s moved the payload's vx by 9.6 mm/s of its -15.9 mm/s (docs/model.md "Hand-over to
  // full order").
  const auto reduce = [&](const Eigen::VectorXd& x) {
    if (!rigged_) return P.withEndsHeld(x);
    Eigen::VectorXd y(n_);
    y << P.withEndsHeld(x), x.tail<3>();
    return y;
  };
  CoupledState r = full;
  r.q = reduce(full.q);
  r.v = reduce(full.v);
  r.qdd = reduce(full.qdd);
  r.a = full.a.size() == full.q.size() ? reduce(full.a) : r.qdd;
  return r;
}

CoupledState InvariantReducedSolver::expand(const CoupledState& reduced) const {
  const auto grow = [&](const Eigen::VectorXd& y) {
    if (!rigged_) return basis_.expand(y, L_);
    Eigen::VectorXd x(rope_.dofs());
    x << basis_.expand(y, L_), y.tail<3>();
    return x;
  };
  CoupledState f = reduced;
  f.q = grow(reduced.q);
  f.v = grow(reduced.v);
  f.qdd = grow(reduced.qdd);
  f.a = grow(reduced.a);
  return f;
}

double InvariantReducedSolver::projectionError(const Eigen::VectorXd& q) const {
  const Eigen::VectorXd y = projection().withEndsHeld(q);
  double e = 0.0;
  for (int j = 0; j <= rope_.elements(); ++j)
    e = std::max(e, (basis_.nodePosition(y, j) - q.segment<3>(6 * j)).norm());
  return e;
}

double InvariantReducedSolver::energy(const CoupledState& s) const {
  const double ground = ground_ ? ground_->energy(endPoint(s.q)) : 0.0;
  return 0.5 * s.v.dot(massTimes(s.v)) + elasticEnergy(s.q) - appliedForce().dot(s.q) +
         support_.energy(s.z, s.zd) + ground;
}

double InvariantReducedSolver::topTension(const CoupledState& s) const {
  return ropeTopTension(s.lambda, rope_.topMass(), s.qdd.head<3>(), rope_.gravity());
}

}  // namespace crane_twin
