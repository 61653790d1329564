#include "crane_twin/reduced_order_solver.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace crane_twin {

namespace {

// T^T x: sum of the node position components (the translations' generalised force).
Eigen::Vector3d translationSum(const Eigen::VectorXd& x) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (int j = 0; 6 * j < x.size(); ++j) s += x.segment<3>(6 * j);
  return s;
}

std::string at(double t) { return "t = " + std::to_string(t) + " s"; }

}  // namespace

ReducedOrderSolver::ReducedOrderSolver(const AncfRope& rope, RopeSupport& support,
                                       const GeneralizedAlpha& scheme, double time_step,
                                       const ReducedSettings& settings)
    : rope_(rope), support_(support), ga_(scheme), h_(time_step), settings_(settings) {
  const int n = rope_.dofs();
  if (settings_.kept_modes < 1 || settings_.kept_modes > n - 3) {
    throw std::invalid_argument("reduced rope: kept modes must be in 1.." + std::to_string(n - 3) +
                                ", got " + std::to_string(settings_.kept_modes));
  }
  if (!(settings_.delta > 0.0)) throw std::invalid_argument("reduced rope: delta must be > 0");
  if (!(time_step > 0.0)) throw std::invalid_argument("time step must be positive");
  settings_.modes.kept = settings_.kept_modes;
}

Eigen::VectorXd ReducedOrderSolver::expand(const Eigen::VectorXd& y) const {
  const int r = static_cast<int>(phi_.cols());
  Eigen::VectorXd x = phi_ * y.head(r);
  const Eigen::Vector3d ub = y.tail<3>();
  for (int j = 0; j < rope_.nodes(); ++j) x.segment<3>(6 * j) += ub;
  return x;
}

Eigen::VectorXd ReducedOrderSolver::project(const Eigen::VectorXd& x) const {
  // M_r w = [Phi_c^T M x; T^T M x] with M_r = [I Mcb; Mcb^T Mbb]: eliminate w_c = g_c - Mcb w_b.
  const int r = static_cast<int>(phi_.cols());
  const Eigen::VectorXd Mx = rope_.massMatrix() * x;
  const Eigen::VectorXd gc = phi_.transpose() * Mx;
  const Eigen::Vector3d gb = translationSum(Mx);
  const Eigen::Matrix3d S = Mbb_ - Mcb_.transpose() * Mcb_;
  Eigen::VectorXd w(r + 3);
  w.tail<3>() = S.ldlt().solve(gb - Mcb_.transpose() * gc);
  w.head(r) = gc - Mcb_ * w.tail<3>();
  return w;
}

void ReducedOrderSolver::addStaticCorrection(const SparseMatrix& K, const SparseMatrix& M,
                                             const Eigen::VectorXd& load) {
  const int n = rope_.dofs();
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(withoutTopPosition(K));
  if (ldlt.info() != Eigen::Success) {
    throw NumericalFailure(at(s_.t) + ": static correction: singular rope tangent");
  }
  Eigen::VectorXd psi = Eigen::VectorXd::Zero(n);
  if (load.size() != n) throw std::invalid_argument("static correction: load of the wrong size");
  psi.tail(n - 3) = ldlt.solve(Eigen::VectorXd(load.tail(n - 3)));
  // M-orthogonal to the modes; skipped when the modes already span it.
  const double before = std::sqrt(psi.dot(M * psi));
  psi -= phi_ * (phi_.transpose() * (M * psi));
  const double after = std::sqrt(psi.dot(M * psi));
  if (!(after > 1e-8 * before) || !std::isfinite(after)) return;
  psi /= after;
  Eigen::MatrixXd B(n, phi_.cols() + 1);
  B << phi_, psi;
  phi_ = B;
  ritz(K, M);
  ++stats_.static_corrections;
}

