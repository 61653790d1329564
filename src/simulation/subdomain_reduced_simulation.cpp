#include "crane_twin/simulation/subdomain_reduced_simulation.hpp"

#include <cmath>
#include <string>

#include "crane_twin/io/config_reader.hpp"

namespace crane_twin {

int keptRopeModes(const CraneModel& model) { return keptRopeModes(model.scene); }

int keptRopeModes(const Scene& sc) {
  const int n = 6 * (sc.rope.elements + 1);
  if (sc.rope.mode_count > 0) {
    if (sc.rope.mode_count > n - 3) {
      throw InputError(sc.file + ": key 'rope.mode_count': at most " + std::to_string(n - 3) +
                       " (rope DOF less the top node's 3 positions), got " +
                       std::to_string(sc.rope.mode_count));
    }
    return sc.rope.mode_count;
  }
  return std::max(1, std::min(n - 3, static_cast<int>(std::lround(sc.rope.mode_fraction * n)) - 3));
}

namespace {
SubdomainSettings settingsFor(const CraneModel& model) {
  const RopeSettings& r = model.scene.rope;
  SubdomainSettings s;
  s.kept_modes = keptRopeModes(model);
  s.delta = r.subdomain_delta;
  s.update = r.mode_update == "cold" ? ModeUpdate::cold : ModeUpdate::warm;
  s.residual_tolerance = r.subdomain_residual;
  s.corotational = r.subdomain_frame == "corotational";
  s.max_chord_rotation = r.subdomain_rotation;
  return s;
}
}  // namespace

HandOverSettings SubdomainReducedSimulation::handOverSettingsFor() {
  HandOverSettings h;
  h.slack_tension_fraction = kSlackTensionFraction;
  h.taut_tension_fraction = kTautTensionFraction;
  h.slack_strain_fraction = kSlackFraction;
  h.taut_strain_fraction = kTautFraction;
  h.strain_check_steps = kSlackCheckSteps;
  h.hand_back_dwell = 0.0;
  h.hand_back_steps = h.max_hand_back_interval = kHandBackCheckSteps;
  return h;
}

SubdomainReducedSimulation::SubdomainReducedSimulation(const CraneModel& model)
    : HandOverSimulation(model, handOverSettingsFor()) {
  if (model.scene.rope.damping != 0.0) {
    throw InputError(model.scene.file +
                     ": key 'rope.damping': rope damping is built for the "
                     "full-order model only (set rope.model: full)");
  }
  solver_ = std::make_unique<SubdomainReducedSolver>(full_.rope(), full_.support(),
                                                     integratorFor(model.scene),
                                                     model.scene.time_step, settingsFor(model));
}

HandOverSimulation::Start SubdomainReducedSimulation::startReduced(const CoupledState& full) {
  refused_hand_backs_ = 0;
  solver_->initialize(full);
  basis_length_ = -1.0;  // the first hoisting step renews the basis
  hoist_subdomain_ = -1;
  return Start::reduced;  // a subdomain starts on any state
}

bool SubdomainReducedSimulation::tryTakeOver(const CoupledState& f) {
  // A slack episode while the hoist moves stays at full order until it stops (the length
  // changes every step then; measured in docs/model.md). Hand back only when the new basis
  // carries the state: the kinetic energy its projection drops stays under
  // kHandBackEnergyLoss of the rope's kinetic energy relative to its top (a trial restart; a
  // refused one is overwritten by the next).
  if (full_.drives().hoistSpeed() != 0.0) return false;
  const double before = solver_->statistics().projection_energy_loss;
  try {
    solver_->restartAt(f, true);
  } catch (const NumericalFailure&) {
    ++refused_hand_backs_;  // no basis at this state: stay at full order
    return false;
  }
  const double lost = solver_->statistics().projection_energy_loss - before;
  const double kinetic = full_.rope().kineticEnergyRelativeToTop(f.v);
  if (lost > kHandBackEnergyLoss * kinetic) {
    ++refused_hand_backs_;
    return false;
  }
  return true;
}

// The drives have moved the support (the same scheme as the full model): one reduced step.
HandOverSimulation::Verdict SubdomainReducedSimulation::reducedStep() {
  const double length = full_.drives().hoistLength(), from = full_.ropeLength();
  if (length != from && std::abs(length - from) > kHoistStepStrain * end_strain_ * from) {
    // A length change per step that is not small against the rope's static stretch: the
    // rescaled rope is far from any linearisation. Full order until the hoist stops.
    return Verdict::fast_hoist;
  }
  if (length != from) {
    // Hoisting: the full model's rescaling on the expanded state, then a new subdomain: modes
    // and the static-correction vector after a relative length change of kHoistBasisStrain,
    // Rayleigh-Ritz of that block in between (SubdomainReducedSolver header).
    CoupledState f = solver_->fullState();
    Eigen::VectorXd before, after;
    full_.rope().elasticForce(f.q, before);
    full_.applyRopeLength(f);
    full_.rope().elasticForce(f.q, after);
    // The block must be the last hoisting subdomain's (a subdomain started since, by the
    // displacement criterion, a slack episode or at rest, has no static correction).
    const bool renew =
        solver_->statistics().subdomains != hoist_subdomain_ ||
        !(std::abs(full_.ropeLength() - basis_length_) < kHoistBasisStrain * full_.ropeLength());
    solver_->restartAt(f, false,
                       renew ? SubdomainReducedSolver::BasisUpdate::modes_and_correction
                             : SubdomainReducedSolver::BasisUpdate::ritz,
                       Eigen::VectorXd(before - after));
    if (renew) basis_length_ = full_.ropeLength();
    hoist_subdomain_ = solver_->statistics().subdomains;
  }
  solver_->step();  // a failure ends the run (NumericalFailure)
  return Verdict::carried;
}

}  // namespace crane_twin
