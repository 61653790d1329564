#include "crane_twin/integrators/tension_only_step.hpp"

namespace crane_twin {

bool tensionOnlyStep(const TensionOnlyRope& rope, double tolerance, bool hoisting,
                     TensionOnlySwitching& memory, CoupledState& s, double h, std::string& why) {
  const CoupledState start = s;
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
  memory.energy_created += rope.energy_created(start, s);
  ++memory.energy_consistent_steps;
  // (while hoisting too: a generalized-alpha restart after every energy-consistent step raised
  // the energy at each, header)
  memory.switching = rope.switch_work_error(start.q, s.q) > tolerance;
  // Leaving the episode: generalized-alpha restarts from consistent accelerations (a = q'').
  if (!memory.switching) rope.restart_accelerations(s);
  return true;
}

void keepEnergyConsistentMeans(const CoupledState& start, double h, CoupledState& s) {
  s.lambda = 0.5 * (start.lambda + s.lambda);
  s.qdd = (s.v - start.v) / h;
  s.a = s.qdd;
  if (s.z.size() > 0) {
    s.zdd = (s.zd - start.zd) / h;
    s.za = s.zdd;
  }
}

}  // namespace crane_twin
