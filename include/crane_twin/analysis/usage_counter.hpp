// What a run costs the crane (docs/fatigue.md "Usage"), from its output rows (and its steps'
// stresses between them): the lifts (a lift-off as LiftOffMonitor confirms it, to the next
// set-down), each with the lifted mass
// (the model's payload), its dynamic factor phi_2 and its times; over the run the number of
// lifts n, the load spectrum factor k_Q = sum (m_i / m_max)^3 / n (m_max the crane file's
// max_load) and its class Q, the class U of n and of the lifts projected over the crane file's
// design_hours at the run's rate, and per hot spot Miner's sum D of its stress history
// (rainflow counted, analysis/rainflow.hpp, on the hot spot's detail category), D per hour and
// the hours to D = 1 at that rate. The counts can go on from a UsageState (a node's lifetime
// kept across restarts, io/usage_store.hpp).
#pragma once

#include <deque>
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
  double damage = 0.0;           ///< Miner's sum D over the hours counted
  double damage_per_hour = 0.0;  ///< D / hours
  double hours_to_failure = std::numeric_limits<double>::infinity();  ///< 1 / (D per hour)
  /// hours_to_failure below the crane file's design_hours (false without design hours).
  bool short_of_design_life = false;
};

struct UsageReport {
  double hours = 0.0;  ///< simulated time counted [h]
  long lift_count = 0;
  /// The latest lifts, oldest first (every lift of a run up to UsageCounter::kRecentLifts).
  std::vector<LiftRecord> lifts;
  double k_q = 0.0;           ///< 0 without lifts
  std::string u_class;        ///< class U of lift_count
  std::string q_class;        ///< class Q of k_q
  double design_hours = 0.0;  ///< the crane file's design_hours (0: none)
  /// lift_count / hours * design_hours, and its class U (0 and "" without design hours, hours
  /// or lifts).
  double lifts_in_design_life = 0.0;
  std::string u_class_in_design_life;
  std::vector<HotSpotUsage> hot_spots;
};

/// The counts a UsageCounter carries on from (and gives back with state()).
struct UsageState {
  struct HotSpot {
    std::string name;
    double detail_category = 0.0;  ///< [MPa], as counted
    /// Miner's sum of the cycles closed so far (the report adds the residue's half cycles).
    double closed_damage = 0.0;
    RainflowState counter;  ///< the history not yet counted
  };
  double hours = 0.0;  ///< [h]
  long lift_count = 0;
  double max_load = 0.0;                 ///< m_max of the sum below [kg]
  double mass_ratio_cubed_sum = 0.0;     ///< sum (m_i / m_max)^3 over every lift
  std::vector<LiftRecord> recent_lifts;  ///< the latest, oldest first
  std::vector<HotSpot> hot_spots;
};

class UsageCounter {
 public:
  static constexpr std::size_t kRecentLifts = 1000;  ///< lifts a report lists

  /// The payload mass and the hot spots of `model`; m_max from its crane file (none: k_Q 0).
  explicit UsageCounter(const CraneModel& model);
  /// Going on from `before` (its lifts all set down or left open; the next lift is a new one).
  /// Throws std::invalid_argument when `before` counted other hot spots or categories than the
  /// model's, or holds a negative or non-finite figure; a different max_load rescales its sum.
  UsageCounter(const CraneModel& model, const UsageState& before);
  /// One output row, after `lift_off` observed it. `time_offset` [s] is added to the row's and
  /// the monitor's times (a node's simulation that started again after a load change: its
  /// monitor's count starts again from 0 too); the times so shifted must not go back.
  void observe(const SeriesValues& row, const LiftOffMonitor& lift_off, double time_offset = 0.0);
  /// The hot spots' stresses of one time step between the rows [Pa] (Simulation::
  /// hotSpotStresses): the rainflow count takes the crests the rows miss. The row after the
  /// step repeats its last values, a plateau that counts once. Throws std::invalid_argument for
  /// a non-finite stress.
  void observeStep(const Eigen::VectorXd& stresses);
  /// The payload from now on [kg] (~set_payload, or a twin's load cell), the lift under way
  /// included.
  void setPayloadMass(double mass);
  UsageReport report() const;
  /// Everything counted, `before` included.
  UsageState state() const;

 private:
  double hours() const;
  /// (m / m_max)^3 (0 without a max_load), and its sum over every lift counted.
  double massRatioCubed(double mass) const;
  double massRatioCubedSum() const;
  /// Keep `l` among the latest kRecentLifts.
  void remember(const LiftRecord& l);
  /// The hot spots' next stresses [Pa] (a row's or a step's) into their rainflow counts.
  void countStresses(const double* stresses, std::size_t count);
  double payload_mass_ = 0.0, max_load_ = 0.0, design_hours_ = 0.0;
  std::vector<std::string> names_;
  std::vector<SnCurve> curves_;
  /// Per hot spot: its stress history counted as it comes [Pa], and the Miner sum of the
  /// cycles closed so far (the rest when a report asks).
  std::vector<RainflowCounter> counters_;
  std::vector<double> closed_damage_;
  std::deque<LiftRecord> lifts_;  ///< the latest kRecentLifts
  long lift_count_ = 0;
  /// sum (m_i / m_max)^3 over the lifts but the last one when it began in this count (its
  /// mass may still change).
  double earlier_cubed_sum_ = 0.0;
  bool last_from_this_count_ = false;
  int seen_lift_offs_ = 0;  ///< the monitor's count at the last row
  double hours_before_ = 0.0;
  double t0_ = std::numeric_limits<double>::quiet_NaN(), t_ = 0.0;
};

}  // namespace crane_twin
