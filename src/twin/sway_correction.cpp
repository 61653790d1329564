#include "crane_twin/twin/sway_correction.hpp"

#include <Eigen/Geometry>
#include <stdexcept>

#include "crane_twin/integrators/coupled_state.hpp"

namespace crane_twin {

void rotateRopeAboutTop(Eigen::VectorXd& q, Eigen::VectorXd& v, const Eigen::Vector3d& dp,
                        const Eigen::Vector3d& dv) {
  if (q.size() < 12 || q.size() % 6 != 0 || v.size() != q.size()) {
    throw std::invalid_argument("rotateRopeAboutTop: needs ANCF coordinates, 6 per node");
  }
  const int nodes = static_cast<int>(q.size() / 6);
  const Eigen::Vector3d top = q.head<3>(), v_top = v.head<3>();
  const Eigen::Vector3d rho = q.segment<3>(6 * (nodes - 1)) - top;
  const double rho2 = rho.squaredNorm();
  if (!(rho2 > 0.0)) throw std::invalid_argument("rotateRopeAboutTop: rope end at its top");
  const Eigen::Vector3d theta = rho.cross(dp) / rho2;
  const double angle = theta.norm();
  const Eigen::Matrix3d R =
      angle > 0.0 ? Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix()
                  : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d v_rel_end = v.segment<3>(6 * (nodes - 1)) - v_top;
  const Eigen::Vector3d u = dv - (R - Eigen::Matrix3d::Identity()) * v_rel_end;
  const Eigen::Vector3d rho_new = R * rho;
  const Eigen::Vector3d w = rho_new.cross(u) / rho_new.squaredNorm();
  for (int j = 0; j < nodes; ++j) {
    const Eigen::Vector3d r = R * (q.segment<3>(6 * j) - top);
    const Eigen::Vector3d s = R * q.segment<3>(6 * j + 3);
    q.segment<3>(6 * j) = top + r;
    q.segment<3>(6 * j + 3) = s;
    v.segment<3>(6 * j) = v_top + R * (v.segment<3>(6 * j) - v_top) + w.cross(r);
    v.segment<3>(6 * j + 3) = R * v.segment<3>(6 * j + 3) + w.cross(s);
  }
}

void applySwayCorrection(Simulation& sim, const Eigen::Vector3d& dp, const Eigen::Vector3d& dv) {
  CoupledState f = sim.fullState();
  rotateRopeAboutTop(f.q, f.v, dp, dv);
  sim.setRopeMotion(f.q, f.v);
}

}  // namespace crane_twin
