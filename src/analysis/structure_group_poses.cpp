#include "crane_twin/analysis/structure_group_poses.hpp"

#include <stdexcept>
#include <vector>

#include "crane_twin/structure/tower_crane_structure.hpp"

namespace crane_twin {

StructureGroupPoses::StructureGroupPoses(const RopeSupport& support) {
  const TowerCraneStructure* s = support.structure();
  if (!s) return;
  coordinates_ = static_cast<int>(support.size());
  std::map<std::string, std::vector<int>> nodes;
  for (const StructureMember& m : s->members)
    if (!nodes.count(m.group)) nodes[m.group] = s->groupNodes(m.group);
  for (const auto& [group, list] : nodes) {
    if (list.size() < 3) continue;
    Moments g;
    const double w = 1.0 / static_cast<double>(list.size());
    g.xbar.setZero();
    for (int n : list) g.xbar += w * s->nodes[n];
    g.sigma_xx.setZero();
    for (int n : list)
      g.sigma_xx += w * (s->nodes[n] - g.xbar) * (s->nodes[n] - g.xbar).transpose();
    g.U.setZero(3, coordinates_);
    g.C.setZero(9, coordinates_);
    groups_[group] = g;
  }
  // One displacement field per unit coordinate: u_k = T e_k.
  Eigen::VectorXd e = Eigen::VectorXd::Zero(coordinates_);
  for (int k = 0; k < coordinates_; ++k) {
    e.setZero();
    e(k) = 1.0;
    const Eigen::VectorXd u = support.structureDisplacement(e);
    for (auto& [group, g] : groups_) {
      const std::vector<int>& list = nodes[group];
      const double w = 1.0 / static_cast<double>(list.size());
      Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int n : list) {
        const Eigen::Vector3d un = s->nodeDisplacement(u, n);
        mean += w * un;
        c += w * un * (s->nodes[n] - g.xbar).transpose();
      }
      g.U.col(k) = mean;
      g.C.col(k) = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(c.data());
    }
  }
}

FramePose StructureGroupPoses::fit(const std::string& group, const Eigen::VectorXd& z,
                                   double scale) const {
  const auto it = groups_.find(group);
  if (it == groups_.end()) throw std::invalid_argument("no structure group '" + group + "'");
  if (z.size() != coordinates_) {
    throw std::invalid_argument("structure coordinates: " + std::to_string(coordinates_) +
                                " expected, got " + std::to_string(z.size()));
  }
  const Moments& g = it->second;
  const Eigen::Vector3d ybar = g.xbar + scale * (g.U * z);
  const Eigen::Matrix<double, 9, 1> c = g.C * z;
  const Eigen::Matrix3d sigma = g.sigma_xx + scale * Eigen::Map<const Eigen::Matrix3d>(c.data());
  // Umeyama's rotation without scaling: sigma = U D V^T, R = U S V^T with S = diag(1, 1, -1)
  // where det(U) det(V) < 0 (no reflection), t = ybar - R xbar.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d S = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2) = -1.0;
  const Eigen::Matrix3d R = svd.matrixU() * S.asDiagonal() * svd.matrixV().transpose();
  FramePose p;
  p.position = ybar - R * g.xbar;
  p.orientation = Eigen::Quaterniond(R).normalized();
  return p;
}

}  // namespace crane_twin
