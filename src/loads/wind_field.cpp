#include "crane_twin/loads/wind_field.hpp"

#include <cmath>
#include <complex>
#include <random>
#include <stdexcept>
#include <unsupported/Eigen/FFT>

namespace crane_twin {

namespace {
void requireFinite(double v, const char* what, bool non_negative) {
  if (!std::isfinite(v) || (non_negative && v < 0.0)) {
    throw std::invalid_argument(std::string("wind: ") + what +
                                (non_negative ? " must be finite and >= 0" : " must be finite"));
  }
}
}  // namespace

WindField::WindField(const WindSettings& s, double jib_height) : s_(s), jib_height_(jib_height) {
  requireFinite(s.speed, "speed", true);
  requireFinite(s.direction_deg, "direction_deg", false);
  requireFinite(s.profile_exponent, "profile_exponent", true);
  requireFinite(s.gust_intensity, "gust intensity", true);
  requireFinite(s.payload_area, "payload area", true);
  requireFinite(s.payload_drag_coefficient, "payload drag_coefficient", true);
  requireFinite(s.rope_drag_coefficient, "rope_drag_coefficient", true);
  requireFinite(s.in_service_limit, "in_service_limit", true);
  if (!(jib_height > 0.0) || !std::isfinite(jib_height)) {
    throw std::invalid_argument("wind: the jib height must be finite and > 0");
  }
  const double a = s.direction_deg * M_PI / 180.0;
  e_ = Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
  if (s.gust_intensity == 0.0 || s.speed == 0.0) return;
  // n(t_j) = sum_k a_k cos(2 pi f_k t_j + phi_k), f_k = k / T, a_k = sqrt(2 S(f_k) df), scaled
  // so that sum a_k^2 / 2 = 1; by an inverse FFT of the Hermitian spectrum X_k = N/2 a_k e^(i
  // phi_k).
  const int N = kGustSamples;
  const double T = N * kGustSampleStep, df = 1.0 / T;
  std::mt19937 gen(static_cast<std::mt19937::result_type>(s.gust_seed));
  std::vector<double> amp(N / 2, 0.0), phase(N / 2, 0.0);
  double var = 0.0;
  for (int k = 1; k < N / 2; ++k) {
    amp[k] = std::sqrt(2.0 * kaimal(k * df) * df);
    phase[k] = 2.0 * M_PI * (static_cast<double>(gen()) / 4294967296.0);
    var += 0.5 * amp[k] * amp[k];
  }
  const double scale = 1.0 / std::sqrt(var);
  std::vector<std::complex<double>> X(N, 0.0), x;
  for (int k = 1; k < N / 2; ++k) {
    X[k] = 0.5 * N * scale * amp[k] * std::polar(1.0, phase[k]);
    X[N - k] = std::conj(X[k]);
  }
  Eigen::FFT<double> fft;
  fft.inv(x, X);
  n_.resize(N);
  for (int j = 0; j < N; ++j) n_[j] = x[j].real();
}

double WindField::kaimal(double f) const {
  const double U = meanSpeed(jib_height_);
  if (U <= 0.0) return 0.0;
  const double r = kKaimalLength / U;
  return 4.0 * r / std::pow(1.0 + 6.0 * f * r, 5.0 / 3.0);
}

double WindField::meanSpeed(double z) const {
  const double h = std::max(z, 0.0) / kWindReferenceHeight;
  return s_.speed * (s_.profile_exponent == 0.0 ? 1.0 : std::pow(h, s_.profile_exponent));
}

double WindField::gust(double t) const {
  if (n_.empty()) return 0.0;
  const double T = kGustSamples * kGustSampleStep;
  double u = std::fmod(t, T);
  if (u < 0.0) u += T;
  const double p = u / kGustSampleStep;
  const int j = static_cast<int>(std::floor(p)) % kGustSamples;
  const double w = p - std::floor(p);
  return (1.0 - w) * n_[j] + w * n_[(j + 1) % kGustSamples];
}

double WindField::gustFactor(double t) const {
  return measured_ ? 1.0 : 1.0 + s_.gust_intensity * gust(t);
}

Eigen::Vector3d WindField::meanVelocity(double z) const {
  if (measured_) {
    // The profile's shape relative to the jib: U(z) / U(z_jib) = (z / z_jib)^alpha.
    const double shape = s_.profile_exponent == 0.0
                             ? 1.0
                             : std::pow(std::max(z, 0.0) / jib_height_, s_.profile_exponent);
    return shape * *measured_;
  }
  return meanSpeed(z) * e_;
}

void WindField::setMeasured(const Eigen::Vector3d& v) {
  if (!v.allFinite()) throw std::invalid_argument("wind: the measured wind must be finite");
  measured_ = Eigen::Vector3d(v.x(), v.y(), 0.0);
}

double WindField::recordJibSpeed(double t) {
  const double v = velocity(jib_height_, t).norm();
  recent_.emplace_back(t, v);
  recent_sum_ += v;
  while (recent_.size() > 1 && recent_.front().first < t - 3.0 - 1e-9) {
    recent_sum_ -= recent_.front().second;
    recent_.pop_front();
  }
  return recent_sum_ / static_cast<double>(recent_.size());
}

}  // namespace crane_twin
