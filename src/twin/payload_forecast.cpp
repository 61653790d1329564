#include "crane_twin/twin/payload_forecast.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "crane_twin/integrators/numerical_failure.hpp"
#include "crane_twin/io/input_error.hpp"
#include "crane_twin/simulation/simulation_capabilities.hpp"

namespace crane_twin {

PayloadForecaster::PayloadForecaster(const CraneModel& model, double time_step) {
  if (!std::isfinite(time_step) || time_step < 0.0) {
    throw InputError("forecast time step must be >= 0 (0: the scene's), got " +
                     std::to_string(time_step));
  }
  CraneModel m = model;
  if (time_step > 0.0) {
    m.scene.time_step = time_step;
    m.scene.output_interval = std::max(m.scene.output_interval, time_step);
  }
  time_step_ = m.scene.time_step;
  sim_ = makeSimulation(m);
  continuable_ = &requireCapability<ContinuableRun>(*sim_);  // InputError, at once
  sim_->initialize();
}

PayloadForecast PayloadForecaster::run(const Simulation& twin, const CommandEntry& command,
                                       double horizon, double sample_period) {
  return run(
      twin, [command](double, const CraneDrives&) { return command; }, horizon, sample_period);
}

PayloadForecast PayloadForecaster::run(const Simulation& twin, const CommandSource& source,
                                       double horizon, double sample_period) {
  prepare(twin);
  return runPrepared(source, horizon, sample_period);
}

void PayloadForecaster::prepare(const Simulation& twin) {
  cancelled_ = false;
  continuable_->continueFrom(twin);
}

PayloadForecast PayloadForecaster::runPrepared(const CommandSource& source, double horizon,
                                               double sample_period) {
  if (!(horizon > 0.0) || !std::isfinite(horizon)) {
    throw std::invalid_argument("forecast horizon must be > 0");
  }
  if (!(sample_period > 0.0) || !std::isfinite(sample_period)) {
    throw std::invalid_argument("forecast sample period must be > 0");
  }
  if (!source) throw std::invalid_argument("forecast without a command source");
  const auto wall0 = std::chrono::steady_clock::now();
  PayloadForecast f;
  f.t0 = sim_->time();
  const double end = f.t0 + horizon, eps = 0.5 * time_step_;
  double next = f.t0;
  auto record = [&]() {
    const SeriesValues v = sim_->series();
    f.t.push_back(v.t);
    f.payload.push_back(v.payload);
    const double swing = (v.payload - v.trolley).head<2>().norm();
    if (swing > f.max_swing) {
      f.max_swing = swing;
      f.max_swing_time = v.t;
    }
  };
  try {
    while (true) {
      if (sim_->time() >= next - eps) {
        record();
        next += sample_period;
      }
      if (sim_->time() >= end - eps) break;
      if (cancelled_) {
        f.cancelled = true;
        break;
      }
      sim_->setCommand(source(sim_->time(), sim_->drives()));
      sim_->step();
    }
  } catch (const NumericalFailure&) {
    f.failed = true;
  }
  f.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return f;
}

}  // namespace crane_twin
