// Quasi-static wind loads (docs/model.md "Wind"): the drag q Cd A with q = 0.5 rho |u_n| u_n of
// the wind component u_n normal to a member, on
//   - the structure's tube members: Cd = 1.2 (kTubeDragCoefficient) on the outer diameter D,
//     f = 0.5 rho Cd D |u_n| u_n per metre at the member's mid-height, half of f L to each end
//     node (no shielding of one member by another: conservative for a lattice);
//   - the hanging rope: n falls side by side, each of diameter d = sqrt(mu / 0.0040) mm (mu the
//     mass per metre of one fall: 0.0040 kg/m per mm^2 for steel wire rope), at the rope's
//     mid-height, uniform along it (the rope is near vertical: the horizontal wind is normal);
//   - the payload: Cd A at the payload's height.
#pragma once

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <cmath>
#include <vector>

#include "crane_twin/loads/wind_field.hpp"
#include "crane_twin/structure/tower_crane_structure.hpp"

namespace crane_twin {

constexpr double kTubeDragCoefficient = 1.2;
constexpr double kRopeMassPerSquareMillimetre = 0.0040;  ///< [kg/m per mm^2]

/// Diameter of one fall of steel wire rope from its mass per metre [m].
inline double ropeDiameter(double mass_per_length_per_fall) {
  return 1e-3 * std::sqrt(mass_per_length_per_fall / kRopeMassPerSquareMillimetre);
}

/// Free-DOF forces of the wind on the structure's tube members at unit gust factor (the mean
/// wind, or the measured one: WindField::meanVelocity), slewing frame, for slewing angle theta
/// (the wind turned by R(theta)^T into the slewing frame) [N]. At time t the load is
/// g(t)^2 times this (the gust is coherent: u(z, t) = g(t) u_mean(z)).
Eigen::VectorXd structureWindLoad(const TowerCraneStructure& s, const WindField& w, double theta);

/// The same load as fixed patterns and weights, so that a slewing crane's (or a new measured
/// wind's) load is a small product instead of a pass over the members and a projection:
/// the mean wind is u(z) = p(z) V, V the mean wind at the jib height z_jib and
/// p(z) = (max(z, 0) / z_jib)^alpha (WindField::meanVelocity, either profile), so a member of
/// axis e (unit, slewing frame) at mid-height z_m bears
///   F_m = 0.5 rho Cd D L |u_n| u_n = c_m p(z_m)^2 G(v, e),
///   G(v, e) = |v - (v.e) e| (v - (v.e) e),   v = R(theta)^T V,
/// and members of one axis direction (up to its sign: G(v, -e) = G(v, e)) share G. Then
///   structureWindLoad = P w,   w = [G(v, e_1); ...; G(v, e_K)],
/// column block k of P (free DOFs x 3 K) the sum over the members along e_k of c_m p(z_m)^2
/// times half the identity at each end node. `axes` receives e_1 .. e_K.
struct StructureWindPatterns {
  Eigen::SparseMatrix<double> patterns;  ///< P [N s^2 / m^2]
  std::vector<Eigen::Vector3d> axes;     ///< e_k, unit, slewing frame
};
/// P and the axes for a profile exponent alpha >= 0 and the jib height z_jib > 0 [m]
/// (members whose axes differ by under 1e-12 share a direction).
StructureWindPatterns structureWindPatterns(const TowerCraneStructure& s, double profile_exponent,
                                            double jib_height);
/// w of the patterns above for the mean wind v at the jib height, slewing frame [m/s].
Eigen::VectorXd structureWindWeights(const StructureWindPatterns& p, const Eigen::Vector3d& v);

/// Wind force per metre on the hanging rope (falls of diameter d, drag coefficient of the
/// settings) with its mid-point at height z [N/m], crane frame.
Eigen::Vector3d ropeWindLoad(const WindField& w, double t, double z_mid, int falls,
                             double fall_diameter);

/// Wind force on the payload at height z [N], crane frame.
Eigen::Vector3d payloadWindLoad(const WindField& w, double t, double z);

}  // namespace crane_twin
