// The wind of a scene (`wind:`, docs/scenes.md; docs/model.md "Wind"), in the crane's frame
// (z up from the mast foot) [m, s, m/s]:
//   u(z, t) = U(z) g(t) e,   U(z) = speed (max(z, 0) / z_ref)^alpha,   z_ref = 10 m,
//   g(t) = 1 + I n(t),
// e the horizontal unit vector of direction_deg (the direction the air moves towards, from x
// towards y), alpha the power-law profile exponent, I the turbulence intensity and n(t) a
// zero-mean, unit-variance gust process with the Kaimal spectrum of the along-wind component
// (IEC 61400-1 ed. 3, annex B):
//   S(f) = 4 L / U_j / (1 + 6 f L / U_j)^(5/3),   L = 340.2 m,
// U_j the mean speed at the jib's height. n(t) is synthesised once per run by harmonic
// superposition with seeded random phases (std::mt19937), an inverse FFT on 2^16 points at
// 0.1 s (a period of 6553.6 s, linear interpolation between the samples); its discrete spectrum
// is scaled to unit variance. The gust is fully coherent: one g(t) over the whole crane (a
// conservative assumption for the structure's load).
// A measured wind (the node's crane/wind topic) replaces U(z_jib) e g(t) by the measured
// vector at the jib's height; the profile still scales it with height.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

namespace crane_twin {

struct WindSettings {
  double speed = 0.0;              ///< mean speed at 10 m [m/s]
  double direction_deg = 0.0;      ///< where the air moves towards, from x towards y [deg]
  double profile_exponent = 0.14;  ///< power-law exponent alpha [-]
  double gust_intensity = 0.0;     ///< I = sigma_u / U [-] (0: steady)
  int gust_seed = 0;
  double payload_area = 0.0;  ///< projected area of the load [m^2]
  double payload_drag_coefficient = 1.05;
  double rope_drag_coefficient = 1.2;  ///< of the rope's diameter (0: no drag on the rope)
  double in_service_limit = 20.0;      ///< 3 s mean speed at the jib's height [m/s]
};

constexpr double kAirDensity = 1.25;           ///< rho [kg/m^3] (EN 1991-1-4)
constexpr double kWindReferenceHeight = 10.0;  ///< z_ref [m]
constexpr double kKaimalLength = 340.2;        ///< L [m]
constexpr double kGustSampleStep = 0.1;        ///< [s]
constexpr int kGustSamples = 1 << 16;

class WindField {
 public:
  /// Throws std::invalid_argument for a negative speed or intensity, a non-finite value, or a
  /// non-positive jib height.
  WindField(const WindSettings& s, double jib_height);

  const WindSettings& settings() const { return s_; }
  /// Mean speed U(z) [m/s] (no gust, no measurement).
  double meanSpeed(double z) const;
  /// The wind velocity u(z, t) = g(t) meanVelocity(z) [m/s, crane frame].
  Eigen::Vector3d velocity(double z, double t) const { return gustFactor(t) * meanVelocity(z); }
  /// The wind at unit gust factor: U(z) e, or the measured wind scaled by the profile.
  Eigen::Vector3d meanVelocity(double z) const;
  /// The gust factor g(t) = 1 + I n(t) (1 with a measured wind).
  double gustFactor(double t) const;
  /// The unit-variance gust process n(t) (0 without gusts).
  double gust(double t) const;

  /// A measured wind at the jib's height [m/s, crane frame]; replaces the scene's mean and gusts.
  void setMeasured(const Eigen::Vector3d& v);
  bool measured() const { return measured_.has_value(); }

  /// Record the speed at the jib's height at time t and return its mean over the last 3 s
  /// (samples at or after t - 3 s; the first call's sample alone at the start).
  double recordJibSpeed(double t);
  double jibHeight() const { return jib_height_; }

  /// The Kaimal spectrum normalised to unit variance, S(f) / sigma^2 [1/Hz], at the jib's mean.
  double kaimal(double f) const;

 private:
  WindSettings s_;
  double jib_height_;
  Eigen::Vector3d e_;
  std::vector<double> n_;  ///< gust samples (empty: steady)
  std::optional<Eigen::Vector3d> measured_;
  std::deque<std::pair<double, double>> recent_;  ///< (t, speed at the jib)
  double recent_sum_ = 0.0;
};

/// Default projected area of a payload of mass m [kg]: the face of the cube of 1000 kg/m^3 the
/// markers draw (analysis/load_shapes), (m / 1000)^(2/3) [m^2].
inline double payloadCubeFaceArea(double mass) { return std::pow(mass / 1000.0, 2.0 / 3.0); }

/// Quasi-static drag force 0.5 rho Cd A |u| u [N] of an area A [m^2] in the wind u [m/s].
inline Eigen::Vector3d dragForce(double cd_area, const Eigen::Vector3d& u) {
  return 0.5 * kAirDensity * cd_area * u.norm() * u;
}

}  // namespace crane_twin
