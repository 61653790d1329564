// The structure's geometric stiffness under its own weight (P-delta,
// `structure.geometric_stiffness`, docs/model.md "Geometric stiffness"): the static displacement u
// of K u = F (self-weight and the hanging load at the trolley), each member's axial force N from u,
// and
//   K_G = sum_e beamGeometricStiffnessGlobal(N_e),
// so the structure's model stiffness becomes K + K_G (compressed members soften it).
#pragma once

#include <Eigen/Dense>

#include "crane_twin/elements/sparse_assembly.hpp"
#include "crane_twin/structure/tower_crane_structure.hpp"

namespace crane_twin {

/// Free-DOF self-weight load M a, a = (0, 0, -g) on every node's translation [N].
Eigen::VectorXd selfWeightLoad(const TowerCraneStructure& s, double g);

/// Free-DOF displacement u = K^-1 f (sparse LDL^T). Throws std::runtime_error when K is singular.
Eigen::VectorXd staticDisplacement(const TowerCraneStructure& s, const Eigen::VectorXd& f);

/// Axial force of every member [N] (tension positive) for the free-DOF displacement u.
Eigen::VectorXd memberAxialForces(const TowerCraneStructure& s, const Eigen::VectorXd& u);

/// K_G assembled over the members with axial forces N (free DOFs).
SparseMatrix geometricStiffness(const TowerCraneStructure& s, const Eigen::VectorXd& N);

}  // namespace crane_twin
