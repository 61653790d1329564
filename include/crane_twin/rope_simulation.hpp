// A scene with crane: none run at full order: the anchored ANCF rope, its initial state
// (SPEC 2: equilibrium with a holding force, or stress-free), time stepping, and the SPEC 3.1
// time-series row. The ROS-free unit the CLI's `run`, `static` and `modes --part rope` use for
// rope-only scenes.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "crane_twin/anchored_rope_solver.hpp"
#include "crane_twin/crane_model.hpp"
#include "crane_twin/modal_analysis.hpp"

namespace crane_twin {

/// SPEC 3.1 time-series columns, in order.
extern const char* const kSeriesHeader;

class RopeSimulation {
 public:
  /// Throws InputError if the scene is not a crane: none scene with rope.model full.
  explicit RopeSimulation(const CraneModel& model);

  /// Build the initial state of SPEC 2 (t = 0).
  void initialize();
  void step();
  const RopeState& state() const { return state_; }
  const AncfRope& rope() const { return *rope_; }
  const AnchoredRopeSolver& solver() const { return *solver_; }

  /// Write one CSV row of the SPEC 3.1 columns for the current state.
  void writeSeriesRow(std::ostream& out) const;
  /// Write `t,node,x,y,z` rows for every rope node.
  void writeNodeRows(std::ostream& out) const;

  /// Static equilibrium of the scene (SPEC 2 `equilibrium` start, holding force included).
  RopeState staticState(Eigen::Vector3d* holding_force = nullptr);
  /// Rope modes (with the end mass) linearised at the static equilibrium without holding force:
  /// top node's position fixed, slope free.
  ModalBasis ropeModes(int count);

 private:
  const CraneModel& model_;
  std::unique_ptr<AncfRope> rope_;
  std::unique_ptr<AnchoredRopeSolver> solver_;
  RopeState state_;
};

}  // namespace crane_twin
