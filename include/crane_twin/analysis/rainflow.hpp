// Rainflow counting and Miner's sum (docs/fatigue.md): the cycles a stress history holds, after
// ASTM E1049-85 (rainflow counting, the four-point rule), and the damage they do on an
// EN 13001-3-1 S-N curve.
//
// Counting, on the history's turning points (its peaks and valleys; plateaus and points on a
// monotone run dropped): for each four consecutive points S1..S4 with ranges
// dS1 = |S2 - S1|, dS2 = |S3 - S2|, dS3 = |S4 - S3|, when dS2 <= dS1 and dS2 <= dS3 the inner
// pair S2, S3 closes a full cycle of range dS2 and mean (S2 + S3) / 2 and is removed; what
// remains (the residue) counts as half cycles, one per pair of neighbours. On the standard's
// example (-2, 1, -3, 5, -1, 3, -4, 4, -2) this gives its table: range 3 x 0.5, 4 x 1.5,
// 6 x 0.5, 8 x 1.0, 9 x 0.5.
//
// Damage (EN 13001-3-1, the S-N curve of slope m = 3 without cut-off): a cycle of stress range
// ds [MPa] on a detail of category ds_c [MPa] (its range at 2e6 cycles) with the partial
// safety factor gamma_Mf is allowed N = 2e6 (ds_c / (gamma_Mf ds))^3 times; Miner's sum
// D = sum count_i / N_i.
#pragma once

#include <vector>

namespace crane_twin {

struct RainflowCycle {
  double range = 0.0;  ///< |S_b - S_a| [the history's unit]
  double mean = 0.0;   ///< (S_a + S_b) / 2
  double count = 0.0;  ///< 1 (a closed cycle) or 0.5 (a half cycle of the residue)
};

/// The turning points of `history`: its first and last values and every strict peak and valley
/// between (a plateau counts once). Throws std::invalid_argument for a non-finite value.
std::vector<double> turningPoints(const std::vector<double>& history);

/// What a RainflowCounter holds between values (a node's counts kept across its restarts).
struct RainflowState {
  std::vector<double> turning_points;  ///< counted so far, no cycle closed among them
  std::vector<double> pending;  ///< the last one or two values (a turning point once it turns)
};

/// The counting above as the history comes, one value at a time: only the pending turning
/// point and the points not yet counted are kept (a node counting for hours keeps no history).
class RainflowCounter {
 public:
  RainflowCounter() = default;
  /// A counter that goes on from `state` (of state()). Throws std::invalid_argument for a
  /// non-finite value or more than two pending ones.
  explicit RainflowCounter(RainflowState state);
  RainflowState state() const { return {stack_, pending_}; }
  /// The history's next value; the cycles it closes are appended to `closed`. Throws
  /// std::invalid_argument for a non-finite value.
  void add(double x, std::vector<RainflowCycle>& closed);
  /// What the history so far still holds were it to end now: the cycles its last value closes,
  /// then the residue's half cycles. The counter is unchanged.
  std::vector<RainflowCycle> finish() const;

 private:
  /// Four-point rule on the newest four of `s`, repeated while it closes a cycle.
  static void closeCycles(std::vector<double>& s, std::vector<RainflowCycle>& closed);
  std::vector<double> stack_;    ///< turning points not yet counted
  std::vector<double> pending_;  ///< the last one or two values: a turning point once it turns
};

/// The cycles of `history` (see above): the closed cycles in the order they close, then the
/// residue's half cycles from its start. Empty for a history without two turning points.
/// Throws std::invalid_argument for a non-finite value.
std::vector<RainflowCycle> rainflowCount(const std::vector<double>& history);

/// EN 13001-3-1 S-N curve, slope 3, no cut-off.
struct SnCurve {
  double detail_category = 0.0;  ///< ds_c [MPa] (> 0)
  double gamma_mf = 1.0;         ///< partial safety factor gamma_Mf (>= 1)
  /// Cycles to failure at stress range `range_mpa` [MPa]: 2e6 (ds_c / (gamma_Mf ds))^3
  /// (infinite at 0).
  double cyclesToFailure(double range_mpa) const;
  /// Throws std::invalid_argument naming what is wrong.
  void check() const;
};

/// Miner's sum of `cycles` whose ranges are in Pa (the stress_ columns) on `curve`.
double minerDamage(const std::vector<RainflowCycle>& cycles, const SnCurve& curve);

}  // namespace crane_twin
