#include "crane_twin/loads/wind_loads.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace crane_twin {

Eigen::VectorXd structureWindLoad(const TowerCraneStructure& s, const WindField& w, double theta) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(s.free_dofs);
  const Eigen::Matrix3d Rt =
      Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose();
  for (const StructureMember& m : s.members) {
    const double D = s.sections[m.section].outer_diameter;
    if (D <= 0.0) continue;
    const Eigen::Vector3d &X1 = s.nodes[m.node1], &X2 = s.nodes[m.node2];
    const Eigen::Vector3d d = X2 - X1;
    const double L = d.norm();
    if (L <= 0.0) continue;
    const Eigen::Vector3d e = d / L;
    const Eigen::Vector3d u = Rt * w.meanVelocity(0.5 * (X1.z() + X2.z()));
    const Eigen::Vector3d un = u - u.dot(e) * e;
    const Eigen::Vector3d F = dragForce(kTubeDragCoefficient * D * L, un);
    for (int n : {m.node1, m.node2})
      for (int k = 0; k < 3; ++k) {
        const int eq = s.dof_equation[6 * n + k];
        if (eq >= 0) f(eq) += 0.5 * F(k);
      }
  }
  return f;
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