void ReducedOrderSolver::ritz(const SparseMatrix& K, const SparseMatrix& M) {
  const Eigen::MatrixXd Kr = phi_.transpose() * (K * phi_), Mr = phi_.transpose() * (M * phi_);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(
      0.5 * (Kr + Kr.transpose()), 0.5 * (Mr + Mr.transpose()));
  if (es.info() != Eigen::Success) throw NumericalFailure(at(s_.t) + ": Rayleigh-Ritz failed");
  phi_ = phi_ * es.eigenvectors();
  omega2_ = es.eigenvalues();
}

void ReducedOrderSolver::startSubdomain(const Eigen::VectorXd& e, BasisUpdate how,
                                        const Eigen::VectorXd& load) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = rope_.dofs();
  Eigen::VectorXd Q;
  const SparseMatrix K = rope_.tangentStiffness(e, &Q);
  const SparseMatrix& M = rope_.massMatrix();
  if (how == BasisUpdate::ritz && phi_.size() > 0) {
    ritz(K, M);
    ++stats_.ritz_updates;
  } else if (modes_.phi.size() == 0 || settings_.update == ModeUpdate::cold) {
    if (modes_.phi.size() != 0) ++stats_.eigen_solves;
    modes_ = coldRopeModes(K, M, settings_.modes);
  } else {
    ++stats_.eigen_solves;
    try {
      modes_ = warmRopeModes(K, M, modes_, settings_.modes);
    } catch (const std::runtime_error&) {
      ++stats_.cold_fallbacks;
      modes_ = coldRopeModes(K, M, settings_.modes);
    }
  }
  if (how != BasisUpdate::ritz || phi_.size() == 0) {
    phi_ = modes_.phi.leftCols(settings_.kept_modes);
    omega2_ = modes_.omega2.head(settings_.kept_modes);
    if (how == BasisUpdate::modes_and_correction) addStaticCorrection(K, M, load);
  }
  const int r = static_cast<int>(phi_.cols());
  if (!phi_.allFinite() || !omega2_.allFinite()) {
    throw NumericalFailure(at(s_.t) + ": rope mode update gave non-finite modes");
  }
  // T columns: unit translation fields; M T is the mass-weighted field.
  Eigen::MatrixXd MT(n, 3);
  for (int d = 0; d < 3; ++d) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
    for (int j = 0; j < rope_.nodes(); ++j) u(6 * j + d) = 1.0;
    MT.col(d) = M * u;
  }
  Mcb_ = phi_.transpose() * MT;
  for (int d = 0; d < 3; ++d) Mbb_.col(d) = translationSum(MT.col(d));
  const Eigen::VectorXd g = rope_.gravityForce() - Q;
  f_.resize(r + 3);
  f_.head(r) = phi_.transpose() * g;
  f_.tail<3>() = translationSum(g);
  node_rows_.resize(3 * rope_.nodes(), r);
  slope_rows_.resize(3 * rope_.nodes(), r);
  for (int j = 0; j < rope_.nodes(); ++j) {
    node_rows_.middleRows<3>(3 * j) = phi_.middleRows<3>(6 * j);
    slope_rows_.middleRows<3>(3 * j) = phi_.middleRows<3>(6 * j + 3);
  }
  e_m_ = e;
  if (settings_.residual_tolerance > 0.0) {
    K_m_ = K;
    Q_m_ = Q;
  }
  steps_in_subdomain_ = 0;
  G_step_.setConstant(std::nan(""));  // forces the step system's refactorisation
  ++stats_.subdomains;
  if (how != BasisUpdate::ritz) {  // a Ritz block is not the modes of this K
    stats_.max_mode_residual =
        std::max(stats_.max_mode_residual, ropeModeResidual(K, M, modes_, settings_.modes.shift));
  }
  stats_.mode_update_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

