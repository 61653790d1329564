// Finite element model of a flat-top tower crane's steel structure (docs/model.md).
//
// Generated from a CraneDescription in the slewing frame at slewing angle 0 (x along the jib,
// z up, origin at the centre of the mast base):
//  - mast: square lattice, 4 chords, horizontals at every panel level and K (chevron) diagonals
//    on each face meeting at mid-panel chord nodes; base nodes clamped (all 6 DOF);
//  - slewing unit: a stiff box of tube members on the mast top;
//  - jib and counter-jib: triangular lattices (2 bottom chords = trolley rails, 1 top chord),
//    Warren diagonals on the three faces, horizontals at every station;
//  - cab node and lumped masses (counterweight, winch, machinery) shared by nearest nodes.
// Every member is a Timoshenko beam element (rigid joints). M and K are assembled over the
// free DOFs (6 per node, clamped ones removed), constant (linear theory).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "crane_twin/elements/sparse_assembly.hpp"
#include "crane_twin/io/crane_description.hpp"

namespace crane_twin {

struct StructureMember {
  int node1 = 0, node2 = 0;
  int section = 0;  ///< index into TowerCraneStructure::sections
  Eigen::Vector3d orientation = Eigen::Vector3d::UnitZ();
  std::string group;  ///< "mast", "slewing", "jib", "counter_jib", "cab"
};

struct NodeLoad {
  int node = 0;
  double weight = 0.0;
};

class TowerCraneStructure {
 public:
  /// Build the mesh and assemble M and K. Throws InputError on inconsistent geometry.
  static TowerCraneStructure build(const CraneDescription& crane);

  std::vector<Eigen::Vector3d> nodes;  ///< undeformed positions, slewing frame [m]
  std::vector<bool> clamped;           ///< per node
  std::vector<StructureMember> members;
  std::vector<BeamSection> sections;
  std::vector<std::pair<int, double>> lumped_masses;  ///< (node, kg)
  std::vector<int> dof_equation;  ///< 6 * nodes entries: equation number or -1 if clamped
  int free_dofs = 0;
  SparseMatrix K;  ///< free-DOF stiffness [N/m, N/rad, ...]
  SparseMatrix M;  ///< free-DOF consistent mass incl. lumped masses [kg, kg m^2]

  int cab_node = -1;
  std::vector<int> jib_tip_nodes;  ///< bottom chord tip nodes (jib tip = their mean)
  /// Trolley rail: stations (x, left bottom node, right bottom node), increasing x.
  struct RailStation {
    double x;
    int left, right;
  };
  std::vector<RailStation> rail;
  double rail_height = 0.0;  ///< z of the bottom chords [m]

  double memberMass() const { return member_mass_; }
  double lumpedMass() const { return lumped_mass_; }

  /// Nodes and weights whose weighted mean is the trolley point at radius s (linear along
  /// the rail, mean of both rails). Throws std::out_of_range outside the rail.
  std::vector<NodeLoad> trolleyWeights(double radius) const;

  /// Global force vector (free DOFs) for a force f [N] applied at the weighted nodes.
  Eigen::VectorXd pointForce(const std::vector<NodeLoad>& at, const Eigen::Vector3d& f) const;

  /// Translation of a node from a free-DOF displacement vector (0 for clamped DOFs).
  Eigen::Vector3d nodeDisplacement(const Eigen::VectorXd& u, int node) const;

  /// The nodes of the members in `group` ("mast", "jib", ...), ascending; empty for none.
  std::vector<int> groupNodes(const std::string& group) const;

 private:
  int addNode(const Eigen::Vector3d& p);
  void addMember(int a, int b, int section, const std::string& group);
  void addBoom(const CraneDescription& c, const LatticeBoomSpec& b, double direction,
               const std::string& group, int first_top_section);
  double member_mass_ = 0.0;
  double lumped_mass_ = 0.0;
};

}  // namespace crane_twin

namespace crane_twin {

/// Linear static displacement (free DOFs) of the structure under a vertical load m g at the
/// trolley point of radius s: K u = F, solved with CHOLMOD. Throws std::runtime_error if the
/// factorisation fails.
Eigen::VectorXd staticTrolleyLoadDisplacement(const TowerCraneStructure& s, double mass,
                                              double radius, double gravity);

/// Jib-tip displacement (mean of the bottom-chord tip nodes) for a free-DOF displacement u.
Eigen::Vector3d jibTipDisplacement(const TowerCraneStructure& s, const Eigen::VectorXd& u);

/// The jib's own vertical bending at the tip: jib-tip dz less the rigid motion of the jib root
/// section (its dz and its pitch rotation th_y carried over the jib length,
/// dz_rigid = dz_root - th_y (x_tip - x_root)). Separates jib bending from mast tilt.
double jibBendingTipDz(const TowerCraneStructure& s, const Eigen::VectorXd& u);

}  // namespace crane_twin
