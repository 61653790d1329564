#include "crane_twin/elements/ground_contact.hpp"

#include <cmath>
#include <stdexcept>

#include "crane_twin/elements/discrete_gradient.hpp"

namespace crane_twin {

namespace {
void requireFinite(double x, const char* what) {
  if (!std::isfinite(x))
    throw std::invalid_argument(std::string("ground contact: ") + what + " must be finite");
}
}  // namespace

GroundContact::GroundContact(const GroundContactParameters& p) : p_(p) {
  requireFinite(p.height, "height");
  requireFinite(p.stiffness, "stiffness");
  requireFinite(p.damping, "damping");
  requireFinite(p.friction, "friction");
  requireFinite(p.slip_velocity, "slip velocity");
  requireFinite(p.payload_height, "payload height");
  if (!(p.stiffness > 0.0)) throw std::invalid_argument("ground contact: stiffness must be > 0");
  if (!(p.slip_velocity > 0.0))
    throw std::invalid_argument("ground contact: slip velocity must be > 0");
  if (p.damping < 0.0 || p.friction < 0.0 || p.payload_height < 0.0)
    throw std::invalid_argument(
        "ground contact: damping, friction and payload height must be >= 0");
}

double GroundContact::clearance(const Eigen::Vector3d& r) const {
  return r.z() - p_.payload_height - p_.height;
}

double GroundContact::penetration(const Eigen::Vector3d& r) const {
  return std::max(0.0, -clearance(r));
}

double GroundContact::energy(const Eigen::Vector3d& r) const {
  const double pen = penetration(r);
  return 0.5 * p_.stiffness * pen * pen;
}

// f = F_t + N e_z with N = max(0, k p - c v_z) (p > 0), F_t = -mu N v_t / sqrt(|v_t|^2 + v_s^2).
GroundContactForce GroundContact::force(const Eigen::Vector3d& r, const Eigen::Vector3d& v) const {
  GroundContactForce out;
  const double pen = penetration(r);
  if (pen <= 0.0) return out;
  const double N = p_.stiffness * pen - p_.damping * v.z();
  if (N <= 0.0) return out;  // the damper would pull: the load leaves the ground
  out.f.z() = N;
  out.df_dr(2, 2) = -p_.stiffness;
  out.df_dv(2, 2) = -p_.damping;
  if (p_.friction == 0.0) return out;
  const Eigen::Vector2d vt = v.head<2>();
  const double s = std::sqrt(vt.squaredNorm() + p_.slip_velocity * p_.slip_velocity);
  out.f.head<2>() = -p_.friction * N / s * vt;
  // d/dv_t of -mu N v_t / s: -mu N (I / s - v_t v_t^T / s^3), symmetric.
  out.df_dv.topLeftCorner<2, 2>() =
      -p_.friction * N * (Eigen::Matrix2d::Identity() / s - vt * vt.transpose() / (s * s * s));
  return out;
}

Eigen::Vector3d GroundContact::dissipativeForce(const Eigen::Vector3d& r,
                                                const Eigen::Vector3d& v) const {
  Eigen::Vector3d f = force(r, v).f;
  f.z() -= p_.stiffness * penetration(r);
  return f;
}

GroundContactForce GroundContact::stepMeanForce(const Eigen::Vector3d& r0,
                                                const Eigen::Vector3d& r1,
                                                const Eigen::Vector3d& v0,
                                                const Eigen::Vector3d& v1) const {
  const double k = p_.stiffness, zc = p_.height + p_.payload_height;
  const auto U = [&](double z) { return z < zc ? 0.5 * k * (zc - z) * (zc - z) : 0.0; };
  const auto dU = [&](double z) { return z < zc ? -k * (zc - z) : 0.0; };
  const auto ddU = [&](double z) { return z < zc ? k : 0.0; };
  // The secant of U in z (z enters linearly, so the secant in z is the discrete gradient).
  const SquaredLengthSecant sec = squaredLengthSecant(r0.z(), r1.z(), U, dU, ddU);
  const Eigen::Vector3d rm = 0.5 * (r0 + r1), vm = 0.5 * (v0 + v1);
  GroundContactForce mid = force(rm, vm);
  GroundContactForce out;
  out.f = dissipativeForce(rm, vm);
  out.f.z() -= sec.slope;
  // d(2 f_d(r_m, v_m))/dr1 = df_d/dr_m: the dissipative normal part N - k p is -c v_z where
  // N > 0 (no r-derivative) and -k p where the damper's pull is clipped (derivative +k).
  out.df_dr = mid.df_dr;
  const double pm = penetration(rm);
  out.df_dr(2, 2) = (pm > 0.0 && mid.f.z() == 0.0) ? k : 0.0;
  out.df_dr(2, 2) -= 2.0 * sec.curvature;  // d(-2 slope)/dz1
  out.df_dv = mid.df_dv;
  return out;
}

double GroundContact::switchWorkError(const Eigen::Vector3d& r0, const Eigen::Vector3d& r1) const {
  const double k = p_.stiffness, p0 = penetration(r0), p1 = penetration(r1);
  return std::abs(0.5 * k * (p0 + p1) * (r1.z() - r0.z()) + energy(r1) - energy(r0));
}

double groundDamping(double stiffness, double mass, double damping_ratio) {
  return 2.0 * damping_ratio * std::sqrt(stiffness * mass);
}

}  // namespace crane_twin
