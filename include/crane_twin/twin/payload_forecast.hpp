// The twin's forecast (docs/twin.md "Forecast"): a second simulation of the twin's scene, built
// once with its own (coarser) time step, continues from the twin's current state
// (Simulation::continueFrom) under a held rate command for a horizon and samples the payload's
// path. With the live scene's 5 ms steps the twin runs the reduced rope; the forecast's 20 ms
// default keeps the payload within 0.5 mm of the 5 ms run over 40 s of a 5 deg swing and runs
// about 290x real time (docs/twin.md has the commands).
#pragma once

#include <Eigen/Dense>
#include <atomic>
#include <functional>
#include <memory>
#include <vector>

#include "crane_twin/io/scene.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"

namespace crane_twin {

struct PayloadForecast {
  double t0 = 0.0;                       ///< twin time the forecast starts from [s]
  std::vector<double> t;                 ///< predicted times [s of simulated time]
  std::vector<Eigen::Vector3d> payload;  ///< predicted payload positions (crane's base frame)
  double max_swing = 0.0;                ///< largest horizontal payload offset from the trolley [m]
  double max_swing_time = 0.0;           ///< when [s]
  bool failed = false;                   ///< the forecast run failed numerically (path up to then)
  bool cancelled = false;     ///< stopped by cancel() before its horizon (path up to then)
  double wall_seconds = 0.0;  ///< what the run cost [s of wall time]
};

class PayloadForecaster {
 public:
  /// Builds the forecast's own simulation of `model` with `time_step` [s] (> 0; the scene's own
  /// when 0). Throws InputError for a model the forecast cannot continue (docs/twin.md).
  PayloadForecaster(const CraneModel& model, double time_step);
  /// From the twin's state, `horizon` seconds ahead under `command` held throughout, a sample
  /// every `sample_period` seconds (the first at the start). Throws std::invalid_argument for a
  /// horizon or sample period not > 0 and what continueFrom throws.
  PayloadForecast run(const Simulation& twin, const CommandEntry& command, double horizon,
                      double sample_period);
  /// The same with the command asked for before every step (a trajectory being followed).
  using CommandSource = std::function<CommandEntry(double t, const CraneDrives& drives)>;
  PayloadForecast run(const Simulation& twin, const CommandSource& source, double horizon,
                      double sample_period);
  /// The two halves of run(), for a forecast on another thread: prepare() copies the twin's
  /// state (cheap, on the twin's thread); runPrepared() then touches only the forecaster.
  void prepare(const Simulation& twin);
  PayloadForecast runPrepared(const CommandSource& source, double horizon, double sample_period);
  /// Stops a runPrepared() running on another thread after its current step (its forecast then
  /// says cancelled); the next prepare() clears it. A twin shutting down or changing its load
  /// does not wait for a forecast it will drop (a forecast through a set-down's slack rope at
  /// full order takes many wall seconds).
  void cancel() { cancelled_ = true; }
  double timeStep() const { return time_step_; }

 private:
  std::unique_ptr<Simulation> sim_;
  ContinuableRun* continuable_ = nullptr;  ///< sim_'s, checked at construction
  double time_step_ = 0.0;
  std::atomic<bool> cancelled_{false};
};

}  // namespace crane_twin
