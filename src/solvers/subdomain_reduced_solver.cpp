#include "crane_twin/solvers/subdomain_reduced_solver.hpp"

#include <Eigen/Geometry>
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

Eigen::Matrix3d cross(const Eigen::Vector3d& a) {
  Eigen::Matrix3d A;
  A << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return A;
}

}  // namespace

SubdomainReducedSolver::SubdomainReducedSolver(const AncfRope& rope, RopeSupport& support,
                                               const GeneralizedAlpha& scheme, double time_step,
                                               const SubdomainSettings& settings)
    : rope_(rope), support_(support), ga_(scheme), h_(time_step), settings_(settings) {
  const int n = rope_.dofs();
  if (settings_.kept_modes < 1 || settings_.kept_modes > n - 3) {
    throw std::invalid_argument("reduced rope: kept modes must be in 1.." + std::to_string(n - 3) +
                                ", got " + std::to_string(settings_.kept_modes));
  }
  if (!(settings_.delta > 0.0)) throw std::invalid_argument("reduced rope: delta must be > 0");
  if (!(settings_.max_chord_rotation > 0.0)) {
    throw std::invalid_argument("reduced rope: the chord rotation bound must be > 0");
  }
  if (!(time_step > 0.0)) throw std::invalid_argument("time step must be positive");
  settings_.modes.kept = settings_.kept_modes;
}

// theta = c x D_last / |c|^2, R = exp([theta]x), J_l = I + (1 - cos f)/f^2 [theta]x +
// (f - sin f)/f^3 [theta]x^2 with f = |theta| (header).
Eigen::Vector3d SubdomainReducedSolver::chordAngle(const Eigen::Vector3d& d_last) const {
  if (!frame_) return Eigen::Vector3d::Zero();
  return chord_.cross(d_last) / chord_.squaredNorm();
}

Eigen::Vector3d SubdomainReducedSolver::lastNodeDisplacement(const Eigen::VectorXd& x) const {
  return node_rows_.middleRows<3>(3 * (rope_.nodes() - 1)) * x.head(phi_.cols());
}

SubdomainReducedSolver::ChordRotation SubdomainReducedSolver::chordRotation(
    const Eigen::Vector3d& d_last) const {
  ChordRotation c;
  c.theta = chordAngle(d_last);
  const double f = c.theta.norm();
  if (f == 0.0) return c;
  c.R = Eigen::AngleAxisd(f, c.theta / f).toRotationMatrix();
  const double f2 = f * f;
  const double a = f < 1e-4 ? 0.5 - f2 / 24.0 : (1.0 - std::cos(f)) / f2;
  const double b = f < 1e-4 ? 1.0 / 6.0 - f2 / 120.0 : (f - std::sin(f)) / (f2 * f);
  const Eigen::Matrix3d X = cross(c.theta);
  c.J = Eigen::Matrix3d::Identity() + a * X + b * X * X;
  return c;
}

void SubdomainReducedSolver::rotateBlocks(const Eigen::Matrix3d& R, Eigen::MatrixXd& phi) {
  for (int k = 0; 3 * k < phi.rows(); ++k) phi.middleRows<3>(3 * k) = R * phi.middleRows<3>(3 * k);
}

