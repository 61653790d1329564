// The rigid poses of the structure's member groups ("mast", "slewing", "jib", "counter_jib")
// from the structure's coordinates z, without the displacement field (docs/ros.md, the
// structure's frames).
//
// snapshotOf fits each group's nodes x_i, displaced to y_i = x_i + s u_i (u = T z, s the
// drawing scale), with the rigid motion of least squares (rigidFit, Umeyama without scaling).
// That fit depends on the points only through their centroids and their cross-covariance,
//   ybar = xbar + s U z,   Sigma = (1/n) sum (y_i - ybar)(x_i - xbar)^T = Sigma_xx + s C(z),
// both linear in z (U: 3 x m, C: the 9 x m columns of (1/n) sum u_i (x_i - xbar)^T per unit
// coordinate), so they are set up once per support (m displacement fields) and each pose costs
// O(m) instead of the O(n_dof m) field u = T z (a 100-mode T8036: 15 % of the node's run time
// as fast as possible went to that field before).
#pragma once

#include <Eigen/Dense>
#include <map>
#include <string>

#include "crane_twin/analysis/crane_snapshot.hpp"
#include "crane_twin/rope/rope_support.hpp"

namespace crane_twin {

class StructureGroupPoses {
 public:
  /// The groups of `support`'s structure (none for a support without one). The support's
  /// coordinates-to-displacements map T must be constant (structureDisplacement linear in z).
  explicit StructureGroupPoses(const RopeSupport& support);
  /// Whether the structure has a group of that name with at least 3 nodes.
  bool has(const std::string& group) const { return groups_.count(group) > 0; }
  /// The group's rigid fit at coordinates z, displacements drawn `scale` times, in the slewing
  /// frame: what rigidFit of its displaced nodes gives. Throws std::invalid_argument for an
  /// unknown group or a z of another size.
  FramePose fit(const std::string& group, const Eigen::VectorXd& z, double scale) const;

 private:
  struct Moments {
    Eigen::Vector3d xbar;
    Eigen::Matrix3d sigma_xx;  ///< (1/n) sum (x_i - xbar)(x_i - xbar)^T
    Eigen::MatrixXd U;         ///< 3 x m: mean displacement per unit coordinate
    Eigen::MatrixXd C;         ///< 9 x m: (1/n) sum u_i (x_i - xbar)^T per unit coordinate
  };
  std::map<std::string, Moments> groups_;
  int coordinates_ = 0;
};

}  // namespace crane_twin