Eigen::VectorXd ReducedOrderSolver::solveWeighted(double a, double c, double k,
                                                  const Eigen::VectorXd& ry,
                                                  const Eigen::VectorXd& rz,
                                                  const Eigen::Vector3d& rc, Eigen::VectorXd& dz,
                                                  Eigen::Vector3d& dmu, bool cached) {
  const int r = static_cast<int>(phi_.cols()), m = support_.size();
  const Eigen::VectorXd d = Eigen::VectorXd::Constant(r, a) + k * omega2_;
  const Eigen::VectorXd rcd = ry.head(r).cwiseQuotient(d);
  // Row b after eliminating p_c; row lambda after eliminating z.
  const Eigen::Vector3d rb = ry.tail<3>() - a * Mcb_.transpose() * rcd;
  Eigen::VectorXd Azr;
  Eigen::Vector3d rl = rc;
  if (m > 0) {
    Azr = support_.solve(rz);
    rl += support_.pointMotion(Azr);
  }
  Eigen::Matrix<double, 6, 1> rhs;
  rhs << rb, rl;
  Eigen::Matrix<double, 6, 1> x;
  if (cached) {
    x = kkt_lu_.solve(rhs);
  } else {
    x = eliminatedMatrix(a, k, support_.setIterationWeights(a, c, k)).partialPivLu().solve(rhs);
  }
  Eigen::VectorXd dy(r + 3);
  dy.tail<3>() = x.head<3>();
  dy.head(r) = rcd - a * (Mcb_ * x.head<3>()).cwiseQuotient(d);
  dmu = x.tail<3>();
  if (m > 0) dz = Azr + support_.solvePointForce(dmu);
  return dy;
}

// The 6 x 6 system in (u_b, lambda) left after eliminating p_c and z (header): with
// d = a + k Omega^2, [a M_bb - a^2 M_cb^T diag(1/d) M_cb, I; I, -G].
Eigen::Matrix<double, 6, 6> ReducedOrderSolver::eliminatedMatrix(double a, double k,
                                                                 const Eigen::Matrix3d& G) const {
  const Eigen::VectorXd d = Eigen::VectorXd::Constant(omega2_.size(), a) + k * omega2_;
  Eigen::Matrix<double, 6, 6> A;
  A.topLeftCorner<3, 3>() = a * Mbb_ - a * a * Mcb_.transpose() * d.cwiseInverse().asDiagonal() * Mcb_;
  A.topRightCorner<3, 3>().setIdentity();
  A.bottomLeftCorner<3, 3>().setIdentity();
  A.bottomRightCorner<3, 3>() = -G;
  return A;
}

void ReducedOrderSolver::initializeAccelerations() {
  const int r = static_cast<int>(phi_.cols()), m = support_.size();
  Eigen::VectorXd ry = f_;
  ry.head(r) -= omega2_.cwiseProduct(s_.y.head(r));
  Eigen::VectorXd rz, dz;
  if (m > 0) rz = -support_.internalForce(s_.z, s_.zd, Eigen::VectorXd::Zero(m));
  Eigen::Vector3d mu;
  s_.ydd = solveWeighted(1.0, 0.0, 0.0, ry, rz, Eigen::Vector3d::Zero(), dz, mu, false);
  s_.ya = s_.ydd;
  s_.lambda = mu;
  s_.zdd = m > 0 ? dz : Eigen::VectorXd();
  s_.za = s_.zdd;
}

void ReducedOrderSolver::initialize(const CoupledState& full) {
  modes_ = RopeModes{};
  stats_ = ReducedStatistics{};
  s_ = ReducedState{};
  s_.t = full.t;
  startSubdomain(full.q);
  // The first basis is model setup (like the structure's modes), not a mode update.
  stats_.setup_mode_seconds = stats_.mode_update_seconds;
  stats_.mode_update_seconds = 0.0;
  const int r = static_cast<int>(phi_.cols());
  s_.y = Eigen::VectorXd::Zero(r + 3);
  s_.yd = project(full.v);
  s_.z = full.z.size() == support_.size() ? full.z : Eigen::VectorXd::Zero(support_.size());
  s_.zd = full.zd.size() == support_.size() ? full.zd : Eigen::VectorXd::Zero(support_.size());
  const Eigen::VectorXd vr = expand(s_.yd);
  stats_.projection_energy_loss +=
      0.5 * (full.v.dot(rope_.massMatrix() * full.v) - vr.dot(rope_.massMatrix() * vr));
  initializeAccelerations();
}

