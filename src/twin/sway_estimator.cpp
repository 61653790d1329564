#include "crane_twin/twin/sway_estimator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

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
  positive(gate, "gate");
}

SwayEstimator::SwayEstimator(const SwayEstimatorSettings& settings) : settings_(settings) {
  settings_.check();
  reset();
}

void SwayEstimator::reset() {
  P_.setZero();
  const double sp = settings_.initial_position_sigma, sv = settings_.initial_velocity_sigma;
  P_.diagonal() << sp * sp, sp * sp, sv * sv, sv * sv;
}

void SwayEstimator::predict(double h, double length, double gravity) {
  if (!(h >= 0.0) || !std::isfinite(h)) throw std::invalid_argument("predict: h must be >= 0");
  if (!(length > 0.0) || !(gravity > 0.0)) {
    throw std::invalid_argument("predict: pendulum length and gravity must be > 0");
  }
  if (h == 0.0) return;
  const double w = std::sqrt(gravity / length), c = std::cos(w * h), s = std::sin(w * h);
  Eigen::Matrix4d F = Eigen::Matrix4d::Zero();
  for (int a = 0; a < 2; ++a) {
    F(a, a) = c;
    F(a, a + 2) = s / w;
    F(a + 2, a) = -w * s;
    F(a + 2, a + 2) = c;
  }
  const double q = settings_.process_noise;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();
  for (int a = 0; a < 2; ++a) {
    Q(a, a) = q * h * h * h / 3.0;
    Q(a, a + 2) = Q(a + 2, a) = q * h * h / 2.0;
    Q(a + 2, a + 2) = q * h;
  }
  P_ = F * P_ * F.transpose() + Q;
}

SwayUpdate SwayEstimator::update(const Eigen::Vector2d& measured, const Eigen::Vector2d& twin) {
  SwayUpdate u;
  u.innovation = measured - twin;
  if (!u.innovation.allFinite()) return u;
  const double r = settings_.measurement_noise * settings_.measurement_noise;
  const Eigen::Matrix2d S = P_.topLeftCorner<2, 2>() + r * Eigen::Matrix2d::Identity();
  const Eigen::LLT<Eigen::Matrix2d> llt(S);
  u.normalized = u.innovation.dot(llt.solve(u.innovation));
  if (!(u.normalized <= settings_.gate * settings_.gate)) return u;
  // K = P H^T S^-1 (4 x 2)
  const Eigen::Matrix<double, 4, 2> K = llt.solve(P_.topRows<2>()).transpose();
  const Eigen::Vector4d dx = K * u.innovation;
  u.position_correction = dx.head<2>();
  u.velocity_correction = dx.tail<2>();
  // Joseph form keeps P symmetric and positive definite.
  Eigen::Matrix<double, 4, 4> IKH = Eigen::Matrix4d::Identity();
  IKH.leftCols<2>() -= K;
  P_ = IKH * P_ * IKH.transpose() + r * K * K.transpose();
  u.accepted = true;
  return u;
}

double SwayEstimator::positionSigma() const {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(P_.topLeftCorner<2, 2>());
  return std::sqrt(std::max(0.0, es.eigenvalues().maxCoeff()));
}

}  // namespace crane_twin
