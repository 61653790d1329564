#include "crane_twin/elements/beam_geometric_stiffness.hpp"

#include <stdexcept>

namespace crane_twin {

Matrix12d beamGeometricStiffnessLocal(const BeamSection& s, double L, double N) {
  if (!(L > 0.0)) throw std::invalid_argument("beam length must be positive");
  Matrix12d K = Matrix12d::Zero();
  Eigen::Matrix4d B;
  B << 36, 3 * L, -36, 3 * L, 3 * L, 4 * L * L, -3 * L, -L * L, -36, -3 * L, 36, -3 * L, 3 * L,
      -L * L, -3 * L, 4 * L * L;
  B *= N / (30.0 * L);
  // x-y plane (v = u_y, psi = th_z) and x-z plane (v = u_z, psi = -th_y), as timoshenkoBeamLocal.
  const int xy[4] = {1, 5, 7, 11}, xz[4] = {2, 4, 8, 10};
  const double sg[4] = {1.0, -1.0, 1.0, -1.0};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      K(xy[i], xy[j]) += B(i, j);
      K(xz[i], xz[j]) += sg[i] * sg[j] * B(i, j);
    }
  if (s.area > 0.0) {
    const double kt = N * (s.Iy + s.Iz) / (s.area * L);
    K(3, 3) += kt;
    K(9, 9) += kt;
    K(3, 9) -= kt;
    K(9, 3) -= kt;
  }
  return K;
}

Matrix12d beamGeometricStiffnessGlobal(const BeamSection& s, const Eigen::Vector3d& p1,
                                       const Eigen::Vector3d& p2,
                                       const Eigen::Vector3d& orientation, double N) {
  const Eigen::Matrix3d R = beamLocalAxes(p1, p2, orientation);
  Matrix12d T = Matrix12d::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = R;
  return T.transpose() * beamGeometricStiffnessLocal(s, (p2 - p1).norm(), N) * T;
}

double beamAxialForce(const BeamSection& s, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      const Eigen::Vector3d& u1, const Eigen::Vector3d& u2) {
  const Eigen::Vector3d d = p2 - p1;
  const double L = d.norm();
  if (!(L > 0.0)) throw std::invalid_argument("beam length must be positive");
  return s.E * s.area / L * (d / L).dot(u2 - u1);
}

}  // namespace crane_twin
