#include "crane_twin/twin/sway_estimator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

namespace crane_twin {

void SwayEstimatorSettings::check() const {
  auto positive = [](double x, const char* name) {
    if (!std::isfinite(x) || !(x > 0.0)) {
      throw std::invalid_argument(std::string(name) + " must be finite and > 0, got " +
                                  std::to_string(x));
    }
  };
  positive(measurement_noise, "measurement_noise");
  positive(process_noise, "process_noise");
  positive(initial_position_sigma, "initial_position_sigma");
  positive(initial_velocity_sigma, "initial_velocity_sigma");
  positive(structure_sigma, "structure_sigma");
  positive(structure_process_noise, "structure_process_noise");
  positive(gate, "gate");
}

SwayEstimator::SwayEstimator(const SwayEstimatorSettings& settings, const Eigen::VectorXd& phi_norm)
    : settings_(settings), phi_norm_(phi_norm), K_(static_cast<int>(phi_norm.size())) {
  settings_.check();
  for (int k = 0; k < K_; ++k) {
    if (!(phi_norm_[k] > 0.0) || !std::isfinite(phi_norm_[k])) {
      throw std::invalid_argument("structure mode " + std::to_string(k) +
                                  ": |Phi| must be finite and > 0");
    }
  }
  last_phi_ = Eigen::Matrix2Xd::Zero(2, K_);
  reset();
}

void SwayEstimator::reset() {
  const int n = 2 * K_ + 4;
  P_ = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < K_; ++k) {
    const double s = settings_.structure_sigma / phi_norm_[k];
    P_(k, k) = s * s;
    P_(K_ + k, K_ + k) = s * s;  // rescaled by Omega^2 at the first propagation's start
  }
  const double sp = settings_.initial_position_sigma, sv = settings_.initial_velocity_sigma;
  P_.diagonal().tail<4>() << sp * sp, sp * sp, sv * sv, sv * sv;
  refused_in_a_row_ = 0;
  pending_ = 0.0;
  primed_ = false;
}

void SwayEstimator::predict(double h) {
  if (!(h >= 0.0) || !std::isfinite(h)) throw std::invalid_argument("predict: h must be >= 0");
  pending_ += h;
}

void SwayEstimator::propagate(const SwayModel& m) {
  if (m.omega2.size() != K_ || m.damping.size() != K_ || m.phi.cols() != K_) {
    throw std::invalid_argument("sway model with " + std::to_string(m.omega2.size()) +
                                " structure modes, the estimator has " + std::to_string(K_));
  }
  if (!(m.length > 0.0) || !(m.gravity > 0.0) || !(m.tension >= 0.0)) {
    throw std::invalid_argument("sway model: length and gravity must be > 0, tension >= 0");
  }
  last_phi_ = m.phi;
  if (!primed_) {
    // The prior of the modal rates: Omega_k times the amplitude's sigma.
    for (int k = 0; k < K_; ++k) P_(K_ + k, K_ + k) *= m.omega2[k];
    primed_ = true;
  }
  const double dt = pending_;
  pending_ = 0.0;
  if (dt == 0.0) return;
  const int n = 2 * K_ + 4, S = 2 * K_;  // S: index of s
  // x' = A x + G w: rows of eta'' and s'' (see the header).
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd etadd = Eigen::MatrixXd::Zero(K_, n);  // eta'' as a row block
  for (int k = 0; k < K_; ++k) {
    A(k, K_ + k) = 1.0;
    etadd(k, k) = -m.omega2[k];
    etadd(k, K_ + k) = -m.damping[k];
  }
  if (K_ > 0) etadd.block(0, S, K_, 2) = (m.tension / m.length) * m.phi.transpose();
  A.block(K_, 0, K_, n) = etadd;
  A(S, S + 2) = A(S + 1, S + 3) = 1.0;
  A(S + 2, S) = A(S + 3, S + 1) = -m.gravity / m.length;
  if (K_ > 0) A.block(S + 2, 0, 2, n) -= m.phi * etadd;
  // Noise: white accelerations on s'' (q_s) and on the trolley's sideways motion per mode.
  Eigen::MatrixXd Qc = Eigen::MatrixXd::Zero(n, n);
  Qc(S + 2, S + 2) = Qc(S + 3, S + 3) = settings_.process_noise;
  for (int k = 0; k < K_; ++k) {
    Qc(K_ + k, K_ + k) = settings_.structure_process_noise / (phi_norm_[k] * phi_norm_[k]);
  }
  // Van Loan: exp([[-A, Qc], [0, A^T]] dt) = [[., F^-1 Q], [0, F^T]].
  Eigen::MatrixXd V = Eigen::MatrixXd::Zero(2 * n, 2 * n);
  V.topLeftCorner(n, n) = -A * dt;
  V.topRightCorner(n, n) = Qc * dt;
  V.bottomRightCorner(n, n) = A.transpose() * dt;
  const Eigen::MatrixXd E = V.exp();
  const Eigen::MatrixXd F = E.bottomRightCorner(n, n).transpose();
  const Eigen::MatrixXd Q = F * E.topRightCorner(n, n);
  P_ = F * P_ * F.transpose() + 0.5 * (Q + Q.transpose());
}

