// What a run costs the crane (docs/fatigue.md "Usage"), from its output rows: the lifts (a
// lift-off as LiftOffMonitor confirms it, to the next set-down), each with the lifted mass
// (the model's payload), its dynamic factor phi_2 and its times; over the run the number of
// lifts n, the load spectrum factor k_Q = sum (m_i / m_max)^3 / n (m_max the crane file's
// max_load), and per hot spot Miner's sum D of its stress history (rainflow counted,
// analysis/rainflow.hpp, on the hot spot's detail category), D per hour of the run and the
// hours to D = 1 at that rate.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "crane_twin/analysis/rainflow.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/lift_off_monitor.hpp"
#include "crane_twin/simulation/simulation.hpp"

namespace crane_twin {

struct LiftRecord {
  double lift_off = 0.0;                                       ///< [s]
  double set_down = std::numeric_limits<double>::quiet_NaN();  ///< [s], NaN: still lifted
  double mass = 0.0;                                           ///< payload [kg]
  double dynamic_factor = 0.0;                                 ///< phi_2
};

struct HotSpotUsage {
  std::string name;
  double damage = 0.0;           ///< Miner's sum D over the run
  double damage_per_hour = 0.0;  ///< D / run hours
  double hours_to_failure = std::numeric_limits<double>::infinity();  ///< 1 / (D per hour)
};

struct UsageReport {
  double hours = 0.0;  ///< the run's simulated time [h]
  std::vector<LiftRecord> lifts;
  double k_q = 0.0;  ///< 0 without lifts
  std::vector<HotSpotUsage> hot_spots;
};

class UsageCounter {
 public:
  /// The payload mass and the hot spots of `model`; m_max from its crane file (none: k_Q 0).
  explicit UsageCounter(const CraneModel& model);
  /// One output row, after `lift_off` observed it. `time_offset` [s] is added to the row's and
  /// the monitor's times (a node's simulation that started again after a load change: its
  /// monitor's count starts again from 0 too); the times so shifted must not go back.
  void observe(const SeriesValues& row, const LiftOffMonitor& lift_off, double time_offset = 0.0);
  /// The payload from now on [kg] (~set_payload, or a twin's load cell), the lift under way
  /// included.
  void setPayloadMass(double mass);
  UsageReport report() const;

 private:
  double payload_mass_ = 0.0, max_load_ = 0.0;
  std::vector<std::string> names_;
  std::vector<SnCurve> curves_;
  /// Per hot spot: its stress history counted as it comes [Pa], and the Miner sum of the
  /// cycles closed so far (the rest when a report asks).
  std::vector<RainflowCounter> counters_;
  std::vector<double> closed_damage_;
  std::vector<LiftRecord> lifts_;
  int seen_lift_offs_ = 0;  ///< the monitor's count at the last row
  double t0_ = std::numeric_limits<double>::quiet_NaN(), t_ = 0.0;
};

}  // namespace crane_twin