// The linear dynamics read in the chord's frame (header). The rope's equations M e'' = F_g -
// Q(e) + E^T lambda, e = T u_b + top_m + R (base + W), W = D - theta x base the deformation in
// the frame, multiplied by R^T (blockwise; M commutes with it): with Q(base + W) ~ Q_m + K_m W
// = Q_m + K_m D - theta x Q_m (d/dtheta Q(R base) = theta x Q_m, exact for the linear term) and
// R^T e''_rel = W'' + a x (base + W) + [w x]^2 (base + W) + 2 w x W' (w = J theta' the
// frame's angular velocity, a = J theta'' + J' theta' its acceleration), the rows of Phi_c read
//   Phi_c^T [M D'' + K_m D] + M_cb u_b'' = Phi_c^T (F_g - Q_m) + Phi_c^T [(R^T - I) F_g
//       + theta x Q_m - M A base] - M_cb (R^T - I) u_b'',   A = [w x]^2 + [(J - I) theta'' x],
// the inertia of the frame's rotation (centripetal and the Euler term's second-order part;
// m w^2 L is 90 N on the T8036's 2.3 deg swing) and the top's acceleration seen in the frame.
// The translations u_b are inertial: their row, T^T M e'' = W_total + lambda, takes the
// relative inertia rotated into the inertial frame, R T^T M (D'' + A base), so its load is
// -T^T M A base - (R - I) T^T M (D'' + A base). All of it is evaluated at the step's predicted
// state and the last accelerations (explicit: small against the stiffness). Left out:
// Coriolis 2 w x W' and a x W (deformation rates and deformations times the frame's rates),
// and J' theta'. Every term is a 3 x 3 matrix applied blockwise to a field x, projected as
// sum_kl A_kl [Phi_c; T]^T (e_k x_l): the 9-column tables below.
Eigen::Matrix<double, Eigen::Dynamic, 9> SubdomainReducedSolver::blockwiseTable(
    const Eigen::VectorXd& x) const {
  const int r = static_cast<int>(phi_.cols()), n = rope_.dofs();
  Eigen::Matrix<double, Eigen::Dynamic, 9> t(r + 3, 9);
  for (int c = 0; c < 9; ++c) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
    for (int k = 0; 3 * k < n; ++k) u(3 * k + c / 3) = x(3 * k + c % 3);
    t.col(c).head(r) = phi_.transpose() * u;
    t.col(c).tail<3>() = translationSum(u);
  }
  return t;
}

void SubdomainReducedSolver::prepareFrameLoads(const Eigen::VectorXd& Q) {
  if (!frame_) return;
  centrifugal_ = blockwiseTable(rope_.massMatrix() * base_);  // M (A base) = A (M base)
  gravity_rotation_ = blockwiseTable(rope_.gravityForce());
  elastic_rotation_ = blockwiseTable(Q);
  gravity_rotation_.bottomRows<3>().setZero();
  elastic_rotation_.bottomRows<3>().setZero();
}

Eigen::VectorXd SubdomainReducedSolver::frameLoad(const Eigen::VectorXd& y,
                                                  const Eigen::VectorXd& yd,
                                                  const Eigen::VectorXd& ydd) const {
  const int r = static_cast<int>(phi_.cols());
  if (!frame_) return Eigen::VectorXd::Zero(r + 3);
  const ChordRotation c = chordRotation(lastNodeDisplacement(y));
  const Eigen::Vector3d w = c.J * chordAngle(lastNodeDisplacement(yd));
  const Eigen::Vector3d euler =
      (c.J - Eigen::Matrix3d::Identity()) * chordAngle(lastNodeDisplacement(ydd));
  const Eigen::Matrix3d A =
      w * w.transpose() - w.squaredNorm() * Eigen::Matrix3d::Identity() + cross(euler);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  auto vec = [](const Eigen::Matrix3d& X) {
    Eigen::Matrix<double, 9, 1> v;
    for (int i = 0; i < 9; ++i) v(i) = X(i / 3, i % 3);
    return v;
  };
  const Eigen::Matrix<double, 9, 1> a = vec(A);
  Eigen::VectorXd out = gravity_rotation_ * vec(c.R.transpose() - I) +
                        elastic_rotation_ * vec(cross(c.theta)) - centrifugal_ * a;
  out.head(r) -= Mcb_ * ((c.R.transpose() - I) * ydd.tail<3>());
  out.tail<3>() -= (c.R - I) * (Mcb_.transpose() * ydd.head(r) + centrifugal_.bottomRows<3>() * a);
  return out;
}

Eigen::VectorXd SubdomainReducedSolver::centripetalField(const Eigen::VectorXd& v) const {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(base_.size());
  if (!frame_) return a;
  const int last = 6 * (rope_.nodes() - 1);
  const Eigen::Vector3d w = chordAngle(v.segment<3>(last) - v.head<3>());
  for (int k = 0; 3 * k < a.size(); ++k)
    a.segment<3>(3 * k) = w.cross(w.cross(base_.segment<3>(3 * k)));
  return a;
}

Eigen::VectorXd SubdomainReducedSolver::expand(const Eigen::VectorXd& y) const {
  const int r = static_cast<int>(phi_.cols());
  Eigen::VectorXd x = phi_ * y.head(r);
  const Eigen::Vector3d ub = y.tail<3>();
  for (int j = 0; j < rope_.nodes(); ++j) x.segment<3>(6 * j) += ub;
  return x;
}

