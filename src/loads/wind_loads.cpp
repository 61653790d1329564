#include "crane_twin/loads/wind_loads.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace crane_twin {

namespace {

// The tube members that take wind (an outer diameter and a length): visit(m, e, L, D, z_m) with
// the unit axis e (slewing frame), the length L and diameter D [m] and the mid-height z_m [m].
template <class Visit>
void forEachWindMember(const TowerCraneStructure& s, Visit&& visit) {
  for (const StructureMember& m : s.members) {
    const double D = s.sections[m.section].outer_diameter;
    if (D <= 0.0) continue;
    const Eigen::Vector3d &X1 = s.nodes[m.node1], &X2 = s.nodes[m.node2];
    const Eigen::Vector3d d = X2 - X1;
    const double L = d.norm();
    if (L <= 0.0) continue;
    visit(m, Eigen::Vector3d(d / L), L, D, 0.5 * (X1.z() + X2.z()));
  }
}

// add(equation, component) for the translational free DOFs of both end nodes of m.
template <class Add>
void forEachEndDof(const TowerCraneStructure& s, const StructureMember& m, Add&& add) {
  for (int n : {m.node1, m.node2})
    for (int i = 0; i < 3; ++i) {
      const int eq = s.dof_equation[6 * n + i];
      if (eq >= 0) add(eq, i);
    }
}

}  // namespace

Eigen::VectorXd structureWindLoad(const TowerCraneStructure& s, const WindField& w, double theta) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.free_dofs);
  const Eigen::Matrix3d Rt =
      Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose();
  forEachWindMember(
      s, [&](const StructureMember& m, const Eigen::Vector3d& e, double L, double D, double z) {
        const Eigen::Vector3d u = Rt * w.meanVelocity(z);
        const Eigen::Vector3d un = u - u.dot(e) * e;
        const Eigen::Vector3d F = dragForce(kTubeDragCoefficient * D * L, un);
        forEachEndDof(s, m, [&](int eq, int i) { f(eq) += 0.5 * F(i); });
      });
  return f;
}

StructureWindPatterns structureWindPatterns(const TowerCraneStructure& s, double profile_exponent,
                                            double jib_height) {
  if (!(profile_exponent >= 0.0) || !std::isfinite(profile_exponent) || !(jib_height > 0.0) ||
      !std::isfinite(jib_height)) {
    throw std::invalid_argument(
        "structure wind patterns: the profile exponent must be finite and >= 0 and the jib "
        "height finite and > 0");
  }
  StructureWindPatterns p;
  std::vector<Eigen::Triplet<double>> entries;
  forEachWindMember(s, [&](const StructureMember& m, const Eigen::Vector3d& e, double L, double D,
                           double z) {
    std::size_t k = 0;
    while (k < p.axes.size() && (p.axes[k] - e).norm() >= 1e-12 && (p.axes[k] + e).norm() >= 1e-12)
      ++k;
    if (k == p.axes.size()) p.axes.push_back(e);
    // c_m p(z_m)^2, c_m = 0.5 rho Cd D L (dragForce), half to each end node.
    const double shape =
        profile_exponent == 0.0 ? 1.0 : std::pow(std::max(z, 0.0) / jib_height, profile_exponent);
    const double c = 0.5 * kAirDensity * kTubeDragCoefficient * D * L * shape * shape;
    forEachEndDof(s, m, [&](int eq, int i) {
      entries.emplace_back(eq, static_cast<int>(3 * k) + i, 0.5 * c);
    });
  });
  p.patterns.resize(s.free_dofs, static_cast<Eigen::Index>(3 * p.axes.size()));
  p.patterns.setFromTriplets(entries.begin(), entries.end());  // (duplicates summed)
  return p;
}

Eigen::VectorXd structureWindWeights(const StructureWindPatterns& p, const Eigen::Vector3d& v) {
  Eigen::VectorXd w(static_cast<Eigen::Index>(3 * p.axes.size()));
  for (std::size_t k = 0; k < p.axes.size(); ++k) {
    const Eigen::Vector3d& e = p.axes[k];
    const Eigen::Vector3d vn = v - v.dot(e) * e;
    w.segment<3>(static_cast<Eigen::Index>(3 * k)) = vn.norm() * vn;
  }
  return w;
}

Eigen::Vector3d ropeWindLoad(const WindField& w, double t, double z_mid, int falls,
                             double fall_diameter) {
  const double cd = w.settings().rope_drag_coefficient;
  return dragForce(cd * falls * fall_diameter, w.velocity(z_mid, t));
}

Eigen::Vector3d payloadWindLoad(const WindField& w, double t, double z) {
  const WindSettings& s = w.settings();
  return dragForce(s.payload_drag_coefficient * s.payload_area, w.velocity(z, t));
}

}  // namespace crane_twin
