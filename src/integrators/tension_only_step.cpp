#include "crane_twin/integrators/tension_only_step.hpp"

namespace crane_twin {

bool tensionOnlyStep(const TensionOnlyRope& rope, double tolerance, bool hoisting,
                     TensionOnlySwitching& memory, CoupledState& s, double h, std::string& why) {
  memory.start = s;  // (into the memory's storage: no allocation once sized)
  const CoupledState& start = memory.start;
  if (!memory.switching) {
    if (rope.generalized_alpha_step(s, h, why)) {
      const double switch_error = rope.switch_work_error(start.q, s.q);
      if (switch_error == 0.0) return true;
      if (hoisting || switch_error <= tolerance) {
        const double created = rope.energy_created(start, s);
        if (memory.energy_created + created <= tolerance) {
          memory.energy_created += created;
          return true;
        }
      }
    }
    s = start;
  }
  if (!rope.energy_consistent_step(s, h, why)) return false;
  // (its energy falls by theta dv^T M dv and the dampers' work, energyConsistentScheme: it adds
  // nothing to the run's created energy, and what it dissipates buys generalized-alpha nothing)
  ++memory.energy_consistent_steps;
  // (while hoisting too: a generalized-alpha restart after every energy-consistent step raised
  // the energy at each, header)
  memory.switching = rope.switch_work_error(start.q, s.q) > tolerance;
  // Leaving the episode: generalized-alpha restarts from consistent accelerations (a = q'').
  if (!memory.switching) rope.restart_accelerations(s);
  return true;
}

GeneralizedAlpha energyConsistentScheme(double h) {
  GeneralizedAlpha g;
  g.gamma = 1.0;
  g.beta = 0.5 + kEnergyDecayRate * h;
  return g;
}

void startEnergyConsistentStep(CoupledState& s) {
  s.qdd.setZero();
  s.a.setZero();
  if (s.z.size() > 0) {
    s.zdd.setZero();
    s.za.setZero();
  }
}

}  // namespace crane_twin
