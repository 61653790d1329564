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

SubdomainReducedSimulation::SubdomainReducedSimulation(const CraneModel& model) : full_(model) {
  if (model.scene.rope.damping != 0.0) {
    throw InputError(model.scene.file +
                     ": key 'rope.damping': rope damping is built for the "
                     "full-order model only (set rope.model: full)");
  }

  solver_ = std::make_unique<SubdomainReducedSolver>(full_.rope(), full_.support(),
                                                     integratorFor(model.scene),
                                                     model.scene.time_step, settingsFor(model));
}

void SubdomainReducedSimulation::initialize() {
  const CraneModel& m = full_.model();
  weight_ = (m.end_mass + m.ropeMass()) * m.scene.gravity;
  end_strain_ = m.end_mass * m.scene.gravity / m.rope.axialStiffnessAt(m.scene.rope.length);
  reduced_steps_ = 0;
  full_order_ = false;
  full_order_steps_ = 0;
  slack_episodes_ = 0;
  fast_hoist_episodes_ = 0;
  refused_hand_backs_ = 0;
  solver_->initialize(full_.initialState());
  basis_length_ = -1.0;  // the first hoisting step renews the basis
  hoist_subdomain_ = -1;
}

void SubdomainReducedSimulation::setCommand(const CommandEntry& command) {
  full_.setCommand(command);
}

// The drives move the support first (the same scheme as the full model), then one reduced step.
void SubdomainReducedSimulation::step() {
  if (full_order_) {  // slack episode: full order until the rope is taut again
    full_.step();
    ++full_order_steps_;
    // Taut again everywhere: every node's axial strain |r_x| - 1 above kTautFraction of the
    // static strain under the end mass alone (the least-loaded point of a hanging rope).
    const double least = AncfRope::minNodalStrain(full_.state().q);
    // A slack episode while the hoist moves stays at full order until it stops (the length
    // changes every step then; measured in docs/model.md).
    if (least > kTautFraction * end_strain_ &&
        full_.solver().topTension(full_.state()) > kTautTensionFraction * weight_ &&
        full_.drives().hoistSpeed() == 0.0 && full_order_steps_ % kHandBackCheckSteps == 0) {
      // Hand back only when the new basis carries the state: the kinetic energy its
      // projection drops stays under kHandBackEnergyLoss of the rope's kinetic energy
      // relative to its top (a trial restart; a refused one is overwritten by the next).
      const CoupledState& f = full_.state();
      const double before = solver_->statistics().projection_energy_loss;
      try {
        solver_->restartAt(f, true);
      } catch (const NumericalFailure&) {
        ++refused_hand_backs_;  // no basis at this state: stay at full order
        return;
      }
      const double lost = solver_->statistics().projection_energy_loss - before;
      const double kinetic = full_.rope().kineticEnergyRelativeToTop(f.v);
      if (!(lost > kHandBackEnergyLoss * kinetic)) {
        full_order_ = false;
      } else {
        ++refused_hand_backs_;
      }
    }
    return;
  }
  full_.advanceDrives(solver_->state().t, full_.solver().timeStep(), solver_->state().z);
  const double length = full_.drives().hoistLength(), from = full_.ropeLength();
  if (length != from && std::abs(length - from) > kHoistStepStrain * end_strain_ * from) {
    // A length change per step that is not small against the rope's static stretch: the
    // rescaled rope is far from any linearisation. Full order until the hoist stops.
    full_.setState(solver_->fullState());
    full_.stepAfterDrives();
    full_order_ = true;
    ++full_order_steps_;
    ++fast_hoist_episodes_;
    return;
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
  solver_->step();
  const bool slack = weight_ > 0.0 && (solver_->topTension() < kSlackTensionFraction * weight_ ||
                                       (++reduced_steps_ % kSlackCheckSteps == 0 &&
                                        solver_->minNodalStrain() < kSlackFraction * end_strain_));
  if (slack) {
    full_.setState(solver_->fullState());
    full_order_ = true;
    ++slack_episodes_;
  }
}

SeriesValues SubdomainReducedSimulation::series() const {
  SeriesValues v = full_.seriesOf(fullState());
  v.subdomains = solver_->statistics().subdomains;
  v.full_order_steps = full_order_steps_;
  return v;
}

}  // namespace crane_twin
