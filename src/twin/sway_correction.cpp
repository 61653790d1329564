#include "crane_twin/twin/sway_correction.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "crane_twin/integrators/coupled_state.hpp"
#include "crane_twin/rope/rope_support.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"
#include "crane_twin/structure/structure_support.hpp"

namespace crane_twin {

void rotateRopeAboutTop(Eigen::VectorXd& q, Eigen::VectorXd& v, const Eigen::Vector3d& dp,
                        const Eigen::Vector3d& dv, std::vector<bool> position_blocks) {
  if (position_blocks.empty()) {
    if (q.size() < 12 || q.size() % 6 != 0) {
      throw std::invalid_argument("rotateRopeAboutTop: needs ANCF coordinates, 6 per node");
    }
    for (int b = 0; 3 * b < q.size(); ++b) position_blocks.push_back(b % 2 == 0);
  }
  const int blocks = static_cast<int>(position_blocks.size());
  if (v.size() != q.size() || q.size() != 3 * blocks || blocks < 2 || !position_blocks[0]) {
    throw std::invalid_argument("rotateRopeAboutTop: coordinates and their blocks differ");
  }
  int end = blocks - 1;
  while (!position_blocks[end]) --end;
  const Eigen::Vector3d top = q.head<3>(), v_top = v.head<3>();
  const Eigen::Vector3d rho = q.segment<3>(3 * end) - top;
  const double rho2 = rho.squaredNorm();
  if (!(rho2 > 0.0)) throw std::invalid_argument("rotateRopeAboutTop: rope end at its top");
  const Eigen::Vector3d theta = rho.cross(dp) / rho2;
  const double angle = theta.norm();
  const Eigen::Matrix3d R = angle > 0.0 ? Eigen::AngleAxisd(angle, theta / angle).toRotationMatrix()
                                        : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d v_rel_end = v.segment<3>(3 * end) - v_top;
  const Eigen::Vector3d u = dv - (R - Eigen::Matrix3d::Identity()) * v_rel_end;
  const Eigen::Vector3d rho_new = R * rho;
  const Eigen::Vector3d w = rho_new.cross(u) / rho_new.squaredNorm();
  for (int b = 0; b < blocks; ++b) {
    if (position_blocks[b]) {
      const Eigen::Vector3d r = R * (q.segment<3>(3 * b) - top);
      q.segment<3>(3 * b) = top + r;
      v.segment<3>(3 * b) = v_top + R * (v.segment<3>(3 * b) - v_top) + w.cross(r);
    } else {
      const Eigen::Vector3d s = R * q.segment<3>(3 * b);
      q.segment<3>(3 * b) = s;
      v.segment<3>(3 * b) = R * v.segment<3>(3 * b) + w.cross(s);
    }
  }
}

void applyTwinCorrection(Simulation& sim, const SwayUpdate& u, const std::vector<int>& modes) {
  CorrectableMotion& target = requireCapability<CorrectableMotion>(sim);  // before any work
  CoupledState f = sim.fullState();
  const std::vector<bool> blocks = sim.fullStatePositionBlocks();
  if (!modes.empty()) {
    if (u.structure_correction.size() != static_cast<int>(modes.size()) ||
        u.structure_rate_correction.size() != static_cast<int>(modes.size())) {
      throw std::invalid_argument("applyTwinCorrection: update and mode list differ in size");
    }
    Eigen::VectorXd dz = Eigen::VectorXd::Zero(f.z.size()), dzd = dz;
    for (std::size_t k = 0; k < modes.size(); ++k) {
      if (modes[k] < 0 || modes[k] >= f.z.size()) {
        throw std::invalid_argument("applyTwinCorrection: mode index out of range");
      }
      dz[modes[k]] = u.structure_correction[k];
      dzd[modes[k]] = u.structure_rate_correction[k];
    }
    f.z += dz;
    f.zd += dzd;
    // The rope goes with its top: translated by the trolley point's motion.
    const Eigen::Vector3d dp = sim.support().pointMotion(dz), dv = sim.support().pointMotion(dzd);
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      if (!blocks[b]) continue;
      f.q.segment<3>(3 * b) += dp;
      f.v.segment<3>(3 * b) += dv;
    }
  }
  rotateRopeAboutTop(
      f.q, f.v, Eigen::Vector3d(u.position_correction.x(), u.position_correction.y(), 0.0),
      Eigen::Vector3d(u.velocity_correction.x(), u.velocity_correction.y(), 0.0), blocks);
  target.setMotion(f);
}

namespace {

// The support point's motion per unit modal coordinate (3 x K, world frame).
Eigen::Matrix3Xd modeMotions(const Simulation& sim, const std::vector<int>& modes) {
  const RopeSupport& support = sim.support();
  Eigen::Matrix3Xd phi(3, modes.size());
  Eigen::VectorXd e = Eigen::VectorXd::Zero(support.size());
  for (std::size_t k = 0; k < modes.size(); ++k) {
    e.setZero();
    e[modes[k]] = 1.0;
    phi.col(k) = support.pointMotion(e);
  }
  return phi;
}

}  // namespace

std::vector<int> swayCouplingModes(const Simulation& sim, double max_hz, int max_modes) {
  const auto* modal = dynamic_cast<const ModalStructureSupport*>(&sim.support());
  if (!modal) return {};
  const Eigen::VectorXd& w2 = modal->omega2();
  const double w2_max = std::pow(2.0 * M_PI * max_hz, 2);
  std::vector<int> low;
  for (int k = 0; k < w2.size(); ++k)
    if (w2[k] <= w2_max) low.push_back(k);
  const Eigen::Matrix3Xd phi = modeMotions(sim, low);
  double largest = 0.0;
  for (int k = 0; k < phi.cols(); ++k) largest = std::max(largest, phi.col(k).head<2>().norm());
  std::vector<int> out;
  for (int k = 0; k < phi.cols() && static_cast<int>(out.size()) < max_modes; ++k) {
    const double sideways = phi.col(k).head<2>().norm(), vertical = std::abs(phi(2, k));
    // Mostly sideways at the trolley: a payload's horizontal position cannot tell a mode that
    // mostly lifts the trolley, and correcting one would move the load up and down.
    if (largest > 0.0 && sideways >= 0.05 * largest && sideways >= vertical) out.push_back(low[k]);
  }
  return out;
}

SwayModel swayModelAt(const Simulation& sim, const SeriesValues& v, const std::vector<int>& modes,
                      double gravity) {
  SwayModel m;
  m.gravity = gravity;
  m.length = std::max((v.payload - v.trolley).norm(), 1e-3);
  m.tension = v.rope_top_tension;
  m.omega2 = Eigen::VectorXd::Zero(modes.size());
  m.damping = Eigen::VectorXd::Zero(modes.size());
  if (!modes.empty()) {
    const auto* modal = dynamic_cast<const ModalStructureSupport*>(&sim.support());
    if (!modal)
      throw std::invalid_argument("swayModelAt: structure modes without a modal structure");
    for (std::size_t k = 0; k < modes.size(); ++k) {
      m.omega2[k] = modal->omega2()[modes[k]];
      m.damping[k] = modal->dampingTerms()[modes[k]];
    }
  }
  m.phi = modeMotions(sim, modes).topRows<2>();
  return m;
}

Eigen::VectorXd modeMotionNorms(const Simulation& sim, const std::vector<int>& modes) {
  return modeMotions(sim, modes).topRows<2>().colwise().norm().transpose();
}

}  // namespace crane_twin
