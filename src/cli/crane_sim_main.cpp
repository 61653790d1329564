// crane_sim: the command-line tool of docs/cli.md (no ROS). Exit status 0 on success, 2 on bad
// input (message on stderr), 1 on a numerical failure.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "crane_twin/analysis/accuracy_sweep.hpp"
#include "crane_twin/analysis/rainflow.hpp"
#include "crane_twin/analysis/trajectory_compare.hpp"
#include "crane_twin/io/config_reader.hpp"
#include "crane_twin/io/csv_columns.hpp"
#include "crane_twin/simulation/crane_model.hpp"
#include "crane_twin/simulation/crane_simulation.hpp"
#include "crane_twin/simulation/invariant_reduced_simulation.hpp"
#include "crane_twin/simulation/pendulum_crane_simulation.hpp"
#include "crane_twin/simulation/simulation.hpp"
#include "crane_twin/structure/modal_cache.hpp"
#include "run_recorder.hpp"

namespace ct = crane_twin;

namespace {

struct SceneArgs {
  std::string scene;
  std::vector<std::string> sets;
};

void addSceneArgs(CLI::App* cmd, SceneArgs& a) {
  cmd->add_option("scene", a.scene, "scene file (YAML)")->required();
  cmd->add_option("--set", a.sets, "override a scene key: dotted.path=value (value is YAML)")
      ->take_all();
}

int runInfo(const SceneArgs& a) {
  const ct::CraneModel m = ct::buildCraneModel(ct::loadScene(a.scene, a.sets));
  std::printf("structure_nodes,%d\n",
              m.structure ? static_cast<int>(m.structure->nodes.size()) : 0);
  std::printf("structure_elements,%d\n",
              m.structure ? static_cast<int>(m.structure->members.size()) : 0);
  std::printf("structure_dofs,%d\n", m.structure ? m.structure->free_dofs : 0);
  std::printf("structure_mass,%.1f\n",
              m.structure ? m.structure->memberMass() + m.structure->lumpedMass() : 0.0);
  std::printf("rope_elements,%d\n", m.scene.rope.elements);
  std::printf("rope_dofs,%d\n", m.ropeDofs());
  std::printf("rope_mass,%.3f\n", m.ropeMass());
  // Beyond docs/cli.md's required keys: what was built and the static load check of docs/model.md.
  std::printf("structure_model,%s\n", ct::name(m.scene.structure_model));
  std::printf("rope_model,%s\n", ct::name(m.scene.rope.model));
  std::printf("end_mass,%.1f\n", m.end_mass);
  // What a run of this scene integrates (only what the scene calls for is built).
  const ct::Scene& sc = m.scene;
  int structureCoords = 0;
  if (m.structure && sc.structure_model == ct::StructureModel::modal)
    structureCoords = sc.structure_modes;
  if (m.structure && sc.structure_model == ct::StructureModel::full)
    structureCoords = m.structure->free_dofs;
  std::printf("integrated_structure_coordinates,%d\n", structureCoords);
  const bool pendulum = ct::ropeModelOf(sc) == ct::RopeModelKind::pendulum;
  std::printf("integrated_rope_coordinates,%d\n", ct::integratedRopeCoordinates(m));
  // The pendulum is a straight bar: it has no bending whatever rope.bending says.
  std::printf("rope_bending,%s\n", sc.rope.bending && !pendulum ? "on" : "off");
  std::printf("rope_damping_s,%g\n", sc.rope.damping);
  std::printf("structural_damping_ratio,%g\n",
              m.structure && sc.structure_model != ct::StructureModel::rigid
                  ? sc.structure_damping_ratio
                  : 0.0);
  std::printf("slewing_inertial_loads,%s\n", sc.slew_inertial_loads ? "on" : "off");
  std::printf("slewing_drive,%s\n", ct::name(sc.slew_drive.model));
  std::printf("rope_tension_only,%s\n", sc.rope.tension_only ? "on" : "off");
  std::printf("rope_safety_factor,%g\n", sc.rope.safety_factor);
  std::printf("rope_reeving_length_m,%g\n", sc.rope.reeving_length);
  std::printf("hook_rigging_length_m,%g\n", sc.hook_rigging_length);
  std::printf("structure_geometric_stiffness,%s\n",
              sc.structure_geometric_stiffness ? "on" : "off");
  std::printf("wind,%s\n", sc.wind ? "on" : "off");
  std::printf("command_entries,%zu\n", sc.commands.size());
  if (m.structure) {
    std::printf("structure_member_mass,%.1f\n", m.structure->memberMass());
    std::printf("structure_lumped_mass,%.1f\n", m.structure->lumpedMass());
    const Eigen::VectorXd u = ct::staticTrolleyLoadDisplacement(
        *m.structure, m.scene.payload_mass, m.scene.trolley_radius, m.scene.gravity);
    std::printf("payload_jib_tip_dz,%.6f\n", ct::jibTipDisplacement(*m.structure, u).z());
    std::printf("payload_jib_bending_dz,%.6f\n", ct::jibBendingTipDz(*m.structure, u));
  }
  return 0;
}

int runModes(const SceneArgs& a, int count, const std::string& part) {
  const ct::CraneModel m = ct::buildCraneModel(ct::loadScene(a.scene, a.sets));
  if (part == "rope") {
    ct::CraneSimulation sim(m);
    if (count < 1 || count >= sim.rope().dofs() - 3) {
      std::cerr << "--count must be in 1.." << sim.rope().dofs() - 4 << ", got " << count << "\n";
      return 2;
    }
    const ct::ModalBasis b = sim.ropeModes(count);
    std::printf("index,frequency_hz\n");
    for (int i = 0; i < count; ++i) std::printf("%d,%.6f\n", i + 1, b.frequencyHz(i));
    return 0;
  }
  if (!m.structure) {
    std::cerr << a.scene << ": key 'crane': scene has no structure (crane: none); "
              << "use --part rope\n";
    return 2;
  }
  if (count < 1 || count >= m.structure->free_dofs) {
    std::cerr << "--count must be in 1.." << m.structure->free_dofs - 1 << ", got " << count
              << "\n";
    return 2;
  }
  ct::ModalOptions opt;
  opt.count = count;
  const ct::ModalBasis b = ct::cachedLowestModes(m.structure->K, m.structure->M, opt);
  std::printf("index,frequency_hz\n");
  for (int i = 0; i < count; ++i) std::printf("%d,%.6f\n", i + 1, b.frequencyHz(i));
  return 0;
}

struct RunArgs {
  std::string out, nodes;
  bool quiet = false;
};

std::ofstream openOutput(const std::string& path, const char* option) {
  std::ofstream f(path);
  if (!f) throw ct::InputError(std::string(option) + " '" + path + "': cannot open for writing");
  return f;
}

// The usage block (docs/cli.md, docs/fatigue.md "Usage"), before the summary line.
void printUsage(const ct::UsageReport& u) {
  std::printf("usage: hours=%.6g lifts=%ld k_Q=%.6g u_class=%s q_class=%s\n", u.hours, u.lift_count,
              u.k_q, u.u_class.c_str(), u.q_class.c_str());
  if (u.design_hours > 0.0) {
    std::printf("usage_design: design_hours=%g lifts_in_design_life=%.6g u_class=%s\n",
                u.design_hours, u.lifts_in_design_life,
                u.u_class_in_design_life.empty() ? "none" : u.u_class_in_design_life.c_str());
  }
  for (const ct::LiftRecord& l : u.lifts) {
    std::printf("usage_lift: lift_off_s=%.3f set_down_s=%.3f mass_kg=%g phi_2=%.4g\n", l.lift_off,
                l.set_down, l.mass, l.dynamic_factor);
  }
  for (const ct::HotSpotUsage& h : u.hot_spots) {
    std::printf("usage_hot_spot: name=%s damage=%.6g damage_per_h=%.6g hours_to_d1=%.6g%s\n",
                h.name.c_str(), h.damage, h.damage_per_hour, h.hours_to_failure,
                h.short_of_design_life ? " short_of_design_hours=1" : "");
  }
}

int runRun(const SceneArgs& a, const RunArgs& r) {
  const ct::CraneModel m = ct::buildCraneModel(ct::loadScene(a.scene, a.sets));
  const std::unique_ptr<ct::Simulation> sim = ct::makeSimulation(m);
  std::ofstream series, nodes;
  if (!r.out.empty()) series = openOutput(r.out, "--out");
  if (!r.nodes.empty()) nodes = openOutput(r.nodes, "--nodes");
  const ct::Scene& sc = m.scene;
  const long steps = std::lround(sc.duration / sc.time_step);
  const long every = std::max(1L, std::lround(sc.output_interval / sc.time_step));
  const bool bar = !r.quiet && isatty(fileno(stdout)) && isatty(fileno(stderr));
  if (series) series << ct::seriesHeader(m) << "\n";
  if (nodes) nodes << "t,node,x,y,z\n";
  // The rows, physical warnings (each kind reported on stderr when first seen, with a count of
  // the output rows that carried it at the end; the CSV carries them in every row), lift-offs,
  // tension peaks and usage; a speculation's held back until it is kept or taken back.
  double wall = 0.0;  // the steps alone: no setup, no output
  std::optional<ct::RunRecorder> recorder;
  try {
    sim->initialize();
    recorder.emplace(m, *sim, series ? &series : nullptr, nodes ? &nodes : nullptr, every, bar);
    recorder->recordStart();
    for (long k = 1; k <= steps; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      sim->step();
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      recorder->recordStep(k);
      if (bar && (k % std::max(1L, steps / 100) == 0 || k == steps)) {
        std::fprintf(stderr, "\r[%-50s] %5.1f%%  t = %.2f s",
                     std::string(50 * k / steps, '#').c_str(), 100.0 * k / steps, sim->time());
      }
    }
  } catch (const ct::NumericalFailure& e) {
    if (recorder) recorder->finish();
    if (bar) std::fprintf(stderr, "\n");
    std::cerr << "numerical failure: " << e.what() << "\n";
    return 1;
  }
  recorder->finish();
  if (bar) std::fprintf(stderr, "\n");
  for (const auto& [bit, rows] : recorder->warned()) {
    std::fprintf(stderr, "warning: %s in %ld output rows\n", ct::warningName(bit), rows);
  }
  const ct::RunStatistics stats = sim->statistics();
  if (stats.halved_steps > 0) {
    std::fprintf(stderr, "note: halved_steps=%ld (steps where Newton failed at the full size)\n",
                 stats.halved_steps);
  }
  const double simS = steps * sc.time_step;
  // Warning counts: the bits seen (docs/cli.md) and, per bit, the output rows that carried it.
  int seen = 0;
  std::string rows_per_bit;
  for (const auto& [bit, rows] : recorder->warned()) {
    seen |= bit;
    rows_per_bit +=
        (rows_per_bit.empty() ? "" : ",") + std::to_string(bit) + ":" + std::to_string(rows);
  }
  printUsage(recorder->usage());
  std::printf(
      "summary: wall_s=%.3g sim_s=%g rtf=%.3g steps=%ld subdomains=%d mode_updates_s=%.3g "
      "hand_overs=%ld taken_back=%ld full_order_steps=%ld warnings_seen=%d warning_rows=%s "
      "energy_consistent_steps=%ld halved_steps=%ld lift_offs=%d lift_off_factor=%.4g "
      "peak_tension_ratio=%.4g basis_additions=%ld\n",
      wall, simS, simS / wall, steps, stats.subdomains, stats.mode_update_seconds, stats.hand_overs,
      stats.hand_backs_taken_back, stats.full_order_steps, seen,
      rows_per_bit.empty() ? "none" : rows_per_bit.c_str(), stats.energy_consistent_steps,
      stats.halved_steps, recorder->liftOff().liftOffs(), recorder->liftOff().factor(),
      recorder->peakTension() / m.rope.breaking_force, stats.basis_additions);
  return 0;
}

// The hot spots' stresses of the structure's state z (docs/fatigue.md) as stress_<name> keys.
void printStresses(const ct::CraneModel& m, const Eigen::VectorXd& z) {
  if (!m.hot_spots) return;
  const Eigen::VectorXd sigma = m.hot_spots->stresses(z);
  for (std::size_t i = 0; i < m.hot_spots->rows.size(); ++i) {
    std::printf("stress_%s,%.6f\n", m.hot_spots->rows[i].name.c_str(), sigma(i));
  }
}

// The scene's start at rest: the static equilibrium, or a landed start (itself a rest state: the
// load on the ground, the rope hanging unloaded, no holding force).
template <class Sim>
ct::CoupledState restingStart(const ct::CraneModel& m, Sim& sim, Eigen::Vector3d& H) {
  H.setZero();
  if (m.scene.initial_mode != ct::InitialMode::landed) return sim.staticState(&H);
  sim.initialize();
  return sim.fullState();
}

int runStatic(const SceneArgs& a) {
  const ct::CraneModel m = ct::buildCraneModel(ct::loadScene(a.scene, a.sets));
  Eigen::Vector3d H;
  if (m.scene.rope.model == ct::RopeModel::pendulum) {
    ct::PendulumCraneSimulation sim(m);
    const ct::CoupledState s = restingStart(m, sim, H);
    const Eigen::Vector3d p = s.q.tail<3>();
    std::printf("payload_x,%.9f\npayload_y,%.9f\npayload_z,%.9f\n", p.x(), p.y(), p.z());
    std::printf("rope_top_tension,%.6f\n", sim.topTension(s));
    std::printf("jib_tip_dz,%.9f\n", sim.support().jibTipDisplacement(s.z).z());
    std::printf("cab_dx,%.9f\n", sim.support().cabDisplacement(s.z).x());
    std::printf("holding_force_x,%.6f\nholding_force_y,%.6f\n", H.x(), H.y());
    printStresses(m, s.z);
    return 0;
  }
  ct::CraneSimulation sim(m);
  const ct::CoupledState s = restingStart(m, sim, H);
  const Eigen::Vector3d p = sim.rope().position(s.q, sim.rope().nodes() - 1);
  std::printf("payload_x,%.9f\npayload_y,%.9f\npayload_z,%.9f\n", p.x(), p.y(), p.z());
  std::printf("rope_top_tension,%.6f\n", sim.solver().topTension(s));
  std::printf("jib_tip_dz,%.9f\n", sim.support().jibTipDisplacement(s.z).z());
  std::printf("cab_dx,%.9f\n", sim.support().cabDisplacement(s.z).x());
  std::printf("holding_force_x,%.6f\nholding_force_y,%.6f\n", H.x(), H.y());
  printStresses(m, s.z);
  return 0;
}

int runCompare(const std::string& a, const std::string& b, const std::string& na,
               const std::string& nb, const ct::TimeWindow& window) {
  if (na.empty() != nb.empty()) {
    throw ct::InputError("--nodes-a and --nodes-b go together (the rope RMS error needs both)");
  }
  const ct::ErrorMetrics m =
      ct::compareTrajectories(ct::readTrajectory(a, na), ct::readTrajectory(b, nb), window);
  std::printf("common_times,%d\n", m.common_times);
  std::printf("payload_error_max,%.9g\n", m.payload_max);
  std::printf("payload_error_relative,%.9g\n", m.payload_relative);
  if (m.rope_rms_max >= 0.0) {
    std::printf("rope_rms_max,%.9g\n", m.rope_rms_max);
    std::printf("rope_rms_relative,%.9g\n",
                m.rope_length > 0 ? m.rope_rms_max / m.rope_length : 0.0);
  }
  std::printf("cab_error_max,%.9g\n", m.cab_max);
  std::printf("jib_tip_error_max,%.9g\n", m.jib_tip_max);
  std::printf("tension_error_max,%.9g\n", m.tension_max);
  std::printf("tension_error_relative,%.9g\n", m.tension_relative);
  std::printf("payload_error_at,%.9g\n", m.payload_max_at);
  if (m.rope_rms_max >= 0.0) std::printf("rope_rms_at,%.9g\n", m.rope_rms_max_at);
  return 0;
}

struct SweepArgs {
  std::string out;
  bool quick = false;
  double reference_dt = 0.0;
  double interval = 0.02;
};

int runSweep(const SceneArgs& a, const SweepArgs& w) {
  const ct::Scene scene = ct::loadScene(a.scene, a.sets);
  if (w.reference_dt > scene.time_step) {
    throw ct::InputError("--reference-dt " + ct::shownNumber(w.reference_dt) +
                         " s: the reference must not take a longer step than the scene's "
                         "time_step (" +
                         ct::shownNumber(scene.time_step) + " s)");
  }
  const double refDt = w.reference_dt > 0.0 ? w.reference_dt : 0.5 * scene.time_step;
  std::ofstream out;
  if (!w.out.empty()) out = openOutput(w.out, "--out");
  std::string name = a.scene.substr(a.scene.find_last_of('/') + 1);
  name = name.substr(0, name.rfind(".yaml"));
  if (out) out << ct::kSweepHeader << "\n";
  std::printf("%s\n", ct::kSweepHeader);
  const auto cases = ct::sweepGrid(scene, w.quick);
  try {
    ct::runSweep(a.scene, a.sets, cases, refDt, w.interval, [&](const ct::SweepResult& r) {
      const std::string row = ct::sweepRow(name, r);
      std::printf("%s\n", row.c_str());
      std::fflush(stdout);
      if (out) out << row << "\n" << std::flush;
    });
  } catch (const ct::NumericalFailure& e) {
    std::cerr << "numerical failure: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

// crane_sim rainflow (docs/cli.md, docs/fatigue.md): the cycles of one column, and with a
// detail category Miner's sum on its S-N curve.
int runRainflow(const std::string& file, const std::string& column,
                const std::optional<double>& category, double gamma_mf) {
  std::vector<double> history;
  for (const auto& row : ct::readCsvColumns(file, {column})) history.push_back(row[0]);
  std::optional<ct::SnCurve> curve;
  if (category) {
    curve = ct::SnCurve{*category, gamma_mf};
    try {
      curve->check();
    } catch (const std::invalid_argument& e) {
      throw ct::InputError(std::string("--detail-category / --gamma-mf: ") + e.what());
    }
  }
  const std::vector<ct::RainflowCycle> cycles = ct::rainflowCount(history);
  std::printf("range,mean,count\n");
  for (const ct::RainflowCycle& c : cycles) {
    std::printf("%.10g,%.10g,%g\n", c.range, c.mean, c.count);
  }
  if (curve) std::printf("damage,%.12g\n", ct::minerDamage(cycles, *curve));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"crane_sim: flat-top tower crane multibody simulator (crane_twin)"};
  app.require_subcommand(1);
  SceneArgs infoArgs, modesArgs;
  CLI::App* info = app.add_subcommand("info", "print the model's size as key,value lines");
  addSceneArgs(info, infoArgs);
  CLI::App* modes = app.add_subcommand("modes", "print natural frequencies as index,frequency_hz");
  addSceneArgs(modes, modesArgs);
  int count = 10;
  std::string part = "structure";
  modes->add_option("--count", count, "number of modes");
  modes->add_option("--part", part, "structure or rope")
      ->check(CLI::IsMember({"structure", "rope"}));
  SceneArgs runArgs, staticArgs;
  RunArgs runOpts;
  CLI::App* run = app.add_subcommand("run", "integrate the scene and write the time series");
  addSceneArgs(run, runArgs);
  run->add_option("--out", runOpts.out, "time-series CSV (docs/cli.md columns)");
  run->add_option("--nodes", runOpts.nodes, "rope nodes CSV: t,node,x,y,z");
  run->add_flag("--quiet", runOpts.quiet, "no progress bar");
  CLI::App* stat = app.add_subcommand("static", "print the static equilibrium as key,value");
  addSceneArgs(stat, staticArgs);
  std::string cmpA, cmpB, cmpNA, cmpNB;
  CLI::App* cmp = app.add_subcommand(
      "compare", "error metrics of run A against run B (docs/accuracy-vs-time.md)");
  cmp->add_option("a", cmpA, "time-series CSV of run A")->required();
  cmp->add_option("b", cmpB, "time-series CSV of run B (the reference)")->required();
  cmp->add_option("--nodes-a", cmpNA, "nodes CSV of run A");
  cmp->add_option("--nodes-b", cmpNB, "nodes CSV of run B");
  ct::TimeWindow cmpWindow;
  cmp->add_option("--from", cmpWindow.from, "compare output times t >= FROM only [s]");
  cmp->add_option("--to", cmpWindow.to, "compare output times t <= TO only [s]");
  SceneArgs sweepArgs;
  SweepArgs sweepOpts;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "accuracy against wall time, full and reduced (docs/accuracy-vs-time.md)");
  addSceneArgs(sweep, sweepArgs);
  sweep->add_option("--out", sweepOpts.out, "CSV of the results");
  sweep->add_flag("--quick", sweepOpts.quick, "a few settings only");
  sweep
      ->add_option("--reference-dt", sweepOpts.reference_dt,
                   "time step of the full-order reference (default: half the scene's)")
      ->check(CLI::PositiveNumber);
  sweep->add_option("--interval", sweepOpts.interval, "sampling interval of the comparison [s]")
      ->check(CLI::PositiveNumber);
  std::string rfFile, rfColumn;
  double rfCategory = 0.0, rfGamma = 1.0;
  CLI::App* rainflow = app.add_subcommand(
      "rainflow", "rainflow-count one column of a CSV, and Miner's sum (docs/fatigue.md)");
  rainflow->add_option("file", rfFile, "CSV with a header row")->required();
  rainflow->add_option("--column", rfColumn, "the column to count (stress_ columns: Pa)")
      ->required();
  CLI::Option* rfCategoryOpt =
      rainflow
          ->add_option("--detail-category", rfCategory,
                       "EN 13001-3-1 detail category [MPa]: end with damage,<Miner sum>")
          ->check(CLI::PositiveNumber);
  rainflow->add_option("--gamma-mf", rfGamma, "partial safety factor gamma_Mf (>= 1)")
      ->check(CLI::Range(1.0, 1e9))
      ->needs(rfCategoryOpt);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  try {
    if (*info) return runInfo(infoArgs);
    if (*modes) return runModes(modesArgs, count, part);
    if (*run) return runRun(runArgs, runOpts);
    if (*stat) return runStatic(staticArgs);
    if (*cmp) return runCompare(cmpA, cmpB, cmpNA, cmpNB, cmpWindow);
    if (*sweep) return runSweep(sweepArgs, sweepOpts);
    if (*rainflow) {
      return runRainflow(rfFile, rfColumn,
                         rfCategoryOpt->count() ? std::optional<double>(rfCategory) : std::nullopt,
                         rfGamma);
    }
  } catch (const ct::InputError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "numerical failure: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
