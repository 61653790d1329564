// A scene run with the paper's subdomain reduced rope (R-ANCF; rope.model: reduced with
// rope.reduction: subdomains, docs/model.md): the same rope, support and initial equilibrium as
// the full-order model (CraneSimulation), integrated by
// SubdomainReducedSolver. Hoisting: every step that changes the rope's length rescales the expanded
// state as the full model does and starts a new subdomain with a static-correction vector.
//
// Slack rope: a linearisation about a (nearly) slack rope is degenerate (compressed sections
// give negative stiffness, and the modes of a rope about to go slack cannot carry it through),
// so when the rope's top tension falls below kSlackTensionFraction of the hanging weight, or
// (checked every kSlackCheckSteps steps) any node's axial strain below kSlackFraction of the
// static strain under the end mass, the run hands its expanded state to the full-order solver,
// and takes it back (a new subdomain) once every node's strain is above kTautFraction of it, the
// top tension above kTautTensionFraction of the weight, and the new basis carries the state: the
// kinetic energy its projection drops is under kHandBackEnergyLoss of the rope's kinetic energy
// relative to its top (checked every kHandBackCheckSteps full-order steps). Without the hand-over
// a 60 deg release (the rope goes almost slack 0.19 s after release) blew up to 35 MN; without
// the energy check the run chattered between the models and the top tension spiked to 2.5 MN
// (docs/stability.md).
#pragma once

#include "crane_twin/simulation/hand_over_simulation.hpp"
#include "crane_twin/solvers/subdomain_reduced_solver.hpp"

namespace crane_twin {

/// Rope modes kept for a scene: rope.mode_count if set, else mode_fraction of the rope DOF less
/// the three translations, at least 1 (docs/model.md). Throws InputError naming the key.
int keptRopeModes(const CraneModel& model);
int keptRopeModes(const Scene& scene);

class SubdomainReducedSimulation final : public HandOverSimulation {
 public:
  explicit SubdomainReducedSimulation(const CraneModel& model);
  /// Hand-over thresholds (HandOverSettings): nodal axial strain / static strain under the end
  /// mass, and top tension / hanging weight (payload, hook block, rope), with hysteresis:
  /// slack under 0.3 (strain, checked every 5 steps) and 0.3 (tension), taut above 0.6 and
  /// 0.45, higher than the invariant basis's: a linearisation about a nearly slack rope is
  /// degenerate. Hand-back trials every kHandBackCheckSteps full-order steps from the
  /// hand-over on, while the hoist stands still.
  static HandOverSettings handOverSettingsFor();
  static constexpr double kSlackFraction = 0.3, kTautFraction = 0.6;
  static constexpr double kSlackTensionFraction = 0.3, kTautTensionFraction = 0.45;
  static constexpr int kSlackCheckSteps = 5;
  /// Hand-back check: fraction of the rope's relative kinetic energy the projection onto the new
  /// basis may drop, and how often (full-order steps) it is tried. Measured on the 60 deg
  /// release, 40 elements: 1e-4 and 2e-4 keep the peak tension at 170 kN (full order: 179 kN),
  /// 5e-4 lets a 1.6 MN spike through (docs/stability.md).
  static constexpr double kHandBackEnergyLoss = 1e-4;
  static constexpr int kHandBackCheckSteps = 10;
  /// Hoisting: relative rope length change |L - L_basis| / L after which a subdomain renews its
  /// modes and static correction instead of re-linearising the previous block (Rayleigh-Ritz).
  /// Measured (10 modes, payload error against full order): a fixed 0.05 m was fine on 60 m
  /// ropes (1.6e-2 m on t8036_hoist_60_20_50) but let hard_hoist_60_3_60 fail at 63.4 s while
  /// lowering from 3 m (0.05 m is 1.7 % of 3 m); 1e-3 of L still failed there at 64.8 s; 2e-4
  /// runs it through with 0.058 m (4.6e-3 m on the hoisting scene, 5.6e-3 m on the cycle).
  static constexpr double kHoistBasisStrain = 2e-4;
  /// Hoisting faster than kHoistStepStrain x the static strain under the end mass per step
  /// (|dL| / L per step) runs at full order until the hoist stops (docs/model.md).
  static constexpr double kHoistStepStrain = 0.25;
  int slackEpisodes() const { return static_cast<int>(handOvers(Cause::slack)); }
  /// Hand-back trials refused because the new basis dropped too much of the state's energy.
  long refusedHandBacks() const { return refused_hand_backs_; }
  /// Hand-overs to full order because the length changed too fast per step.
  long fastHoistEpisodes() const { return handOvers(Cause::fast_hoist); }
  const SubdomainReducedSolver& solver() const { return *solver_; }

 protected:
  Start startReduced(const CoupledState& full) override;
  Verdict reducedStep() override;
  bool tryTakeOver(const CoupledState& full) override;
  CoupledState handOverState(Cause) override { return solver_->fullState(); }
  bool restartsAtHandOver() const override { return false; }
  double reducedTime() const override { return solver_->state().t; }
  const Eigen::VectorXd& reducedSupport() const override { return solver_->state().z; }
  Eigen::Vector3d reducedNode(int j) const override { return solver_->nodePosition(j); }
  CoupledState expandReduced() const override { return solver_->fullState(); }
  SeriesValues reducedSeries() const override { return full_.seriesOf(solver_->fullState()); }
  double reducedLength() const override { return full_.ropeLength(); }
  double reducedTopTension() const override { return solver_->topTension(); }
  double reducedMinStrain() const override { return solver_->minNodalStrain(); }
  int reducedSubdomains() const override { return solver_->statistics().subdomains; }
  double reducedModeUpdateSeconds() const override {
    return solver_->statistics().mode_update_seconds;
  }

 private:
  std::unique_ptr<SubdomainReducedSolver> solver_;
  double basis_length_ = -1.0;  ///< rope length of the last full basis update while hoisting
  int hoist_subdomain_ = -1;    ///< the solver's subdomain count after the last hoisting restart
  long refused_hand_backs_ = 0;
};

}  // namespace crane_twin
