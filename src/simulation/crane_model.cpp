#include "crane_twin/simulation/crane_model.hpp"

#include <Eigen/SparseCholesky>

#include "crane_twin/io/input_error.hpp"
#include "crane_twin/structure/geometric_stiffness.hpp"

namespace crane_twin {

// P-delta (docs/model.md "Geometric stiffness"): K + K_G(N), N the members' axial forces under
// the self-weight and the static hanging load (end mass, hanging rope, trolley) at the scene's
// trolley radius. Refused when the structure buckles under it (K + K_G not positive definite).
void addGeometricStiffness(CraneModel& m) {
  TowerCraneStructure& st = *m.structure;
  const double g = m.scene.gravity;
  const double hanging = m.hangingPointMass() + m.ropeMass() + m.trolleyMass();
  const Eigen::VectorXd f =
      selfWeightLoad(st, g) + st.pointForce(st.trolleyWeights(m.scene.trolley_radius),
                                            Eigen::Vector3d(0.0, 0.0, -hanging * g));
  m.structure_axial_forces = memberAxialForces(st, staticDisplacement(st, f));
  st.K = st.K + geometricStiffness(st, m.structure_axial_forces);
  Eigen::SimplicialLLT<SparseMatrix> llt(st.K);
  if (llt.info() != Eigen::Success) {
    throw InputError(
        m.scene.file +
        ": key 'structure.geometric_stiffness': the structure buckles "
        "under its own weight and the hanging load (K + K_G is not positive definite)");
  }
}

CraneModel buildCraneModel(const Scene& scene) {
  CraneModel m;
  m.scene = scene;
  // Even a rigid structure needs the geometry (rail, jib tip, cab reference points).
  if (scene.crane) m.structure = TowerCraneStructure::build(*scene.crane);
  const int n = scene.rope.falls;
  m.rope.mass_per_length = n * scene.rope.mass_per_length;
  m.rope.axial_stiffness = n * scene.rope.axial_stiffness;
  m.rope.bending_stiffness = scene.rope.bending ? n * scene.rope.bending_stiffness : 0.0;
  m.rope.breaking_force = n * scene.rope.breaking_force;
  m.rope.reeving_equivalent_length = scene.rope.reeving_length / n;
  m.end_mass = scene.payload_mass + (scene.hasRigging() ? 0.0 : scene.hookBlockMass());
  m.hook_mass = scene.hasRigging() ? scene.hookBlockMass() : 0.0;
  if (scene.structure_geometric_stiffness) addGeometricStiffness(m);
  return m;
}

GeneralizedAlpha integratorFor(const Scene& sc) {
  return sc.integrator == "newmark" ? GeneralizedAlpha::newmark()
                                    : GeneralizedAlpha::fromRhoInf(sc.rho_inf);
}

std::optional<GroundContact> groundContactOf(const CraneModel& m) {
  if (!m.scene.ground) return std::nullopt;
  const GroundSettings& g = *m.scene.ground;
  GroundContactParameters p;
  p.height = g.height;
  p.stiffness = g.stiffness;
  p.damping = groundDamping(g.stiffness, m.end_mass, g.damping_ratio);
  p.friction = g.friction;
  p.payload_height = m.scene.payload_height;
  return GroundContact(p);
}

}  // namespace crane_twin