// Paper eq. (10) measured on the deformation part Phi_c p_c: the rigid translation T u_b costs
// the linearisation nothing (Q(e + T u) = Q(e), K T = 0), so a trolley travelling or slewing
// does not by itself cut subdomains; the swing it excites does.
double ReducedOrderSolver::maxNodeIncrement() const {
  const int r = static_cast<int>(phi_.cols());
  const Eigen::VectorXd inc = node_rows_ * s_.y.head(r);
  double worst = 0.0;
  for (int j = 0; j < rope_.nodes(); ++j) worst = std::max(worst, inc.segment<3>(3 * j).squaredNorm());
  return std::sqrt(worst);
}

void ReducedOrderSolver::step() {
  const int r = static_cast<int>(phi_.cols()), m = support_.size();
  const double h = h_, bh2 = ga_.beta * h * h, massWeight = ga_.massWeight();
  const Eigen::VectorXd ydd0 = s_.ydd, ya0 = s_.ya, zdd0 = s_.zdd, za0 = s_.za;
  ga_.predict(h, ydd0, ya0, s_.y, s_.yd);
  if (m > 0) ga_.predict(h, zdd0, za0, s_.z, s_.zd);
  // The step's 6 x 6 system: refactorised when the subdomain or the support's G changes.
  const Eigen::Matrix3d G = support_.setIterationWeights(massWeight, ga_.gamma * h, bh2);
  if (!(G == G_step_)) {
    kkt_lu_.compute(eliminatedMatrix(massWeight, bh2, G));
    G_step_ = G;
  }
  // Residuals scaled by beta h^2 (as the full-order solver's); the system is linear: one solve.
  Eigen::VectorXd ry(r + 3);
  ry.head(r) = s_.ydd.head(r) + Mcb_ * s_.ydd.tail<3>() + omega2_.cwiseProduct(s_.y.head(r)) -
               f_.head(r);
  ry.tail<3>() = Mcb_.transpose() * s_.ydd.head(r) + Mbb_ * s_.ydd.tail<3>() - f_.tail<3>() +
                 s_.lambda;
  ry *= -bh2;
  Eigen::VectorXd rz, dz;
  if (m > 0) rz = -bh2 * (support_.internalForce(s_.z, s_.zd, s_.zdd) - support_.pointForceToCoordinates(s_.lambda));
  const Eigen::Vector3d rc = -(e_m_.head<3>() + s_.y.tail<3>() - support_.point(s_.z));
  Eigen::Vector3d dmu;
  const Eigen::VectorXd dy = solveWeighted(massWeight, ga_.gamma * h, bh2, ry, rz, rc, dz, dmu, true);
  ga_.correct(h, dy, s_.y, s_.yd, s_.ydd);
  s_.lambda += dmu / bh2;
  if (m > 0) {
    ga_.correct(h, dz, s_.z, s_.zd, s_.zdd);
    s_.za = ga_.nextA(zdd0, za0, s_.zdd);
  }
  s_.ya = ga_.nextA(ydd0, ya0, s_.ydd);
  s_.t += h;
  if (!s_.y.allFinite() || !s_.yd.allFinite() || !s_.z.allFinite() || !s_.lambda.allFinite()) {
    throw NumericalFailure(at(s_.t) + ": non-finite reduced state");
  }
  ++steps_in_subdomain_;
  const bool residualCut = settings_.residual_tolerance > 0.0 &&
                           steps_in_subdomain_ % settings_.residual_check_steps == 0 &&
                           linearisationResidual() > settings_.residual_tolerance;
  if (residualCut || maxNodeIncrement() > settings_.delta) {
    // Switch: rebuild the linearisation at the current state and carry the state over.
    restartAt(fullState());
  }
}