Eigen::VectorXd SubdomainReducedSolver::project(const Eigen::VectorXd& x) const {
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

void SubdomainReducedSolver::addStaticCorrection(const SparseMatrix& K, const SparseMatrix& M,
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

void SubdomainReducedSolver::ritz(const SparseMatrix& K, const SparseMatrix& M) {
  const Eigen::MatrixXd Kr = phi_.transpose() * (K * phi_), Mr = phi_.transpose() * (M * phi_);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (Kr + Kr.transpose()),
                                                                     0.5 * (Mr + Mr.transpose()));
  if (es.info() != Eigen::Success) throw NumericalFailure(at(s_.t) + ": Rayleigh-Ritz failed");
  phi_ = phi_ * es.eigenvectors();
  omega2_ = es.eigenvalues();
}

void SubdomainReducedSolver::startSubdomain(const Eigen::VectorXd& e, BasisUpdate how,
                                            const Eigen::VectorXd& load) {
  const auto t0 = std::chrono::steady_clock::now();
  const int n = rope_.dofs();
  Eigen::VectorXd Q;
  const SparseMatrix K = rope_.tangentStiffness(e, &Q);
  const SparseMatrix& M = rope_.massMatrix();
  const int last = rope_.nodes() - 1;
  const Eigen::Vector3d chord = e.segment<3>(6 * last) - e.head<3>();
  if (settings_.corotational && modes_.phi.size() > 0) {
    // The modes of the rotated rope are the rotated modes (header): the update starts there.
    const Eigen::Matrix3d R =
        Eigen::Quaterniond::FromTwoVectors(basis_chord_, chord).toRotationMatrix();
    rotateBlocks(R, modes_.phi);
    if (how == BasisUpdate::ritz) rotateBlocks(R, phi_);  // other updates rebuild phi_
  }
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
  basis_chord_ = chord;
  // Hoisting subdomains last a step (every length change starts one): the linear map there.
  frame_ = settings_.corotational && how == BasisUpdate::modes;
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
  base_ = e;
  for (int j = 0; j <= last; ++j) base_.segment<3>(6 * j) -= e.head<3>();
  chord_ = chord;
  if (settings_.residual_tolerance > 0.0) {
    K_m_ = K;
    Q_m_ = Q;
  }
  prepareFrameLoads(Q);
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

Eigen::VectorXd SubdomainReducedSolver::solveWeighted(
    double a, double c, double k, const Eigen::VectorXd& ry, const Eigen::VectorXd& rz,
    const Eigen::Vector3d& rc, Eigen::VectorXd& dz, Eigen::Vector3d& dmu, bool cached) {
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
Eigen::Matrix<double, 6, 6> SubdomainReducedSolver::eliminatedMatrix(
    double a, double k, const Eigen::Matrix3d& G) const {
  const Eigen::VectorXd d = Eigen::VectorXd::Constant(omega2_.size(), a) + k * omega2_;
  Eigen::Matrix<double, 6, 6> A;
  A.topLeftCorner<3, 3>() =
      a * Mbb_ - a * a * Mcb_.transpose() * d.cwiseInverse().asDiagonal() * Mcb_;
  A.topRightCorner<3, 3>().setIdentity();
  A.bottomLeftCorner<3, 3>().setIdentity();
  A.bottomRightCorner<3, 3>() = -G;
  return A;
}

void SubdomainReducedSolver::initializeAccelerations() {
  const int r = static_cast<int>(phi_.cols()), m = support_.size();
  Eigen::VectorXd ry = f_ + frameLoad(s_.y, s_.yd, Eigen::VectorXd::Zero(r + 3));
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

void SubdomainReducedSolver::initialize(const CoupledState& full) {
  modes_ = RopeModes{};
  stats_ = SubdomainStatistics{};
  s_ = SubdomainReducedState{};
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
// does not by itself cut subdomains; the swing it excites does. In the chord's frame
// (corotational) the chord's rotation costs nothing either (header): the criterion reads the
// deformation W_j = D_j - theta x base_j, and the rotation is bounded by
// settings_.max_chord_rotation.
double SubdomainReducedSolver::maxNodeIncrement() const {
  const int r = static_cast<int>(phi_.cols()), last = rope_.nodes() - 1;
  const Eigen::VectorXd inc = node_rows_ * s_.y.head(r);
  const Eigen::Vector3d theta = chordAngle(inc.segment<3>(3 * last));
  double worst = 0.0;
  for (int j = 0; j <= last; ++j) {
    worst = std::max(worst,
                     (inc.segment<3>(3 * j) - theta.cross(base_.segment<3>(6 * j))).squaredNorm());
  }
  return std::sqrt(worst);
}

void SubdomainReducedSolver::step() {
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
  // Residuals scaled by beta h^2 (as the full-order solver's); the system is linear: one solve
  // (the frame loads, .cpp top, explicit at the predicted state).
  const Eigen::VectorXd f = f_ + frameLoad(s_.y, s_.yd, ydd0);
  Eigen::VectorXd ry(r + 3);
  ry.head(r) =
      s_.ydd.head(r) + Mcb_ * s_.ydd.tail<3>() + omega2_.cwiseProduct(s_.y.head(r)) - f.head(r);
  ry.tail<3>() =
      Mcb_.transpose() * s_.ydd.head(r) + Mbb_ * s_.ydd.tail<3>() - f.tail<3>() + s_.lambda;
  ry *= -bh2;
  Eigen::VectorXd rz, dz;
  if (m > 0)
    rz = -bh2 * (support_.internalForce(s_.z, s_.zd, s_.zdd) -
                 support_.pointForceToCoordinates(s_.lambda));
  const Eigen::Vector3d rc = -(e_m_.head<3>() + s_.y.tail<3>() - support_.point(s_.z));
  Eigen::Vector3d dmu;
  const Eigen::VectorXd dy =
      solveWeighted(massWeight, ga_.gamma * h, bh2, ry, rz, rc, dz, dmu, true);
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
  const bool rotationCut =
      frame_ && chordAngle(lastNodeDisplacement(s_.y)).norm() > settings_.max_chord_rotation;
  // The displacement check costs O(n r): with many modes it runs every r / kCheckedModesPerStep
  // steps (the deformation moves little in between; the step is linear, so a late check only
  // lets the subdomain run a few steps past delta).
  const long every = std::max(1, r / kCheckedModesPerStep);
  const bool displacementCut =
      steps_in_subdomain_ % every == 0 && maxNodeIncrement() > settings_.delta;
  if (residualCut || rotationCut || displacementCut) {
    // Switch: rebuild the linearisation at the current state and carry the state over.
    restartAt(fullState());
  }
}

void SubdomainReducedSolver::restartAt(const CoupledState& f, bool consistent_accelerations,
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
  const Eigen::VectorXd ac = centripetalField(f.v);
  s_.ydd = project(f.qdd - ac);
  s_.ya = project(f.a - ac);
  if (consistent_accelerations) initializeAccelerations();
  const Eigen::VectorXd vr = expand(s_.yd);
  const SparseMatrix& M = rope_.massMatrix();
  stats_.projection_energy_loss += 0.5 * (f.v.dot(M * f.v) - vr.dot(M * vr));
}

// max over nodes of |Q(e_m + W) - Q_m - K_m W| (translational rows) [N], W = e - e_m in the
// fixed frame.
double SubdomainReducedSolver::linearisationResidual() const {
  // In the chord's frame the linearisation is about the deformation W = D - theta x base.
  Eigen::VectorXd de = phi_ * s_.y.head(phi_.cols());
  const Eigen::Vector3d theta = chordAngle(de.segment<3>(6 * (rope_.nodes() - 1)));
  for (int k = 0; 3 * k < de.size(); ++k)
    de.segment<3>(3 * k) -= theta.cross(base_.segment<3>(3 * k));
  Eigen::VectorXd Q;
  rope_.elasticForce(e_m_ + de, Q);
  const Eigen::VectorXd res = Q - Q_m_ - K_m_ * de;
  double worst = 0.0;
  for (int j = 0; j < rope_.nodes(); ++j) worst = std::max(worst, res.segment<3>(6 * j).norm());
  return worst;
}

// The co-rotational map and its rates (header), per 3-row block b of node positions and slopes:
// e_b = top + R W_b, W_b = base_b + D_b - theta x base_b; e_b' = u_b' + w x R W_b + R W_b';
// e_b'' = u_b'' + J theta'' x R W_b + w x (w x R W_b) + 2 w x R W_b' + R W_b''
// (w = J theta'; the d/dt J term, second order in theta, is left out). The generalized-alpha
// variable a is mapped as an acceleration.
CoupledState SubdomainReducedSolver::fullState() const { return fullStateOf(s_); }

CoupledState SubdomainReducedSolver::fullStateOf(const SubdomainReducedState& st) const {
  const int r = static_cast<int>(phi_.cols());
  const Eigen::VectorXd D = phi_ * st.y.head(r), Dv = phi_ * st.yd.head(r),
                        Da = phi_ * st.ydd.head(r), Dg = phi_ * st.ya.head(r);
  const int last = 6 * (rope_.nodes() - 1);
  const ChordRotation c = chordRotation(D.segment<3>(last));
  const Eigen::Vector3d thv = chordAngle(Dv.segment<3>(last)),
                        tha = chordAngle(Da.segment<3>(last)),
                        thg = chordAngle(Dg.segment<3>(last));
  const Eigen::Vector3d w = c.J * thv, alpha = c.J * tha, alpha_g = c.J * thg;
  CoupledState f;
  f.t = st.t;
  const int n = rope_.dofs();
  f.q.resize(n);
  f.v.resize(n);
  f.qdd.resize(n);
  f.a.resize(n);
  for (int k = 0; 3 * k < n; ++k) {
    const Eigen::Vector3d b = base_.segment<3>(3 * k);
    const Eigen::Vector3d RW = c.R * (b + D.segment<3>(3 * k) - c.theta.cross(b));
    const Eigen::Vector3d RWv = c.R * (Dv.segment<3>(3 * k) - thv.cross(b));
    const Eigen::Vector3d common = w.cross(w.cross(RW)) + 2.0 * w.cross(RWv);
    f.q.segment<3>(3 * k) = RW;
    f.v.segment<3>(3 * k) = w.cross(RW) + RWv;
    f.qdd.segment<3>(3 * k) =
        alpha.cross(RW) + common + c.R * (Da.segment<3>(3 * k) - tha.cross(b));
    f.a.segment<3>(3 * k) =
        alpha_g.cross(RW) + common + c.R * (Dg.segment<3>(3 * k) - thg.cross(b));
    if (k % 2 == 0) {  // a node position: the top's motion
      f.q.segment<3>(3 * k) += e_m_.head<3>() + st.y.tail<3>();
      f.v.segment<3>(3 * k) += st.yd.tail<3>();
      f.qdd.segment<3>(3 * k) += st.ydd.tail<3>();
      f.a.segment<3>(3 * k) += st.ya.tail<3>();
    }
  }
  f.z = st.z;
  f.zd = st.zd;
  f.zdd = st.zdd;
  f.za = st.za;
  f.lambda = st.lambda;
  return f;
}

Eigen::Vector3d SubdomainReducedSolver::nodePosition(int j) const {
  const int r = static_cast<int>(phi_.cols());
  const Eigen::Vector3d b = base_.segment<3>(6 * j),
                        Dj = node_rows_.middleRows<3>(3 * j) * s_.y.head(r);
  const ChordRotation c = chordRotation(lastNodeDisplacement(s_.y));
  return e_m_.head<3>() + s_.y.tail<3>() + c.R * (b + Dj - c.theta.cross(b));
}

double SubdomainReducedSolver::minNodalStrain() const {
  const int r = static_cast<int>(phi_.cols());
  const Eigen::VectorXd slopes = slope_rows_ * s_.y.head(r);
  const Eigen::Vector3d theta = chordAngle(lastNodeDisplacement(s_.y));
  double least = 1e300;
  for (int j = 0; j < rope_.nodes(); ++j) {
    // |R W| = |W|: the slope's length needs no rotation, only theta.
    const Eigen::Vector3d b = base_.segment<3>(6 * j + 3);
    least = std::min(least, (b + slopes.segment<3>(3 * j) - theta.cross(b)).norm() - 1.0);
  }
  return least;
}

double SubdomainReducedSolver::constraintError() const {
  return (e_m_.head<3>() + s_.y.tail<3>() - support_.point(s_.z)).norm();
}

double SubdomainReducedSolver::topTension() const {
  return ropeTopTension(s_.lambda, rope_.topMass(), s_.ydd.tail<3>(), rope_.gravity());
}

}  // namespace crane_twin
