#include "crane_twin/simulation/crane_model.hpp"

namespace crane_twin {

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
  m.end_mass = scene.payload_mass + scene.hookBlockMass();
  return m;
}

}  // namespace crane_twin