void ReducedOrderSolver::restartAt(const CoupledState& f, bool consistent_accelerations,
                                   BasisUpdate how, const Eigen::VectorXd& load) {
  try {
    startSubdomain(f.q, how, load);
  } catch (const NumericalFailure&) {
    throw;
  } catch (const std::runtime_error& ex) {
    throw NumericalFailure(at(s_.t) + ": rope mode update failed: " + ex.what());
  }
  const int r = static_cast<int>(phi_.cols());
  s_.t = f.t;  // f may come from the full-order solver (a slack episode), not from s_
  s_.z = f.z;
  s_.zd = f.zd;
  s_.zdd = f.zdd;
  s_.za = f.za;
  s_.lambda = f.lambda;
  s_.y.setZero(r + 3);
  s_.yd = project(f.v);
  s_.ydd = project(f.qdd);
  s_.ya = project(f.a);
  if (consistent_accelerations) initializeAccelerations();
  const Eigen::VectorXd vr = expand(s_.yd);
  const SparseMatrix& M = rope_.massMatrix();
  stats_.projection_energy_loss += 0.5 * (f.v.dot(M * f.v) - vr.dot(M * vr));
}

// max over nodes of |Q(e) - Q_m - K_m (e - e_m)| (translational rows) [N].
double ReducedOrderSolver::linearisationResidual() const {
  const Eigen::VectorXd de = expand(s_.y);
  Eigen::VectorXd Q;
  rope_.elasticForce(e_m_ + de, Q);
  const Eigen::VectorXd r = Q - Q_m_ - K_m_ * de;
  double worst = 0.0;
  for (int j = 0; j < rope_.nodes(); ++j) worst = std::max(worst, r.segment<3>(6 * j).norm());
  return worst;
}

CoupledState ReducedOrderSolver::fullState() const {
  CoupledState f;
  f.t = s_.t;
  f.q = e_m_ + expand(s_.y);
  f.v = expand(s_.yd);
  f.qdd = expand(s_.ydd);
  f.a = expand(s_.ya);
  f.z = s_.z;
  f.zd = s_.zd;
  f.zdd = s_.zdd;
  f.za = s_.za;
  f.lambda = s_.lambda;
  return f;
}

Eigen::Vector3d ReducedOrderSolver::nodePosition(int j) const {
  const int r = static_cast<int>(phi_.cols());
  return e_m_.segment<3>(6 * j) + node_rows_.middleRows<3>(3 * j) * s_.y.head(r) + s_.y.tail<3>();
}

Eigen::Vector3d ReducedOrderSolver::nodeVelocity(int j) const {
  const int r = static_cast<int>(phi_.cols());
  return node_rows_.middleRows<3>(3 * j) * s_.yd.head(r) + s_.yd.tail<3>();
}

double ReducedOrderSolver::minNodalStrain() const {
  const int r = static_cast<int>(phi_.cols());
  const Eigen::VectorXd slopes = slope_rows_ * s_.y.head(r);
  double least = 1e300;
  for (int j = 0; j < rope_.nodes(); ++j) {
    least = std::min(least, (e_m_.segment<3>(6 * j + 3) + slopes.segment<3>(3 * j)).norm() - 1.0);
  }
  return least;
}

double ReducedOrderSolver::constraintError() const {
  return (e_m_.head<3>() + s_.y.tail<3>() - support_.point(s_.z)).norm();
}

double ReducedOrderSolver::topTension() const {
  return (s_.lambda + rope_.topMass() * (s_.ydd.tail<3>() - rope_.gravity())).norm();
}

}  // namespace crane_twin
