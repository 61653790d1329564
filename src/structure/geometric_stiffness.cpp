#include "crane_twin/structure/geometric_stiffness.hpp"

#include <Eigen/SparseCholesky>
#include <stdexcept>

#include "crane_twin/elements/beam_geometric_stiffness.hpp"

namespace crane_twin {

Eigen::VectorXd selfWeightLoad(const TowerCraneStructure& s, double g) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(s.free_dofs);
  for (std::size_t n = 0; n < s.nodes.size(); ++n) {
    const int e = s.dof_equation[6 * n + 2];
    if (e >= 0) a(e) = -g;
  }
  return s.M * a;
}

Eigen::VectorXd staticDisplacement(const TowerCraneStructure& s, const Eigen::VectorXd& f) {
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(s.K);
  if (ldlt.info() != Eigen::Success) throw std::runtime_error("structure stiffness is singular");
  return ldlt.solve(f);
}

Eigen::VectorXd memberAxialForces(const TowerCraneStructure& s, const Eigen::VectorXd& u) {
  Eigen::VectorXd N(s.members.size());
  for (std::size_t k = 0; k < s.members.size(); ++k) {
    const StructureMember& m = s.members[k];
    N(k) = beamAxialForce(s.sections[m.section], s.nodes[m.node1], s.nodes[m.node2],
                          s.nodeDisplacement(u, m.node1), s.nodeDisplacement(u, m.node2));
  }
  return N;
}

SparseMatrix geometricStiffness(const TowerCraneStructure& s, const Eigen::VectorXd& N) {
  if (N.size() != static_cast<Eigen::Index>(s.members.size())) {
    throw std::invalid_argument("geometricStiffness: one axial force per member");
  }
  SparseAssembler A(s.free_dofs);
  std::vector<int> eq(12);
  for (std::size_t k = 0; k < s.members.size(); ++k) {
    const StructureMember& m = s.members[k];
    for (int d = 0; d < 6; ++d) {
      eq[d] = s.dof_equation[6 * m.node1 + d];
      eq[6 + d] = s.dof_equation[6 * m.node2 + d];
    }
    A.add(beamGeometricStiffnessGlobal(s.sections[m.section], s.nodes[m.node1], s.nodes[m.node2],
                                       m.orientation, N(k)),
          eq);
  }
  return A.build();
}

}  // namespace crane_twin