const Eigen::MatrixXd& SwayEstimator::covariance(const SwayModel& model) {
  propagate(model);
  return P_;
}

Eigen::MatrixXd SwayEstimator::observation(const Eigen::Matrix2Xd& phi) const {
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, 2 * K_ + 4);
  H.leftCols(K_) = phi;
  H(0, 2 * K_) = H(1, 2 * K_ + 1) = 1.0;
  return H;
}

Eigen::Matrix2d SwayEstimator::payloadCovariance(const SwayModel& model) {
  propagate(model);
  const Eigen::MatrixXd H = observation(model.phi);
  return H * P_ * H.transpose();
}

SwayUpdate SwayEstimator::update(const Eigen::Vector2d& measured, const Eigen::Vector2d& twin,
                                 const SwayModel& model) {
  SwayUpdate u;
  u.structure_correction = Eigen::VectorXd::Zero(K_);
  u.structure_rate_correction = Eigen::VectorXd::Zero(K_);
  if (refused_in_a_row_ >= kReacquireAfter) {
    reset();
    u.reacquired = true;
  }
  propagate(model);
  u.innovation = measured - twin;
  if (!u.innovation.allFinite()) return u;
  const int n = 2 * K_ + 4, S = 2 * K_;
  const Eigen::MatrixXd H = observation(model.phi);
  const double r = settings_.measurement_noise * settings_.measurement_noise;
  const Eigen::Matrix2d Sm = H * P_ * H.transpose() + r * Eigen::Matrix2d::Identity();
  const Eigen::LLT<Eigen::Matrix2d> llt(Sm);
  u.normalized = u.innovation.dot(llt.solve(u.innovation));
  if (!(u.normalized <= settings_.gate * settings_.gate)) {
    ++refused_in_a_row_;
    return u;
  }
  refused_in_a_row_ = 0;
  const Eigen::MatrixXd PHt = P_ * H.transpose();                    // n x 2
  const Eigen::MatrixXd K = llt.solve(PHt.transpose()).transpose();  // n x 2
  const Eigen::VectorXd dx = K * u.innovation;
  u.structure_correction = dx.head(K_);
  u.structure_rate_correction = dx.segment(K_, K_);
  u.position_correction = dx.segment<2>(S);
  u.velocity_correction = dx.segment<2>(S + 2);
  const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(n, n) - K * H;
  P_ = IKH * P_ * IKH.transpose() + r * K * K.transpose();
  u.accepted = true;
  return u;
}

double SwayEstimator::positionSigma() const {
  const Eigen::MatrixXd H = observation(last_phi_);
  const Eigen::Matrix2d C = H * P_ * H.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(C);
  return std::sqrt(std::max(0.0, es.eigenvalues().maxCoeff()));
}

}  // namespace crane_twin
