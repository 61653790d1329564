// What accuracy costs in time (docs/accuracy-vs-time.md): run a converged full-order reference
// once, then the full model over time steps and the reduced model over mode count, delta, structure
// modes and time step, each measured against the reference with the error metrics of
// docs/accuracy-vs-time.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "crane_twin/analysis/trajectory_compare.hpp"
#include "crane_twin/simulation/crane_model.hpp"

namespace crane_twin {

/// One setting of the sweep: the model and the scene overrides that make it.
struct SweepCase {
  std::string model;  ///< rope model: "pendulum", "full" or "reduced"
  std::vector<std::string> overrides;
  double time_step = 0.0;
  int rope_modes = 0;  ///< reduced: kept fixed-top modes
  double delta = 0.0;  ///< reduced: subdomain delta [m]
  int structure_modes = 0;
  StructureModel structure_model = StructureModel::modal;  ///< the fidelity ladder
  std::string frame = "-";  ///< reduced: subdomain frame, fixed | corotational
};

struct SweepResult {
  SweepCase setting;
  double wall_s = 0.0;  ///< integration only (steps), without setup and sampling
  double rtf = 0.0;     ///< simulated / wall seconds
  int subdomains = 0;
  double mode_updates_s = 0.0;
  ErrorMetrics error;  ///< against the reference
};

/// Integrate a scene, sampling payload, cab, jib tip and every rope node every `interval` s.
/// Returns the trajectory; wall time of the steps alone, subdomains and mode-update time out.
Trajectory recordRun(const CraneModel& model, double interval, double* wall_s = nullptr,
                     int* subdomains = nullptr, double* mode_updates_s = nullptr);

/// The grid of docs/accuracy-vs-time.md for a scene: full at 1, 2, 5, 10, 20, 50, 100 ms; reduced
/// at 6, 10, 20 modes x delta 0.05, 0.2, 0.5 m x 1, 5, 10 ms, plus the paper's point (mode_fraction
/// 0.5, the scene's delta and step) and 20 structure modes at one reduced setting; and the fidelity
/// ladder (docs/scenes.md): the pendulum rope at 1, 10 and 50 ms with the scene's structure, at
/// 10 ms with 20 structure modes, and the rigid structure under the pendulum (1 and 10 ms), the
/// full rope (10 ms) and the reduced rope (10 modes, 0.2 m, 5 ms). The reduced grid runs in the
/// scene's subdomain frame; the paper's fixed frame is added at 10 modes x delta x 5 ms and at the
/// paper's point when the scene uses the chord's frame, and 10 modes at 20 and 50 ms. `quick` keeps
/// a few.
std::vector<SweepCase> sweepGrid(const Scene& scene, bool quick);

/// Run the reference (full order at `reference_dt`) and every case. `progress` is told each
/// finished result. Throws what the runs throw.
std::vector<SweepResult> runSweep(const std::string& scene_file,
                                  const std::vector<std::string>& overrides,
                                  const std::vector<SweepCase>& cases, double reference_dt,
                                  double interval,
                                  const std::function<void(const SweepResult&)>& progress = {});

/// CSV header and row of a result.
extern const char* const kSweepHeader;
std::string sweepRow(const std::string& scene, const SweepResult& r);

}  // namespace crane_twin
