#include "crane_twin/simulation/speculation_follower.hpp"

#include <utility>

namespace crane_twin {

SpeculationFollower::SpeculationFollower(Simulation& sim, Recording recording)
    : speculative_(capabilityOf<SpeculativeRun>(sim)), recording_(std::move(recording)) {
  if (speculative_) {
    speculative_->setReplayObserver([this](long replayed_steps) { replayed(replayed_steps); });
  }
}

SpeculationFollower::~SpeculationFollower() {
  if (speculative_) speculative_->setReplayObserver({});
}

void SpeculationFollower::step(long k) {
  // (a take-back within this step has closed the speculation already: replayed)
  if (holding_ && !speculative_->speculating()) keepHeld();
  follow(k);
}

void SpeculationFollower::finish() {
  if (holding_) keepHeld();
}

void SpeculationFollower::keepHeld() {
  holding_ = false;
  call(recording_.keep);
}

void SpeculationFollower::follow(long k) {
  // A hand-back in this step (or a start that speculates): its checkpoint is this step's state.
  if (!holding_ && speculative_ && speculative_->speculating()) {
    holding_ = true;
    checkpoint_step_ = k;
    call(recording_.hold);
  }
  recording_.record(k);
}

void SpeculationFollower::replayed(long replayed_steps) {
  if (replayed_steps == 0) {
    holding_ = false;
    call(recording_.drop);
  }
  recording_.record(checkpoint_step_ + replayed_steps);
}

}  // namespace crane_twin
